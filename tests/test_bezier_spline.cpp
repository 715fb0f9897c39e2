// BezierSpline: global evaluation against the segments, derivatives against long double
// finite differences, locate, split (C-infinity joint), remove joint (exact after split, an upper
// error bound otherwise, checked by brute-force sampling), elevation, sampling, closed layout, and
// input validation.

#include <catch2/catch.hpp>

#include <freeform/curve/bezier_spline.h>
#include <freeform/curve/continuity.h>

#include <cmath>
#include <random>

#include "support/random.h"

namespace test_bezier_spline {

using namespace freeform;
using freeform::test::randomPoints;
using Spline2 = BezierSpline<double, 2>;

namespace {

std::vector<double> randomIntervals(int count, std::uint32_t seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.25, 3.0);
    std::vector<double> h(static_cast<std::size_t>(count));
    for (double& x : h) x = u(rng);
    return h;
}

} // namespace

TEST_CASE("a two-segment spline: hand-computed values and derivatives", "[spline]")
{
    // Segment 0: (0,0),(1,2),(3,2),(4,0) on [0, 1]; segment 1: (4,0),(5,-2),(7,-2),(8,0) on [1, 3].
    PointMatrix<double, 2> p(2, 7);
    p << 0, 1, 3, 4, 5, 7, 8, 0, 2, 2, 0, -2, -2, 0;
    const Spline2 s(3, false, p, {1.0, 2.0});
    CHECK(s.segmentCount() == 2);
    CHECK(s.jointCount() == 3);
    CHECK(s.domainEnd() == 3.0);
    CHECK(s.evaluate(0.5) == Eigen::Vector2d(2, 1.5));
    CHECK(s.evaluate(2.0) == Eigen::Vector2d(6, -1.5)); // t = 1/2 of segment 1
    const auto d = s.derivatives(2.0, 3);
    CHECK(d.col(1) == Eigen::Vector2d(2.25, 0));  // (4.5, 0) / 2
    CHECK(d.col(2) == Eigen::Vector2d(0, 3));     // (0, 12) / 4
    CHECK(d.col(3) == Eigen::Vector2d(-1.5, 0));  // (-12, 0) / 8
    const auto loc = s.locate(1.0);
    CHECK(loc.segment == 1);
    CHECK(loc.t == 0.0);
    CHECK(s.locate(3.0).segment == 1);
    CHECK(s.locate(3.0).t == 1.0);
    CHECK(s.locate(0.25).t == 0.25);
    CHECK(s.knot(1) == 1.0);
    // One-sided first derivatives at joint 1: left 3 ((4,0) - (3,2)) / 1, right 3 ((5,-2) - (4,0)) / 2.
    CHECK(s.leftDerivatives(1, 1).col(1) == Eigen::Vector2d(3, -6));
    CHECK(s.rightDerivatives(1, 1).col(1) == Eigen::Vector2d(1.5, -3));
    CHECK_THROWS_WITH(s.leftDerivatives(0, 1), Catch::Contains("no left side"));
    CHECK_THROWS_WITH(s.rightDerivatives(2, 1), Catch::Contains("no right side"));
}

TEST_CASE("global derivatives agree with long double finite differences", "[spline]")
{
    for (std::uint32_t seed = 1; seed <= 5; ++seed) {
        const int n = 2 + static_cast<int>(seed % 4), L = 4;
        const auto p = randomPoints<long double, 2>(L * n + 1, seed);
        std::vector<long double> h;
        for (double x : randomIntervals(L, seed)) h.push_back(x);
        const BezierSpline<long double, 2> s(n, false, p, h);
        for (long double T : {0.3L, 1.7L, 2.9L}) {
            if (T >= s.domainEnd()) continue;
            const auto at = s.locate(T);
            if (at.t < 0.01L || at.t > 0.99L) continue; // stay inside one segment
            const long double step = 1e-5L;
            const auto d = s.derivatives(T, 2);
            const auto fd1 = ((s(T + step) - s(T - step)) / (2 * step)).eval();
            const auto fd2 = ((s(T + step) - 2 * s(T) + s(T - step)) / (step * step)).eval();
            CAPTURE(seed, static_cast<double>(T));
            CHECK(static_cast<double>((d.col(1) - fd1).norm()) < 1e-7 * (1 + static_cast<double>(d.col(1).norm())));
            CHECK(static_cast<double>((d.col(2) - fd2).norm()) < 1e-3 * (1 + static_cast<double>(d.col(2).norm())));
        }
    }
}

