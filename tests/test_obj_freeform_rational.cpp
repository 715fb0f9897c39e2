// OBJ free-form rational Bézier and B-spline (NURBS) geometry (issue 13): a hand-written quadratic
// NURBS circle lies on the unit circle, a hand-written bilinear B-spline patch evaluates to a known
// function (checks u varies fastest and the grid size comes from the knot counts), round trips keep
// every number and the text, and the strict reader names the line of every error.

#include <catch2/catch.hpp>

#include <cmath>

#include "freeform/curve/nurbs_curve.h"
#include "freeform/io/obj_freeform.h"
#include "support/obj_errors.h"
#include "freeform/surface/nurbs_surface.h"
#include "support/random.h"

namespace test_obj_freeform_rational {

using namespace freeform;

namespace {

// The 9-point quadratic NURBS unit circle (corner weights cos 45 degrees), as a user would type it:
// weights as the 4th coordinate of v, the knot vector in parm u, curv over the whole domain [0, 4].
const std::string kCircle = "# unit circle\n"
                            "v 1 0 0\nv 1 1 0 0.7071067811865476\nv 0 1 0 1\nv -1 1 0 0.7071067811865476\n"
                            "v -1 0 0\nv -1 -1 0 0.7071067811865476\nv 0 -1 0\nv 1 -1 0 0.7071067811865476\nv 1 0 0\n"
                            "o circle\ncstype rat bspline\ndeg 2\n"
                            "curv 0 4 1 2 3 4 5 6 7 8 9\n"
                            "parm u 0 0 0 1 1 2 2 3 3 4 4 4\n"
                            "end\n";

std::string err(const std::string& text) { return test::objError(text); }

} // namespace

TEST_CASE("a hand-written rational B-spline circle lies on the unit circle", "[obj][nurbs]")
{
    const Document d = parseObjFreeform(kCircle, "circle.obj");
    REQUIRE(d.objects.size() == 1);
    CHECK(d.objects[0].name == "circle");
    const auto& c = std::get<NurbsCurveData>(d.objects[0].data);
    CHECK(c.degree == 2);
    CHECK(c.knots == std::vector<double>{0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4});
    REQUIRE(c.weights.size() == 9);
    CHECK(c.weights[0] == 1.0);
    CHECK(c.weights[1] == 0.7071067811865476);
    CHECK(c.weights[2] == 1.0); // written explicitly as "v 0 1 0 1"
    const NurbsCurve<double, 3> curve(c.degree, c.knots, PointMatrix<double, 3>(c.points),
                                      Eigen::Map<const Eigen::VectorXd>(c.weights.data(), 9));
    double worst = 0;
    for (int k = 0; k <= 400; ++k) {
        const double u = 4.0 * k / 400;
        const Eigen::Vector3d p = curve.evaluate(u);
        worst = std::max(worst, std::abs(p.head<2>().norm() - 1.0));
        CHECK(p.z() == 0.0);
    }
    CHECK(worst < 1e-15);
    // Symmetry: the middle of each quarter is at 45 degrees, and the knots hit the axes.
    const Eigen::Vector3d mid = curve.evaluate(0.5);
    CHECK(std::abs(mid.x() - mid.y()) < 1e-15);
    CHECK((curve.evaluate(1.0) - Eigen::Vector3d(0, 1, 0)).norm() < 1e-15);
    CHECK((curve.evaluate(2.0) - Eigen::Vector3d(-1, 0, 0)).norm() < 1e-15);
    // Written back: rat bspline, the weights as 4th coordinates, and the text is stable.
    const std::string text = formatObjFreeform(d);
    CHECK(text.find("cstype rat bspline\ndeg 2\ncurv 0 4 1 2 3 4 5 6 7 8 9\nparm u 0 0 0 1 1 2 2 3 3 4 4 4\nend\n") !=
          std::string::npos);
    CHECK(text.find("v 1 1 0 0.7071067811865476\n") != std::string::npos);
    CHECK(formatObjFreeform(parseObjFreeform(text)) == text);
}

TEST_CASE("a piecewise rational Bézier curve becomes a NURBS curve with double interior knots", "[obj][nurbs]")
{
    // Two quarter circles joined at (0, 1), segment ends 0 1 2 (parm u).
    const std::string text = "v 1 0 0\nv 1 1 0 0.7071067811865476\nv 0 1 0\nv -1 1 0 0.7071067811865476\nv -1 0 0\n"
                             "cstype rat bezier\ndeg 2\ncurv 0 2 1 2 3 4 5\nparm u 0 1 2\nend\n";
    const Document d = parseObjFreeform(text, "half.obj");
    const auto& c = std::get<NurbsCurveData>(d.objects[0].data);
    CHECK(c.knots == std::vector<double>{0, 0, 0, 1, 1, 2, 2, 2});
    const NurbsCurve<double, 3> curve(2, c.knots, PointMatrix<double, 3>(c.points),
                                      Eigen::Map<const Eigen::VectorXd>(c.weights.data(), 5));
    for (double u : {0.1, 0.5, 0.9, 1.3, 1.77})
        CHECK(std::abs(curve.evaluate(u).head<2>().norm() - 1.0) < 1e-15);
    // A single rational segment is a rational_bezier_curve.
    const Document one =
        parseObjFreeform("v 1 0 0\nv 1 1 0 0.7071067811865476\nv 0 1 0\ncstype rat bezier\ndeg 2\ncurv 0 1 1 2 3\nend\n");
    const auto& q = std::get<RationalBezierCurveData>(one.objects[0].data);
    CHECK(q.weights == std::vector<double>{1, 0.7071067811865476, 1});
}

TEST_CASE("a piecewise rational Bézier surface (parm u and v with the patch ends) becomes a NURBS surface", "[obj][nurbs]")
{
    // Half a cylinder of radius 1: two quarter circles in u (patch ends 0 0.5 2), two linear pieces
    // in v (ends 0 1 3, heights z 0 1 3, so z = v). 5 x 3 points listed u fastest.
    const double h = 0.7071067811865476;
    const double x[5] = {1, 1, 0, -1, -1}, y[5] = {0, 1, 1, 1, 0}, w[5] = {1, h, 1, h, 1}, z[3] = {0, 1, 3};
    const std::string text =
        "v 1 0 0 1\nv 1 1 0 0.7071067811865476\nv 0 1 0 1\n"
        "v -1 1 0 0.7071067811865476\nv -1 0 0 1\nv 1 0 1 1\n"
        "v 1 1 1 0.7071067811865476\nv 0 1 1 1\nv -1 1 1 0.7071067811865476\n"
        "v -1 0 1 1\nv 1 0 3 1\nv 1 1 3 0.7071067811865476\n"
        "v 0 1 3 1\nv -1 1 3 0.7071067811865476\nv -1 0 3 1\n"
        "o halfcyl\ncstype rat bezier\ndeg 2 1\nsurf 0 2 0 3 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15\n"
        "parm u 0 0.5 2\nparm v 0 1 3\nend\n";
    const Document d = parseObjFreeform(text, "halfcyl.obj");
    REQUIRE(d.objects.size() == 1);
    const auto& s = std::get<NurbsSurfaceData>(d.objects[0].data);
    CHECK(s.degree == std::array<int, 2>{2, 1});
    CHECK(s.rows == 5);
    CHECK(s.cols == 3);
    CHECK(s.knots[0] == std::vector<double>{0, 0, 0, 0.5, 0.5, 2, 2, 2});
    CHECK(s.knots[1] == std::vector<double>{0, 0, 1, 3, 3});
    // Value for value: point (i, j) and its weight where the file put them.
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 3; ++j) {
            CHECK(s.points.col(i * 3 + j) == Eigen::Vector3d(x[i], y[i], z[j]));
            CHECK(s.weights[static_cast<std::size_t>(i * 3 + j)] == w[i]);
        }
    const NurbsSurface<double, 3> surface(2, 1, s.knots[0], s.knots[1], PointMatrix<double, 3>(s.points),
                                          Eigen::Map<const Eigen::VectorXd>(s.weights.data(), 15));
    for (double u : {0.0, 0.2, 0.5, 0.9, 1.4, 2.0})
        for (double v : {0.0, 0.4, 1.0, 2.2, 3.0}) {
            const Eigen::Vector3d p = surface.evaluate(u, v);
            CHECK(std::abs(p.head<2>().norm() - 1.0) <= 1e-15);
            CHECK(std::abs(p.z() - v) <= 1e-15 * 3);
            CHECK(p.y() >= 0);
        }
    // Patch (1, 1) on its own, as a rational Bézier patch in local parameters, against the NURBS.
    PointMatrix<double, 3> pts(3, 6);
    Eigen::VectorXd pw(6);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 2; ++j) {
            pts.col(i * 2 + j) = Eigen::Vector3d(x[2 + i], y[2 + i], z[1 + j]);
            pw[i * 2 + j] = w[2 + i];
        }
    const RationalBezierSurface<double, 3> patch(2, 1, pts, pw);
    for (double a : {0.0, 0.3, 0.8})
        for (double b : {0.1, 0.6, 1.0})
            CHECK((patch.evaluate(a, b) - surface.evaluate(0.5 + 1.5 * a, 1 + 2 * b)).norm() <= 1e-15 * 4);
    // The tool writes it as the same nurbs_surface (cstype rat bspline); that file round trips byte for byte.
    const std::string written = formatObjFreeform(d);
    CHECK(written.find("cstype rat bspline\ndeg 2 1\n") != std::string::npos);
    const Document back = parseObjFreeform(written, "back.obj");
    const auto& s2 = std::get<NurbsSurfaceData>(back.objects[0].data);
    CHECK(s2.knots == s.knots);
    CHECK(s2.points == s.points);
    CHECK(s2.weights == s.weights);
    CHECK(formatObjFreeform(back) == written);
    // A polynomial piecewise Bézier surface is read the same way, without weights.
    const std::string poly = "v 0 0 0\nv 1 0 0\nv 2 0 1\nv 0 1 0\nv 1 1 0\nv 2 1 1\n"
                       "cstype bezier\ndeg 1 1\nsurf 0 2 0 1 1 2 3 4 5 6\nparm u 0 1 2\nparm v 0 1\nend\n";
    const Document polyDoc = parseObjFreeform(poly);
    const auto& ps = std::get<NurbsSurfaceData>(polyDoc.objects[0].data);
    CHECK(ps.weights.empty());
    CHECK(ps.knots[0] == std::vector<double>{0, 0, 1, 2, 2});
    CHECK(ps.points.col(2 * 2 + 1) == Eigen::Vector3d(2, 1, 1));
    // A count that does not fit the patches the parm lists give is refused with the line.
    CHECK(err("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\ncstype rat bezier\ndeg 1 1\nsurf 0 2 0 1 1 2 3 4 5\n"
              "parm u 0 1 2\nparm v 0 1\nend\n")
              .find("line 8: 5 control points do not fit 2 x 1 patches of degree (1, 1)") != std::string::npos);
}

