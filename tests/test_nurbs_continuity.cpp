// Continuity of NURBS curves from the geometry: knots inserted into smooth curves keep their
// level whatever their multiplicity, a polynomial curve's report equals the Bézier-spline report of
// curve/continuity.h on the same pieces, a real kink is found, and the rational circle is G2.

#include <catch2/catch.hpp>

#include <freeform/curve/bezier_spline.h>
#include <freeform/curve/nurbs_continuity.h>

#include "support/random.h"

namespace test_nurbs_continuity {

using namespace freeform;
using freeform::test::randomPoints;

TEST_CASE("continuity comes from the geometry, not the multiplicity", "[nurbs][continuity]")
{
    for (int p = 2; p <= 5; ++p) {
        // Clamped uniform curve: C^(p-1) at its simple knots.
        const auto kv = KnotVector<double>::clampedUniform(p, p + 4);
        const NurbsCurve<double, 3> c(p, kv.knots(), randomPoints<double, 3>(p + 4, 3u + p));
        const auto base = continuityReport(c);
        REQUIRE(base.size() == 3);
        for (const auto& j : base) {
            CHECK(j.C == p - 1);
            CHECK(j.G >= std::min(p - 1, 2));
        }
        // Inserting 0.5 until multiplicity p (Bézier form there) leaves the curve C^(p-1).
        const double mid = kv.knots()[p + 2]; // an existing interior knot
        const auto bez = c.insertKnot(mid, p - 1);
        for (const auto& j : continuityReport(bez)) CHECK(j.C == p - 1);
        // Inserting a new knot where the curve is one polynomial: C^p there (C-infinity).
        const auto extra = c.insertKnot(0.1, p);
        bool found = false;
        for (const auto& j : continuityReport(extra))
            if (j.t == 0.1) {
                found = true;
                CHECK(j.C == p);
            }
        CHECK(found);
        // The polynomial report is the Bézier-spline report on the same pieces.
        const auto pieces = c.bezierPieces();
        PointMatrix<double, 3> pts(3, static_cast<Eigen::Index>(pieces.size()) * p + 1);
        for (std::size_t i = 0; i < pieces.size(); ++i) pts.middleCols(static_cast<Eigen::Index>(i) * p, p + 1) = pieces[i].controlPoints();
        std::vector<double> h;
        for (std::size_t i = 0; i + 1 < c.breakpoints().size(); ++i) h.push_back(c.breakpoints()[i + 1] - c.breakpoints()[i]);
        const auto spline = continuityReport(BezierSpline<double, 3>(p, false, pts, h));
        REQUIRE(spline.size() == base.size());
        for (std::size_t i = 0; i < base.size(); ++i) {
            CHECK(spline[i].C == base[i].C);
            CHECK(spline[i].G == base[i].G);
            CHECK(spline[i].t == Approx(base[i].t).epsilon(1e-15));
        }
    }
}

TEST_CASE("a kink and the rational circle", "[nurbs][continuity]")
{
    // Multiplicity p at 0.5 and a moved middle control point: C0 only, not G1.
    PointMatrix<double, 2> pts(2, 7);
    pts << 0, 1, 2, 3, 4, 5, 6,
           0, 1, 0, 2, 0, 1, 0;
    const NurbsCurve<double, 2> kink(3, {0, 0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1, 1}, pts);
    const auto r = continuityReport(kink);
    REQUIRE(r.size() == 1);
    CHECK(r[0].C == 0);
    CHECK(r[0].G == 0);
    // The circle of quadratic quarter arcs (knots of multiplicity 2): C1 and G2 at every joint.
    const auto circle = NurbsCurve<double, 2>::circle(Eigen::Vector2d(0, 0), 1.0);
    const auto rc = continuityReport(circle);
    REQUIRE(rc.size() == 3);
    for (const auto& j : rc) {
        CHECK(j.C >= 1);
        CHECK(j.G == 2);
    }
}

} // namespace test_nurbs_continuity
