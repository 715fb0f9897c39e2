// AnyCurve and AnySurface (document/model.h) over every curve kind and every (u, v) surface kind,
// against values computed here without them: circles and cylinders in closed form (a point's
// radius, the tangent (-sin, cos) of an arc parametrised by its angle), Bernstein sums written
// out, a uniform cubic B-spline surface's linear precision, central differences of the points for
// the derivatives, the kind table for which objects are curves and surfaces.

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "freeform/document/document.h"

namespace test_any_geometry {

using namespace freeform;

namespace {

const double kH = std::sqrt(0.5); // the middle weight of a quarter circle

// One object of every curve kind, every (u, v) surface kind, and a lattice, which is neither.
// "tcyl" is the quarter cylinder x^2 + y^2 = 1, 0 <= z <= 2, as a trimmed surface whose u is the
// angle (map_u half_angle over [0, pi/2], the NURBS's knots on the same interval, as Open CASCADE's
// conversion gives them); its trim is the whole box.
const char* kDocument = R"({"format": "freeform", "version": 1, "objects": [
  {"name": "bc", "type": "bezier_curve", "points": [[0,0],[1,2],[3,2],[4,0]]},
  {"name": "bs", "type": "bezier_spline", "degree": 2, "closed": false, "points": [[0,0],[1,0],[1,1],[2,2],[3,1]],
   "intervals": [1, 2]},
  {"name": "db", "type": "deboor_spline", "degree": 3, "end": "clamped", "points": [[0,0,0],[1,1,0],[2,0,1],[3,1,1]]},
  {"name": "arc", "type": "rational_bezier_curve", "points": [[1,0],[1,1],[0,1]], "weights": [1, 0.7071067811865476, 1]},
  {"name": "circle", "type": "nurbs_curve", "degree": 2, "knots": [0,0,0,1,1,2,2,3,3,4,4,4],
   "points": [[1,0,0],[1,1,0],[0,1,0],[-1,1,0],[-1,0,0],[-1,-1,0],[0,-1,0],[1,-1,0],[1,0,0]],
   "weights": [1,0.7071067811865476,1,0.7071067811865476,1,0.7071067811865476,1,0.7071067811865476,1]},
  {"name": "patch", "type": "bezier_surface", "degree": [2, 1],
   "points": [[[0,0,0],[0,1,1]],[[1,0,2],[1,1,0]],[[2,0,0],[2,1,1]]]},
  {"name": "dbs", "type": "deboor_surface", "degree": [3, 3], "end": ["open", "open"],
   "points": [[[0,0,1.0],[0,1,0.75],[0,2,0.5],[0,3,0.25]],
              [[1,0,1.5],[1,1,1.25],[1,2,1.0],[1,3,0.75]],
              [[2,0,2.0],[2,1,1.75],[2,2,1.5],[2,3,1.25]],
              [[3,0,2.5],[3,1,2.25],[3,2,2.0],[3,3,1.75]],
              [[4,0,3.0],[4,1,2.75],[4,2,2.5],[4,3,2.25]]]},
  {"name": "cyl", "type": "rational_bezier_surface", "degree": [2, 1],
   "points": [[[1,0,0],[1,0,2]],[[1,1,0],[1,1,2]],[[0,1,0],[0,1,2]]],
   "weights": [[1,1],[0.7071067811865476,0.7071067811865476],[1,1]]},
  {"name": "ncyl", "type": "nurbs_surface", "degree": [2, 1], "knots": [[0,0,0,2,2,2],[1,1,3,3]],
   "points": [[[1,0,0],[1,0,2]],[[1,1,0],[1,1,2]],[[0,1,0],[0,1,2]]],
   "weights": [[1,1],[0.7071067811865476,0.7071067811865476],[1,1]]},
  {"name": "tcyl", "type": "trimmed_surface", "degree": [2, 1],
   "knots": [[0,0,0,1.5707963267948966,1.5707963267948966,1.5707963267948966],[0,0,1,1]],
   "points": [[[1,0,0],[1,0,2]],[[1,1,0],[1,1,2]],[[0,1,0],[0,1,2]]],
   "weights": [[1,1],[0.7071067811865476,0.7071067811865476],[1,1]],
   "map_u": {"kind": "half_angle", "start": 0, "span": 1.5707963267948966, "spans": 1},
   "domain": [0, 1.5707963267948966, 0, 1],
   "loops": [[
     {"degree": 1, "knots": [0,0,1,1], "points": [[0,0],[1.5707963267948966,0]], "range": [0, 1]},
     {"degree": 1, "knots": [0,0,1,1], "points": [[1.5707963267948966,0],[1.5707963267948966,1]], "range": [0, 1]},
     {"degree": 1, "knots": [0,0,1,1], "points": [[1.5707963267948966,1],[0,1]], "range": [0, 1]},
     {"degree": 1, "knots": [0,0,1,1], "points": [[0,1],[0,0]], "range": [0, 1]}]]},
  {"name": "L", "type": "lattice", "degree": [1, 1, 1], "origin": [0, 0, 0], "axes": [[1,0,0],[0,1,0],[0,0,1]],
   "points": [[0,0,0],[0,0,1],[0,1,0],[0,1,1],[1,0,0],[1,0,1],[1,1,0],[1,1,1]]}
]})";

