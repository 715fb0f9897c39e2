// The spline commands of the `freeform` tool: eval of bezier_spline and deboor_spline, continuity,
// interpolate and convert --to, their output contracts, and bad input (exit 1) / bad usage (exit 2)
// with one "error:" line, nothing on stdout and no output file.

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>

#include "support/cli.h"
#include "support/cli_errors.h"

namespace test_cli_spline {

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
    return std::string(FREEFORM_TEST_TMP) + "/" + name;
}

std::string document(const std::string& file, const std::string& objects)
{
    const std::string path = tmp(file);
    writeText(path, R"({"format": "freeform", "version": 1, "objects": [)" + objects + "]}");
    return path;
}

/// Segment 0: the cubic arch (0,0),(1,2),(3,2),(4,0) on [0, 1]; segment 1 on [1, 3].
const char* kSpline = R"({"name": "s", "type": "bezier_spline", "degree": 3, "closed": false,
    "points": [[0,0],[1,2],[3,2],[4,0],[5,-2],[7,-2],[8,0]], "intervals": [1, 2]})";
/// Left: y = 0 on [0, 3]; right: y = 20.25 s^3 on [3, 6]: C2 with a third-derivative jump of 4.5.
const char* kJump = R"({"name": "j", "type": "bezier_spline", "degree": 3,
    "points": [[0,0],[1,0],[2,0],[3,0],[4,0],[5,0],[6,20.25]], "intervals": [3, 3]})";
const char* kDeBoor = R"({"name": "d", "type": "deboor_spline", "degree": 3, "end": "clamped",
    "points": [[0,0],[1,3],[4,4],[6,1],[8,0]], "intervals": [1, 2]})";

} // namespace

TEST_CASE("eval of a bezier_spline at a global parameter", "[cli]")
{
    const std::string doc = document("spl_eval.json", kSpline);
    const auto r = cli("eval " + freeform::test::shellQuote(doc) + " --object s --at 2 --derivatives 3");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const Json j = Json::parse(r.out);
    // T = 2 is t = 1/2 of segment 1 (length 2): the mirrored arch, derivatives scaled by 2^-k.
    CHECK(j["object"] == "s");
    CHECK(j["t"].get<double>() == 2.0);
    CHECK(j["point"] == Json::array({6.0, -1.5}));
    CHECK(j["derivatives"][0] == Json::array({2.25, 0.0}));
    CHECK(j["derivatives"][1] == Json::array({0.0, 3.0}));
    CHECK(j["derivatives"][2] == Json::array({-1.5, 0.0}));
    CHECK(r.out.rfind(R"({"object":"s","t":2.0,"point":)", 0) == 0);
    // The end of the domain is T = 3.
    CHECK(Json::parse(cli("eval " + freeform::test::shellQuote(doc) + " --object s --at 3").out)["point"] == Json::array({8.0, 0.0}));
    requireError(cli("eval " + freeform::test::shellQuote(doc) + " --object s --at 3.5"), 1, "outside the spline's domain [0, 3]");
    requireError(cli("eval " + freeform::test::shellQuote(doc) + " --object s --at -0.1"), 1, "outside");
}

TEST_CASE("eval of a clamped deboor_spline starts and ends at the end de Boor points", "[cli]")
{
    const std::string doc = document("spl_deboor.json", kDeBoor);
    const auto start = cli("eval " + freeform::test::shellQuote(doc) + " --object d --at 0 --derivatives 1");
    INFO(start.err);
    REQUIRE(start.status == 0);
    const Json a = Json::parse(start.out);
    CHECK(a["point"] == Json::array({0.0, 0.0}));
    // Clamped: f'(0) = 3 (d_1 - d_0) / h_0 = (3, 9).
    CHECK(a["derivatives"][0][0].get<double>() == Approx(3.0).epsilon(1e-14));
    CHECK(a["derivatives"][0][1].get<double>() == Approx(9.0).epsilon(1e-14));
    const Json b = Json::parse(cli("eval " + freeform::test::shellQuote(doc) + " --object d --at 3").out);
    CHECK(b["point"] == Json::array({8.0, 0.0}));
}

