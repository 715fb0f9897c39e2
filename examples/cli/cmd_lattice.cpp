// freeform lattice: write the identity lattice around a mesh.

#include <array>
#include <cmath>

#include "command.h"
#include "freeform/io/geometry_data.h"
#include "freeform/io/mesh_io.h"
#include "freeform/volume/lattice.h"

namespace freeform::cli {

/// "L,M,N" into three degrees 1..kMaxDegree (shared with `freeform bench`).
std::array<int, 3> parseDegrees(const std::string& text, const std::string& option)
{
    const std::vector<double> v = parseNumberList(text, option, 3);
    std::array<int, 3> d{};
    for (int a = 0; a < 3; ++a) {
        const double x = v[static_cast<std::size_t>(a)];
        if (x != std::floor(x) || x < 1 || x > kMaxDegree)
            throw UsageError("option " + option + ": degrees must be integers in 1.." + std::to_string(kMaxDegree) +
                             ", found \"" + text + "\"");
        d[static_cast<std::size_t>(a)] = static_cast<int>(x);
    }
    return d;
}

namespace {

int runLattice(const std::vector<std::string>& argv)
{
    const Args args(argv, {"fit", "degree", "margin", "outside", "name", "output"}, {});
    args.expectPositional(0, "");
    const std::string meshPath = args.required("fit");
    const std::string output = args.required("output");
    const std::array<int, 3> degree = parseDegrees(args.get("degree").value_or("3,3,3"), "--degree");
    double margin = 0.05;
    if (const auto m = args.get("margin")) {
        margin = parseNumber(*m, "--margin");
        if (margin < 0) throw UsageError("option --margin: must not be negative");
    }
    OutsidePolicy outside = OutsidePolicy::Clamp;
    if (const auto o = args.get("outside")) {
        if (*o != "keep" && *o != "clamp" && *o != "extrapolate")
            throw UsageError("option --outside: \"" + *o + "\" is not one of keep, clamp, extrapolate");
        outside = parseOutsidePolicy(*o, "--outside");
    }
    const std::string name = args.get("name").value_or("lattice");
    if (name.empty()) throw UsageError("option --name: the name must not be empty");

    const PolygonMesh mesh = readPolygonMesh(meshPath);
    const Lattice lattice = Lattice::fit(mesh.positions, degree, margin, outside);
    Document doc;
    doc.objects.push_back({name, latticeToData(lattice), ""});
    writeDocument(doc, output);

    Json out;
    out["output"] = output;
    out["object"] = name;
    out["vertices"] = mesh.vertexCount();
    out["degree"] = Json::array({degree[0], degree[1], degree[2]});
    out["origin"] = pointJson(lattice.origin().data(), 3);
    Json axes = Json::array();
    for (int a = 0; a < 3; ++a) axes.push_back(pointJson(lattice.axes().col(a).data(), 3));
    out["axes"] = std::move(axes);
    printJson(out);
    return 0;
}

const RegisterCommand reg({"lattice", "write the identity FFD lattice around a mesh",
                           "usage: freeform lattice --fit MESH [--degree L,M,N] [--margin F] [--outside POLICY]\n"
                           "                        [--name NAME] -o LATTICE.json\n"
                           "\n"
                           "Writes a document with one lattice object: the identity (rest) lattice of degrees\n"
                           "(L, M, N) around the axis-aligned bounding box of the mesh's vertices.\n"
                           "\n"
                           "  --fit MESH        the mesh (.obj .ply .stl .off .gltf .glb)\n"
                           "  --degree L,M,N    degrees in s, t, u (default 3,3,3: 4 x 4 x 4 control points)\n"
                           "  --margin F        each side of the box is pushed out by F times its largest\n"
                           "                    extent (default 0.05)\n"
                           "  --outside POLICY  keep | clamp | extrapolate, for points outside the lattice\n"
                           "                    (default clamp; see docs/ffd.md)\n"
                           "  --name NAME       the object's name (default \"lattice\")\n"
                           "  -o, --output FILE the document to write (atomically)\n"
                           "\n"
                           "Prints {\"output\", \"object\", \"vertices\", \"degree\", \"origin\", \"axes\"}.\n"
                           "Exit status: 0 ok, 1 bad input (mesh file), 2 bad usage.\n",
                           runLattice});

} // namespace
} // namespace freeform::cli
