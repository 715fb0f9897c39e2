// `freeform info`: the report of OBJ files with known topology (exact JSON, key order), the genus
// note, --details, and bad input (missing, malformed, unknown format, no argument); a document's
// part in every build, and CAD files refused by name in a build without Open CASCADE.

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <freeform/cad/cad_file.h>
#include <freeform/core/warning.h>
#include <freeform/io/mesh_io.h>

#include "support/meshes.h"
#include "support/cli.h"
#include "support/cli_errors.h"

namespace test_cli_info {

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

std::string tmp(const std::string& name)
{
    return std::string(FREEFORM_TEST_TMP) + "/cli_info_" + name;
}

/// The mesh as an OBJ file written here, independently of the library's writer.
std::string writeObj(const freeform::PolygonMesh& m, const std::string& name)
{
    std::ostringstream text;
    text.precision(17);
    text << "# " << name << "\n";
    for (int v = 0; v < m.vertexCount(); ++v)
        text << "v " << m.positions(0, v) << ' ' << m.positions(1, v) << ' ' << m.positions(2, v) << '\n';
    for (int f = 0; f < m.faceCount(); ++f) {
        text << 'f';
        for (int k = 0; k < m.faceSize(f); ++k) text << ' ' << m.face(f)[k] + 1;
        text << '\n';
    }
    const std::string path = tmp(name);
    writeText(path, text.str());
    return path;
}

} // namespace

TEST_CASE("info on a cube: the whole line, keys in the documented order", "[cli]")
{
    const auto r = cli("info " + freeform::test::shellQuote(writeObj(freeform::test::cube(), "cube.obj")));
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(r.err.empty());
    CHECK(r.out ==
          R"({"vertices":8,"edges":12,"faces":6,"boundary_edges":0,"boundary_loops":0,"components":1,"manifold":true,"closed":true,"euler":2,"genus":0})"
          "\n");
}

TEST_CASE("info on a torus, a two-hole slab and two components", "[cli]")
{
    const Json torus = Json::parse(cli("info " + freeform::test::shellQuote(writeObj(freeform::test::quadTorus(12, 6), "torus.obj"))).out);
    CHECK(torus["vertices"] == 72);
    CHECK(torus["edges"] == 144);
    CHECK(torus["faces"] == 72);
    CHECK(torus["closed"] == true);
    CHECK(torus["euler"] == 0);
    CHECK(torus["genus"] == 1);
    CHECK(!torus.contains("genus_note"));

    const Json slab = Json::parse(cli("info " + freeform::test::shellQuote(writeObj(freeform::test::holedSlab(2), "slab.obj"))).out);
    CHECK(slab["euler"] == -2);
    CHECK(slab["genus"] == 2);

    const Json two = Json::parse(
        cli("info " + freeform::test::shellQuote(writeObj(freeform::test::disjointUnion(freeform::test::tetrahedron(), freeform::test::quadTorus(5, 4)), "two.obj"))).out);
    CHECK(two["components"] == 2);
    CHECK(two["euler"] == 2);
    CHECK(two["genus"] == 1);
}

TEST_CASE("info on a disk: genus null with a note", "[cli]")
{
    const auto r = cli("info " + freeform::test::shellQuote(writeObj(freeform::test::fanDisk(6), "disk.obj")));
    REQUIRE(r.status == 0);
    CHECK(r.out ==
          R"({"vertices":7,"edges":12,"faces":6,"boundary_edges":6,"boundary_loops":1,"components":1,"manifold":true,"closed":false,"euler":1,"genus":null,"genus_note":"it has 1 boundary loop; the genus is given for closed surfaces only"})"
          "\n");
}

