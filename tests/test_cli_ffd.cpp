// `freeform lattice`, `freeform ffd`, `freeform eval` on lattices and `freeform bench`: lossless
// identity round trips, affine lattices, reports, fold-overs and every failure leaving no output.

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <Eigen/LU>

#include <filesystem>

#include <freeform/io/mesh_io.h>

#include "support/cli.h"
#include "support/cli_errors.h"

namespace test_cli_ffd {

namespace {
/// The tool in process (support/cli.h); test_cli_eval and test_cli_process start the binary.
freeform::test::ProcessResult cli(const std::string& arguments)
{
    return freeform::test::cliInProcess(arguments);
}
} // namespace
using freeform::test::slurp;
using freeform::test::writeText;
using Json = nlohmann::json;
using freeform::test::requireError;

namespace {

std::string tmp(const std::string& name)
{
    return std::string(FREEFORM_TEST_TMP) + "/ffd_" + name;
}

std::string sample(const std::string& name)
{
    return std::string(FREEFORM_SOURCE_DIR) + "/data/meshes/" + name;
}

bool exists(const std::string& path)
{
    return std::filesystem::exists(path);
}

/// Writes the lattice document for `mesh` and returns its JSON.
Json fitLattice(const std::string& mesh, const std::string& out, const std::string& extra = "")
{
    const auto r = cli("lattice --fit '" + mesh + "' -o '" + out + "' " + extra);
    INFO(r.err);
    REQUIRE(r.status == 0);
    return Json::parse(slurp(out));
}

/// The document with every lattice point mapped by f.
template <typename F>
void mapLattice(Json doc, const std::string& out, F f)
{
    for (auto& p : doc["objects"][0]["points"]) {
        const Eigen::Vector3d q = f(Eigen::Vector3d(p[0].get<double>(), p[1].get<double>(), p[2].get<double>()));
        p = Json::array({q[0], q[1], q[2]});
    }
    writeText(out, doc.dump());
}

} // namespace

TEST_CASE("lattice --fit writes the identity lattice around the mesh", "[cli]")
{
    const std::string mesh = sample("sphere.obj");
    const Json doc = fitLattice(mesh, tmp("fit.json"), "--degree 2,3,1 --margin 0.1");
    const auto& l = doc["objects"][0];
    CHECK(l["type"] == "lattice");
    CHECK(l["degree"] == Json::array({2, 3, 1}));
    CHECK(l["points"].size() == 3 * 4 * 2);
    CHECK(l["outside"] == "clamp");
    // Independent bounding box of the file's vertices.
    const auto m = freeform::readPolygonMesh(mesh);
    const Eigen::Vector3d lo = m.positions.rowwise().minCoeff(), hi = m.positions.rowwise().maxCoeff();
    const double pad = 0.1 * (hi - lo).maxCoeff();
    for (int a = 0; a < 3; ++a) {
        CHECK(l["origin"][a].get<double>() == Approx(lo[a] - pad).epsilon(1e-15));
        CHECK(l["axes"][a][a].get<double>() == Approx(hi[a] - lo[a] + 2 * pad).epsilon(1e-15));
    }
    // The last point is the far corner of the box.
    const auto& last = l["points"][23];
    for (int a = 0; a < 3; ++a) CHECK(last[a].get<double>() == Approx(hi[a] + pad).epsilon(1e-15));
}

TEST_CASE("lattice --fit takes a document's part, in every build", "[cli]")
{
    // data/parts/plate.json: the plate [0, 40] x [0, 30] x [0, 10] with a hole through it, ten
    // vertices. The default margin pushes each side out by 0.05 x 40 = 2.
    const std::string plate = std::string(FREEFORM_SOURCE_DIR) + "/data/parts/plate.json";
    const std::string out = tmp("plate_lattice.json");
    const auto r = cli("lattice --fit '" + plate + "' --degree 1,1,1 -o '" + out + "'");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const Json report = Json::parse(r.out);
    CHECK(report["vertices"] == 10);
    CHECK(report["origin"] == Json::array({-2.0, -2.0, -2.0}));
    CHECK(report["axes"] == Json::array({Json::array({44.0, 0.0, 0.0}), Json::array({0.0, 34.0, 0.0}), Json::array({0.0, 0.0, 14.0})}));
    CHECK(Json::parse(slurp(out))["objects"][0]["points"][7] == Json::array({42.0, 32.0, 12.0}));
    // --object names the part; a name the document lacks is bad input, --object with a mesh bad usage.
    CHECK(cli("lattice --fit '" + plate + "' --object plate -o '" + out + "'").status == 0);
    requireError(cli("lattice --fit '" + plate + "' --object hull -o '" + tmp("none.json") + "'"), 1, "hull");
    CHECK_FALSE(exists(tmp("none.json")));
    requireError(cli("lattice --fit '" + sample("cube.obj") + "' --object plate -o x.json"), 2, "--object");
}

TEST_CASE("identity FFD round trips keep every file byte for byte", "[cli]")
{
    for (const std::string name : {"sphere.obj", "sphere.ply", "sphere.off", "sphere.stl", "cube.obj"}) {
        CAPTURE(name);
        const std::string in = sample(name);
        const std::string ext = name.substr(name.find('.'));
        fitLattice(in, tmp("id.json"));
        const std::string out = tmp("identity" + ext);
        std::filesystem::remove(out);
        const auto r = cli("ffd '" + in + "' --lattice '" + tmp("id.json") + "' -o '" + out + "'");
        INFO(r.err);
        REQUIRE(r.status == 0);
        CHECK(slurp(out) == slurp(in));
        const Json report = Json::parse(r.out);
        CHECK(report["min_det_j"] == 1.0);
        CHECK(report["max_det_j"] == 1.0);
        CHECK(report["fold_count"] == 0);
        CHECK(report["certificate"]["verdict"] == "certified injective");
    }
}

TEST_CASE("identity FFD through glTF keeps positions, faces, UVs and normals", "[cli]")
{
    for (const std::string name : {"sphere.gltf", "sphere.glb"}) {
        CAPTURE(name);
        const std::string in = sample(name);
        fitLattice(in, tmp("idg.json"));
        const std::string out = tmp("identity_" + name);
        const auto r = cli("ffd '" + in + "' --lattice '" + tmp("idg.json") + "' -o '" + out + "'");
        INFO(r.err);
        REQUIRE(r.status == 0);
        const auto a = freeform::readPolygonMesh(in), b = freeform::readPolygonMesh(out);
        CHECK(a.positions == b.positions);
        CHECK(a.normals == b.normals);
        CHECK(a.texcoords == b.texcoords);
        CHECK(a.faceVertices == b.faceVertices);
    }
}

TEST_CASE("an affine lattice moves a mesh by exactly A x + b and keeps the rest of the file", "[cli]")
{
    const std::string in = sample("sphere.obj");
    const Json doc = fitLattice(in, tmp("affine_base.json"));
    Eigen::Matrix3d a = Eigen::Vector3d(2.0, 1.0, 0.5).asDiagonal();
    a(0, 1) = 0.25;
    const Eigen::Vector3d b(1, -2, 3);
    mapLattice(doc, tmp("affine.json"), [&](const Eigen::Vector3d& p) { return Eigen::Vector3d(a * p + b); });
    const std::string out = tmp("affine.obj"), report = tmp("affine_report.json");
    const auto r = cli("ffd '" + in + "' --lattice '" + tmp("affine.json") + "' -o '" + out + "' --report '" + report + "'");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const auto before = freeform::readPolygonMesh(in), after = freeform::readPolygonMesh(out);
    REQUIRE(after.vertexCount() == before.vertexCount());
    for (int i = 0; i < before.vertexCount(); ++i) {
        CHECK((after.positions.col(i) - (a * before.positions.col(i) + b)).norm() < 1e-12);
        if (before.normals.cols() > 0)
            CHECK((after.normals.col(i) - (a.inverse().transpose() * before.normals.col(i)).normalized()).norm() < 1e-9);
    }
    CHECK(after.faceVertices == before.faceVertices);
    CHECK(after.faceStart == before.faceStart);
    CHECK(after.texcoords == before.texcoords);
    // Lines other than v / vn (groups, materials, texture coordinates, comments) are unchanged.
    auto otherLines = [](const std::string& text) {
        std::string kept;
        std::size_t start = 0;
        while (start < text.size()) {
            const std::size_t end = text.find('\n', start);
            const std::string line = text.substr(start, end - start);
            if (line.rfind("v ", 0) != 0 && line.rfind("vn ", 0) != 0) kept += line + "\n";
            if (end == std::string::npos) break;
            start = end + 1;
        }
        return kept;
    };
    CHECK(otherLines(slurp(out)) == otherLines(slurp(in)));
    const Json rep = Json::parse(slurp(report));
    CHECK(rep == Json::parse(r.out));
    CHECK(rep["vertices"] == before.vertexCount());
    CHECK(rep["outside"] == 0);
    CHECK(rep["min_det_j"].get<double>() == Approx(a.determinant()).epsilon(1e-12));
    CHECK(rep["max_det_j"].get<double>() == Approx(a.determinant()).epsilon(1e-12));
    CHECK(rep["fold_count"] == 0);
    CHECK(rep["certificate"]["verdict"] == "certified injective");
    CHECK(rep["certificate"]["degree"] == Json::array({8, 8, 8}));
}

TEST_CASE("ffd output format follows the extension; recomputed normals; folds are reported", "[cli]")
{
    const std::string in = sample("sphere.obj");
    const Json doc = fitLattice(in, tmp("conv_base.json"), "--degree 2,2,2");
    // Crossed: the middle layer in s pushed beyond the far side.
    Json crossed = doc;
    const double sx = doc["objects"][0]["axes"][0][0].get<double>();
    for (int j = 0; j < 9; ++j) crossed["objects"][0]["points"][9 + j][0] = crossed["objects"][0]["points"][9 + j][0].get<double>() + 1.5 * sx;
    writeText(tmp("crossed.json"), crossed.dump());
    const std::string out = tmp("crossed.ply");
    const auto r = cli("ffd '" + in + "' --lattice '" + tmp("crossed.json") + "' -o '" + out + "' --normals recompute");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const Json rep = Json::parse(r.out);
    CHECK(rep["fold_count"].get<int>() > 0);
    CHECK(rep["min_det_j"].get<double>() <= 0);
    CHECK(rep["certificate"]["verdict"] == "folds");
    CHECK(rep["folds"].size() == rep["fold_count"].get<std::size_t>());
    const auto ply = freeform::readPolygonMesh(out);
    CHECK(ply.vertexCount() == freeform::readPolygonMesh(in).vertexCount());
}

TEST_CASE("eval on a lattice prints the point, partial derivatives and det J", "[cli]")
{
    const std::string path = tmp("eval.json");
    // Degree 1, unit cube frame scaled by 2; the far corner (1,1,1) moved by (1, 0, 0).
    writeText(path, R"({"format": "freeform", "version": 1, "objects": [
        {"name": "L", "type": "lattice", "degree": [1, 1, 1], "origin": [0, 0, 0],
         "axes": [[2, 0, 0], [0, 2, 0], [0, 0, 2]],
         "points": [[0,0,0],[0,0,2],[0,2,0],[0,2,2],[2,0,0],[2,0,2],[2,2,0],[3,2,2]]}]})");
    const auto r = cli("eval " + freeform::test::shellQuote(path) + " --object L --at 1,1,1 --derivatives 1");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const Json j = Json::parse(r.out);
    CHECK(j["point"] == Json::array({3.0, 2.0, 2.0}));
    // f = X0 + 2 (s,t,u) + s t u (1,0,0): f_s = (2 + t u, 0, 0), f_t = (s u, 2, 0), f_u = (s t, 0, 2).
    CHECK(j["derivatives"][0]["s"] == Json::array({3.0, 0.0, 0.0}));
    CHECK(j["derivatives"][0]["t"] == Json::array({1.0, 2.0, 0.0}));
    CHECK(j["derivatives"][0]["u"] == Json::array({1.0, 0.0, 2.0}));
    CHECK(j["derivatives"][0]["det"] == 12.0 / 8.0); // det [f_s f_t f_u] / det [S T U]
    const auto mid = Json::parse(cli("eval " + freeform::test::shellQuote(path) + " --object L --at 0.5,0.5,0 --derivatives 1").out);
    CHECK(mid["point"] == Json::array({1.0, 1.0, 0.0}));
    CHECK(mid["derivatives"][0]["det"] == 1.0);
    requireError(cli("eval " + freeform::test::shellQuote(path) + " --object L --at 0.5,0.5,1.5"), 1, "outside the lattice's domain");
    requireError(cli("eval " + freeform::test::shellQuote(path) + " --object L --at 0.5,0.5,0.5 --derivatives 2"), 1, "--derivatives 0 or 1");
    requireError(cli("eval " + freeform::test::shellQuote(path) + " --object L --at 0.5,0.5"), 2, "expected 3");
}

