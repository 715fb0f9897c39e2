// freeform lattice: write the identity lattice around a mesh.

#include <array>
#include <cmath>
#include <memory>

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

struct LatticeOptions {
    std::string fit, degree = "3,3,3", outside = "clamp", name = "lattice", output, object;
    double margin = 0.05;
    const CLI::Option* objectGiven = nullptr;
};

Json lattice(const LatticeOptions& o)
{
    const std::string& meshPath = o.fit;
    const std::string& output = o.output;
    const std::array<int, 3> degree = parseDegrees(o.degree, "--degree");
    const double margin = o.margin;
    if (margin < 0) throw UsageError("option --margin: must not be negative");
    const OutsidePolicy outside = parseOutsidePolicy(o.outside, "--outside");
    const std::string& name = o.name;
    if (name.empty()) throw UsageError("option --name: the name must not be empty");

    // A part's box is the box of its faces' control nets and vertices (it holds the part). A
    // document (.json) is fitted around its part, as `info` reads it.
    const bool document = lowerExtension(meshPath) == ".json";
    if (given(o.objectGiven) && !document) throw UsageError("option --object applies to a document's part (.json)");
    Lattice::Points positions;
    long long vertices = 0;
    if (isPartFileName(meshPath) || document) {
        positions = partBoxCorners(meshPath, given(o.objectGiven) ? std::optional<std::string>(o.object) : std::nullopt, vertices);
    } else {
        PolygonMesh mesh = readPolygonMesh(meshPath);
        vertices = mesh.vertexCount();
        positions = std::move(mesh.positions);
    }
    const Lattice fitted = Lattice::fit(positions, degree, margin, outside);
    Document doc;
    doc.objects.push_back({name, latticeToData(fitted), ""});
    writeDocument(doc, output);

    Json out;
    out["output"] = output;
    out["object"] = name;
    out["vertices"] = vertices;
    out["degree"] = Json::array({degree[0], degree[1], degree[2]});
    out["origin"] = pointJson(fitted.origin().data(), 3);
    Json axes = Json::array();
    for (int a = 0; a < 3; ++a) axes.push_back(pointJson(fitted.axes().col(a).data(), 3));
    out["axes"] = std::move(axes);
    return out;
}

} // namespace

Action defineLattice(CLI::App& app)
{
    auto o = std::make_shared<LatticeOptions>();
    app.footer("Writes a document with one lattice object: the identity (rest) lattice of degrees\n"
               "(L, M, N) around the axis-aligned bounding box of the mesh's vertices (of a part's\n"
               "faces and vertices for a STEP or IGES part, or a document's part).\n"
               "\n"
               "Prints {\"output\", \"object\", \"vertices\", \"degree\", \"origin\", \"axes\"}.\n"
               "Exit status: 0 ok, 1 bad input (mesh file), 2 bad usage.");
    app.add_option("--fit", o->fit, "the mesh (.obj .ply .stl .off .gltf .glb) or part (.step .stp .iges .igs .brep, or a document's part: .json)")
        ->type_name("MESH")
        ->required();
    o->objectGiven = app.add_option("--object", o->object, "the document's part to fit (default: its only part)")->type_name("NAME");
    app.add_option("--degree", o->degree, "degrees in s, t, u (3,3,3: 4 x 4 x 4 control points)")
        ->type_name("L,M,N")
        ->capture_default_str();
    addNumber(app, "--margin", o->margin, "each side of the box is pushed out by F times its largest extent")
        ->type_name("F")
        ->capture_default_str();
    app.add_option("--outside", o->outside, "for points outside the lattice (see docs/ffd.md)")
        ->type_name("POLICY")
        ->check(CLI::IsMember({"keep", "clamp", "extrapolate"}))
        ->capture_default_str();
    app.add_option("--name", o->name, "the object's name")->type_name("NAME")->capture_default_str();
    app.add_option("-o,--output", o->output, "the document to write (atomically)")->type_name("FILE")->required();
    return [o] { return lattice(*o); };
}

} // namespace freeform::cli