TEST_CASE("closed splines: the last segment ends at point 0", "[spline]")
{
    const auto p = randomPoints<double, 2>(9, 3);
    const Spline2 s(3, true, p, {1.0, 2.0, 0.5});
    CHECK(s.segmentCount() == 3);
    CHECK(s.jointCount() == 3);
    CHECK(s.evaluate(s.domainEnd()) == p.col(0));
    CHECK(s.segmentPoints(2).col(3) == p.col(0));
    CHECK(s.pointIndex(2, 3) == 0);
    const auto back = s.leftDerivatives(0, 0);
    CHECK(back.col(0) == p.col(0));
}

TEST_CASE("splitting a segment keeps the curve and adds a C-infinity joint", "[spline]")
{
    for (const bool closed : {false, true}) {
        const int n = 4, L = 3;
        const auto p = randomPoints<double, 2>(closed ? L * n : L * n + 1, 9);
        const Spline2 s(n, closed, p, randomIntervals(L, 10));
        for (int i = 0; i < L; ++i) {
            const Spline2 t = s.splitSegment(i, 0.3);
            CAPTURE(closed, i);
            REQUIRE(t.segmentCount() == L + 1);
            CHECK(t.domainEnd() == Approx(s.domainEnd()).epsilon(1e-15));
            for (int k = 0; k <= 50; ++k) {
                const double T = s.domainEnd() * k / 50;
                CHECK((t.evaluate(T) - s.evaluate(T)).norm() < 1e-13);
            }
            const auto report = continuityReport(t);
            for (const auto& j : report)
                if (j.joint == i + 1) CHECK(j.C == n); // one polynomial across the new joint
            // Removing the new joint gives the original back, with an error bound of (almost) 0.
            const auto merged = t.removeJoint(i + 1);
            CHECK(merged.errorBound < 1e-12);
            REQUIRE(merged.spline.controlPoints().cols() == p.cols());
            CHECK((merged.spline.controlPoints() - p).cwiseAbs().maxCoeff() < 1e-12);
            CHECK(merged.spline.intervals()[i] == Approx(s.intervals()[i]).epsilon(1e-15));
        }
    }
    const Spline2 s(3, false, randomPoints<double, 2>(7, 1));
    CHECK_THROWS_WITH(s.splitSegment(0, 1.0), Catch::Contains("strictly inside"));
    CHECK_THROWS_WITH(s.splitSegment(2, 0.5), Catch::Contains("outside 0..1"));
}

TEST_CASE("removing a real joint reports an upper bound of the error", "[spline]")
{
    for (const int n : {1, 2, 3, 4, 5}) {
        const int L = 3;
        const auto p = randomPoints<double, 2>(L * n + 1, 20 + static_cast<std::uint32_t>(n));
        const auto h = randomIntervals(L, 30);
        const Spline2 s(n, false, p, h);
        const auto merged = s.removeJoint(1);
        CAPTURE(n);
        REQUIRE(merged.spline.segmentCount() == 2);
        CHECK(merged.spline.intervals()[0] == Approx(h[0] + h[1]).epsilon(1e-15));
        // Brute force: the distance at the same global parameter never exceeds the bound.
        double worst = 0;
        for (int k = 0; k <= 2000; ++k) {
            const double T = (h[0] + h[1]) * k / 2000;
            worst = std::max(worst, (merged.spline.evaluate(T) - s.evaluate(T)).norm());
        }
        CHECK(worst <= merged.errorBound * (1 + 1e-12));
        CHECK(worst > 0);
        // The outer ends and the joint after the merged segment stay where they were.
        CHECK(merged.spline.evaluate(0) == s.evaluate(0));
        CHECK((merged.spline.evaluate(h[0] + h[1]) - s.evaluate(h[0] + h[1])).norm() == 0);
        // Derivatives up to (n-1)/2 at the outer ends are kept.
        const int r = (n - 1) / 2;
        const auto a = merged.spline.derivatives(0, r), b = s.derivatives(0, r);
        CHECK((a - b).cwiseAbs().maxCoeff() < 1e-9 * (1 + b.cwiseAbs().maxCoeff()));
        if (n % 2 == 0) CHECK((merged.spline.evaluate(h[0]) - s.evaluate(h[0])).norm() < 1e-12);
    }
    const Spline2 s(3, true, randomPoints<double, 2>(9, 4), {1.0, 2.0, 3.0});
    const auto m = s.removeJoint(0);
    REQUIRE(m.spline.segmentCount() == 2);
    // Joint 0 removed: the spline now starts at old joint 1, the merged segment is the last one.
    CHECK(m.spline.controlPoints().col(0) == s.controlPoints().col(3));
    CHECK(m.spline.intervals()[1] == 4.0);
    CHECK_THROWS_WITH((Spline2(3, false, randomPoints<double, 2>(7, 1)).removeJoint(0)), Catch::Contains("not an inner joint"));
}