TEST_CASE("bad input gives one error line, exit status 1 and no output file", "[cli]")
{
    const std::string lattice = tmp("bad_lattice.json");
    fitLattice(sample("cube.obj"), lattice);
    struct Case {
        const char* name;
        const char* text;
        const char* fragment;
    };
    const Case cases[] = {
        {"truncated.obj", "v 0 0 0\nv 1 0 0\nv 1 1", "truncated.obj"},
        {"nan.obj", "v 0 0 0\nv nan 0 0\nv 1 1 0\nf 1 2 3\n", "nan.obj"},
        {"range.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 9\n", "range.obj"},
        {"short.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n", "short.ply"},
        {"bad.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0\n", "bad.stl"},
        {"bad.xyz", "0 0 0\n", "bad.xyz"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.name);
        const std::string in = tmp(c.name);
        writeText(in, c.text);
        const std::string out = tmp(std::string("never_") + c.name + ".obj");
        std::filesystem::remove(out);
        requireError(cli("ffd '" + in + "' --lattice '" + lattice + "' -o '" + out + "'"), 1, c.fragment);
        CHECK(!exists(out));
    }
    // A missing mesh, a malformed lattice, a lattice that is not one: no output, an existing
    // output untouched.
    const std::string out = tmp("kept.obj");
    writeText(out, "keep me\n");
    requireError(cli("ffd '" + tmp("missing.obj") + "' --lattice '" + lattice + "' -o '" + out + "'"), 1, "missing.obj");
    writeText(tmp("wrong_count.json"), R"({"format": "freeform", "version": 1, "objects": [
        {"name": "L", "type": "lattice", "degree": [1, 1, 1], "origin": [0, 0, 0],
         "axes": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "points": [[0,0,0]]}]})");
    requireError(cli("ffd '" + sample("cube.obj") + "' --lattice '" + tmp("wrong_count.json") + "' -o '" + out + "'"), 1,
                 "degree needs 8");
    writeText(tmp("curve.json"), R"({"format": "freeform", "version": 1, "objects": [
        {"name": "c", "type": "bezier_curve", "points": [[0,0],[1,1]]}]})");
    requireError(cli("ffd '" + sample("cube.obj") + "' --lattice '" + tmp("curve.json") + "' -o '" + out + "'"), 1,
                 "has no lattice");
    CHECK(slurp(out) == "keep me\n");
    requireError(cli("lattice --fit '" + tmp("nan.obj") + "' -o '" + tmp("never.json") + "'"), 1, "nan.obj");
    CHECK(!exists(tmp("never.json")));
}