TypedDocument load() { return TypedDocument(parseDocument(kDocument, "any.json"), ""); }

/// Central difference of f at t, step h.
template <class F>
Eigen::VectorXd central(F f, double t, double h)
{
    return (f(t + h) - f(t - h)) / (2 * h);
}

} // namespace

TEST_CASE("AnyCurve takes every curve kind and nothing else", "[document][any]")
{
    const TypedDocument doc = load();
    int curves = 0;
    for (const TypedObject& o : doc.objects()) {
        INFO(o.name());
        const auto curve = AnyCurve::of(o);
        CHECK(curve.has_value() == o.info().isCurve());
        curves += curve.has_value();
        const auto surface = AnySurface::of(o);
        CHECK(surface.has_value() == (o.info().isSurface() && o.kind() != ObjectKind::SubdivisionSurface));
    }
    CHECK(curves == 5);
    // Every curve kind and every (u, v) surface kind of the table is in the document, so a new one
    // without a case in AnyCurve::of or AnySurface::of fails here.
    int curveKinds = 0, surfaceKinds = 0, surfaces = 0;
    for (const KindInfo& k : objectKinds()) {
        curveKinds += k.isCurve();
        surfaceKinds += k.isSurface() && k.kind != ObjectKind::SubdivisionSurface;
    }
    for (const TypedObject& o : doc.objects()) surfaces += AnySurface::of(o).has_value();
    CHECK(curveKinds == 5);
    CHECK(surfaceKinds == 5);
    CHECK(surfaces == 5);

    using F = AnyCurve::Form;
    const struct {
        const char* name;
        F form;
        int dimension;
        double start, end;
    } expected[] = {{"bc", F::Bezier, 2, 0, 1},         {"bs", F::Spline, 2, 0, 3}, {"db", F::Spline, 3, 0, 1},
                    {"arc", F::RationalBezier, 2, 0, 1}, {"circle", F::Nurbs, 3, 0, 4}};
    for (const auto& e : expected) {
        INFO(e.name);
        const AnyCurve c = *AnyCurve::of(doc.object(e.name));
        CHECK(c.form() == e.form);
        CHECK(c.dimension() == e.dimension);
        CHECK(c.domainStart() == e.start);
        CHECK(c.domainEnd() == e.end);
        CHECK(c.isRational() == (e.form == F::RationalBezier || e.form == F::Nurbs));
        CHECK(c.spline3().has_value() == !c.isRational());
        CHECK_FALSE(c.closed());
    }
}

