// The command-line contract for surfaces: `eval` of bezier_surface / deboor_surface, `tessellate`
// (document or .bpt to OBJ with v, vt, vn, f v/vt/vn) and `convert` to and from OBJ free-form.

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "support/cli.h"
#include "support/cli_errors.h"

namespace test_cli_surface {

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

const std::string kTeapot = std::string(FREEFORM_SOURCE_DIR) + "/data/teapot.bpt";

/// f(u, v) = (u, v, uv) as a bilinear bezier_surface, and a 4 x 4 open de Boor grid z = x^2.
std::string surfaceDoc()
{
    const std::string path = tmp("cli_surface.json");
    std::string grid = "[";
    for (int r = 0; r < 4; ++r) {
        grid += r ? ",[" : "[";
        for (int c = 0; c < 4; ++c) {
            if (c) grid += ',';
            grid += '[';
            grid += std::to_string(r);
            grid += ',';
            grid += std::to_string(c);
            grid += ',';
            grid += std::to_string(r * r);
            grid += ']';
        }
        grid += "]";
    }
    grid += "]";
    writeText(path, R"({"format": "freeform", "version": 1, "objects": [
        {"name": "p", "type": "bezier_surface", "degree": [1, 1], "points": [[[0,0,0],[0,1,0]],[[1,0,0],[1,1,1]]]},
        {"name": "g", "type": "deboor_surface", "degree": [3, 3], "end": ["open", "open"], "points": )" + grid + R"(},
        {"name": "c", "type": "bezier_curve", "points": [[0,0],[1,1]]}]})");
    return path;
}

std::vector<std::string> linesStarting(const std::string& text, const std::string& prefix)
{
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (line.rfind(prefix, 0) == 0) out.push_back(line);
    return out;
}
} // namespace

TEST_CASE("eval of a bezier_surface: point, normal and derivatives up to K", "[cli][surface]")
{
    const auto r = cli("eval " + freeform::test::shellQuote(surfaceDoc()) + " --object p --at 0.25,0.5 --derivatives 2");
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(r.out.rfind(R"({"object":"p","u":0.25,"v":0.5,"point":[0.25,0.5,0.125],"normal":)", 0) == 0);
    const Json j = Json::parse(r.out);
    const double w = std::sqrt(1 + 0.25 * 0.25 + 0.5 * 0.5);
    CHECK(j["normal"][0].get<double>() == Approx(-0.5 / w).epsilon(1e-15));
    CHECK(j["normal"][1].get<double>() == Approx(-0.25 / w).epsilon(1e-15));
    CHECK(j["normal"][2].get<double>() == Approx(1 / w).epsilon(1e-15));
    const Json& d = j["derivatives"];
    REQUIRE(d.size() == 5);
    CHECK(d["u"] == Json::array({1.0, 0.0, 0.5}));
    CHECK(d["v"] == Json::array({0.0, 1.0, 0.25}));
    CHECK(d["uu"] == Json::array({0.0, 0.0, 0.0}));
    CHECK(d["uv"] == Json::array({0.0, 0.0, 1.0}));
    CHECK(d["vv"] == Json::array({0.0, 0.0, 0.0}));
    // Keys in the documented order.
    CHECK(r.out.find(R"("derivatives":{"u":)") != std::string::npos);
    CHECK(r.out.find(R"("uu":[0.0,0.0,0.0],"uv":)") != std::string::npos);
    const auto r3 = cli("eval " + freeform::test::shellQuote(surfaceDoc()) + " --object p --at 0.25,0.5 --derivatives 3");
    const Json j3 = Json::parse(r3.out);
    for (const char* key : {"uuu", "uuv", "uvv", "vvv"}) CHECK(j3["derivatives"].contains(key));
    CHECK(Json::parse(cli("eval " + freeform::test::shellQuote(surfaceDoc()) + " --object p --at 1,1").out).contains("derivatives") == false);
}

TEST_CASE("eval of a deboor_surface: the uniform bicubic B-spline", "[cli][surface]")
{
    // Grid point (r, c) = (r, c, r^2); the B-spline reproduces quadratics: at (s, t) in the only
    // patch, x = 1 + s, y = 1 + t, z = x^2 + 1/3 (the B-spline of r^2 is x^2 + 1/3).
    const auto r = cli("eval " + freeform::test::shellQuote(surfaceDoc()) + " --object g --at 0.5,0.25 --derivatives 1");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const Json j = Json::parse(r.out);
    CHECK(j["point"][0].get<double>() == Approx(1.5).epsilon(1e-15));
    CHECK(j["point"][1].get<double>() == Approx(1.25).epsilon(1e-15));
    CHECK(j["point"][2].get<double>() == Approx(1.5 * 1.5 + 1.0 / 3).epsilon(1e-14));
    CHECK(j["derivatives"]["u"][2].get<double>() == Approx(3.0).epsilon(1e-14));
    requireError(cli("eval " + freeform::test::shellQuote(surfaceDoc()) + " --object g --at 1.5,0.5"), 1, "outside the surface's domain [0, 1]");
}