TEST_CASE("a hand-written bilinear B-spline patch: u varies fastest, the grid from the knot counts", "[obj][nurbs]")
{
    // 3 x 2 points P(i, j) = (i, j, i j) with knots u 0 0 1 2 2 (x = u exactly: the Greville
    // abscissae are 0 1 2) and v 0 0 1 1, so the surface is (u, v, u v). Listed u fastest.
    const std::string text = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 1\nv 2 1 2\n"
                             "cstype bspline\ndeg 1 1\nsurf 0 2 0 1 1 2 3 4 5 6\n"
                             "parm u 0 0 1 2 2\nparm v 0 0 1 1\nend\n";
    const Document d = parseObjFreeform(text, "grid.obj");
    const auto& s = std::get<NurbsSurfaceData>(d.objects[0].data);
    CHECK(s.rows == 3);
    CHECK(s.cols == 2);
    CHECK(s.weights.empty());
    const NurbsSurface<double, 3> surface(1, 1, s.knots[0], s.knots[1], PointMatrix<double, 3>(s.points));
    CHECK(surface.controlPoint(2, 1) == Eigen::Vector3d(2, 1, 2));
    CHECK(surface.controlPoint(1, 0) == Eigen::Vector3d(1, 0, 0));
    for (double u : {0.0, 0.3, 1.5, 2.0})
        for (double v : {0.0, 0.25, 1.0})
            CHECK((surface.evaluate(u, v) - Eigen::Vector3d(u, v, u * v)).norm() < 1e-15);
    // A non-rational B-spline is written as cstype bspline, 3 coordinates per vertex, byte for byte.
    const std::string back = formatObjFreeform(d);
    CHECK(back.find("v 2 1 2\n") != std::string::npos);
    CHECK(back.find("cstype bspline\ndeg 1 1\nsurf 0 2 0 1 1 2 3 4 5 6\nparm u 0 0 1 2 2\nparm v 0 0 1 1\nend\n") !=
          std::string::npos);
    CHECK(formatObjFreeform(parseObjFreeform(back)) == back);
}

