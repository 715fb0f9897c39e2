// freeform subdivide: the limit surface of a control cage (any mesh file) as a triangle mesh.

#include <filesystem>

#include "command.h"
#include "freeform/io/geometry_data.h"
#include "freeform/io/mesh_io.h"
#include "freeform/subdivision/subdivision_surface.h"

namespace freeform::cli {
namespace {

int runSubdivide(const std::vector<std::string>& argv)
{
    const Args args(argv, {"output", "scheme", "level", "tolerance", "lattice", "object", "boundary"}, {});
    args.expectPositional(1, "the cage (freeform subdivide CAGE -o OUT)");
    const std::string input = args.positional()[0];
    const std::string output = args.required("output");
    if (args.has("level") && args.has("tolerance")) throw UsageError("give either --level or --tolerance, not both");
    if (args.has("object") && !args.has("lattice")) throw UsageError("option --object names the lattice of --lattice");
    SubdivisionTessellationOptions options;
    if (const auto t = args.get("tolerance")) {
        options.tolerance = parseNumber(*t, "--tolerance");
        if (!(options.tolerance > 0)) throw UsageError("option --tolerance: must be positive");
    }
    if (const auto l = args.get("level")) {
        options.level = parseInteger(*l, "--level");
        if (options.level < 1 || options.level > options.maxLevel) throw UsageError("option --level: must be in 1..256");
    }
    std::optional<SubdivisionScheme> scheme;
    if (const auto s = args.get("scheme")) {
        if (*s != "catmark" && *s != "loop") throw UsageError("option --scheme: \"" + *s + "\" is not one of catmark, loop");
        scheme = parseSubdivisionScheme(*s, "--scheme");
    }
    BoundaryInterpolation boundary = BoundaryInterpolation::EdgeOnly;
    if (const auto b = args.get("boundary")) {
        if (*b != "edge_only" && *b != "edge_and_corner" && *b != "none")
            throw UsageError("option --boundary: \"" + *b + "\" is not one of edge_only, edge_and_corner, none");
        boundary = parseBoundaryInterpolation(*b, "--boundary");
    }

    SubdivisionCage cage = readCage(input);
    const SubdivisionScheme chosen = scheme ? *scheme : defaultScheme(cage.mesh);
    std::string latticeName;
    if (const auto latticePath = args.get("lattice")) {
        const Document doc = readDocument(*latticePath);
        const DocumentObject& object = findLattice(doc, args.get("object"));
        latticeName = object.name;
        cage = deformCage(cage, latticeFromData(std::get<LatticeData>(object.data)));
    }
    const SubdivisionSurface surface = [&] {
        try {
            return SubdivisionSurface(std::move(cage), chosen, boundary);
        } catch (const Error& e) {
            throw Error(input + ": " + e.what());
        }
    }();
    SubdivisionTessellationReport report;
    const PolygonMesh mesh = surface.tessellate(options, &report);
    writePolygonMesh(mesh, output);

    int minRate = 0, maxRate = 0;
    for (int r : report.rates) {
        if (r == 0) continue;
        minRate = minRate == 0 ? r : std::min(minRate, r);
        maxRate = std::max(maxRate, r);
    }
    Json out;
    out["input"] = input;
    out["output"] = output;
    out["scheme"] = toString(chosen);
    out["boundary"] = toString(boundary);
    if (!latticeName.empty()) out["lattice"] = latticeName;
    out["cage_vertices"] = surface.cage().mesh.vertexCount();
    out["cage_faces"] = surface.faceCount();
    out["creases"] = surface.cage().creases.size();
    out["corners"] = surface.cage().corners.size();
    out["segments"] = Json::array({minRate, maxRate});
    out["vertices"] = mesh.vertexCount();
    out["triangles"] = mesh.faceCount();
    printJson(out);
    return 0;
}

const RegisterCommand reg({"subdivide", "the limit surface of a control cage (Catmull-Clark or Loop) as a triangle mesh",
                           "usage: freeform subdivide CAGE -o OUT [--scheme catmark|loop] [--level N | --tolerance E]\n"
                           "                          [--boundary B] [--lattice LAT.json [--object NAME]]\n"
                           "\n"
                           "Reads the control cage CAGE (any mesh format: .obj .ply .stl .off .gltf .glb; OBJ crease\n"
                           "tags \"t crease 2/1 V0 V1 S\" and \"t corner 1/1 V S\" with 0-based indices are honoured),\n"
                           "evaluates its limit surface with OpenSubdiv and writes it as a triangle mesh with analytic\n"
                           "unit normals. Points on a cage edge are shared by its two faces, so a closed cage gives a\n"
                           "closed mesh. docs/subdivision.md explains the schemes and the options.\n"
                           "\n"
                           "  -o, --output F    the mesh to write, format from the extension (temporary file, then rename)\n"
                           "  --scheme S        catmark (Catmull-Clark, any polygons) or loop (triangles only);\n"
                           "                    default: loop when every face is a triangle, else catmark\n"
                           "  --level N         N segments along every cage edge (default 8; 1..256)\n"
                           "  --tolerance E     adaptive segments per face: certified (Bezier bound) on regular faces,\n"
                           "                    estimated from sampled second derivatives elsewhere\n"
                           "  --boundary B      edge_only (default), edge_and_corner or none (boundary faces dropped)\n"
                           "  --lattice F       deform the cage through the lattice of the document F first (the\n"
                           "                    smooth limit of the deformed cage; equal to deforming the limit\n"
                           "                    surface only for an affine lattice)\n"
                           "  --object NAME     the lattice object of F when it has several\n"
                           "\n"
                           "Output: {\"input\", \"output\", \"scheme\", \"boundary\", [\"lattice\"], \"cage_vertices\",\n"
                           "\"cage_faces\", \"creases\", \"corners\", \"segments\": [min, max], \"vertices\", \"triangles\"}.\n"
                           "Exit status: 0 ok, 1 bad input (an unusable cage: one error line naming the face, edge or\n"
                           "vertex; no output file), 2 bad usage.\n",
                           runSubdivide});

} // namespace
} // namespace freeform::cli