TEST_CASE("AnyCurve: points by hand, derivatives by differences, weights as stored", "[document][any]")
{
    const TypedDocument doc = load();
    // The cubic Bézier curve at t = 1/4: Bernstein 27/64, 27/64, 9/64, 1/64.
    const AnyCurve bc = *AnyCurve::of(doc.object("bc"));
    const Eigen::VectorXd p = bc.point(0.25);
    CHECK(p[0] == Approx((27 * 0 + 27 * 1 + 9 * 3 + 1 * 4) / 64.0).margin(1e-15));
    CHECK(p[1] == Approx((27 * 0 + 27 * 2 + 9 * 2 + 1 * 0) / 64.0).margin(1e-15));
    CHECK(bc.weights() == Eigen::VectorXd::Ones(4));

    // The quarter circle: every point at radius 1; at t = 1/2 the point (h, h) (the rational
    // quadratic's middle: (1/4 + h/2) / (1/2 + h/2) = h for h = cos 45 degrees).
    const AnyCurve arc = *AnyCurve::of(doc.object("arc"));
    CHECK((arc.point(0.5) - Eigen::Vector2d(kH, kH)).norm() <= 2e-16);
    CHECK(arc.weights()[1] == kH);
    CHECK(arc.controlPoints().col(1) == Eigen::Vector2d(1, 1));

    // The full circle: radius 1 everywhere, derivatives 1 and 2 against differences of the points
    // and of the first derivatives.
    const AnyCurve circle = *AnyCurve::of(doc.object("circle"));
    for (const AnyCurve* c : {&arc, &circle})
        for (int k = 0; k <= 20; ++k) {
            const double t = c->domainStart() + (c->domainEnd() - c->domainStart()) * k / 20.0;
            CHECK(std::abs(c->point(t).norm() - 1) <= 4e-16);
            if (k == 0 || k == 20) continue;
            const Eigen::MatrixXd d = c->derivatives(t, 2);
            const double h = 1e-5;
            const Eigen::VectorXd d1 = central([&](double s) -> Eigen::VectorXd { return c->point(s); }, t, h);
            const Eigen::VectorXd d2 = central([&](double s) -> Eigen::VectorXd { return c->derivatives(s, 1).col(1); }, t, h);
            if (std::abs(t - std::round(t)) < 2 * h) continue; // a knot of the circle: the second derivative jumps
            CHECK((d.col(1) - d1).norm() <= 1e-8 * d.col(1).norm());
            CHECK((d.col(2) - d2).norm() <= 1e-7 * std::max(1.0, d.col(2).norm()));
        }

    // The spline with intervals 1 and 2: its global T runs to 3 and its second segment starts at
    // T = 1 with the segment's own Bernstein form in (T - 1) / 2.
    const AnyCurve bs = *AnyCurve::of(doc.object("bs"));
    const Eigen::VectorXd q = bs.point(2); // local 1/2 of points (1,1), (2,2), (3,1)
    CHECK(q[0] == Approx(0.25 * 1 + 0.5 * 2 + 0.25 * 3).margin(1e-15));
    CHECK(q[1] == Approx(0.25 * 1 + 0.5 * 2 + 0.25 * 1).margin(1e-15));
    CHECK(bs.spline3()->evaluate(2) == Eigen::Vector3d(q[0], q[1], 0));
}

TEST_CASE("AnyCurve::polyline of a rational curve keeps within the tolerance", "[document][any]")
{
    const TypedDocument doc = load();
    for (const char* name : {"arc", "circle"})
        for (double tolerance : {1e-2, 1e-4}) {
            INFO(name << " at " << tolerance);
            const AnyCurve c = *AnyCurve::of(doc.object(name));
            const Eigen::Matrix<double, 3, Eigen::Dynamic> line = c.polyline(tolerance);
            REQUIRE(line.cols() >= 3);
            CHECK((line.col(0).head(c.dimension()) - c.point(c.domainStart())).norm() == 0);
            CHECK((line.col(line.cols() - 1).head(c.dimension()) - c.point(c.domainEnd())).norm() <= 1e-15);
            double sagitta = 0;
            for (Eigen::Index i = 0; i < line.cols(); ++i) {
                CHECK(std::abs(line.col(i).norm() - 1) <= 4e-16); // every vertex on the circle
                CHECK(line(2, i) == 0);
                // The chord to the next vertex lies within tolerance of its arc: its middle is at
                // distance 1 - |m| from the circle, the largest distance of the chord.
                if (i + 1 < line.cols()) sagitta = std::max(sagitta, 1 - (0.5 * (line.col(i) + line.col(i + 1))).norm());
            }
            CHECK(sagitta <= tolerance);
            CHECK(sagitta > tolerance / 16); // and not far finer than asked
        }
}