TEST_CASE("rational and NURBS objects: document -> OBJ -> document keeps every number, text byte for byte", "[obj][nurbs]")
{
    Document doc;
    doc.source = "sample";
    NurbsSurfaceData s;
    s.degree = {2, 3};
    s.rows = 5;
    s.cols = 6;
    s.knots[0] = {0, 0, 0, 0.25, 1.5, 2, 2, 2};
    s.knots[1] = {-1, -1, -1, -1, 0.1, 0.7, 3, 3, 3, 3};
    s.points = test::randomPoints<double, 3>(30, 11);
    const Eigen::MatrixXd w = test::randomPoints<double, 3>(10, 12).array() + 1.5; // in [0.5, 2.5]
    for (int k = 0; k < 30; ++k) s.weights.push_back(w(k % 3, k / 3));
    doc.objects.push_back({"nurbs", s, ""});
    NurbsCurveData c;
    c.degree = 3;
    c.knots = {0, 0.5, 1, 1.5, 2, 2.5, 3, 3.5, 4, 4.5}; // unclamped, 6 points
    c.points = test::randomPoints<double, 2>(6, 13);
    doc.objects.push_back({"open", c, ""});
    RationalBezierSurfaceData r;
    r.degree = {1, 2};
    r.points = test::randomPoints<double, 3>(6, 14);
    r.weights = {1, 2, 0.5, 0.25, 3, 1.125};
    doc.objects.push_back({"rpatch", r, ""});
    RationalBezierCurveData rc{test::randomPoints<double, 3>(4, 15), {1, 0.3, 0.7, 2}};
    doc.objects.push_back({"rcurve", rc, ""});

    const std::string text = formatObjFreeform(doc);
    const Document back = parseObjFreeform(text, "back.obj");
    REQUIRE(back.objects.size() == 4);
    const auto& s2 = std::get<NurbsSurfaceData>(back.objects[0].data);
    CHECK(s2.degree == s.degree);
    CHECK(s2.rows == 5);
    CHECK(s2.cols == 6);
    CHECK(s2.knots == s.knots);
    CHECK(s2.points == s.points);
    CHECK(s2.weights == s.weights);
    const auto& c2 = std::get<NurbsCurveData>(back.objects[1].data);
    CHECK(c2.degree == 3);
    CHECK(c2.knots == c.knots);
    REQUIRE(c2.points.rows() == 3); // 2D is written with z = 0
    CHECK(c2.points.topRows(2) == c.points);
    CHECK(c2.points.row(2).isZero(0));
    CHECK(c2.weights.empty());
    const auto& r2 = std::get<RationalBezierSurfaceData>(back.objects[2].data);
    CHECK(r2.degree == r.degree);
    CHECK(r2.points == r.points);
    CHECK(r2.weights == r.weights);
    const auto& rc2 = std::get<RationalBezierCurveData>(back.objects[3].data);
    CHECK(rc2.points == rc.points);
    CHECK(rc2.weights == rc.weights);
    CHECK(formatObjFreeform(back) == text);
    // The surfaces agree as functions too (an independent check of the point order).
    const NurbsSurface<double, 3> a(2, 3, s.knots[0], s.knots[1], PointMatrix<double, 3>(s.points),
                                    Eigen::Map<const Eigen::VectorXd>(s.weights.data(), 30));
    const NurbsSurface<double, 3> b(2, 3, s2.knots[0], s2.knots[1], PointMatrix<double, 3>(s2.points),
                                    Eigen::Map<const Eigen::VectorXd>(s2.weights.data(), 30));
    CHECK(a.evaluate(1.1, 0.2) == b.evaluate(1.1, 0.2));
}

