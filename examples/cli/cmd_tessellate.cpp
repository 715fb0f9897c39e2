// freeform tessellate: surfaces of a document (or a .bpt patch file) to a triangle mesh in OBJ.

#include <filesystem>

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

int runTessellate(const std::vector<std::string>& argv)
{
    const Args args(argv, {"output", "tolerance", "segments", "object"}, {"outward"});
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
    printJson(out);
    return 0;
}

const RegisterCommand reg({"tessellate", "surfaces (document or .bpt) to a triangle mesh (OBJ with normals and uv)",
                           "usage: freeform tessellate IN.json|IN.bpt -o OUT.obj [--tolerance E | --segments N]\n"
                           "                          [--object NAME] [--outward]\n"
                           "\n"
                           "Tessellates every bezier_surface and deboor_surface of the document (or the one named by\n"
                           "--object), or every patch of a .bpt file, into one triangle mesh. Patches that share a side\n"
                           "(identical control points) share its vertices, so a closed complex gives a closed mesh.\n"
                           "The OBJ has v, vt (u, v of the patch), vn (the surface's unit normal) and f v/vt/vn.\n"
                           "\n"
                           "  -o, --output F    the .obj file to write (written to a temporary file, then renamed)\n"
                           "  --tolerance E     adaptive: every surface point lies within E of the mesh (certified\n"
                           "                    bound from the control net, docs/surfaces.md)\n"
                           "  --segments N      uniform: N x N cells per patch (default 8; 1..4096)\n"
                           "  --object NAME     only this surface object of the document\n"
                           "  --outward         reverse the triangles and the normals: normals along -(f_u x f_v)\n"
                           "                    (outward for teapot.bpt, whose f_u x f_v points inwards)\n"
                           "\n"
                           "Output: {\"output\": F, \"patches\": P, \"vertices\": V, \"triangles\": T, \"error_bound\": B}\n"
                           "with B the largest certified distance bound over the patches.\n"
                           "Exit status: 0 ok, 1 bad input, 2 bad usage.\n",
                           runTessellate});

} // namespace
} // namespace freeform::cli
