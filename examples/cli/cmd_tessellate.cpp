// freeform tessellate: surfaces of a document (or a .bpt patch file) to a triangle mesh in OBJ.

#include <filesystem>

#include "command.h"
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

int runTessellate(const std::vector<std::string>& argv)
{
    const Args args(argv, {"output", "tolerance", "segments", "object", "max-triangles", "refinement", "measure"}, {"outward"});
    args.expectPositional(1, "the input (freeform tessellate IN.json|IN.bpt -o OUT.obj)");
    const std::string input = args.positional()[0];
    const std::string output = args.required("output");
    if (!hasExtension(output, ".obj")) throw UsageError("option -o: the output must be an .obj file");
    if (args.has("tolerance") && args.has("segments")) throw UsageError("give either --tolerance or --segments, not both");
    TessellationOptions options;
    if (const auto t = args.get("tolerance")) {
        options.tolerance = parseNumber(*t, "--tolerance");
        if (!(options.tolerance > 0)) throw UsageError("option --tolerance: must be positive");
    } else {
        int n = 8;
        if (const auto s = args.get("segments")) n = parseInteger(*s, "--segments");
        if (n < 1 || n > 4096) throw UsageError("option --segments: must be in 1..4096");
        options.segmentsU = options.segmentsV = n;
    }
    options.flipNormals = args.has("outward");
    if (const auto m = args.get("max-triangles")) {
        options.maxTriangles = parseInteger(*m, "--max-triangles");
        if (options.maxTriangles < 0) throw UsageError("option --max-triangles: must be 0 (no limit) or positive");
    }
    if (const auto r = args.get("refinement")) {
        if (*r == "patch-grid") options.refinement = TessellationRefinement::PatchGrid;
        else if (*r != "local") throw UsageError("option --refinement: local or patch-grid");
    }
    if (const auto m = args.get("measure")) {
        if (*m == "geometric") options.measure = TessellationMeasure::Geometric;
        else if (*m != "parametric") throw UsageError("option --measure: parametric or geometric");
    }
    options.sampleDeviation = true;

    PatchComplex complex;
    if (hasExtension(input, ".bpt")) {
        if (args.has("object")) throw UsageError("option --object applies to documents, not .bpt files");
        complex = readBpt(input);
    } else {
        const Document doc = readDocument(input);
        if (const auto name = args.get("object")) {
            complex = surfacePatches(doc, doc.object(*name));
        } else {
            for (const DocumentObject& o : doc.objects) {
                if (!isSurfaceObject(o)) continue;
                PatchComplex part = surfacePatches(doc, o);
                complex.patches.insert(complex.patches.end(), part.patches.begin(), part.patches.end());
            }
            if (complex.patches.empty())
                throw Error(doc.source + ": the document has no surface objects (bezier_surface, deboor_surface)");
        }
    }
    TessellationReport report;
    const PolygonMesh mesh = tessellate(complex, options, &report);
    writePolygonMesh(mesh, output);
    Json out;
    out["output"] = output;
    out["patches"] = complex.patches.size();
    out["vertices"] = mesh.vertexCount();
    out["triangles"] = mesh.faceCount();
    out["error_bound"] = report.errorBound;
    out["measured_parametric"] = report.measuredParametric;
    out["measured_geometric"] = report.measuredGeometric;
    printJson(out);
    return 0;
}

const RegisterCommand reg({"tessellate", "surfaces (document or .bpt) to a triangle mesh (OBJ with normals and uv)",
                           "usage: freeform tessellate IN.json|IN.bpt -o OUT.obj [--tolerance E | --segments N]\n"
                           "                          [--object NAME] [--outward] [--max-triangles N]\n"
                           "                          [--refinement local|patch-grid] [--measure parametric|geometric]\n"
                           "\n"
                           "Tessellates every bezier_surface and deboor_surface of the document (or the one named by\n"
                           "--object), or every patch of a .bpt file, into one triangle mesh. Patches that share a side\n"
                           "(identical control points) share its vertices, so a closed complex gives a closed mesh.\n"
                           "The OBJ has v, vt (u, v of the patch), vn (the surface's unit normal) and f v/vt/vn.\n"
                           "\n"
                           "  -o, --output F    the .obj file to write (written to a temporary file, then renamed)\n"
                           "  --tolerance E     adaptive: every surface point lies within E of the mesh and every\n"
                           "                    mesh point within E of the surface (certified bound from the\n"
                           "                    control nets, docs/surfaces.md)\n"
                           "  --refinement R    local (default): each patch refined where its curvature needs it;\n"
                           "                    patch-grid: one grid per patch from the bound of its whole net\n"
                           "  --measure M       parametric (default): the bound holds both ways, as above;\n"
                           "                    geometric: only every mesh point lies within E of the surface\n"
                           "                    (fewer triangles: the tangential part of the error is not counted)\n"
                           "  --max-triangles N refuse (exit 1, with the estimate) a mesh of more than N triangles\n"
                           "                    (default 10000000; 0: no limit)\n"
                           "  --segments N      uniform: N x N cells per patch (default 8; 1..4096)\n"
                           "  --object NAME     only this surface object of the document\n"
                           "  --outward         reverse the triangles and the normals: normals along -(f_u x f_v)\n"
                           "                    (outward for teapot.bpt, whose f_u x f_v points inwards)\n"
                           "\n"
                           "Output: {\"output\": F, \"patches\": P, \"vertices\": V, \"triangles\": T, \"error_bound\": B,\n"
                           "\"measured_parametric\": MP, \"measured_geometric\": MG} with B the largest certified distance\n"
                           "bound over the patches, MP and MG the largest deviations found at 12 points per triangle\n"
                           "(triangle point to the surface point with the same (u, v); to its foot point).\n"
                           "Exit status: 0 ok, 1 bad input, 2 bad usage.\n",
                           runTessellate});

} // namespace
} // namespace freeform::cli
