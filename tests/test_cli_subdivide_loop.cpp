// The command-line report of the certified Loop tessellation (docs/subdivision.md, "Loop cages";
// docs/cli.md): `subdivide --tolerance` and `tessellate --object` on a closed Loop cage report
// "certified": true where every face's bound is within the tolerance, and the mesh is closed genus 0;
// an open Loop cage keeps the estimate and says "certified": false.

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>

#include "support/cli.h"

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

TEST_CASE("subdivide --tolerance: an open Loop cage keeps the estimate and says so", "[cli]")
{
    // A fan of six triangles around a raised centre: a boundary, so not on the certified path.
    const std::string fan = tmp("loop_fan.obj");
    {
        std::string text = "v 0 0 0.5\n";
        for (int k = 0; k < 6; ++k) text += "v " + std::to_string(std::cos(k * M_PI / 3)) + " " + std::to_string(std::sin(k * M_PI / 3)) + " 0\n";
        for (int k = 0; k < 6; ++k) text += "f 1 " + std::to_string(k + 2) + " " + std::to_string((k + 1) % 6 + 2) + "\n";
        freeform::test::writeText(fan, text);
    }
    const std::string out = tmp("loop_fan_out.obj");
    const auto r = cli("subdivide '" + fan + "' -o '" + out + "' --tolerance 1e-2");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const Json j = Json::parse(r.out);
    CHECK(j["scheme"] == "loop");
    CHECK(j["certified"] == false);
    CHECK(j["faces_certified"] == 0);
    CHECK_FALSE(j.contains("error_bound"));
    CHECK(info(out)["boundary_loops"] == 1);
}
