// OBJ free-form geometry: round trips keep every number, the surface point order (u fastest) is
// checked against a hand-written file, and the strict reader names the line of every error.

#include <catch2/catch.hpp>

#include "freeform/io/obj_freeform.h"
#include "support/obj_errors.h"
#include "freeform/surface/bezier_surface.h"
#include "support/random.h"

namespace test_obj_freeform {

using namespace freeform;

namespace {
Document sampleDocument()
{
    Document doc;
    doc.source = "sample";
    doc.objects.push_back({"arc", BezierCurveData{test::randomPoints<double, 3>(4, 1)}, ""});
    BezierSplineData spline;
    spline.degree = 2;
    spline.points = test::randomPoints<double, 3>(7, 2);
    spline.intervals = {0.5, 2, 1.25};
    doc.objects.push_back({"spline", spline, ""});
    BezierSurfaceData patch;
    patch.degree = {2, 3};
    patch.points = test::randomPoints<double, 3>(12, 3);
    doc.objects.push_back({"patch", patch, ""});
    return doc;
}
} // namespace

TEST_CASE("document -> OBJ -> document keeps every object and number", "[obj]")
{
    const Document doc = sampleDocument();
    const std::string text = formatObjFreeform(doc);
    CHECK(text.find("cstype bezier") != std::string::npos);
    CHECK(text.find("deg 2 3") != std::string::npos);
    const Document back = parseObjFreeform(text, "back.obj");
    REQUIRE(back.objects.size() == 3);
    CHECK(back.objects[0].name == "arc");
    CHECK(std::get<BezierCurveData>(back.objects[0].data).points == std::get<BezierCurveData>(doc.objects[0].data).points);
    const auto& s = std::get<BezierSplineData>(back.objects[1].data);
    CHECK(s.degree == 2);
    CHECK_FALSE(s.closed);
    CHECK(s.points == std::get<BezierSplineData>(doc.objects[1].data).points);
    CHECK(s.intervals == std::vector<double>{0.5, 2, 1.25});
    const auto& p = std::get<BezierSurfaceData>(back.objects[2].data);
    CHECK(p.degree == std::array<int, 2>{2, 3});
    CHECK(p.points == std::get<BezierSurfaceData>(doc.objects[2].data).points);
    // And again: the text is stable.
    CHECK(formatObjFreeform(back) == text);
    // Only one object.
    const Document one = parseObjFreeform(formatObjFreeform(doc, "patch"));
    REQUIRE(one.objects.size() == 1);
    CHECK(one.objects[0].name == "patch");
    CHECK_THROWS_WITH(formatObjFreeform(doc, "nope"), Catch::Contains("nope"));
}

TEST_CASE("a hand-written OBJ patch: u varies fastest, relative indices, continuation lines", "[obj]")
{
    // A bilinear patch f(u, v) = (u, v, uv) given by 4 points in OBJ order (u fastest):
    // (0,0) (1,0) (0,1) (1,1).
    const std::string text = "# test\n"
                             "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 1\n"
                             "cstype bezier\ndeg 1 1\n"
                             "surf 0 1 0 1 -4 -3 \\\n -2 -1\n"
                             "parm u 0 1\nparm v 0 1\nend\n"
                             "f 1 2 3\n";
    const Document d = parseObjFreeform(text, "hand.obj");
    REQUIRE(d.objects.size() == 1);
    CHECK(d.objects[0].name == "surface1");
    const auto& s = std::get<BezierSurfaceData>(d.objects[0].data);
    const BezierSurface<double, 3> patch(1, 1, PointMatrix<double, 3>(s.points));
    CHECK((patch.evaluate(0.3, 0.8) - Eigen::Vector3d(0.3, 0.8, 0.3 * 0.8)).norm() < 1e-15);
    CHECK(patch.controlPoint(1, 0) == Eigen::Vector3d(1, 0, 0));
    CHECK(patch.controlPoint(0, 1) == Eigen::Vector3d(0, 1, 0));
}

TEST_CASE("2D curves are written with z = 0 and read back as 3D", "[obj]")
{
    Document doc;
    doc.objects.push_back({"c", BezierCurveData{test::randomPoints<double, 2>(3, 5)}, ""});
    const Document back = parseObjFreeform(formatObjFreeform(doc));
    const auto& p = std::get<BezierCurveData>(back.objects[0].data).points;
    REQUIRE(p.rows() == 3);
    CHECK(p.topRows(2) == std::get<BezierCurveData>(doc.objects[0].data).points);
    CHECK(p.row(2).isZero(0));
}

TEST_CASE("OBJ free-form errors name the line", "[obj][errors]")
{
    const std::string v4 = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 1\n";
    auto err = [](const std::string& text) { return test::objError(text); };
    // (Issue 13 made rat bezier and [rat] bspline supported: the other types are still refused.)
    CHECK(err(v4 + "cstype cardinal\n") ==
          "x.obj: line 5: curve type \"cardinal\" is not supported (bezier, rat bezier, bspline, rat bspline)");
    CHECK(err(v4 + "cstype rat taylor\n") ==
          "x.obj: line 5: curve type \"rat taylor\" is not supported (bezier, rat bezier, bspline, rat bspline)");
    CHECK(err(v4 + "deg 3\ncurv 0 1 1 2 3 4\nend\n") == "x.obj: line 6: curv before \"cstype bezier\"");
    CHECK(err(v4 + "cstype bezier\ndeg 2\ncurv 0 1 1 2 3 4\nend\n").find("line 7: 4 control points do not fit degree 2") !=
          std::string::npos);
    CHECK(err(v4 + "cstype bezier\ndeg 1\ncurv 0 1 1 5\nend\n") ==
          "x.obj: line 7: vertex index 5 is out of range (4 vertices so far)");
    CHECK(err(v4 + "cstype bezier\ndeg 3\ncurv 0 1 1 2 3 4\n") == "x.obj: line 7: curv element has no \"end\"");
    CHECK(err(v4 + "cstype bezier\ndeg 1 1\nsurf 0 1 0 1 1 2 3\nend\n").find("line 7: 3 control points do not fit degree (1, 1)") !=
          std::string::npos);
    CHECK(err(v4 + "cstype bezier\ndeg 3\ncurv 0 1 1 2 3 4\ntrim 0 1 1\nend\n") ==
          "x.obj: line 8: trim outside a surf element");
    CHECK(err(v4 + "cstype bezier\ndeg 1\ncurv 0 2 1 2 3\nparm u 0 1\nend\n") ==
          "x.obj: line 9: parm u has 2 values, 2 segments need 3");
    CHECK(err(v4 + "cstype bezier\ndeg 1\ncurv 0 2 1 2 3\nparm u 0 1 1\n").find("line 8: parm values must increase") !=
          std::string::npos);
    CHECK(err("v 0 0 zz\n") == "x.obj: line 1: \"zz\" is not a finite number");
    CHECK(err("frobnicate 1\n") == "x.obj: line 1: unknown statement \"frobnicate\"");
    CHECK(err("end\n") == "x.obj: line 1: end without a curv, curv2 or surf element");
    CHECK(err(v4 + "cstype bezier\ndeg 0\n") == "x.obj: line 6: degree 0 is outside 1..67");
}

TEST_CASE("objects without an OBJ free-form form are refused by name", "[obj][errors]")
{
    Document doc;
    doc.source = "d.json";
    BezierSplineData closed;
    closed.closed = true;
    closed.points = test::randomPoints<double, 3>(6, 1);
    doc.objects.push_back({"ring", closed, ""});
    CHECK_THROWS_WITH(formatObjFreeform(doc), Catch::Contains("d.json: object \"ring\": a closed bezier_spline"));
    doc.objects.clear();
    doc.objects.push_back({"g", DeBoorSurfaceData{}, ""});
    CHECK_THROWS_WITH(formatObjFreeform(doc), Catch::Contains("type deboor_surface has no OBJ free-form form"));
}

} // namespace test_obj_freeform
