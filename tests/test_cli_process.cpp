// The freeform binary against the in-process library (support/cli.h): the same bytes on stdout and
// stderr and the same exit status, so the in-process command tests speak for the tool; and what only
// a process shows: stdout holds nothing but the JSON line, also when an error ends the run.

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>

#include "support/cli.h"

namespace test_cli_process {

using freeform::test::cli;
using freeform::test::cliInProcess;
using freeform::test::writeText;
using Json = nlohmann::json;

namespace {
std::string tmp(const std::string& name)
{
    return std::string(FREEFORM_TEST_TMP) + "/" + name;
}
} // namespace

TEST_CASE("the binary and the library agree byte for byte", "[cli]")
{
    const std::string d = tmp("cli_process.json");
    writeText(d, R"({"format": "freeform", "version": 1, "objects": [
        {"name": "c", "type": "bezier_curve", "points": [[0,0],[1,2],[3,2],[4,0]]}]})");
    const std::string mesh = std::string(FREEFORM_SOURCE_DIR) + "/data/meshes/cube.obj";
    for (const std::string& line :
         {"eval " + d + " --object c --at 0.25 --derivatives 3", "eval " + d + " --object c --at 2",
          "eval " + d + " --object nope --at 0.5", "eval " + d + " --at 0.5", "eval " + d + " --object c --at 0.5 --x",
          "info " + mesh, "info " + mesh + " --details", std::string("frobnicate"), std::string(""),
          std::string("--help"), std::string("--version"), std::string("ffd --help"), std::string("convert --help")}) {
        INFO(line);
        const auto binary = cli(line);
        const auto inProcess = cliInProcess(line);
        CHECK(binary.status == inProcess.status);
        CHECK(binary.out == inProcess.out);
        CHECK(binary.err == inProcess.err);
    }
}

TEST_CASE("stdout holds only the JSON line; errors only stderr", "[cli]")
{
    const std::string mesh = std::string(FREEFORM_SOURCE_DIR) + "/data/meshes/cube.obj";
    const auto ok = cli("info " + freeform::test::shellQuote(mesh));
    REQUIRE(ok.status == 0);
    CHECK(ok.err.empty());
    CHECK(std::count(ok.out.begin(), ok.out.end(), '\n') == 1);
    const Json j = Json::parse(ok.out); // the whole of stdout parses
    CHECK(j["vertices"] == 8);          // a cube: 8 corners, 12 edges, 6 quads
    CHECK(j["edges"] == 12);
    CHECK(j["faces"] == 6);
    for (const std::string& bad : {"info " + tmp("missing.obj"), std::string("info --bogus"), std::string("info")}) {
        const auto r = cli(bad);
        INFO(bad);
        CHECK(r.status != 0);
        CHECK(r.out.empty());
        CHECK(r.err.rfind("error: ", 0) == 0);
    }
}

} // namespace test_cli_process
