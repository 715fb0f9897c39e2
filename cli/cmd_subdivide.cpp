// freeform subdivide: the limit surface of a control cage (any mesh file) as a triangle mesh.

#include <filesystem>
#include <memory>

#include "command.h"
#include "freeform/io/geometry_data.h"
#include "freeform/io/mesh_io.h"
#include "freeform/subdivision/subdivision_surface.h"

namespace freeform::cli {
namespace {

struct SubdivideOptions {
    std::vector<std::string> positional;
    std::string output, scheme, boundary = "edge_only", lattice, object;
    int level = 8;
    double tolerance = 0;
    const CLI::Option* levelGiven = nullptr;
    const CLI::Option* toleranceGiven = nullptr;
    const CLI::Option* schemeGiven = nullptr;
    const CLI::Option* latticeGiven = nullptr;
    const CLI::Option* objectGiven = nullptr;
};

Json subdivide(const SubdivideOptions& o)
{
    expectPositional(o.positional, 1, "the cage (freeform subdivide CAGE -o OUT)");
    const std::string& input = o.positional[0];
    const std::string& output = o.output;
    if (given(o.levelGiven) && given(o.toleranceGiven)) throw UsageError("give either --level or --tolerance, not both");
    if (given(o.objectGiven) && !given(o.latticeGiven)) throw UsageError("option --object names the lattice of --lattice");
    SubdivisionTessellationOptions options;
    if (given(o.toleranceGiven)) {
        options.tolerance = o.tolerance;
        if (!(options.tolerance > 0)) throw UsageError("option --tolerance: must be positive");
    }
    if (given(o.levelGiven)) {
        options.level = o.level;
        if (options.level < 1 || options.level > options.maxLevel) throw UsageError("option --level: must be in 1..256");
    }
    std::optional<SubdivisionScheme> scheme;
    if (given(o.schemeGiven)) scheme = parseSubdivisionScheme(o.scheme, "--scheme");
    const BoundaryInterpolation boundary = parseBoundaryInterpolation(o.boundary, "--boundary");

    SubdivisionCage cage = readCage(input);
    const SubdivisionScheme chosen = scheme ? *scheme : defaultScheme(cage.mesh);
    std::string latticeName;
    if (given(o.latticeGiven)) {
        const Document doc = readDocument(o.lattice);
        const DocumentObject& object =
            findLattice(doc, given(o.objectGiven) ? std::optional<std::string>(o.object) : std::nullopt,
                        "choose one with --object");
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
    if (options.tolerance > 0) {
        // docs/subdivision.md, "Certified tessellation": the bound holds both ways on every face
        // counted in faces_certified; the other faces (or the whole cage, off the certified path)
        // have only an estimate.
        int certifiedFaces = 0;
        for (char c : report.faceCertified) certifiedFaces += c ? 1 : 0;
        out["certified"] = report.certifiedPath && certifiedFaces == surface.faceCount();
        out["faces_certified"] = certifiedFaces;
        if (report.certifiedPath) {
            out["error_bound"] = report.errorBound;
            out["cells"] = report.cells;
            out["leaves"] = report.leaves;
        }
    }
    return out;
}

} // namespace

Action defineSubdivide(CLI::App& app)
{
    auto o = std::make_shared<SubdivideOptions>();
    app.footer("Reads the control cage CAGE (any mesh format: .obj .ply .stl .off .gltf .glb; OBJ crease\n"
               "tags \"t crease 2/1 V0 V1 S\" and \"t corner 1/1 V S\" with 0-based indices are honoured),\n"
               "evaluates its limit surface with OpenSubdiv and writes it as a triangle mesh with analytic\n"
               "unit normals. Points on a cage edge are shared by its two faces, so a closed cage gives a\n"
               "closed mesh. docs/subdivision.md explains the schemes and the options.\n"
               "\n"
               "Output: {\"input\", \"output\", \"scheme\", \"boundary\", [\"lattice\"], \"cage_vertices\",\n"
               "\"cage_faces\", \"creases\", \"corners\", \"segments\": [min, max], \"vertices\", \"triangles\"}, and with\n"
               "--tolerance \"certified\", \"faces_certified\" (and on the certified path \"error_bound\", \"cells\",\n"
               "\"leaves\").\n"
               "Exit status: 0 ok, 1 bad input (an unusable cage: one error line naming the face, edge or\n"
               "vertex; no output file), 2 bad usage.");
    addPositionals(app, "CAGE", o->positional, "the control cage (a mesh file)");
    app.add_option("-o,--output", o->output, "the mesh to write, format from the extension (temporary file, then rename)")
        ->type_name("FILE")
        ->required();
    o->schemeGiven = app.add_option("--scheme", o->scheme,
                                    "catmark (Catmull-Clark, any polygons) or loop (triangles only); default: loop "
                                    "when every face is a triangle, else catmark")
                         ->type_name("S")
                         ->check(CLI::IsMember({"catmark", "loop"}));
    o->levelGiven = addNumber(app, "--level", o->level, "N segments along every cage edge (1..256)")
                        ->type_name("N")
                        ->capture_default_str();
    o->toleranceGiven = addNumber(app, "--tolerance", o->tolerance,
                                  "adaptive to distance E, certified on every Catmull-Clark and Loop cage (Bezier cells and "
                                  "1-ring hulls, docs/subdivision.md; a face whose cells stay above E at the deepest "
                                  "level is reported in faces_certified) (not with --level)")
                            ->type_name("E");
    app.add_option("--boundary", o->boundary, "boundary interpolation: edge_only, edge_and_corner, or none (boundary faces dropped)")
        ->type_name("B")
        ->check(CLI::IsMember({"edge_only", "edge_and_corner", "none"}))
        ->capture_default_str();
    o->latticeGiven = app.add_option("--lattice", o->lattice,
                                     "deform the cage through the lattice of the document F first (the smooth limit "
                                     "of the deformed cage; equal to deforming the limit surface only for an affine "
                                     "lattice)")
                          ->type_name("F");
    o->objectGiven = app.add_option("--object", o->object, "the lattice object of F when it has several")->type_name("NAME");
    return [o] { return subdivide(*o); };
}

} // namespace freeform::cli
