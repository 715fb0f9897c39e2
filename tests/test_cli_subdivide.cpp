// The command-line contract for subdivision surfaces: `subdivide` (cage file to limit mesh, read
// back by `info` for its topology), `eval` of a subdivision_surface object, and the errors.

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "support/cli.h"
#include "support/cli_errors.h"

namespace test_cli_subdivide {

namespace {
/// The tool in process (support/cli.h); test_cli_eval and test_cli_process start the binary.
freeform::test::ProcessResult cli(const std::string& arguments)
{
    return freeform::test::cliInProcess(arguments);
}
} // namespace
using freeform::test::writeText;
using Json = nlohmann::json;
using freeform::test::requireError;

namespace {

std::string tmp(const std::string& name) { return std::string(FREEFORM_TEST_TMP) + "/" + name; }
std::string cage(const std::string& name) { return std::string(FREEFORM_SOURCE_DIR) + "/data/cages/" + name; }

Json info(const std::string& mesh)
{
    const auto r = cli("info '" + mesh + "'");
    INFO(r.err);
    REQUIRE(r.status == 0);
    return Json::parse(r.out);
}

} // namespace

TEST_CASE("subdivide: cube cage -> closed genus 0, torus cage -> genus 1", "[cli]")
{
    const std::string cube = tmp("sub_cube.ply");
    std::filesystem::remove(cube);
    auto r = cli("subdivide '" + cage("cube.obj") + "' -o '" + cube + "' --level 4");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const Json j = Json::parse(r.out);
    CHECK(j["scheme"] == "catmark");
    CHECK(j["cage_faces"] == 6);
    CHECK(j["vertices"] == 8 + 12 * 3 + 6 * 9);
    CHECK(j["triangles"] == 6 * 4 * 4 * 2);
    const Json ci = info(cube);
    CHECK(ci["closed"] == true);
    CHECK(ci["euler"] == 2);
    CHECK(ci["genus"] == 0);

    const std::string torus = tmp("sub_torus.obj");
    r = cli("subdivide '" + cage("torus.obj") + "' -o '" + torus + "' --tolerance 1e-3");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const Json ti = info(torus);
    CHECK(ti["closed"] == true);
    CHECK(ti["genus"] == 1);
    // The certified path (docs/subdivision.md): every face of the torus cage is certified.
    const Json tj = Json::parse(r.out);
    CHECK(tj["certified"] == true);
    CHECK(tj["faces_certified"] == 32);
    CHECK(tj["error_bound"].get<double>() <= 1e-3);
    CHECK(tj["error_bound"].get<double>() > 0);
    CHECK(tj["leaves"].get<long long>() >= tj["cells"].get<long long>());
    // freeform tessellate on a subdivision_surface object takes the same certified path.
    const std::string tessellated = tmp("tess_torus.obj");
    r = cli("tessellate '" + cage("torus.json") + "' --object torus -o '" + tessellated + "' --tolerance 1e-3");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const Json tt = Json::parse(r.out);
    CHECK(tt["certified"] == true);
    CHECK(tt["error_bound"].get<double>() <= 1e-3);
    CHECK(tt["triangles"] == tj["triangles"]);
    CHECK(info(tessellated)["genus"] == 1);

    // Triangles default to Loop.
    const std::string octa = tmp("sub_octa.off");
    r = cli("subdivide '" + cage("octahedron.obj") + "' -o '" + octa + "' --level 2");
    REQUIRE(r.status == 0);
    CHECK(Json::parse(r.out)["scheme"] == "loop");
    CHECK(info(octa)["genus"] == 0);
}

TEST_CASE("subdivide --tolerance: holes, boundary none, smoothtriangles and one-face corners are certified", "[cli]")
{
    // Each took the estimate path before (certified: false); docs/subdivision.md, "What is
    // certified and what not".
    const std::string cube = freeform::test::slurp(cage("cube.obj"));
    struct Case {
        std::string name, text, extra;
        int faces;
    };
    std::string grid;
    for (int r = 0; r < 5; ++r)
        for (int c = 0; c < 5; ++c) grid += "v " + std::to_string(0.5 * r) + " " + std::to_string(0.5 * c) + " " + std::to_string(0.1 * ((r * c) % 3)) + "\n";
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
            grid += "f " + std::to_string(r * 5 + c + 1) + " " + std::to_string((r + 1) * 5 + c + 1) + " " + std::to_string((r + 1) * 5 + c + 2) +
                    " " + std::to_string(r * 5 + c + 2) + "\n";
    const std::vector<Case> cases = {
        {"sub_hole.obj", cube + "t hole 1/0/0 2\n", "", 6},
        {"sub_none.obj", grid, " --boundary none", 16},
        {"sub_corner.obj", grid, "", 16}, // edge_only (the default): four boundary vertices of one face
        {"sub_smoothtri.obj",
         "v 1 0 -0.7\nv -0.5 0.866 -0.7\nv -0.5 -0.866 -0.7\nv 1 0 0.7\nv -0.5 0.866 0.7\nv -0.5 -0.866 0.7\n"
         "f 3 2 1\nf 4 5 6\nf 1 2 5 4\nf 2 3 6 5\nf 3 1 4 6\nt smoothtriangles 0/0/1 smooth\n",
         "", 5},
    };
    for (const Case& c : cases) {
        INFO(c.name);
        writeText(tmp(c.name), c.text);
        const std::string out = tmp(c.name + ".out.obj");
        std::filesystem::remove(out);
        const auto r = cli("subdivide '" + tmp(c.name) + "' -o '" + out + "' --tolerance 1e-2" + c.extra);
        INFO(r.err);
        REQUIRE(r.status == 0);
        const Json j = Json::parse(r.out);
        CHECK(j["certified"] == true);
        CHECK(j["faces_certified"] == c.faces);
        CHECK(j["error_bound"].get<double>() <= 1e-2);
        CHECK(j["error_bound"].get<double>() > 0);
        CHECK(std::filesystem::exists(out));
    }
}

TEST_CASE("subdivide --lattice: an affine lattice moves the limit mesh affinely", "[cli]")
{
    // Rest lattice of degree 1 around [-2,2]^3, every point doubled in x and shifted by 1 in z.
    Json points = Json::array();
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
            for (int k = 0; k < 2; ++k) points.push_back({2 * (-2.0 + 4 * i), -2.0 + 4 * j, -2.0 + 4 * k + 1});
    const Json doc = {{"format", "freeform"},
                      {"version", 1},
                      {"objects",
                       {{{"name", "lat"},
                         {"type", "lattice"},
                         {"degree", {1, 1, 1}},
                         {"origin", {-2, -2, -2}},
                         {"axes", {{4, 0, 0}, {0, 4, 0}, {0, 0, 4}}},
                         {"points", points}}}}};
    writeText(tmp("sub_lattice.json"), doc.dump());
    const auto r = cli("subdivide '" + cage("creased_cube.obj") + "' -o '" + tmp("sub_lat.obj") + "' --level 1 --lattice '" +
                       tmp("sub_lattice.json") + "'");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const Json j = Json::parse(r.out);
    CHECK(j["lattice"] == "lat");
    CHECK(j["creases"] == 4);
    CHECK(j["corners"] == 2);
    // Level 1: the mesh vertices are the limit points of the cage vertices; vertex 1 (-1,-1,1) is
    // a sharp corner, so it is its own limit: (-2, -1, 2) after the lattice.
    std::istringstream obj(freeform::test::slurp(tmp("sub_lat.obj")));
    std::string key;
    double nearest = 1e300;
    int count = 0;
    for (std::string line; std::getline(obj, line);) {
        std::istringstream in(line);
        double x, y, z;
        if (!(in >> key) || key != "v" || !(in >> x >> y >> z)) continue;
        ++count;
        nearest = std::min(nearest, std::hypot(x + 2, y + 1, z - 2));
    }
    CHECK(count == 8);
    CHECK(nearest < 1e-12);
}

TEST_CASE("eval on a subdivision_surface object", "[cli]")
{
    // The 4 x 4 cage z = 0 except vertex (1, 1) at z = 36: face 4 (the centre) is regular, and its
    // corner 0 is vertex (1, 1), whose limit is (16 * 36) / 36 = 16 above the plane.
    Json vertices = Json::array(), faces = Json::array();
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) vertices.push_back({r, c, r == 1 && c == 1 ? 36 : 0});
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) faces.push_back({r * 4 + c, (r + 1) * 4 + c, (r + 1) * 4 + c + 1, r * 4 + c + 1});
    Json doc = {{"format", "freeform"},
                {"version", 1},
                {"objects", {{{"name", "s"}, {"type", "subdivision_surface"}, {"vertices", vertices}, {"faces", faces}}}}};
    writeText(tmp("sub_doc.json"), doc.dump());
    auto r = cli("eval '" + tmp("sub_doc.json") + "' --object s --at 4,0,0");
    INFO(r.err);
    REQUIRE(r.status == 0);
    Json j = Json::parse(r.out);
    CHECK(j["face"] == 4);
    CHECK(std::abs(j["point"][0].get<double>() - 1) < 1e-13);
    CHECK(std::abs(j["point"][1].get<double>() - 1) < 1e-13);
    CHECK(std::abs(j["point"][2].get<double>() - 16) < 1e-13);
    CHECK(j["derivatives"].contains("u"));
    CHECK(j["derivatives"].contains("v"));
    CHECK(std::abs(j["normal"][2].get<double>()) > 0); // a unit vector

    // A cage file relative to the document, with a crease side-car.
    std::filesystem::create_directories(tmp("subdoc"));
    std::filesystem::copy_file(cage("cube.obj"), tmp("subdoc/cube.obj"), std::filesystem::copy_options::overwrite_existing);
    doc = {{"format", "freeform"},
           {"version", 1},
           {"objects", {{{"name", "c"}, {"type", "subdivision_surface"}, {"mesh", "cube.obj"}, {"corners", {{0, 10}}}}}}};
    writeText(tmp("subdoc/doc.json"), doc.dump());
    r = cli("eval '" + tmp("subdoc/doc.json") + "' --object c --at 0,0,0");
    INFO(r.err);
    REQUIRE(r.status == 0);
    j = Json::parse(r.out);
    for (int k = 0; k < 3; ++k) CHECK(std::abs(j["point"][k].get<double>() + 1) < 1e-12); // sharp corner 0 = (-1,-1,-1)

    requireError(cli("eval '" + tmp("subdoc/doc.json") + "' --object c --at 6,0,0"), 1, "face 6 is out of range");
    requireError(cli("eval '" + tmp("subdoc/doc.json") + "' --object c --at 0,2,0"), 1, "outside the domain");
    requireError(cli("eval '" + tmp("subdoc/doc.json") + "' --object c --at 0.5,0,0"), 2, "FACE must be");
}