TEST_CASE("continuity prints every joint with C, G and the jumps", "[cli]")
{
    const std::string doc = document("spl_cont.json", std::string(kJump) + "," + kSpline + "," + kDeBoor);
    const auto r = cli("continuity " + freeform::test::shellQuote(doc) + " --object j");
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(r.out == R"({"object":"j","joints":[{"joint":1,"t":3.0,"C":2,"G":2,"jumps":[0.0,0.0,0.0,4.5]}]})"
                   "\n");
    // The two-segment arch spline: C0 with a first-derivative jump, G1 (tangents (3,-6) and (1.5,-3)).
    const Json s = Json::parse(cli("continuity " + freeform::test::shellQuote(doc) + " --object s").out);
    CHECK(s["joints"][0]["C"] == 0);
    CHECK(s["joints"][0]["G"] == 1);
    CHECK(s["joints"][0]["jumps"][1].get<double>() == Approx(std::sqrt(1.5 * 1.5 + 3.0 * 3.0)).epsilon(1e-15));
    // A de Boor spline is C2 at its joints.
    const Json d = Json::parse(cli("continuity " + freeform::test::shellQuote(doc) + " --object d").out);
    REQUIRE(d["joints"].size() == 1);
    CHECK(d["joints"][0]["C"] == 2);
    // A loose tolerance lets the jump in the first derivative pass.
    const Json loose = Json::parse(cli("continuity " + freeform::test::shellQuote(doc) + " --object s --tolerance 10").out);
    CHECK(loose["joints"][0]["C"].get<int>() >= 1);
    requireError(cli("continuity " + freeform::test::shellQuote(doc) + " --object s --tolerance 0"), 2, "--tolerance");
    requireError(cli("continuity " + freeform::test::shellQuote(doc) + " --object nope"), 1, "no object named \"nope\"");
}

TEST_CASE("continuity reports the closing joint of a closed spline", "[cli]")
{
    const std::string doc = document("spl_closed.json", R"({"name": "c", "type": "deboor_spline", "degree": 3,
        "end": "closed", "points": [[0,0],[2,0],[2,2],[0,2]]})");
    const Json j = Json::parse(cli("continuity " + freeform::test::shellQuote(doc) + " --object c").out);
    REQUIRE(j["joints"].size() == 4);
    CHECK(j["joints"][0]["joint"] == 0);
    CHECK(j["joints"][0]["t"] == 0.0);
    for (const auto& e : j["joints"]) CHECK(e["C"] == 2);
}

TEST_CASE("interpolate writes a bezier_spline through the points", "[cli]")
{
    const std::string in = tmp("spl_points.json"), out = tmp("spl_interp.json");
    writeText(in, R"({"points": [[0,0],[3,4],[6,0],[9,4]]})");
    std::filesystem::remove(out);
    const auto r = cli("interpolate " + freeform::test::shellQuote(in) + " -o " + freeform::test::shellQuote(out));
    INFO(r.err);
    REQUIRE(r.status == 0);
    const Json summary = Json::parse(r.out);
    CHECK(summary["object"] == "interpolant");
    CHECK(summary["segments"] == 3);
    CHECK(summary["end"] == "natural");
    CHECK(summary["param"] == "chord");
    const Json doc = Json::parse(slurp(out));
    const Json& o = doc["objects"][0];
    CHECK(o["name"] == "interpolant");
    CHECK(o["type"] == "bezier_spline");
    CHECK(o["intervals"] == Json::array({5.0, 5.0, 5.0})); // chord lengths
    CHECK(o["points"].size() == 10);
    CHECK(o["points"][3] == Json::array({3.0, 4.0}));
    // Through every point: eval at the knots 0, 5, 10, 15.
    const auto e = cli("eval " + freeform::test::shellQuote(out) + " --object interpolant --at 10");
    CHECK(Json::parse(e.out)["point"] == Json::array({6.0, 0.0}));

    // Given parameters and clamped ends.
    writeText(in, R"({"points": [[0,0],[1,1],[2,0]], "params": [0, 1, 3]})");
    const auto c = cli("interpolate " + freeform::test::shellQuote(in) + " -o " + freeform::test::shellQuote(out) + " --end clamped --start-derivative 1,0 --end-derivative 0,-1");
    INFO(c.err);
    REQUIRE(c.status == 0);
    CHECK(Json::parse(c.out)["param"] == "given");
    const Json cd = Json::parse(slurp(out));
    CHECK(cd["objects"][0]["intervals"] == Json::array({1.0, 2.0}));
    // b_1 = p_0 + h_0 m_0 / 3 = (1/3, 0).
    CHECK(cd["objects"][0]["points"][1][0].get<double>() == Approx(1.0 / 3).epsilon(1e-15));

    // Periodic: a closed spline.
    writeText(in, R"({"points": [[1,0],[0,1],[-1,0],[0,-1]]})");
    REQUIRE(cli("interpolate " + freeform::test::shellQuote(in) + " -o " + freeform::test::shellQuote(out) + " --end periodic --param uniform").status == 0);
    const Json pd = Json::parse(slurp(out));
    CHECK(pd["objects"][0]["closed"] == true);
    CHECK(pd["objects"][0]["points"].size() == 12);
}