TEST_CASE("info on non-manifold input reports instead of failing", "[cli]")
{
    const std::string path = tmp("fan.obj");
    writeText(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n");
    const auto r = cli("info " + freeform::test::shellQuote(path));
    INFO(r.err);
    REQUIRE(r.status == 0);
    const Json j = Json::parse(r.out);
    CHECK(j["manifold"] == false);
    CHECK(j["edges"] == 7);
    CHECK(j["boundary_edges"] == 6);
    CHECK(j["genus"].is_null());
    CHECK(j["genus_note"].get<std::string>().rfind("not a manifold", 0) == 0);

    const Json d = Json::parse(cli("info " + freeform::test::shellQuote(path) + " --details").out);
    CHECK(d["non_manifold_edges"] == Json::parse("[[0, 1, 3]]"));
    CHECK(d["non_manifold_vertices"] == Json::parse("[[0, 3], [1, 3]]"));
    CHECK(d["inconsistent_edges"] == Json::array());
    CHECK(d["isolated_vertices"] == 0);
    REQUIRE(d["component_reports"].size() == 1);
    CHECK(d["component_reports"][0]["manifold"] == false);
    // --details adds keys after the standard ones, which stay as they were.
    CHECK(d["vertices"] == j["vertices"]);
    CHECK(d.size() == j.size() + 7);
}

TEST_CASE("info on a Klein bottle: closed manifold, not orientable", "[cli]")
{
    const Json j = Json::parse(cli("info " + freeform::test::shellQuote(writeObj(freeform::test::kleinBottle(5, 4), "klein.obj")) + " --details").out);
    CHECK(j["manifold"] == true);
    CHECK(j["closed"] == true);
    CHECK(j["euler"] == 0);
    CHECK(j["genus"].is_null());
    CHECK(j["genus_note"].get<std::string>().find("not orientable") != std::string::npos);
    CHECK(j["orientable"] == false);
}

TEST_CASE("info reads every mesh format", "[cli]")
{
    // Hand-written OFF, ASCII PLY and ASCII STL tetrahedra (STL corners are welded on reading).
    const std::string off = tmp("tet.off"), ply = tmp("tet.ply"), stl = tmp("tet.stl");
    writeText(off, "OFF\n4 4 6\n1 1 1\n1 -1 -1\n-1 1 -1\n-1 -1 1\n3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n");
    writeText(ply, "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                   "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
                   "1 1 1\n1 -1 -1\n-1 1 -1\n-1 -1 1\n3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n");
    const freeform::PolygonMesh tet = freeform::test::tetrahedron();
    std::string solid = "solid tet\n";
    for (int f = 0; f < 4; ++f) {
        solid += "facet normal 0 0 0\nouter loop\n";
        for (int k = 0; k < 3; ++k) {
            const auto p = tet.positions.col(tet.face(f)[k]);
            solid += "vertex " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z()) + "\n";
        }
        solid += "endloop\nendfacet\n";
    }
    writeText(stl, solid + "endsolid tet\n");
    const std::string expected =
        R"({"vertices":4,"edges":6,"faces":4,"boundary_edges":0,"boundary_loops":0,"components":1,"manifold":true,"closed":true,"euler":2,"genus":0})"
        "\n";
    for (const auto& path : {off, ply, stl}) {
        const auto r = cli("info " + freeform::test::shellQuote(path));
        INFO(path << ": " << r.err);
        CHECK(r.out == expected);
    }
    // glTF (text and binary), written by the library's mesh writer: a torus as triangles.
    const freeform::PolygonMesh torus = freeform::test::splitQuads(freeform::test::quadTorus(6, 4));
    for (const char* ext : {".gltf", ".glb", ".ply", ".obj"}) {
        const std::string path = tmp(std::string("torus") + ext);
        freeform::writePolygonMesh(torus, path);
        const auto r = cli("info " + freeform::test::shellQuote(path));
        INFO(path << ": " << r.err);
        REQUIRE(r.status == 0);
        const Json j = Json::parse(r.out);
        CHECK(j["vertices"] == 24);
        CHECK(j["faces"] == 48);
        CHECK(j["edges"] == 72);
        CHECK(j["genus"] == 1);
    }
}