TEST_CASE("eval of surfaces: bad usage and bad input", "[cli][surface][errors]")
{
    requireError(cli("eval " + freeform::test::shellQuote(surfaceDoc()) + " --object p --at 0.5"), 2, "expected 2 comma-separated numbers");
    requireError(cli("eval " + freeform::test::shellQuote(surfaceDoc()) + " --object p --at 0.5,x"), 2, "not a finite number");
    requireError(cli("eval " + freeform::test::shellQuote(surfaceDoc()) + " --object p --at 0.5,1.01"), 1, "outside");
    const std::string bad = tmp("cli_surface_bad.json");
    writeText(bad, R"({"format": "freeform", "version": 1, "objects": [
        {"name": "g", "type": "deboor_surface", "degree": [3, 3], "end": ["open", "closed"],
         "points": [[[0,0,0],[1,0,0],[2,0,0]],[[0,1,0],[1,1,0],[2,1,0]],[[0,2,0],[1,2,0],[2,2,0]]]}]})");
    requireError(cli("eval " + freeform::test::shellQuote(bad) + " --object g --at 0.5,0.5"), 1, "3 rows are too few for end condition \"open\"");
}

TEST_CASE("tessellate the teapot .bpt into an OBJ with v, vt, vn and f v/vt/vn", "[cli][tessellate]")
{
    const std::string out = tmp("cli_teapot.obj");
    std::filesystem::remove(out);
    const auto r = cli("tessellate " + freeform::test::shellQuote(kTeapot) + " -o " + freeform::test::shellQuote(out) + " --tolerance 0.01 --outward");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const Json j = Json::parse(r.out);
    CHECK(j["patches"] == 32);
    CHECK(j["error_bound"].get<double>() <= 0.01);
    const std::string text = slurp(out);
    const auto v = linesStarting(text, "v "), vt = linesStarting(text, "vt "), vn = linesStarting(text, "vn "),
               f = linesStarting(text, "f ");
    CHECK(static_cast<long>(v.size()) == j["vertices"].get<long>());
    CHECK(vt.size() == v.size());
    CHECK(vn.size() == v.size());
    CHECK(static_cast<long>(f.size()) == j["triangles"].get<long>());
    // f a/a/a b/b/b c/c/c
    std::istringstream first(f.front());
    std::string tag, corner;
    first >> tag;
    int corners = 0;
    while (first >> corner) {
        ++corners;
        const auto a = corner.substr(0, corner.find('/'));
        CHECK(corner == a + "/" + a + "/" + a);
    }
    CHECK(corners == 3);
    // --segments 2: 32 patches of 2 x 2 cells, welded.
    const auto r2 = cli("tessellate " + freeform::test::shellQuote(kTeapot) + " -o " + freeform::test::shellQuote(out) + " --segments 2");
    REQUIRE(r2.status == 0);
    CHECK(Json::parse(r2.out)["triangles"].get<long>() <= 32 * 8);
}

TEST_CASE("tessellate a document: all surfaces or --object", "[cli][tessellate]")
{
    const std::string out = tmp("cli_doc.obj");
    const auto all = cli("tessellate " + freeform::test::shellQuote(surfaceDoc()) + " -o " + freeform::test::shellQuote(out) + " --segments 3");
    INFO(all.err);
    REQUIRE(all.status == 0);
    CHECK(Json::parse(all.out)["patches"] == 2);
    CHECK(Json::parse(all.out)["triangles"] == 36);
    const auto one = cli("tessellate " + freeform::test::shellQuote(surfaceDoc()) + " --object p -o " + freeform::test::shellQuote(out) + " --segments 3");
    REQUIRE(one.status == 0);
    CHECK(Json::parse(one.out)["vertices"] == 16);
    requireError(cli("tessellate " + freeform::test::shellQuote(surfaceDoc()) + " --object c -o " + freeform::test::shellQuote(out)), 1, "is not a surface");
}