TEST_CASE("OBJ rational and B-spline errors name the line", "[obj][nurbs][errors]")
{
    const std::string v4 = "v 0 0 0\nv 1 0 0 0\nv 0 1 0\nv 1 1 1\n";
    CHECK(err(v4 + "cstype rat bezier\ndeg 3\ncurv 0 1 1 2 3 4\nend\n") ==
          "x.obj: line 7: vertex 2 (line 2) has weight 0; rational weights must be positive");
    // Without rat the weight is not used.
    CHECK(err(v4 + "cstype bezier\ndeg 3\ncurv 0 1 1 2 3 4\nend\n") == "no error");
    CHECK(err(v4 + "cstype bspline\ndeg 2\ncurv 0 1 1 2 3 4\nend\n") ==
          "x.obj: line 7: a bspline element needs \"parm u\" (its knot vector)");
    CHECK(err(v4 + "cstype bspline\ndeg 2\ncurv 0 1 1 2 3 4\nparm u 0 0 0 1 1 1\nend\n") ==
          "x.obj: line 9: parm u has 6 knots, 4 control points of degree 2 need 7");
    CHECK(err(v4 + "cstype bspline\ndeg 2\ncurv 0 1 1 2 3 4\nparm u 0 0 0 1 0.5 1 1\n") ==
          "x.obj: line 8: parm knots must not decrease");
    CHECK(err(v4 + "cstype bspline\ndeg 2\ncurv 0 0.5 1 2 3 4\nparm u 0 0 0 0.5 1 1 1\nend\n") ==
          "x.obj: line 7: the parameter range 0 0.5 in u is not the knot domain 0 1 (a part of a B-spline is not supported)");
    CHECK(err(v4 + "cstype bspline\ndeg 1\ncurv 0 1 1 2 3 4\nparm u 0 0 0 0 1 1\nend\n").find("x.obj: line 9: parm u: knot") == 0);
    CHECK(err(v4 + "cstype bspline\ndeg 1 1\nsurf 0 1 0 1 1 2 3\nparm u 0 0 1 1\nparm v 0 0 1 1\nend\n")
              .find("x.obj: line 7: 3 control points do not fit parm u (4 knots) and parm v (4 knots)") == 0);
    CHECK(err(v4 + "cstype bspline\ndeg 1 1\nsurf 0 1 0 1 1 2 3 4\nparm u 0 0 1 1\nend\n") ==
          "x.obj: line 7: a bspline surf needs \"parm u\" and \"parm v\" (its knot vectors)");
    CHECK(err(v4 + "cstype rat bspline\ndeg 1\ncurv 0 1 1 3\nparm u 0 0 1 1\nhole 0 1 1\nend\n") ==
          "x.obj: line 9: hole outside a surf element");
    CHECK(err(v4 + "cstype rat bspline\ndeg 1\ncurv 0 1 1 3\nscrv 0 1 1\nend\n") ==
          "x.obj: line 8: special curves and points (scrv) are not supported");
    CHECK(err(v4 + "cstype rat bezier\ndeg 1 1\nsurf 0 1 0 1 1 3 4 3 4 3 4 3 4\nend\n").find("x.obj: line 7: 9 control points") == 0);
    CHECK(err(v4 + "cstype bspline\ndeg 1\nbmat u 1 0 0 1\n") ==
          "x.obj: line 7: \"bmat\" is not supported (Bézier and B-spline curves and surfaces only)");
}

} // namespace test_obj_freeform_rational