TEST_CASE("degree elevation of the chain keeps the curve", "[spline]")
{
    for (const bool closed : {false, true}) {
        const auto p = randomPoints<double, 3>(closed ? 12 : 13, 40);
        const BezierSpline<double, 3> s(3, closed, p, {1.0, 0.5, 2.0, 1.5});
        const auto e = s.elevated(2);
        CHECK(e.degree() == 5);
        CHECK(e.controlPoints().cols() == (closed ? 20 : 21));
        for (int k = 0; k <= 40; ++k) {
            const double T = s.domainEnd() * k / 40;
            CHECK((e.evaluate(T) - s.evaluate(T)).norm() < 1e-14);
            CHECK((e.derivatives(T, 1).col(1) - s.derivatives(T, 1).col(1)).norm() < 1e-12);
        }
    }
}

TEST_CASE("sampling into polylines", "[spline]")
{
    const auto p = randomPoints<double, 2>(7, 50);
    const Spline2 s(3, false, p, {2.0, 1.0});
    const auto poly = s.sample(4);
    REQUIRE(poly.cols() == 9);
    for (int k = 0; k < 8; ++k) {
        const int seg = k / 4;
        const double T = s.knot(seg) + s.intervals()[seg] * (k % 4) / 4.0;
        CHECK((poly.col(k) - s.evaluate(T)).norm() < 1e-14);
    }
    CHECK(poly.col(8) == p.col(6));
    const Spline2 c(3, true, randomPoints<double, 2>(6, 51));
    CHECK(c.sample(3).col(6) == c.controlPoints().col(0));
    const auto ts = s.sampleAdaptive(1e-3);
    CHECK(ts.front() == 0.0);
    CHECK(ts.back() == 3.0);
    CHECK(std::is_sorted(ts.begin(), ts.end()));
    // Every polyline piece is within the tolerance of the curve between its ends (checked densely).
    for (std::size_t i = 0; i + 1 < ts.size(); ++i) {
        const Eigen::Vector2d a = s.evaluate(ts[i]), b = s.evaluate(ts[i + 1]);
        for (int k = 1; k < 10; ++k) {
            const double u = k / 10.0;
            const Eigen::Vector2d q = s.evaluate(ts[i] + u * (ts[i + 1] - ts[i]));
            const Eigen::Vector2d ab = b - a;
            const double w = std::clamp((q - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
            CHECK((q - (a + w * ab)).norm() <= 1e-3 * (1 + 1e-9));
        }
    }
}

TEST_CASE("BezierSpline validation names what is wrong", "[spline]")
{
    CHECK_THROWS_WITH((Spline2(3, false, randomPoints<double, 2>(6, 1))), Catch::Contains("6 points do not fit degree 3"));
    CHECK_THROWS_WITH((Spline2(3, true, randomPoints<double, 2>(7, 1))), Catch::Contains("L*degree points"));
    CHECK_THROWS_WITH((Spline2(0, false, randomPoints<double, 2>(2, 1))), Catch::Contains("degree 0"));
    CHECK_THROWS_WITH((Spline2(3, false, randomPoints<double, 2>(7, 1), {1.0})), Catch::Contains("1 intervals for 2 segments"));
    CHECK_THROWS_WITH((Spline2(3, false, randomPoints<double, 2>(7, 1), {1.0, 0.0})), Catch::Contains("interval 1"));
    CHECK_THROWS_WITH((Spline2(3, false, randomPoints<double, 2>(7, 1), {-2.0, 1.0})), Catch::Contains("interval 0"));
    PointMatrix<double, 2> bad = randomPoints<double, 2>(4, 1);
    bad(1, 2) = std::nan("");
    CHECK_THROWS_WITH(Spline2(3, false, bad), Catch::Contains("point 2 coordinate 1 is not finite"));
    CHECK_THROWS_WITH((Spline2(3, false, randomPoints<double, 2>(7, 1)).deBoorPoints(EndCondition::Closed)),
                      Catch::Contains("open spline"));
    CHECK_THROWS_WITH((Spline2(2, false, randomPoints<double, 2>(5, 1)).deBoorPoints(EndCondition::Open)),
                      Catch::Contains("cubic"));
}

} // namespace test_bezier_spline
