// freeform ffd: deform a mesh file through a lattice, losslessly (only positions, normals and
// tangents change; everything else in the file is written back as read).

#include <algorithm>

#include "command.h"
#include "freeform/io/mesh_io.h"
#include "freeform/volume/deform.h"

namespace freeform::cli {
namespace {

const DocumentObject& findLattice(const Document& doc, const std::optional<std::string>& name)
{
    if (name) {
        const DocumentObject& o = doc.object(*name);
        if (!std::holds_alternative<LatticeData>(o.data))
            throw Error(doc.source + ": object \"" + *name + "\" is a " + objectType(o.data) + ", not a lattice");
        return o;
    }
    const DocumentObject* found = nullptr;
    for (const DocumentObject& o : doc.objects) {
        if (!std::holds_alternative<LatticeData>(o.data)) continue;
        if (found) throw Error(doc.source + ": has several lattices; choose one with --object");
        found = &o;
    }
    if (!found) throw Error(doc.source + ": has no lattice object");
    return *found;
}

bool isIdentity(const Eigen::Matrix3d& j)
{
    return j == Eigen::Matrix3d::Identity();
}

int runFfd(const std::vector<std::string>& argv)
{
    const Args args(argv, {"lattice", "object", "output", "normals", "strength", "threads", "report"}, {});
    args.expectPositional(1, "the mesh file (freeform ffd MESH --lattice LATTICE.json -o OUT)");
    const std::string meshPath = args.positional()[0];
    const std::string latticePath = args.required("lattice");
    const std::string output = args.required("output");
    NormalMode normals = NormalMode::Jacobian;
    if (const auto n = args.get("normals")) {
        if (*n != "jacobian" && *n != "recompute")
            throw UsageError("option --normals: \"" + *n + "\" is not one of jacobian, recompute");
        normals = parseNormalMode(*n, "--normals");
    }
    DeformOptions options;
    if (const auto s = args.get("strength")) options.strength = parseNumber(*s, "--strength");
    if (const auto t = args.get("threads")) {
        options.threads = parseInteger(*t, "--threads");
        if (options.threads < 0) throw UsageError("option --threads: must not be negative");
    }
    const auto reportPath = args.get("report");

    const Document doc = readDocument(latticePath);
    const DocumentObject& object = findLattice(doc, args.get("object"));
    const Lattice lattice = Lattice::fromData(std::get<LatticeData>(object.data));
    MeshFile file = MeshFile::read(meshPath);

    // Positions, with the Jacobian of every position for the normals and tangents anchored there.
    auto& positions = file.positions();
    const Eigen::Index count = positions.cols();
    const FfdBinding<double> binding(lattice, positions);
    Eigen::Matrix<double, 3, Eigen::Dynamic> moved(3, count);
    Eigen::Matrix<double, 9, Eigen::Dynamic> jacobians(9, count);
    FfdOutputs<double> out;
    out.positions = moved.data();
    out.jacobians = jacobians.data();
    DeformReport report;
    binding.deform(lattice, out, options, &report);
    positions = moved;
    auto jacobianAt = [&](int v) { return Eigen::Matrix3d(Eigen::Map<const Eigen::Matrix3d>(jacobians.col(v).data())); };

    auto& n = file.normals();
    const auto& normalAnchors = file.normalAnchors();
    if (n.cols() > 0) {
        if (normals == NormalMode::Recompute) {
            const Eigen::Matrix<double, 3, Eigen::Dynamic> fresh = areaWeightedNormals(file.toPolygonMesh());
            for (Eigen::Index i = 0; i < n.cols(); ++i) {
                const int a = normalAnchors[static_cast<std::size_t>(i)];
                if (a >= 0 && fresh.col(a).squaredNorm() > 0) n.col(i) = fresh.col(a);
            }
        } else {
            for (Eigen::Index i = 0; i < n.cols(); ++i) {
                const int a = normalAnchors[static_cast<std::size_t>(i)];
                if (a < 0) continue;
                const Eigen::Matrix3d j = jacobianAt(a);
                if (!isIdentity(j)) n.col(i) = transformNormal(j, n.col(i)); // untouched where the map is I
            }
        }
    }
    auto& tangents = file.tangents();
    const auto& tangentAnchors = file.tangentAnchors();
    for (Eigen::Index i = 0; i < tangents.cols(); ++i) {
        const int a = tangentAnchors[static_cast<std::size_t>(i)];
        if (a < 0) continue;
        const Eigen::Matrix3d j = jacobianAt(a);
        if (!isIdentity(j)) tangents.col(i).head<3>() = transformTangent(j, tangents.col(i).head<3>()); // w kept
    }

    // The certificate for the lattice box; a vertex inside the box with det J <= 0 decides "folds".
    const Certificate cert = certify(lattice, options.strength);
    const auto& outsideList = binding.outsideVertices();
    std::size_t insideFolds = 0;
    for (int v : report.folds)
        if (!std::binary_search(outsideList.begin(), outsideList.end(), v)) ++insideFolds;
    const Verdict verdict = insideFolds > 0 ? Verdict::Folds : cert.verdict;

    Json j;
    j["input"] = meshPath;
    j["output"] = output;
    j["lattice"] = object.name;
    j["vertices"] = report.vertices;
    j["outside"] = report.outside;
    j["min_det_j"] = report.minDetJ;
    j["max_det_j"] = report.maxDetJ;
    j["fold_count"] = report.foldCount;
    Json folds = Json::array();
    for (std::size_t i = 0; i < std::min<std::size_t>(report.folds.size(), 1000); ++i) folds.push_back(report.folds[i]);
    j["folds"] = std::move(folds); // the first 1000 fold-over vertices (0-based, file order)
    Json c;
    c["verdict"] = toString(verdict);
    const auto degree = jacobianPolynomial(lattice, options.strength).degree;
    c["degree"] = Json::array({degree[0], degree[1], degree[2]});
    c["min_coefficient"] = cert.minCoefficient;
    c["max_coefficient"] = cert.maxCoefficient;
    if (cert.verdict == Verdict::Folds) c["witness"] = pointJson(cert.witness.data(), 3);
    j["certificate"] = std::move(c);

    file.write(output);
    if (reportPath) writeFileAtomically(*reportPath, j.dump(2) + "\n");
    printJson(j);
    return 0;
}

const RegisterCommand reg({"ffd", "deform a mesh file through a lattice (free-form deformation)",
                           "usage: freeform ffd MESH --lattice LATTICE.json -o OUT [--object NAME]\n"
                           "                    [--normals jacobian|recompute] [--strength W] [--threads T]\n"
                           "                    [--report REPORT.json]\n"
                           "\n"
                           "Moves every vertex of MESH through the lattice (p' = p + W sum B (P - R)) and writes\n"
                           "OUT in the format of its extension. Written back in the same format, the file keeps\n"
                           "everything but positions, normals and tangents as it was (faces, texture\n"
                           "coordinates, groups, materials, colours, vertex order). See docs/ffd.md.\n"
                           "\n"
                           "  --lattice FILE    a document with the lattice object\n"
                           "  --object NAME     which lattice, when the document has several\n"
                           "  -o, --output OUT  the deformed mesh (.obj .ply .stl .off .gltf .glb), atomically\n"
                           "  --normals MODE    jacobian: cof(J) n renormalised (default); recompute:\n"
                           "                    area-weighted vertex normals of the deformed mesh\n"
                           "  --strength W      scales the deformation (default 1)\n"
                           "  --threads T       worker threads (default 0: all cores)\n"
                           "  --report FILE     also write the report (below) to FILE\n"
                           "\n"
                           "Prints the report: {\"input\", \"output\", \"lattice\", \"vertices\", \"outside\",\n"
                           "\"min_det_j\", \"max_det_j\", \"fold_count\", \"folds\" (first 1000 vertex indices with\n"
                           "det J <= 0), \"certificate\": {\"verdict\": \"certified injective\" | \"folds\" |\n"
                           "\"undecided\", \"degree\", \"min_coefficient\", \"max_coefficient\"[, \"witness\"]}}.\n"
                           "Exit status: 0 ok, 1 bad input (mesh, lattice), 2 bad usage. On error no output\n"
                           "file is written.\n",
                           runFfd});

} // namespace
} // namespace freeform::cli