TEST_CASE("usage errors exit with status 2", "[cli]")
{
    const std::string lattice = tmp("usage_lattice.json");
    fitLattice(sample("cube.obj"), lattice);
    requireError(cli("ffd '" + sample("cube.obj") + "' --lattice '" + lattice + "' -o x.obj --normals bogus"), 2, "--normals");
    requireError(cli("ffd '" + sample("cube.obj") + "' --lattice '" + lattice + "'"), 2, "--output");
    requireError(cli("lattice --fit '" + sample("cube.obj") + "' --degree 3,3 -o x.json"), 2, "--degree");
    requireError(cli("lattice --fit '" + sample("cube.obj") + "' --degree 0,1,1 -o x.json"), 2, "--degree");
    requireError(cli("bench --vertices 0"), 2, "--vertices");
    const auto help = cli("ffd --help");
    CHECK(help.status == 0);
    for (const char* option : {"--lattice", "--normals", "--report", "--strength", "--threads", "--object"})
        CHECK(help.out.find(option) != std::string::npos);
}

TEST_CASE("bench prints the documented keys", "[cli]")
{
    const auto r = cli("bench --vertices 5000 --degree 2,2,2 --threads 1 --runs 3");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const Json j = Json::parse(r.out);
    CHECK(r.out.rfind(R"({"vertices":5000,"degree":[2,2,2],"threads":1,"median_ms":)", 0) == 0);
    CHECK(j["median_ms"].get<double>() > 0);
    CHECK(j["vertices_per_second"].get<double>() == Approx(5000 / (j["median_ms"].get<double>() / 1000)));
    CHECK(j["scalar"] == "double");
    const auto f = Json::parse(cli("bench --vertices 2000 --float --normals --runs 1").out);
    CHECK(f["scalar"] == "float");
    CHECK(f["normals"] == true);
}

} // namespace test_cli_ffd
