// freeform convert --to deboor_spline --end open|clamped|closed: the de Boor form of a C2 cubic
// Bézier spline under a chosen end condition, round trips through both forms, and the errors
// (an end condition the spline cannot have: exit 1; a bad or misplaced --end: exit 2).

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>

#include "support/cli.h"
#include "support/cli_errors.h"

namespace test_cli_spline_end {

using freeform::test::requireError;

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

namespace {

std::string tmp(const std::string& name)
{
    return std::string(FREEFORM_TEST_TMP) + "/" + name;
}

std::string document(const std::string& file, const std::string& objects)
{
    const std::string path = tmp(file);
    writeText(path, R"({"format": "freeform", "version": 1, "objects": [)" + objects + "]}");
    return path;
}

/// Open end condition, non-uniform intervals, 3D.
const char* kOpen = R"({"name": "o", "type": "deboor_spline", "degree": 3, "end": "open",
    "points": [[0,0,0],[1,3,1],[4,4,-1],[6,1,2],[8,0,0],[9,2,1]], "intervals": [1, 2, 0.5]})";
/// Closed, uniform.
const char* kClosed = R"({"name": "c", "type": "deboor_spline", "degree": 3, "end": "closed",
    "points": [[0,0],[2,0],[3,2],[1,3],[-1,2]]})";

Json run(const std::string& args)
{
    const auto r = cli(args);
    INFO(args << "\nstderr: " << r.err);
    REQUIRE(r.status == 0);
    return Json::parse(r.out);
}

Json objectPoints(const std::string& path)
{
    return Json::parse(slurp(path))["objects"][0]["points"];
}

void checkSame(const Json& a, const Json& b, double margin)
{
    REQUIRE(a.size() == b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        REQUIRE(a[i].size() == b[i].size());
        for (std::size_t k = 0; k < a[i].size(); ++k)
            CHECK(a[i][k].get<double>() == Approx(b[i][k].get<double>()).margin(margin));
    }
}

} // namespace

TEST_CASE("convert --end open recovers the open de Boor points; clamped describes the same curve", "[cli]")
{
    const std::string doc = document("end_open.json", kOpen);
    const std::string bez = tmp("end_open_bez.json"), open = tmp("end_open_back.json");
    run("convert " + freeform::test::shellQuote(doc) + " --object o --to bezier_spline -o " + freeform::test::shellQuote(bez));

    // Open: the round trip de Boor -> Bézier -> de Boor gives back the input.
    const Json summary = run("convert " + freeform::test::shellQuote(bez) + " --object o --to deboor_spline --end open -o " + freeform::test::shellQuote(open));
    CHECK(summary["end"] == "open");
    CHECK(summary["points"] == 6);
    const Json back = Json::parse(slurp(open))["objects"][0];
    CHECK(back["end"] == "open");
    CHECK(back["intervals"] == Json::array({1.0, 2.0, 0.5}));
    checkSame(back["points"], Json::parse(std::string("[") + kOpen + "]")[0]["points"], 1e-12);

    // Clamped (also the default for an open spline): other de Boor points, the same Bézier spline,
    // starting at the first de Boor point.
    const std::string clamped = tmp("end_open_clamped.json"), dflt = tmp("end_open_default.json");
    CHECK(run("convert " + freeform::test::shellQuote(bez) + " --object o --to deboor_spline --end clamped -o " + freeform::test::shellQuote(clamped))["end"] == "clamped");
    CHECK(run("convert " + freeform::test::shellQuote(bez) + " --object o --to deboor_spline -o " + freeform::test::shellQuote(dflt))["end"] == "clamped");
    CHECK(objectPoints(clamped) == objectPoints(dflt));
    CHECK(objectPoints(clamped)[0] == objectPoints(bez)[0]);
    CHECK(objectPoints(clamped) != back["points"]);
    const std::string again = tmp("end_open_again.json");
    run("convert " + freeform::test::shellQuote(clamped) + " --object o --to bezier_spline -o " + freeform::test::shellQuote(again));
    checkSame(objectPoints(again), objectPoints(bez), 1e-12);
}

TEST_CASE("convert --end closed on a closed spline; end conditions the spline cannot have", "[cli]")
{
    const std::string doc = document("end_closed.json", kClosed);
    const std::string bez = tmp("end_closed_bez.json"), back = tmp("end_closed_back.json");
    run("convert " + freeform::test::shellQuote(doc) + " --object c --to bezier_spline -o " + freeform::test::shellQuote(bez));
    CHECK(run("convert " + freeform::test::shellQuote(bez) + " --object c --to deboor_spline --end closed -o " + freeform::test::shellQuote(back))["end"] == "closed");
    checkSame(objectPoints(back), Json::parse(std::string("[") + kClosed + "]")[0]["points"], 1e-12);

    const std::string none = tmp("end_none.json");
    std::filesystem::remove(none);
    requireError(cli("convert " + freeform::test::shellQuote(bez) + " --object c --to deboor_spline --end open -o " + freeform::test::shellQuote(none)), 1, "use --end closed");
    requireError(cli("convert " + freeform::test::shellQuote(bez) + " --object c --to deboor_spline --end clamped -o " + freeform::test::shellQuote(none)), 1, "closed");
    const std::string openDoc = document("end_open2.json", kOpen), openBez = tmp("end_open2_bez.json");
    run("convert " + freeform::test::shellQuote(openDoc) + " --object o --to bezier_spline -o " + freeform::test::shellQuote(openBez));
    requireError(cli("convert " + freeform::test::shellQuote(openBez) + " --object o --to deboor_spline --end closed -o " + freeform::test::shellQuote(none)), 1,
                 "use --end open or --end clamped");
    CHECK_FALSE(std::filesystem::exists(none));

    // Bad usage: exit 2.
    requireError(cli("convert " + freeform::test::shellQuote(openBez) + " --object o --to deboor_spline --end natural -o " + freeform::test::shellQuote(none)), 2,
                 "\"natural\" is not one of open, clamped, closed");
    requireError(cli("convert " + freeform::test::shellQuote(doc) + " --object c --to bezier_spline --end open -o " + freeform::test::shellQuote(none)), 2,
                 "--end: goes with --to deboor_spline only");
    requireError(cli("convert " + freeform::test::shellQuote(doc) + " --end open -o " + freeform::test::shellQuote(tmp("end_none.obj"))), 2, "--end");
    CHECK_FALSE(std::filesystem::exists(none));
    CHECK_FALSE(std::filesystem::exists(tmp("end_none.obj")));
    CHECK(cli("convert --help").out.find("--end") != std::string::npos);
}

} // namespace test_cli_spline_end