TEST_CASE("info: bad input and bad usage", "[cli]")
{
    requireError(cli("info " + freeform::test::shellQuote(tmp("does-not-exist.obj"))), 1, "does-not-exist.obj");

    const std::string outOfRange = tmp("bad_index.obj");
    writeText(outOfRange, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    requireError(cli("info " + freeform::test::shellQuote(outOfRange)), 1, "bad_index.obj");

    const std::string garbage = tmp("garbage.obj");
    writeText(garbage, "v 0 0 zero\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    requireError(cli("info " + freeform::test::shellQuote(garbage)), 1, "garbage.obj");

    const std::string unknown = tmp("mesh.xyz");
    writeText(unknown, "1 2 3\n");
    requireError(cli("info " + freeform::test::shellQuote(unknown)), 1, "mesh.xyz");

    requireError(cli("info"), 2, "missing the mesh file");
    requireError(cli("info a.obj b.obj"), 2, "unexpected argument");
    requireError(cli("info a.obj --genus"), 2, "unknown option --genus");

    const auto help = cli("info --help");
    CHECK(help.status == 0);
    for (const char* word : {"--details", "genus_note", "boundary_loops"}) CHECK(help.out.find(word) != std::string::npos);
}

TEST_CASE("info on a file the reader accepts with a warning: one warning line on stderr, the JSON on stdout", "[cli]")
{
    // A PLY header line Blender 2.47 wrote (docs/mesh-io.md, leniency): kept as a comment, and the
    // library's warning (freeform/core/warning.h) reaches the CLI's stderr, not stdout.
    const std::string ply = tmp("blender_info.ply");
    writeText(ply, "ply\nformat ascii 1.0\nCreated by Blender3D 247 - www.blender.org\nelement vertex 3\nproperty float x\n"
                   "property float y\nproperty float z\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n"
                   "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    const auto r = cli("info " + freeform::test::shellQuote(ply));
    REQUIRE(r.status == 0);
    CHECK(Json::parse(r.out)["faces"] == 1);
    CHECK(r.out.find("warning") == std::string::npos);
    CHECK(r.err.rfind("warning: ", 0) == 0);
    CHECK(r.err.find("unknown header line 'Created' kept as a comment") != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.err.back() == '\n');
    // The run's handler is gone with the run: a later warning reaches whoever set one, not the
    // closed run's stream.
    std::vector<std::string> seen;
    const freeform::ScopedWarningHandler capture([&seen](const std::string& m) { seen.push_back(m); });
    (void)cli("info " + freeform::test::shellQuote(ply));
    CHECK(seen.empty()); // the run had its own handler
    freeform::warn("after the run");
    CHECK(seen == std::vector<std::string>{"after the run"});
}

TEST_CASE("a document's part in every build; without Open CASCADE a CAD file refused by name, nothing written", "[cli]")
{
    using freeform::test::shellQuote;
    // data/parts/plate.json: a 40 x 30 x 10 plate with a through hole (docs/cad.md, "Documents").
    const std::string plate = std::string(FREEFORM_SOURCE_DIR) + "/data/parts/plate.json";
    const auto r = cli("info " + shellQuote(plate));
    REQUIRE(r.status == 0);
    const Json j = Json::parse(r.out);
    CHECK(j["faces"] == 7);
    CHECK(j["edges"] == 15);
    CHECK(j["vertices"] == 10);
    CHECK(j["closed"] == true);
    const std::string step = tmp("plate.step");
    std::filesystem::remove(step);
    const auto c = cli("convert " + shellQuote(plate) + " -o " + shellQuote(step));
    if (freeform::cadFilesSupported()) {
        REQUIRE(c.status == 0);
        const auto back = cli("info " + shellQuote(step));
        REQUIRE(back.status == 0);
        CHECK(Json::parse(back.out)["faces"] == 7);
    } else {
        requireError(c, 1, "plate.step: this freeform was built without Open CASCADE");
        CHECK_FALSE(std::filesystem::exists(step));
        requireError(cli("info " + shellQuote(step)), 1, "without Open CASCADE");
    }
}

} // namespace test_cli_info