TEST_CASE("AnySurface takes every (u, v) surface kind: domains, points, normals, jets", "[document][any]")
{
    const TypedDocument doc = load();
    const double pi = std::numbers::pi;
    const struct {
        const char* name;
        std::array<double, 4> domain;
    } expected[] = {{"patch", {0, 1, 0, 1}},
                    {"dbs", {0, 2, 0, 1}},
                    {"cyl", {0, 1, 0, 1}},
                    {"ncyl", {0, 2, 1, 3}},
                    {"tcyl", {0, pi / 2, 0, 1}}};
    for (const auto& e : expected) {
        INFO(e.name);
        const AnySurface s = *AnySurface::of(doc.object(e.name));
        CHECK(s.domain() == e.domain);
        CHECK((s.patches() != nullptr) == (std::string(e.name) == "patch" || std::string(e.name) == "dbs"));
        CHECK((s.trimmed() != nullptr) == (std::string(e.name) == "tcyl"));
    }

    // The Bézier patch at (1/2, 1/4): Bernstein 1/4, 1/2, 1/4 along u, 3/4, 1/4 along v.
    const AnySurface patch = *AnySurface::of(doc.object("patch"));
    CHECK(patch.point(0.5, 0.25).isApprox(Eigen::Vector3d(1, 0.25, 0.75 * (0.5 * 2) + 0.25 * (0.25 + 0.25)), 1e-15));

    // The uniform cubic B-spline surface on the 5 x 4 grid P_ij = (i, j, i/2 - j/4 + 1): 5 - 3 = 2
    // spans along u and 4 - 3 = 1 along v, and uniform B-splines reproduce linear functions, so
    // S(u, v) = P at (1 + u, 1 + v) everywhere, and du x dv = (1, 0, 1/2) x (0, 1, -1/4) = (-1/2, 1/4, 1).
    const AnySurface dbs = *AnySurface::of(doc.object("dbs"));
    const Eigen::Vector3d up = Eigen::Vector3d(-0.5, 0.25, 1).normalized();
    for (int i = 0; i <= 8; ++i)
        for (int j = 0; j <= 4; ++j) {
            const double u = 2.0 * i / 8, v = 1.0 * j / 4, x = 1 + u, y = 1 + v;
            CHECK((dbs.point(u, v) - Eigen::Vector3d(x, y, 0.5 * x - 0.25 * y + 1)).norm() <= 1e-14);
            CHECK((dbs.normal(u, v) - up).norm() <= 1e-14);
            const Eigen::MatrixXd jet = dbs.jet(u, v, 2);
            CHECK((jet.col(1) - Eigen::Vector3d(1, 0, 0.5)).norm() <= 1e-13);
            CHECK((jet.col(2) - Eigen::Vector3d(0, 1, -0.25)).norm() <= 1e-13);
            CHECK(jet.rightCols(3).norm() <= 1e-12); // no second derivatives on a plane's linear map
        }

    // The three cylinders: radius 1, z = 2 v (ncyl: v in [1, 3], z = v - 1), the normal radial and
    // outward (u turns counter-clockwise, v goes up: (-sin, cos, 0) x (0, 0, 2) = 2 (cos, sin, 0)).
    for (const char* name : {"cyl", "ncyl", "tcyl"}) {
        INFO(name);
        const AnySurface s = *AnySurface::of(doc.object(name));
        const auto d = s.domain();
        for (int i = 0; i <= 6; ++i)
            for (int j = 0; j <= 4; ++j) {
                const double u = d[0] + (d[1] - d[0]) * i / 6.0, v = d[2] + (d[3] - d[2]) * j / 4.0;
                const Eigen::Vector3d p = s.point(u, v);
                CHECK(std::abs(p.head<2>().norm() - 1) <= 4e-16);
                CHECK(p.z() == Approx(2.0 * j / 4.0).margin(1e-15));
                const Eigen::Vector3d radial(p.x(), p.y(), 0);
                CHECK((s.normal(u, v) - radial).norm() <= 1e-14);
                const Eigen::MatrixXd jet = s.jet(u, v, 1);
                CHECK(jet.col(0) == p);
                if (i == 0 || i == 6 || j == 0 || j == 4) continue;
                const double h = 1e-6;
                CHECK((jet.col(1) - (s.point(u + h, v) - s.point(u - h, v)) / (2 * h)).norm() <= 1e-8);
                CHECK((jet.col(2) - (s.point(u, v + h) - s.point(u, v - h)) / (2 * h)).norm() <= 1e-8);
            }
    }
    // The trimmed cylinder's u is the angle: the point is (cos u, sin u, 2 v) and d/du (-sin u, cos u, 0).
    const AnySurface tcyl = *AnySurface::of(doc.object("tcyl"));
    for (double u : {0.1, 0.7, 1.3}) {
        const Eigen::MatrixXd jet = tcyl.jet(u, 0.5, 1);
        CHECK((jet.col(0) - Eigen::Vector3d(std::cos(u), std::sin(u), 1)).norm() <= 1e-15);
        CHECK((jet.col(1) - Eigen::Vector3d(-std::sin(u), std::cos(u), 0)).norm() <= 1e-14);
        CHECK((jet.col(2) - Eigen::Vector3d(0, 0, 2)).norm() <= 1e-14);
    }
    CHECK_THROWS_WITH(tcyl.jet(0.5, 0.5, 2), Catch::Contains("first derivatives only"));
    // Second derivatives of the others against differences of the first.
    for (const char* name : {"patch", "cyl", "ncyl"}) {
        INFO(name);
        const AnySurface s = *AnySurface::of(doc.object(name));
        const auto d = s.domain();
        const double u = d[0] + 0.37 * (d[1] - d[0]), v = d[2] + 0.61 * (d[3] - d[2]), h = 1e-5;
        const Eigen::MatrixXd jet = s.jet(u, v, 2);
        const Eigen::Vector3d uu = (s.jet(u + h, v, 1).col(1) - s.jet(u - h, v, 1).col(1)) / (2 * h);
        const Eigen::Vector3d uv = (s.jet(u, v + h, 1).col(1) - s.jet(u, v - h, 1).col(1)) / (2 * h);
        const Eigen::Vector3d vv = (s.jet(u, v + h, 1).col(2) - s.jet(u, v - h, 1).col(2)) / (2 * h);
        CHECK((jet.col(Patch::jetIndex(2, 0)) - uu).norm() <= 1e-7);
        CHECK((jet.col(Patch::jetIndex(1, 1)) - uv).norm() <= 1e-7);
        CHECK((jet.col(Patch::jetIndex(0, 2)) - vv).norm() <= 1e-7);
    }
}

