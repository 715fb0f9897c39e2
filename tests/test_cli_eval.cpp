// The `freeform` command-line contract: `eval` output, exit statuses, and errors on stderr only.

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "support/cli.h"
#include "support/cli_errors.h"

namespace test_cli_eval {

namespace {
/// In process (support/cli.h); "help texts" and "bad usage exits 2" start the binary.
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
    return std::string(FREEFORM_TEST_TMP) + "/" + name;
}

std::string curveDoc()
{
    const std::string path = tmp("cli_curve.json");
    writeText(path, R"({"format": "freeform", "version": 1, "objects": [
        {"name": "c", "type": "bezier_curve", "points": [[0,0],[1,2],[3,2],[4,0]]},
        {"name": "h", "type": "bezier_curve", "points": [[0,0,0],[0.1,0.2,0.3],[1,1,1]]}]})");
    return path;
}
} // namespace

TEST_CASE("eval prints the point and the derivatives of a curve", "[cli]")
{
    const auto r = cli("eval " + freeform::test::shellQuote(curveDoc()) + " --object c --at 0.5 --derivatives 4");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const Json j = Json::parse(r.out);
    CHECK(j["object"] == "c");
    CHECK(j["t"].get<double>() == 0.5);
    CHECK(j["point"] == Json::array({2.0, 1.5}));
    REQUIRE(j["derivatives"].size() == 4);
    CHECK(j["derivatives"][0] == Json::array({4.5, 0.0}));
    CHECK(j["derivatives"][1] == Json::array({0.0, -12.0}));
    CHECK(j["derivatives"][2] == Json::array({-12.0, 0.0}));
    CHECK(j["derivatives"][3] == Json::array({0.0, 0.0}));
    // Keys in the documented order; one line.
    CHECK(r.out.rfind(R"({"object":"c","t":0.5,"point":)", 0) == 0);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
}

TEST_CASE("eval numbers read back to the same double", "[cli]")
{
    const auto r = cli("eval " + freeform::test::shellQuote(curveDoc()) + " --object h --at 0.1");
    REQUIRE(r.status == 0);
    const Json j = Json::parse(r.out);
    // f(0.1) of the quadratic (0,0,0),(0.1,0.2,0.3),(1,1,1): 2 t (1-t) b1 + t^2 b2, in double.
    const double t = 0.1, w1 = 2 * t * (1 - t), w2 = t * t;
    CHECK(j["point"][0].get<double>() == 0.0 * (1 - t) * (1 - t) + w1 * 0.1 + w2 * 1.0);
    CHECK(j.contains("derivatives") == false);
    const auto r3 = cli("eval " + freeform::test::shellQuote(curveDoc()) + " --object h --at 1 --derivatives 1");
    CHECK(Json::parse(r3.out)["derivatives"][0] == Json::array({1.8, 1.6, 1.4}));
}

TEST_CASE("help texts", "[cli]")
{
    const auto top = freeform::test::cli("--help");
    CHECK(top.status == 0);
    CHECK(top.out.find("eval") != std::string::npos);
    const auto ev = freeform::test::cli("eval --help");
    CHECK(ev.status == 0);
    for (const char* option : {"--object", "--at", "--derivatives"}) CHECK(ev.out.find(option) != std::string::npos);
}

TEST_CASE("bad usage exits 2", "[cli][errors]")
{
    const std::string d = curveDoc();
    requireError(freeform::test::cli(""), 2, "no command");
    requireError(freeform::test::cli("frobnicate"), 2, "unknown command");
    requireError(freeform::test::cli("eval " + freeform::test::shellQuote(d) + " --at 0.5"), 2, "--object is required");
    requireError(freeform::test::cli("eval " + freeform::test::shellQuote(d) + " --object c"), 2, "--at is required");
    requireError(freeform::test::cli("eval --object c --at 0.5"), 2, "missing the document");
    requireError(freeform::test::cli("eval " + freeform::test::shellQuote(d) + " --object c --at abc"), 2, "not a finite number");
    requireError(freeform::test::cli("eval " + freeform::test::shellQuote(d) + " --object c --at 0.5 --derivatives -1"), 2, "must not be negative");
    requireError(freeform::test::cli("eval " + freeform::test::shellQuote(d) + " --object c --at 0.5 --bogus"), 2, "unknown option --bogus");
    requireError(freeform::test::cli("eval " + freeform::test::shellQuote(d) + " " + freeform::test::shellQuote(d) + " --object c --at 0.5"), 2, "unexpected argument");
}

TEST_CASE("bad input exits 1", "[cli][errors]")
{
    requireError(cli("eval " + freeform::test::shellQuote(tmp("does_not_exist.json")) + " --object c --at 0.5"), 1, "cannot open");
    requireError(cli("eval " + freeform::test::shellQuote(curveDoc()) + " --object nope --at 0.5"), 1, "no object named \"nope\"");
    requireError(cli("eval " + freeform::test::shellQuote(curveDoc()) + " --object c --at 1.5"), 1, "outside");
    const std::string broken = tmp("cli_broken.json");
    writeText(broken, R"({"format": "freeform", "version": 1, "objects": [{"name": "c", "type": "bezier_curve", "points": [[0,0],[1]]}]})");
    requireError(cli("eval " + freeform::test::shellQuote(broken) + " --object c --at 0.5"), 1, "points[1]");
    writeText(broken, R"({"format": "freeform", "version": 1, "objects": [{"name": "c", "type": "bezier_curve", "points": [[0,0],[1,NaN]]}]})");
    requireError(cli("eval " + freeform::test::shellQuote(broken) + " --object c --at 0.5"), 1, "not valid JSON");
    writeText(broken, R"({"format": "freeform", "version": 1, "objects": [{"name": "c", "type": "bezier_curb", "points": [[0,0]]}]})");
    requireError(cli("eval " + freeform::test::shellQuote(broken) + " --object c --at 0.5"), 1, "unknown object type");
    writeText(broken, "");
    requireError(cli("eval " + freeform::test::shellQuote(broken) + " --object c --at 0.5"), 1, "not valid JSON");
}

} // namespace test_cli_eval
