// freeform ffd DOC.json: Bézier curves, splines and patches of a document deformed exactly, checked
// against the trilinear map x + s t u d written out by hand (evaluated here by an independent de
// Casteljau); skipped objects, the report, and the errors.

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <Eigen/Core>

#include <filesystem>
#include <vector>

#include "support/cli.h"

namespace test_cli_ffd_document {

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
using V = Eigen::Vector3d;

namespace {

std::string tmp(const std::string& name)
{
    return std::string(FREEFORM_TEST_TMP) + "/" + name;
}

const V kD(0.25, -0.5, 1.0);

/// The unit-cube trilinear lattice with corner (1,1,1) moved by kD: x -> x + x y z kD inside.
std::string latticeDocument(const std::string& file, int degree = 1)
{
    Json points = Json::array();
    for (int i = 0; i <= degree; ++i)
        for (int j = 0; j <= degree; ++j)
            for (int k = 0; k <= degree; ++k) {
                V p(double(i) / degree, double(j) / degree, double(k) / degree);
                if (i == degree && j == degree && k == degree) p += kD;
                points.push_back({p.x(), p.y(), p.z()});
            }
    Json lat = {{"name", "L"}, {"type", "lattice"}, {"degree", {degree, degree, degree}}, {"origin", {0, 0, 0}},
                {"axes", {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}, {"points", points}, {"outside", "clamp"}};
    const std::string path = tmp(file);
    writeText(path, Json({{"format", "freeform"}, {"version", 1}, {"objects", {lat}}}).dump());
    return path;
}

V expected(const V& x)
{
    return x + x.x() * x.y() * x.z() * kD;
}

V point(const Json& p)
{
    return V(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
}

/// de Casteljau on JSON points [first, first + count).
V casteljau(const Json& pts, std::size_t first, std::size_t count, double t)
{
    std::vector<V> w;
    for (std::size_t i = 0; i < count; ++i) w.push_back(point(pts[first + i]));
    for (std::size_t r = 1; r < count; ++r)
        for (std::size_t i = 0; i + r < count; ++i) w[i] = (1 - t) * w[i] + t * w[i + 1];
    return w[0];
}

const char* kObjects = R"([
  {"name": "curve", "type": "bezier_curve", "points": [[0.1,0.2,0.3],[0.9,0.1,0.5],[0.5,0.9,0.9]]},
  {"name": "flat", "type": "bezier_curve", "points": [[0,0],[1,1]]},
  {"name": "patch", "type": "bezier_surface", "degree": [1, 2],
   "points": [[[0.1,0.1,0.2],[0.2,0.5,0.9],[0.1,0.9,0.3]], [[0.9,0.2,0.8],[0.8,0.6,0.1],[0.9,0.9,0.7]]]},
  {"name": "spline", "type": "bezier_spline", "degree": 2, "closed": false,
   "points": [[0.1,0.1,0.1],[0.5,0.2,0.9],[0.6,0.6,0.6],[0.7,1.0,0.3],[0.9,0.8,0.9]], "intervals": [1, 2]},
  {"name": "deboor", "type": "deboor_spline", "degree": 3, "end": "clamped",
   "points": [[0.1,0.1,0.1],[0.3,0.8,0.2],[0.6,0.3,0.9],[0.9,0.9,0.8],[0.7,0.2,0.4]]},
  {"name": "out", "type": "bezier_curve", "points": [[0.5,0.5,0.5],[1.5,0.5,0.5]]}
])";

Json deform(const std::string& tag, std::string& output)
{
    const std::string lat = latticeDocument(tag + "_lat.json");
    const std::string doc = tmp(tag + "_doc.json");
    writeText(doc, std::string(R"({"format": "freeform", "version": 1, "objects": )") + kObjects + "}");
    output = tmp(tag + "_out.json");
    const auto r = cli("ffd " + freeform::test::shellQuote(doc) + " --lattice " + freeform::test::shellQuote(lat) + " -o " + freeform::test::shellQuote(output) + " --report " + freeform::test::shellQuote(tmp(tag + "_report.json")));
    INFO(r.err);
    REQUIRE(r.status == 0);
    REQUIRE(r.err.empty());
    const Json report = Json::parse(r.out);
    CHECK(Json::parse(slurp(tmp(tag + "_report.json"))) == report);
    return report;
}

} // namespace

TEST_CASE("ffd on a document composes every 3D Bézier object with the lattice", "[cli]")
{
    std::string output;
    const Json report = deform("ffdoc", output);
    const Json doc = Json::parse(slurp(output));
    const Json& objects = doc["objects"];
    REQUIRE(objects.size() == 6);

    // The report: what was deformed, to which degree, and what was skipped.
    REQUIRE(report["objects"].size() == 5);
    CHECK(report["lattice"] == "L");
    CHECK(report["objects"][0] == Json({{"name", "curve"}, {"from", "bezier_curve"}, {"type", "bezier_curve"},
                                        {"degree", 6}, {"inside", true}}));
    CHECK(report["objects"][1]["degree"] == Json::array({3, 6}));
    CHECK(report["objects"][2]["degree"] == 6);
    CHECK(report["objects"][3]["from"] == "deboor_spline");
    CHECK(report["objects"][3]["type"] == "bezier_spline");
    CHECK(report["objects"][3]["degree"] == 9);
    CHECK(report["objects"][4]["name"] == "out");
    CHECK(report["objects"][4]["inside"] == false);
    REQUIRE(report["skipped"].size() == 1);
    CHECK(report["skipped"][0]["name"] == "flat");
    CHECK(report["certificate"]["verdict"] == "certified injective");

    // The curve: degree 2 (1+1+1) = 6, and it is the deformed curve at every parameter.
    const Json& curve = objects[0]["points"];
    REQUIRE(curve.size() == 7);
    const Json original = Json::parse(kObjects)[0]["points"];
    for (int i = 0; i <= 20; ++i) {
        const double t = i / 20.0;
        CHECK((casteljau(curve, 0, 7, t) - expected(casteljau(original, 0, 3, t))).norm() < 1e-14);
    }
    CHECK(objects[1] == Json::parse(kObjects)[1]); // 2D: copied unchanged

    // The patch: degrees (3, 6); evaluate by rows, then the column.
    const Json& patch = objects[2];
    CHECK(patch["degree"] == Json::array({3, 6}));
    REQUIRE(patch["points"].size() == 4); // rows i = 0..3 of 7 points each
    const Json p0 = Json::parse(kObjects)[2]["points"];
    for (int a = 0; a <= 8; ++a)
        for (int b = 0; b <= 8; ++b) {
            const double u = a / 8.0, v = b / 8.0;
            Json column = Json::array(), column0 = Json::array();
            for (int i = 0; i <= 3; ++i) {
                REQUIRE(patch["points"][i].size() == 7);
                const V x = casteljau(patch["points"][i], 0, 7, v);
                column.push_back({x.x(), x.y(), x.z()});
            }
            for (int i = 0; i <= 1; ++i) {
                const V x = casteljau(p0[i], 0, 3, v);
                column0.push_back({x.x(), x.y(), x.z()});
            }
            CHECK((casteljau(column, 0, 4, u) - expected(casteljau(column0, 0, 2, u))).norm() < 1e-14);
        }

    // The spline: two segments of degree 6 sharing the joint, same intervals.
    const Json& spline = objects[3];
    CHECK(spline["degree"] == 6);
    CHECK(spline["intervals"] == Json::array({1.0, 2.0}));
    REQUIRE(spline["points"].size() == 13);
    const Json s0 = Json::parse(kObjects)[3]["points"];
    for (int seg = 0; seg < 2; ++seg)
        for (int i = 0; i <= 10; ++i) {
            const double t = i / 10.0;
            const V got = casteljau(spline["points"], static_cast<std::size_t>(6 * seg), 7, t);
            CHECK((got - expected(casteljau(s0, static_cast<std::size_t>(2 * seg), 3, t))).norm() < 1e-14);
        }

    // The clamped de Boor spline became a Bézier spline of degree 9 starting and ending at the
    // deformed end de Boor points.
    const Json& db = objects[4];
    CHECK(db["type"] == "bezier_spline");
    CHECK(db["degree"] == 9);
    REQUIRE(db["points"].size() == 19);
    CHECK((point(db["points"][0]) - expected(V(0.1, 0.1, 0.1))).norm() < 1e-15);
    CHECK((point(db["points"][18]) - expected(V(0.7, 0.2, 0.4))).norm() < 1e-15);

    // The lattice object is not in this document; objects outside the box follow the polynomial.
    const Json& out = objects[5]["points"];
    REQUIRE(out.size() == 4);
    CHECK((point(out[3]) - expected(V(1.5, 0.5, 0.5))).norm() < 1e-14);
}

TEST_CASE("ffd on a document: bad usage and bad input", "[cli]")
{
    const std::string lat = latticeDocument("ffdbad_lat.json");
    const std::string doc = tmp("ffdbad_doc.json");
    writeText(doc, std::string(R"({"format": "freeform", "version": 1, "objects": )") + kObjects + "}");
    auto requireError = [](const freeform::test::ProcessResult& r, int status, const std::string& fragment) {
        INFO("stderr: " << r.err);
        CHECK(r.status == status);
        CHECK(r.out.empty());
        CHECK(r.err.rfind("error: ", 0) == 0);
        CHECK(r.err.find(fragment) != std::string::npos);
    };
    const std::string obj = tmp("ffdbad_out.obj"), json = tmp("ffdbad_out.json");
    std::filesystem::remove(obj);
    std::filesystem::remove(json);
    requireError(cli("ffd " + freeform::test::shellQuote(doc) + " --lattice " + freeform::test::shellQuote(lat) + " -o " + freeform::test::shellQuote(obj)), 2, "OUT.json");
    requireError(cli("ffd " + freeform::test::shellQuote(std::string(FREEFORM_SOURCE_DIR) + "/data/meshes/cube.obj") + " --lattice " + freeform::test::shellQuote(lat) + " -o " + freeform::test::shellQuote(json)), 2,
                 "not a document");
    requireError(cli("ffd " + freeform::test::shellQuote(doc) + " --lattice " + freeform::test::shellQuote(lat) + " -o " + freeform::test::shellQuote(json) + " --normals recompute"), 2, "meshes only");

    // A cubic lattice on a degree-8 curve: degree 72 is above the limit of 67.
    const std::string cubic = latticeDocument("ffdbad_cubic.json", 3);
    const std::string high = tmp("ffdbad_high.json");
    Json points = Json::array();
    for (int i = 0; i <= 8; ++i) points.push_back({i / 8.0, 0.5, 0.5});
    writeText(high, Json({{"format", "freeform"}, {"version", 1},
                          {"objects", {{{"name", "h"}, {"type", "bezier_curve"}, {"points", points}}}}})
                        .dump());
    requireError(cli("ffd " + freeform::test::shellQuote(high) + " --lattice " + freeform::test::shellQuote(cubic) + " -o " + freeform::test::shellQuote(json)), 1, "object \"h\"");
    const std::string broken = tmp("ffdbad_broken.json");
    writeText(broken, "{\"format\": \"freeform\", \"version\": 1, \"objects\": [");
    requireError(cli("ffd " + freeform::test::shellQuote(broken) + " --lattice " + freeform::test::shellQuote(lat) + " -o " + freeform::test::shellQuote(json)), 1, "ffdbad_broken.json");
    CHECK_FALSE(std::filesystem::exists(obj));
    CHECK_FALSE(std::filesystem::exists(json));
}

} // namespace test_cli_ffd_document
