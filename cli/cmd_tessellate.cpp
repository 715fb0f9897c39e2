// freeform tessellate: surfaces of a document (or a .bpt patch file) to a triangle mesh in OBJ.

#include <algorithm>
#include <filesystem>
#include <memory>
#include <optional>

#include "command.h"
#include "freeform/document/operations.h"
#include "freeform/io/bpt.h"
#include "freeform/io/mesh_io.h"
#include "freeform/subdivision/subdivision_surface.h"
#include "freeform/tessellate/tessellate.h"

namespace freeform::cli {
namespace {

bool hasExtension(const std::string& path, const std::string& ext)
{
    std::string e = std::filesystem::path(path).extension().string();
    for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return e == ext;
}

struct TessellateOptions {
    std::vector<std::string> positional;
    std::string output, object;
    double tolerance = 0;
    int segments = 8;
    bool outward = false;
    long maxTriangles = 10'000'000;
    std::string refinement = "local", measure = "parametric";
    const CLI::Option* toleranceGiven = nullptr;
    const CLI::Option* segmentsGiven = nullptr;
    const CLI::Option* objectGiven = nullptr;
};

/// A subdivision_surface named by --object: the library's tessellation (certified with a tolerance
/// on every Catmull-Clark and Loop cage, docs/subdivision.md), reported with the patch fields where they apply.
Json subdivisionCommand(const SubdivisionSurface& surface, const TessellateOptions& o, const std::string& output)
{
    SubdivisionTessellationOptions options;
    if (given(o.toleranceGiven)) options.tolerance = o.tolerance;
    else options.level = std::clamp(o.segments, 1, options.maxLevel);
    SubdivisionTessellationReport report;
    PolygonMesh mesh = surface.tessellate(options, &report);
    if (o.outward) {
        for (int f = 0; f < mesh.faceCount(); ++f) std::swap(mesh.faceVertices[3 * static_cast<std::size_t>(f) + 1], mesh.faceVertices[3 * static_cast<std::size_t>(f) + 2]);
        mesh.normals = -mesh.normals;
    }
    if (o.maxTriangles > 0 && mesh.faceCount() > o.maxTriangles)
        throw Error("tessellation: " + std::to_string(mesh.faceCount()) + " triangles exceed --max-triangles " + std::to_string(o.maxTriangles));
    writePolygonMesh(mesh, output);
    int certifiedFaces = 0;
    for (char c : report.faceCertified) certifiedFaces += c ? 1 : 0;
    Json out;
    out["output"] = output;
    out["patches"] = report.cells;
    out["vertices"] = mesh.vertexCount();
    out["triangles"] = mesh.faceCount();
    if (report.certifiedPath) out["error_bound"] = report.errorBound;
    out["certified"] = report.certifiedPath && certifiedFaces == surface.faceCount();
    out["faces_certified"] = certifiedFaces;
    if (report.certifiedPath) {
        out["cells"] = report.cells;
        out["leaves"] = report.leaves;
    }
    return out;
}

/// A STEP or IGES part: the certified watertight mesh of freeform/brep/part_mesh.h.
Json partCommand(const TessellateOptions& o)
{
    const std::string& input = o.positional[0];
    if (!hasExtension(o.output, ".obj") && !hasExtension(o.output, ".ply") && !hasExtension(o.output, ".stl"))
        throw UsageError("option -o: a part's mesh must be an .obj, .ply or .stl file");
    if (!given(o.toleranceGiven)) throw UsageError("a part needs --tolerance E (the certified distance bound)");
    if (!(o.tolerance > 0)) throw UsageError("option --tolerance: must be positive");
    if (given(o.segmentsGiven) || given(o.objectGiven) || o.outward || o.refinement != "local" || o.measure != "parametric")
        throw UsageError("a part takes only --tolerance and --max-triangles");
    if (o.maxTriangles < 0) throw UsageError("option --max-triangles: must be 0 (no limit) or positive");
    return partTessellate(input, o.output, o.tolerance, o.maxTriangles);
}

Json tessellateCommand(const TessellateOptions& o)
{
    expectPositional(o.positional, 1, "the input (freeform tessellate IN.json|IN.bpt|PART.step -o OUT.obj)");
    const std::string& input = o.positional[0];
    const std::string& output = o.output;
    if (isPartFileName(input)) return partCommand(o);
    if (!hasExtension(output, ".obj")) throw UsageError("option -o: the output must be an .obj file");
    if (given(o.toleranceGiven) && given(o.segmentsGiven)) throw UsageError("give either --tolerance or --segments, not both");
    TessellationOptions options;
    if (given(o.toleranceGiven)) {
        options.tolerance = o.tolerance;
        if (!(options.tolerance > 0)) throw UsageError("option --tolerance: must be positive");
    } else {
        const int n = o.segments;
        if (n < 1 || n > 4096) throw UsageError("option --segments: must be in 1..4096");
        options.segmentsU = options.segmentsV = n;
    }
    options.flipNormals = o.outward;
    if (o.maxTriangles < 0) throw UsageError("option --max-triangles: must be 0 (no limit) or positive");
    options.maxTriangles = o.maxTriangles;
    if (o.refinement == "patch-grid") options.refinement = TessellationRefinement::PatchGrid;
    if (o.measure == "geometric") options.measure = TessellationMeasure::Geometric;
    options.sampleDeviation = true;

    DocumentTessellation result;
    if (hasExtension(input, ".bpt")) {
        if (given(o.objectGiven)) throw UsageError("option --object applies to documents, not .bpt files");
        const PatchComplex complex = readBpt(input);
        result.mesh = tessellate(complex, options, &result.report);
        result.patches = complex.patches.size();
    } else {
        const TypedDocument doc = TypedDocument::read(input);
        const TypedObject* object = given(o.objectGiven) ? &doc.object(o.object) : nullptr;
        if (const auto* sub = object ? std::get_if<SubdivisionObject>(&object->geometry()) : nullptr)
            return subdivisionCommand(sub->surface, o, output);
        if (object && (object->kind() == ObjectKind::Part || object->kind() == ObjectKind::TrimmedSurface)) {
            // A part (or trimmed surface) named by --object: the certified watertight part mesh,
            // reported as for a STEP or IGES part.
            if (!given(o.toleranceGiven)) throw UsageError("a part needs --tolerance E (the certified distance bound)");
            if (o.outward || o.refinement != "local" || o.measure != "parametric")
                throw UsageError("a part takes only --tolerance and --max-triangles");
            std::string name;
            const Part part = documentPart(input, object->name(), name);
            Json out = partMeshCommand(part, output, o.tolerance, o.maxTriangles);
            out["object"] = name;
            return out;
        }
        result = tessellateDocument(doc, object, options); // the document layer (document/operations.h)
    }
    const PolygonMesh& mesh = result.mesh;
    const TessellationReport& report = result.report;
    const std::size_t patches = result.patches;
    writePolygonMesh(mesh, output);
    Json out;
    out["output"] = output;
    out["patches"] = patches;
    out["vertices"] = mesh.vertexCount();
    out["triangles"] = mesh.faceCount();
    out["error_bound"] = report.errorBound;
    out["measured_parametric"] = report.measuredParametric;
    out["measured_geometric"] = report.measuredGeometric;
    return out;
}

} // namespace

Action defineTessellate(CLI::App& app)
{
    auto o = std::make_shared<TessellateOptions>();
    app.footer("Tessellates every bezier_surface and deboor_surface of the document (or the one named by\n"
               "--object), or every patch of a .bpt file, into one triangle mesh. Patches that share a side\n"
               "(identical control points) share its vertices, so a closed complex gives a closed mesh.\n"
               "The OBJ has v, vt (u, v of the patch), vn (the surface's unit normal) and f v/vt/vn.\n"
               "\n"
               "Output: {\"output\": F, \"patches\": P, \"vertices\": V, \"triangles\": T, \"error_bound\": B,\n"
               "\"measured_parametric\": MP, \"measured_geometric\": MG} with B the largest certified distance\n"
               "bound over the patches, MP and MG the largest deviations found at 12 points per triangle\n"
               "(triangle point to the surface point with the same (u, v); to its foot point).\n"
               "\n"
               "A STEP (.step .stp), IGES (.iges .igs) or BRep (.brep) part, with --tolerance E and -o OUT.obj|.ply|.stl,\n"
               "gives its certified watertight mesh (docs/cad.md): every edge sampled once for both of its\n"
               "faces, every triangle within B <= E of its face. Output: {\"output\", \"faces\", \"triangles\",\n"
               "\"vertices\", \"watertight\", \"error_bound\": B, \"certified\", \"closed_shells\",\n"
               "\"open_mesh_edges\", \"max_vertex_gap\", \"max_trim_deviation\"}.\n"
               "Exit status: 0 ok, 1 bad input, 2 bad usage.");
    addPositionals(app, "IN", o->positional, "the document (IN.json) or Bézier patch file (IN.bpt)");
    app.add_option("-o,--output", o->output, "the .obj file to write (written to a temporary file, then renamed)")
        ->type_name("OUT.obj")
        ->required();
    o->toleranceGiven = addNumber(app, "--tolerance", o->tolerance,
                                  "adaptive: every surface point lies within E of the mesh and every mesh point "
                                  "within E of the surface (certified bound from the control nets, docs/surfaces.md)")
                            ->type_name("E");
    o->segmentsGiven = addNumber(app, "--segments", o->segments, "uniform: N x N cells per patch (1..4096)")
                           ->type_name("N")
                           ->capture_default_str();
    o->objectGiven = app.add_option("--object", o->object, "only this surface object of the document")->type_name("NAME");
    addNumber(app, "--max-triangles", o->maxTriangles,
              "refuse (exit 1, with the estimate) a mesh of more than N triangles (0: no limit)")
        ->type_name("N")
        ->capture_default_str();
    app.add_option("--refinement", o->refinement,
                   "local: each patch refined where its curvature needs it; patch-grid: one grid per patch from "
                   "the bound of its whole net")
        ->type_name("R")
        ->check(CLI::IsMember({"local", "patch-grid"}))
        ->capture_default_str();
    app.add_option("--measure", o->measure,
                   "parametric: the bound holds both ways; geometric: only every mesh point lies within E of the "
                   "surface (fewer triangles: the tangential part of the error is not counted)")
        ->type_name("M")
        ->check(CLI::IsMember({"parametric", "geometric"}))
        ->capture_default_str();
    addFlag(app, "--outward", o->outward,
                 "reverse the triangles and the normals: normals along -(f_u x f_v) (outward for teapot.bpt, whose "
                 "f_u x f_v points inwards)");
    return [o] { return tessellateCommand(*o); };
}

} // namespace freeform::cli
