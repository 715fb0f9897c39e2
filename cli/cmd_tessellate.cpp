// freeform tessellate: surfaces of a document (or a .bpt patch file) to a triangle mesh in OBJ.

#include <filesystem>
#include <memory>
#include <optional>

#include "command.h"
#include "freeform/io/bpt.h"
#include "freeform/io/mesh_io.h"
#include "freeform/tessellate/tessellate.h"
#include "surface_objects.h"

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
    const CLI::Option* toleranceGiven = nullptr;
    const CLI::Option* segmentsGiven = nullptr;
    const CLI::Option* objectGiven = nullptr;
};

Json tessellateCommand(const TessellateOptions& o)
{
    expectPositional(o.positional, 1, "the input (freeform tessellate IN.json|IN.bpt -o OUT.obj)");
    const std::string& input = o.positional[0];
    const std::string& output = o.output;
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

    PatchComplex complex;
    std::vector<const DocumentObject*> rational; // rational_bezier_surface, nurbs_surface
    std::optional<Document> document;
    if (hasExtension(input, ".bpt")) {
        if (given(o.objectGiven)) throw UsageError("option --object applies to documents, not .bpt files");
        complex = readBpt(input);
    } else {
        document = readDocument(input);
        const Document& doc = *document;
        if (given(o.objectGiven) && isRationalSurface(doc.object(o.object))) {
            rational.push_back(&doc.object(o.object));
        } else if (given(o.objectGiven)) {
            complex = surfacePatches(doc, doc.object(o.object));
        } else {
            for (const DocumentObject& o : doc.objects) {
                if (isRationalSurface(o)) rational.push_back(&o);
                if (!isSurfaceObject(o)) continue;
                PatchComplex part = surfacePatches(doc, o);
                complex.patches.insert(complex.patches.end(), part.patches.begin(), part.patches.end());
            }
            if (complex.patches.empty() && rational.empty())
                throw Error(doc.source + ": the document has no surface objects (bezier_surface, deboor_surface)");
        }
    }
    TessellationReport report;
    PolygonMesh mesh = complex.patches.empty() ? PolygonMesh() : tessellate(complex, options, &report);
    std::size_t patches = complex.patches.size();
    if (!rational.empty()) {
        RationalMeshes r = tessellateRationalSurfaces(*document, rational, options);
        if (!complex.patches.empty()) r.meshes.insert(r.meshes.begin(), std::move(mesh));
        mesh = r.meshes.size() == 1 ? std::move(r.meshes.front()) : mergeMeshes(r.meshes);
        patches += static_cast<std::size_t>(r.patches);
        report.errorBound = std::max(report.errorBound, r.errorBound);
    }
    writePolygonMesh(mesh, output);
    Json out;
    out["output"] = output;
    out["patches"] = patches;
    out["vertices"] = mesh.vertexCount();
    out["triangles"] = mesh.faceCount();
    out["error_bound"] = report.errorBound;
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
               "Output: {\"output\": F, \"patches\": P, \"vertices\": V, \"triangles\": T, \"error_bound\": B}\n"
               "with B the largest certified distance bound over the patches.\n"
               "Exit status: 0 ok, 1 bad input, 2 bad usage.");
    addPositionals(app, "IN", o->positional, "the document (IN.json) or Bézier patch file (IN.bpt)");
    app.add_option("-o,--output", o->output, "the .obj file to write (written to a temporary file, then renamed)")
        ->type_name("OUT.obj")
        ->required();
    o->toleranceGiven = addNumber(app, "--tolerance", o->tolerance,
                                  "adaptive: every surface point lies within E of the mesh (certified bound from "
                                  "the control net, docs/surfaces.md)")
                            ->type_name("E");
    o->segmentsGiven = addNumber(app, "--segments", o->segments, "uniform: N x N cells per patch (1..4096)")
                           ->type_name("N")
                           ->capture_default_str();
    o->objectGiven = app.add_option("--object", o->object, "only this surface object of the document")->type_name("NAME");
    addFlag(app, "--outward", o->outward,
                 "reverse the triangles and the normals: normals along -(f_u x f_v) (outward for teapot.bpt, whose "
                 "f_u x f_v points inwards)");
    return [o] { return tessellateCommand(*o); };
}

} // namespace freeform::cli