TEST_CASE("interpolate: bad usage and bad input", "[cli]")
{
    const std::string in = tmp("spl_points_bad.json"), out = tmp("spl_interp_bad.json");
    writeText(in, R"({"points": [[0,0],[3,4],[6,0]]})");
    std::filesystem::remove(out);
    requireError(cli("interpolate " + freeform::test::shellQuote(in) + " -o " + freeform::test::shellQuote(out) + " --end free"), 2, "unknown end condition \"free\"");
    requireError(cli("interpolate " + freeform::test::shellQuote(in) + " -o " + freeform::test::shellQuote(out) + " --param arc"), 2, "unknown parametrization");
    requireError(cli("interpolate " + freeform::test::shellQuote(in) + " -o " + freeform::test::shellQuote(out) + " --end clamped"), 2, "--start-derivative");
    requireError(cli("interpolate " + freeform::test::shellQuote(in) + " -o " + freeform::test::shellQuote(out) + " --start-derivative 1,0"), 2, "clamped only");
    requireError(cli("interpolate " + freeform::test::shellQuote(in) + " -o " + freeform::test::shellQuote(out) + " --end clamped --start-derivative 1,0,0 --end-derivative 1,0,0"),
                 2, "expected 2 numbers");
    requireError(cli("interpolate " + freeform::test::shellQuote(in)), 2, "--output");
    writeText(in, R"({"points": [[0,0],[0,0],[6,0]]})");
    requireError(cli("interpolate " + freeform::test::shellQuote(in) + " -o " + freeform::test::shellQuote(out)), 1, "points 0 and 1 coincide");
    writeText(in, R"({"points": [[0,0],[1,0,0]]})");
    requireError(cli("interpolate " + freeform::test::shellQuote(in) + " -o " + freeform::test::shellQuote(out)), 1, "points[1]");
    writeText(in, R"({"points": [[0,0],[1,0]], "weights": [1]})");
    requireError(cli("interpolate " + freeform::test::shellQuote(in) + " -o " + freeform::test::shellQuote(out)), 1, "unknown field");
    writeText(in, R"({"points": [[0,0],[1,0],[2,1]], "params": [0, 2, 1]})");
    requireError(cli("interpolate " + freeform::test::shellQuote(in) + " -o " + freeform::test::shellQuote(out)), 1, "strictly increasing");
    CHECK_FALSE(std::filesystem::exists(out));
}