TEST_CASE("subdivide: bad cages and bad usage", "[cli]")
{
    const std::string out = tmp("sub_bad.obj");
    auto fails = [&](const std::string& text, const std::string& fragment, const std::string& extra = "") {
        writeText(tmp("sub_bad_cage.obj"), text);
        std::filesystem::remove(out);
        requireError(cli("subdivide '" + tmp("sub_bad_cage.obj") + "' -o '" + out + "'" + extra), 1, fragment);
        CHECK(!std::filesystem::exists(out));
    };
    const std::string square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 1\n";
    fails(square + "f 1 2 3 4\nf 1 2 5\nf 2 1 5\nf 1 2 3\n", "edge 0-1");                 // three faces on an edge
    fails(square + "f 1 2 3 4\nf 1 2 5\n", "runs the same way");                         // inconsistent orientation
    fails(square + "f 1 2 3 4\nt crease 2/1 0 2 10\n", "no such edge");                 // crease on a diagonal
    fails(square + "f 1 2 3 4\n", "Loop", " --scheme loop");                            // quads under Loop
    fails(square + "f 1 2 3 4\nt crease 2/1 0 9 1\n", "sub_bad_cage.obj:7");             // tag index out of range
    requireError(cli("subdivide '" + cage("cube.obj") + "' -o '" + out + "' --level 0"), 2, "--level");
    requireError(cli("subdivide '" + cage("cube.obj") + "' -o '" + out + "' --level 2 --tolerance 1"), 2, "either");
    requireError(cli("subdivide '" + cage("cube.obj") + "' -o '" + out + "' --scheme doo"), 2, "--scheme");
    CHECK(!std::filesystem::exists(out));
}

} // namespace test_cli_subdivide
