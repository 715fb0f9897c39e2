// The v1 document: strict parsing with messages that name the object and field, and a lossless
// write/read round trip.

#include <catch2/catch.hpp>

#include <freeform/io/document.h>

#include <filesystem>

#include "support/process.h"

namespace test_document {

using namespace freeform;

namespace {
std::string doc(const std::string& objects)
{
    return R"({"format": "freeform", "version": 1, "objects": [)" + objects + "]}";
}
} // namespace

TEST_CASE("a curve document parses", "[document]")
{
    const Document d = parseDocument(doc(R"({"name": "c", "type": "bezier_curve", "points": [[0,0],[1,2],[3,2],[4,0]]})"));
    REQUIRE(d.objects.size() == 1);
    const auto& c = std::get<BezierCurveData>(d.object("c").data);
    REQUIRE(c.points.rows() == 2);
    REQUIRE(c.points.cols() == 4);
    CHECK(c.points(1, 1) == 2.0);
    CHECK(objectType(d.object("c").data) == "bezier_curve");
    CHECK_THROWS_WITH(d.object("x"), Catch::Contains("no object named \"x\"") && Catch::Contains("objects: c"));
}

TEST_CASE("every kind of bad document is an error naming object and field", "[document][errors]")
{
    using Catch::Contains;
    CHECK_THROWS_WITH(parseDocument("{", "a.json"), Contains("a.json: line 1: not valid JSON"));
    CHECK_THROWS_WITH(parseDocument("[1]"), Contains("top level"));
    CHECK_THROWS_WITH(parseDocument(R"({"format": "other", "version": 1, "objects": []})"), Contains("\"format\""));
    CHECK_THROWS_WITH(parseDocument(R"({"format": "freeform", "version": 2, "objects": []})"), Contains("version 2"));
    CHECK_THROWS_WITH(parseDocument(R"({"format": "freeform", "objects": []})"), Contains("\"version\": is missing"));
    CHECK_THROWS_WITH(parseDocument(R"({"format": "freeform", "version": 1, "objects": [], "extra": 1})"),
                      Contains("\"extra\": unknown field"));
    CHECK_THROWS_WITH(parseDocument(doc(R"({"name": "c", "type": "nurbs", "points": [[0,0]]})")),
                      Contains("object \"c\"") && Contains("unknown object type \"nurbs\""));
    CHECK_THROWS_WITH(parseDocument(doc(R"({"name": "c", "type": "bezier_curve", "points": [[0,0],[1,2,3]]})")),
                      Contains("object \"c\"") && Contains("points[1]") && Contains("expected 2 coordinates, found 3"));
    CHECK_THROWS_WITH(parseDocument(doc(R"({"name": "c", "type": "bezier_curve", "points": [[0]]})")),
                      Contains("2 or 3 coordinates"));
    CHECK_THROWS_WITH(parseDocument(doc(R"({"name": "c", "type": "bezier_curve", "points": []})")), Contains("no points"));
    CHECK_THROWS_WITH(parseDocument(doc(R"({"name": "c", "type": "bezier_curve", "points": [[0,"x"]]})")),
                      Contains("points[0][1]") && Contains("expected a number"));
    CHECK_THROWS_WITH(parseDocument(doc(R"({"name": "c", "type": "bezier_curve", "points": [[0,1e999]]})")),
                      Contains("out of range") && Contains("1e999"));
    CHECK_THROWS_WITH(parseDocument(doc(R"({"name": "c", "type": "bezier_curve", "points": [[0,0]], "color": 1})")),
                      Contains("\"color\": unknown field"));
    CHECK_THROWS_WITH(parseDocument(doc(R"({"type": "bezier_curve", "points": [[0,0]]})")),
                      Contains("object 0") && Contains("\"name\": is missing"));
    CHECK_THROWS_WITH(parseDocument(doc(R"({"name": "c", "type": "bezier_curve", "points": [[0,0]]},
                                           {"name": "c", "type": "bezier_curve", "points": [[0,0]]})")),
                      Contains("used by an earlier object"));
    CHECK_THROWS_WITH(parseDocument(doc(R"({"name": "s", "type": "bezier_spline", "degree": 3, "points": [[0,0],[1,1],[2,2]]})")),
                      Contains("3 points do not fit degree 3"));
    CHECK_THROWS_WITH(parseDocument(doc(R"({"name": "s", "type": "bezier_spline", "degree": 3,
                                            "points": [[0,0],[1,1],[2,2],[3,3]], "intervals": [0]})")),
                      Contains("intervals[0]") && Contains("positive"));
    CHECK_THROWS_WITH(parseDocument(doc(R"({"name": "d", "type": "deboor_spline", "degree": 3, "end": "loose",
                                            "points": [[0,0],[1,1],[2,2],[3,3]]})")),
                      Contains("\"loose\" is not one of"));
    CHECK_THROWS_WITH(parseDocument(doc(R"({"name": "p", "type": "bezier_surface", "degree": [1, 1],
                                            "points": [[[0,0,0],[1,0,0]]]})")),
                      Contains("grid is 1 x 2"));
    CHECK_THROWS_WITH(parseDocument(doc(R"({"name": "L", "type": "lattice", "degree": [1,1,1], "origin": [0,0,0],
                                            "axes": [[1,0,0],[0,1,0],[0,0,1]], "points": [[0,0,0]]})")),
                      Contains("has 1 points, degree needs 8"));
}

TEST_CASE("write then read gives the same document and the same text", "[document]")
{
    const std::string text = doc(R"({"name": "c", "type": "bezier_curve", "points": [[0.1,0],[1,2e-300],[3,2],[4,0.30000000000000004]]},
        {"name": "s", "type": "bezier_spline", "degree": 2, "closed": false, "points": [[0,0],[1,1],[2,0],[3,1],[4,0]], "intervals": [1, 2.5]},
        {"name": "L", "type": "lattice", "degree": [1,1,1], "origin": [0,0,0], "axes": [[1,0,0],[0,2,0],[0,0,3]],
         "points": [[0,0,0],[0,0,3],[0,2,0],[0,2,3],[1,0,0],[1,0,3],[1,2,0],[1,2,3]], "outside": "keep",
         "editor": {"visible": false}})");
    const Document a = parseDocument(text);
    const std::string once = formatDocument(a);
    const Document b = parseDocument(once);
    CHECK(formatDocument(b) == once);
    const auto& c = std::get<BezierCurveData>(b.object("c").data);
    CHECK(c.points(0, 0) == 0.1);
    CHECK(c.points(1, 1) == 2e-300);
    CHECK(c.points(1, 3) == 0.30000000000000004);
    CHECK(std::get<BezierSplineData>(b.object("s").data).intervals == std::vector<double>{1, 2.5});
    CHECK(std::get<LatticeData>(b.object("L").data).outside == OutsidePolicy::Keep);
    CHECK(b.object("L").editor == R"({"visible":false})");
}

TEST_CASE("atomic writes leave the old file when writing fails", "[document][io]")
{
    namespace fs = std::filesystem;
    const std::string dir = std::string(FREEFORM_TEST_TMP) + "/atomic";
    fs::create_directories(dir);
    const std::string path = dir + "/doc.json";
    writeFileAtomically(path, "first");
    CHECK(freeform::test::slurp(path) == "first");
    CHECK_THROWS_AS(writeFileAtomicallyWith(path, [](std::ostream&) { throw Error("disk on fire"); }), Error);
    CHECK(freeform::test::slurp(path) == "first");
    // No temporary file is left behind.
    int files = 0;
    for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file();
    CHECK(files == 1);
    CHECK_THROWS_WITH(readDocument(dir + "/missing.json"), Catch::Contains("missing.json: cannot open"));
}

} // namespace test_document