TEST_CASE("the document layer evaluates every kind through AnyCurve and AnySurface", "[document][any]")
{
    const TypedDocument doc = load();
    // evaluate() gives what the facades give, for every curve and surface kind.
    for (const char* name : {"bc", "bs", "db", "arc", "circle"}) {
        INFO(name);
        const AnyCurve c = *AnyCurve::of(doc.object(name));
        const double t = c.domainStart() + 0.3 * (c.domainEnd() - c.domainStart());
        const Evaluation e = evaluate(doc, doc.object(name), {t}, 2);
        const Eigen::MatrixXd d = c.derivatives(t, 2);
        CHECK(e.point == Eigen::VectorXd(d.col(0)));
        CHECK(e.derivatives.at(1) == Eigen::VectorXd(d.col(2)));
        CHECK(parameterDomain(doc.object(name)) == std::vector<double>{c.domainEnd()});
    }
    for (const char* name : {"patch", "dbs", "cyl", "ncyl"}) {
        INFO(name);
        const AnySurface s = *AnySurface::of(doc.object(name));
        const auto d = s.domain();
        const Evaluation e = evaluate(doc, doc.object(name), {d[0] + 0.2 * (d[1] - d[0]), d[2] + 0.9 * (d[3] - d[2])}, 1);
        CHECK(e.point == Eigen::VectorXd(s.point(d[0] + 0.2 * (d[1] - d[0]), d[2] + 0.9 * (d[3] - d[2]))));
        CHECK(parameterDomain(doc.object(name)) == std::vector<double>{d[1], d[3]});
    }
    // The words of a parameter outside the domain, per kind (docs/cli.md, "eval").
    CHECK_THROWS_WITH(evaluate(doc, doc.object("circle"), {5}, 0),
                      "any.json: object \"circle\": T = 5 is outside the curve's domain [0, 4]");
    CHECK_THROWS_WITH(evaluate(doc, doc.object("arc"), {-1}, 0),
                      "any.json: object \"arc\": t = -1 is outside the curve's domain [0, 1]");
    CHECK_THROWS_WITH(evaluate(doc, doc.object("bs"), {3.5}, 0),
                      "any.json: object \"bs\": T = 3.5 is outside the spline's domain [0, 3]");
    CHECK_THROWS_WITH(evaluate(doc, doc.object("ncyl"), {1, 0.5}, 0),
                      "any.json: object \"ncyl\": v = 0.5 is outside the surface's domain [1, 3]");
    // A trimmed surface is evaluated as a face: whether the point is inside its trims comes with it.
    const Evaluation t = evaluate(doc, doc.object("tcyl"), {0.5, 0.5}, 0);
    CHECK(t.trim == TrimClass::Inside);
    CHECK(parameterDomain(doc.object("tcyl")) == std::vector<double>{0, std::numbers::pi / 2, 0, 1});
    // Continuity: the circle's interior knots are double (C0 in the parameter, G1 as drawn).
    CHECK(continuity(doc, doc.object("circle")).size() == 3);
    CHECK_THROWS_WITH(continuity(doc, doc.object("arc")), Catch::Contains("not a spline"));
}

} // namespace test_any_geometry