TEST_CASE("convert between de Boor and Bézier form, round trip", "[cli]")
{
    const std::string doc = document("spl_conv.json", std::string(kDeBoor) + "," + kSpline);
    const std::string bez = tmp("spl_conv_bez.json"), back = tmp("spl_conv_back.json");
    const auto r = cli("convert " + freeform::test::shellQuote(doc) + " --object d --to bezier_spline -o " + freeform::test::shellQuote(bez));
    INFO(r.err);
    REQUIRE(r.status == 0);
    const Json summary = Json::parse(r.out);
    CHECK(summary["from"] == "deboor_spline");
    CHECK(summary["to"] == "bezier_spline");
    const Json b = Json::parse(slurp(bez));
    REQUIRE(b["objects"].size() == 2); // the other object is kept
    CHECK(b["objects"][0]["type"] == "bezier_spline");
    CHECK(b["objects"][0]["points"].size() == 7);
    CHECK(b["objects"][0]["points"][0] == Json::array({0.0, 0.0}));
    CHECK(b["objects"][0]["points"][1] == Json::array({1.0, 3.0}));
    const auto r2 = cli("convert " + freeform::test::shellQuote(bez) + " --object d --to deboor_spline -o " + freeform::test::shellQuote(back));
    INFO(r2.err);
    REQUIRE(r2.status == 0);
    CHECK(Json::parse(r2.out)["end"] == "clamped");
    const Json d = Json::parse(slurp(back));
    const Json original = Json::parse(std::string("[") + kDeBoor + "]")[0]["points"];
    REQUIRE(d["objects"][0]["points"].size() == original.size());
    for (std::size_t i = 0; i < original.size(); ++i)
        for (int k = 0; k < 2; ++k)
            CHECK(d["objects"][0]["points"][i][k].get<double>() ==
                  Approx(original[i][k].get<double>()).margin(1e-13));
    // The arch spline is not C2: a clear error, no output file.
    const std::string none = tmp("spl_conv_none.json");
    std::filesystem::remove(none);
    requireError(cli("convert " + freeform::test::shellQuote(doc) + " --object s --to deboor_spline -o " + freeform::test::shellQuote(none)), 1, "not C2 at joint 1");
    CHECK_FALSE(std::filesystem::exists(none));
    requireError(cli("convert " + freeform::test::shellQuote(doc) + " --object d --to deboor_spline -o " + freeform::test::shellQuote(none)), 1, "already a deboor_spline");
    requireError(cli("convert " + freeform::test::shellQuote(doc) + " --object d --to nurbs -o " + freeform::test::shellQuote(none)), 2, "--to");
    CHECK_FALSE(std::filesystem::exists(none));
}

TEST_CASE("bad spline objects: exit 1, nothing on stdout", "[cli]")
{
    const char* cases[][2] = {
        {R"({"name": "b", "type": "bezier_spline", "degree": 3, "points": [[0,0],[1,1],[2,2],[3,3],[4,4]]})",
         "5 points do not fit degree 3"},
        {R"({"name": "b", "type": "bezier_spline", "degree": 3, "points": [[0,0],[1,1],[2,2],[3,3]], "intervals": [0]})",
         "interval length must be positive"},
        {R"({"name": "b", "type": "bezier_spline", "degree": 3, "points": [[0,0],[1,1],[2,2],[3,3]], "intervals": [-1]})",
         "interval length must be positive"},
        {R"({"name": "b", "type": "deboor_spline", "degree": 3, "end": "open", "points": [[0,0],[1,1],[2,2]]})",
         "3 de Boor points are too few for end \"open\""},
        {R"({"name": "b", "type": "deboor_spline", "degree": 3, "end": "closed", "points": [[0,0],[1,1]]})",
         "too few"},
        {R"({"name": "b", "type": "deboor_spline", "degree": 3, "end": "clamped",
             "points": [[0,0],[1,1],[2,2],[3,3],[4,4]], "intervals": [1, 1, 1]})",
         "has 3 lengths for 2 segments"},
        {R"({"name": "b", "type": "deboor_spline", "degree": 3, "end": "closed",
             "points": [[0,0],[1,1],[2,2]], "intervals": [1, 0, 1]})",
         "interval length must be positive"},
        {R"({"name": "b", "type": "deboor_spline", "degree": 3, "end": "natural", "points": [[0,0],[1,1],[2,2],[3,3]]})",
         "\"natural\" is not one of"},
    };
    for (const auto& c : cases) {
        const std::string doc = document("spl_bad.json", c[0]);
        CAPTURE(c[0]);
        requireError(cli("eval " + freeform::test::shellQuote(doc) + " --object b --at 0"), 1, c[1]);
        requireError(cli("continuity " + freeform::test::shellQuote(doc) + " --object b"), 1, c[1]);
    }
    const std::string curve = document("spl_curve.json", R"({"name": "c", "type": "bezier_curve", "points": [[0,0],[1,1]]})");
    requireError(cli("continuity " + freeform::test::shellQuote(curve) + " --object c"), 1, "not a spline");
}

TEST_CASE("spline command help texts list every option", "[cli]")
{
    const auto c = cli("continuity --help");
    CHECK(c.status == 0);
    for (const char* option : {"--object", "--tolerance"}) CHECK(c.out.find(option) != std::string::npos);
    const auto i = cli("interpolate --help");
    CHECK(i.status == 0);
    for (const char* option : {"--output", "--end", "--param", "--start-derivative", "--end-derivative"})
        CHECK(i.out.find(option) != std::string::npos);
}

} // namespace test_cli_spline
