// The command-line report of the certified Loop tessellation (docs/subdivision.md, "Loop cages";
// docs/cli.md): `subdivide --tolerance` and `tessellate --object` on a closed Loop cage report
// "certified": true where every face's bound is within the tolerance, and the mesh is closed genus 0;
// open cages, holes, creases and corners are certified too (one boundary loop where the cage has one).

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "support/cli.h"

namespace test_cli_subdivide_loop {

namespace {

using Json = nlohmann::json;

freeform::test::ProcessResult cli(const std::string& arguments) { return freeform::test::cliInProcess(arguments); }
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

TEST_CASE("subdivide / tessellate --tolerance: a closed Loop cage is certified", "[cli]")
{
    const std::string octa = tmp("loop_octa_certified.obj");
    std::filesystem::remove(octa);
    auto r = cli("subdivide '" + cage("octahedron.obj") + "' -o '" + octa + "' --tolerance 1e-2");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const Json j = Json::parse(r.out);
    CHECK(j["scheme"] == "loop");
    CHECK(j["certified"] == true);
    CHECK(j["faces_certified"] == 8);
    CHECK(j["error_bound"].get<double>() <= 1e-2);
    CHECK(j["error_bound"].get<double>() > 0);
    CHECK(j["leaves"].get<long long>() >= j["cells"].get<long long>());
    const Json oi = info(octa);
    CHECK(oi["closed"] == true);
    CHECK(oi["euler"] == 2);
    CHECK(oi["genus"] == 0);
    CHECK(oi["faces"] == j["triangles"]);

    // The same object through a document.
    const std::string tessellated = tmp("loop_octa_tessellated.obj");
    r = cli("tessellate '" + cage("torus.json") + "' --object octahedron -o '" + tessellated + "' --tolerance 1e-2");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const Json t = Json::parse(r.out);
    CHECK(t["certified"] == true);
    CHECK(t["faces_certified"] == 8);
    CHECK(t["error_bound"] == j["error_bound"]);
    CHECK(t["triangles"] == j["triangles"]);
    CHECK(info(tessellated)["genus"] == 0);
}

TEST_CASE("subdivide --tolerance: open, holed and creased Loop cages are certified", "[cli]")
{
    // A fan of six triangles around a raised centre: a boundary.
    const std::string fan = tmp("loop_fan.obj");
    std::string text = "v 0 0 0.5\n";
    for (int k = 0; k < 6; ++k) text += "v " + std::to_string(std::cos(k * M_PI / 3)) + " " + std::to_string(std::sin(k * M_PI / 3)) + " 0\n";
    for (int k = 0; k < 6; ++k) text += "f 1 " + std::to_string(k + 2) + " " + std::to_string((k + 1) % 6 + 2) + "\n";
    freeform::test::writeText(fan, text);
    const std::string out = tmp("loop_fan_out.obj");
    auto r = cli("subdivide '" + fan + "' -o '" + out + "' --tolerance 1e-2");
    INFO(r.err);
    REQUIRE(r.status == 0);
    Json j = Json::parse(r.out);
    CHECK(j["scheme"] == "loop");
    CHECK(j["certified"] == true);
    CHECK(j["faces_certified"] == 6);
    CHECK(j["error_bound"].get<double>() <= 1e-2);
    Json oi = info(out);
    CHECK(oi["boundary_loops"] == 1);
    CHECK(oi["euler"] == 1);
    CHECK(oi["faces"] == j["triangles"]);

    // The same fan under edge_and_corner.
    r = cli("subdivide '" + fan + "' -o '" + out + "' --tolerance 1e-2 --boundary edge_and_corner");
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(Json::parse(r.out)["certified"] == true);

    // The octahedron with a hole (face 0), an infinitely sharp crease (0-2) and a semi-sharp
    // corner, Chaikin: one boundary loop, the rest closed.
    std::string octa;
    {
        std::ifstream in(cage("octahedron.obj"));
        octa.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    octa += "t hole 1/0/0 0\nt crease 2/1/0 0 2 10\nt corner 1/1/0 5 1.5\nt creasemethod 0/0/1 chaikin\n";
    const std::string holed = tmp("loop_octa_features.obj");
    freeform::test::writeText(holed, octa);
    const std::string holedOut = tmp("loop_octa_features_out.obj");
    r = cli("subdivide '" + holed + "' -o '" + holedOut + "' --tolerance 1e-2");
    INFO(r.err);
    REQUIRE(r.status == 0);
    j = Json::parse(r.out);
    CHECK(j["certified"] == true);
    CHECK(j["faces_certified"] == 8);
    CHECK(j["creases"] == 1);
    CHECK(j["corners"] == 1);
    CHECK(j["error_bound"].get<double>() <= 1e-2);
    oi = info(holedOut);
    CHECK(oi["boundary_loops"] == 1);
    CHECK(oi["euler"] == 1);
    CHECK(oi["manifold"] == true);
}

} // namespace test_cli_subdivide_loop