TEST_CASE("tessellate: bad usage exits 2, bad input 1, no output left behind", "[cli][tessellate][errors]")
{
    const std::string out = tmp("cli_never.obj");
    std::filesystem::remove(out);
    requireError(cli("tessellate " + freeform::test::shellQuote(kTeapot)), 2, "--output is required");
    requireError(cli("tessellate " + freeform::test::shellQuote(kTeapot) + " -o " + freeform::test::shellQuote(out) + " --tolerance 1e-3 --segments 4"), 2, "either --tolerance or --segments");
    requireError(cli("tessellate " + freeform::test::shellQuote(kTeapot) + " -o " + freeform::test::shellQuote(out) + " --segments 0"), 2, "--segments");
    requireError(cli("tessellate " + freeform::test::shellQuote(kTeapot) + " -o " + freeform::test::shellQuote(out) + " --tolerance -1"), 2, "positive");
    requireError(cli("tessellate " + freeform::test::shellQuote(kTeapot) + " -o " + freeform::test::shellQuote(tmp("x.ply"))), 2, ".obj");
    requireError(cli("tessellate " + freeform::test::shellQuote(kTeapot) + " -o " + freeform::test::shellQuote(out) + " --object x"), 2, "--object");
    requireError(cli("tessellate " + freeform::test::shellQuote(tmp("missing.bpt")) + " -o " + freeform::test::shellQuote(out)), 1, "missing.bpt");
    const std::string bad = tmp("cli_bad.bpt");
    writeText(bad, "1\n3 3\n0 0 0\n");
    requireError(cli("tessellate " + freeform::test::shellQuote(bad) + " -o " + freeform::test::shellQuote(out)), 1, "patch 0 ends after 1 of 16 points");
    writeText(bad, "1\n1 1\n0 0 0\n1 0 0\n0 1 0 7\n1 1 1\n");
    requireError(cli("tessellate " + freeform::test::shellQuote(bad) + " -o " + freeform::test::shellQuote(out)), 1, "line 5");
    const std::string curves = tmp("cli_curves.json");
    writeText(curves, R"({"format": "freeform", "version": 1, "objects": [{"name": "c", "type": "bezier_curve", "points": [[0,0],[1,1]]}]})");
    requireError(cli("tessellate " + freeform::test::shellQuote(curves) + " -o " + freeform::test::shellQuote(out)), 1, "no surface objects");
    CHECK_FALSE(std::filesystem::exists(out));
    // A failing run leaves an existing output untouched.
    writeText(out, "keep");
    requireError(cli("tessellate " + freeform::test::shellQuote(bad) + " -o " + freeform::test::shellQuote(out)), 1, "line 5");
    CHECK(slurp(out) == "keep");
}

TEST_CASE("convert a document to OBJ free-form and back", "[cli][convert]")
{
    const std::string obj = tmp("cli_conv.obj"), back = tmp("cli_conv.json");
    const auto r = cli("convert " + freeform::test::shellQuote(surfaceDoc()) + " --object p -o " + freeform::test::shellQuote(obj));
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(Json::parse(r.out)["objects"] == Json::array({"p"}));
    CHECK(slurp(obj).find("surf 0 1 0 1 1 2 3 4") != std::string::npos);
    const auto r2 = cli("convert " + freeform::test::shellQuote(obj) + " -o " + freeform::test::shellQuote(back));
    INFO(r2.err);
    REQUIRE(r2.status == 0);
    const auto e = cli("eval " + freeform::test::shellQuote(back) + " --object p --at 0.25,0.5");
    REQUIRE(e.status == 0);
    CHECK(Json::parse(e.out)["point"] == Json::array({0.25, 0.5, 0.125}));
    // The de Boor surface has no OBJ free-form form: named, exit 1.
    requireError(cli("convert " + freeform::test::shellQuote(surfaceDoc()) + " -o " + freeform::test::shellQuote(obj)), 1, "object \"g\": type deboor_surface");
    requireError(cli("convert " + freeform::test::shellQuote(surfaceDoc()) + " -o " + freeform::test::shellQuote(tmp("x.txt"))), 2, "from .json to .obj");
    const std::string broken = tmp("cli_broken.obj");
    writeText(broken, "v 0 0 0\ncstype bezier\ndeg 1\ncurv 0 1 1 9\nend\n");
    requireError(cli("convert " + freeform::test::shellQuote(broken) + " -o " + freeform::test::shellQuote(back)), 1, "line 4: vertex index 9 is out of range");
}

} // namespace test_cli_surface
