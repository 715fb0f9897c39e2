// Continuity analysis (curve/continuity.h): hand-built joints with known jumps, levels that must
// say no (a kink, G1 without C1, a second derivative off by 1e-7), the tolerance parameter, and
// the closing joint of closed splines.

#include <catch2/catch.hpp>

#include <freeform/curve/continuity.h>

namespace test_continuity {

using namespace freeform;
using Spline2 = BezierSpline<double, 2>;

TEST_CASE("a C2 joint whose third derivative jumps by 4.5", "[continuity]")
{
    // Left: the line y = 0, x = T on [0, 3]; right: x = T, y = 20.25 s^3 with s = (T - 3) / 3.
    // y''' = 6 * 20.25 / 27 = 4.5 on the right, 0 on the left; everything below agrees.
    PointMatrix<double, 2> p(2, 7);
    p << 0, 1, 2, 3, 4, 5, 6, 0, 0, 0, 0, 0, 0, 20.25;
    const auto report = continuityReport(Spline2(3, false, p, {3.0, 3.0}));
    REQUIRE(report.size() == 1);
    CHECK(report[0].joint == 1);
    CHECK(report[0].t == 3.0);
    CHECK(report[0].C == 2);
    CHECK(report[0].G == 2);
    CHECK(report[0].jumps == std::vector<double>{0, 0, 0, 4.5});
}

TEST_CASE("a kink is C0 and G0; a G1 joint with unequal speeds is C0 and G1", "[continuity]")
{
    PointMatrix<double, 2> kink(2, 7);
    kink << 0, 1, 2, 3, 3, 3, 3, 0, 0, 0, 0, 1, 2, 3;
    const auto k = continuityReport(Spline2(3, false, kink))[0];
    CHECK(k.C == 0);
    CHECK(k.G == 0);
    CHECK(k.jumps[0] == 0);
    CHECK(k.jumps[1] == Approx(3 * std::sqrt(2.0)).epsilon(1e-15)); // |3 (0,1) - 3 (1,0)|

    PointMatrix<double, 2> g1(2, 7);
    g1 << 0, 1, 2, 3, 5, 7, 9, 0, 0, 0, 0, 0, 0, 0;
    const auto g = continuityReport(Spline2(3, false, g1))[0];
    CHECK(g.C == 0);
    CHECK(g.G == 2); // a straight line: both curvatures are 0
    CHECK(g.jumps[1] == 3.0); // 3 (2,0) - 3 (1,0)

    // A bend with matching tangents but different curvature: G1, not G2.
    PointMatrix<double, 2> bend(2, 7);
    bend << 0, 1, 2, 3, 4, 5, 6, 0, 0, 0, 0, 0, 1, 1;
    const auto b = continuityReport(Spline2(3, false, bend))[0];
    CHECK(b.C == 1);
    CHECK(b.G == 1);
}

TEST_CASE("the tolerance decides: a second derivative off by about 1e-7 relative", "[continuity]")
{
    // Left c = (0,0),(1,1),(2,1),(3,0); C1: d_1 = 2 c_3 - c_2 = (4,-1); C2 by the A-frame:
    // a = 2 c_2 - c_1 = (3,1), d_2 = 2 d_1 - a = (5,-3). Then d_2 is disturbed by 1e-7.
    PointMatrix<double, 2> p(2, 7);
    p << 0, 1, 2, 3, 4, 5, 6, 0, 1, 1, 0, -1, -3, 0;
    const Spline2 exact(3, false, p);
    CHECK(continuityReport(exact)[0].C == 2);
    p(1, 5) += 1e-7;
    const Spline2 off(3, false, p);
    CHECK(continuityReport(off)[0].C == 1);
    ContinuityTolerances<double> loose;
    loose.relative = 1e-6;
    CHECK(continuityReport(off, loose)[0].C == 2);
}

TEST_CASE("closed splines report the closing joint first, at t = 0", "[continuity]")
{
    PointMatrix<double, 2> p(2, 6);
    p << 0, 1, 2, 3, 2, 1, 0, -1, -1, 0, 1, 1;
    const auto report = continuityReport(Spline2(3, true, p, {1.0, 2.0}));
    REQUIRE(report.size() == 2);
    CHECK(report[0].joint == 0);
    CHECK(report[0].t == 0.0);
    CHECK(report[1].joint == 1);
    CHECK(report[1].t == 1.0);
    // Joint 0: left 3 ((0,0) - (1,1)) / 2 = (-1.5, -1.5), right 3 ((1,-1) - (0,0)) / 1 = (3, -3).
    CHECK(report[0].jumps[1] == Approx(std::sqrt(4.5 * 4.5 + 1.5 * 1.5)).epsilon(1e-15));
    CHECK(report[0].C == 0);
}

TEST_CASE("jointContinuity validation", "[continuity]")
{
    const PointMatrix<double, 2> a = PointMatrix<double, 2>::Zero(2, 4), b = PointMatrix<double, 2>::Zero(2, 3);
    CHECK_THROWS_WITH((jointContinuity<double, 2>(a, b, 1.0, 1.0)), Catch::Contains("same degree"));
    CHECK_THROWS_WITH((jointContinuity<double, 2>(a, a, 0.0, 1.0)), Catch::Contains("positive"));
}

} // namespace test_continuity
