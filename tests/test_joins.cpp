// Joins (curve/joins.h): C1 joins are C1 and in general not C2, G1 joins are G1 and in general not
// C1, C2 joins of cubics are C2 and not C3, for every variant, uniform and non-uniform intervals;
// the continuity is checked from the control points in the test and by the analysis; only the
// documented points move.

#include <catch2/catch.hpp>

#include <freeform/curve/continuity.h>
#include <freeform/curve/joins.h>

#include <random>
#include <set>

#include "support/random.h"

namespace test_joins {

using namespace freeform;
using freeform::test::randomPoints;
using Spline2 = BezierSpline<double, 2>;

namespace {

const JoinMove kMoves[] = {JoinMove::Joint, JoinMove::LeftHandle, JoinMove::RightHandle};

/// Columns that differ between two control point matrices.
std::set<int> movedColumns(const PointMatrix<double, 2>& a, const PointMatrix<double, 2>& b)
{
    std::set<int> out;
    for (int i = 0; i < a.cols(); ++i)
        if (a.col(i) != b.col(i)) out.insert(i);
    return out;
}

Spline2 randomSpline(int n, bool closed, std::uint32_t seed, bool uniform)
{
    const int L = 4;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.3, 3.0);
    std::vector<double> h(L, 1.0);
    if (!uniform)
        for (double& x : h) x = u(rng);
    return Spline2(n, closed, randomPoints<double, 2>(closed ? L * n : L * n + 1, seed), h);
}

/// One-sided first derivatives at joint j, from the control points (independent of the library).
std::pair<Eigen::Vector2d, Eigen::Vector2d> firstDerivatives(const Spline2& s, int j)
{
    const int L = s.segmentCount(), n = s.degree(), li = j == 0 ? L - 1 : j - 1;
    const auto c = s.segmentPoints(li), d = s.segmentPoints(j);
    return {n * (c.col(n) - c.col(n - 1)) / s.intervals()[li], n * (d.col(1) - d.col(0)) / s.intervals()[j]};
}

} // namespace

TEST_CASE("C1 joins are C1 and in general not C2", "[joins]")
{
    for (const int n : {2, 3, 5}) {
        for (const bool closed : {false, true}) {
            for (const bool uniform : {true, false}) {
                for (const JoinMove move : kMoves) {
                    const Spline2 s = randomSpline(n, closed, 7 + static_cast<std::uint32_t>(n), uniform);
                    const int j = closed ? 0 : 2;
                    const Spline2 t = joinC1(s, j, move);
                    CAPTURE(n, closed, uniform, static_cast<int>(move));
                    const auto [dl, dr] = firstDerivatives(t, j);
                    CHECK((dl - dr).norm() < 1e-12 * (1 + dl.norm()));
                    const auto report = continuityReport(t);
                    for (const auto& r : report) {
                        if (r.joint != j) continue;
                        CHECK(r.C == 1);
                        CHECK(r.G == 1);
                    }
                    // What moved: the joint alone, or the one handle on the moving side.
                    const int left = (j == 0 ? s.segmentCount() - 1 : j - 1);
                    const int expected = move == JoinMove::Joint      ? s.pointIndex(j, 0)
                                         : move == JoinMove::LeftHandle ? s.pointIndex(left, n - 1)
                                                                        : s.pointIndex(j, 1);
                    CHECK(movedColumns(s.controlPoints(), t.controlPoints()) == std::set<int>{expected});
                }
            }
        }
    }
}

TEST_CASE("the seed's C1 joint: the midpoint of the neighbouring handles", "[joins]")
{
    PointMatrix<double, 2> p(2, 7);
    p << 0, 1, 2, 5, 4, 6, 7, 0, 1, 2, 9, 4, 1, 0;
    const Spline2 t = joinC1(Spline2(3, false, p), 1, JoinMove::Joint);
    CHECK(t.controlPoints().col(3) == Eigen::Vector2d(3, 3)); // ((2,2) + (4,4)) / 2
    // Ratio form: intervals 1 and 3 put the joint at (3 c_2 + 1 d_1) / 4.
    const Spline2 u = joinC1(Spline2(3, false, p, {1.0, 3.0}), 1, JoinMove::Joint);
    CHECK(u.controlPoints().col(3) == Eigen::Vector2d(2.5, 2.5));
    // Mirror: keep the left handle (2,2) and the joint (5,9): d_1 = (5,9) + ((5,9) - (2,2)).
    const Spline2 v = joinC1(Spline2(3, false, p), 1, JoinMove::RightHandle);
    CHECK(v.controlPoints().col(4) == Eigen::Vector2d(8, 16));
}

TEST_CASE("G1 joins are G1 and in general not C1", "[joins]")
{
    for (const int n : {2, 3, 4}) {
        for (const JoinMove move : kMoves) {
            const Spline2 s = randomSpline(n, false, 50 + static_cast<std::uint32_t>(n), false);
            const Spline2 t = joinG1(s, 1, move);
            CAPTURE(n, static_cast<int>(move));
            const auto [dl, dr] = firstDerivatives(t, 1);
            CHECK((dl.normalized() - dr.normalized()).norm() < 1e-12);
            const auto r = continuityReport(t)[0];
            CHECK(r.joint == 1);
            CHECK(r.C == 0);
            CHECK(r.G == 1);
            if (move != JoinMove::Joint) {
                // The moved handle keeps its length.
                const int idx = move == JoinMove::RightHandle ? s.pointIndex(1, 1) : s.pointIndex(0, n - 1);
                const Eigen::Vector2d joint = s.controlPoints().col(s.pointIndex(1, 0));
                CHECK((t.controlPoints().col(idx) - joint).norm() ==
                      Approx((s.controlPoints().col(idx) - joint).norm()).epsilon(1e-14));
                CHECK(movedColumns(s.controlPoints(), t.controlPoints()) == std::set<int>{idx});
            }
        }
    }
}

TEST_CASE("C2 joins of cubics are C2 and not C3", "[joins]")
{
    for (const bool closed : {false, true}) {
        for (const bool uniform : {true, false}) {
            for (const JoinMove move : kMoves) {
                const Spline2 s = randomSpline(3, closed, 90, uniform);
                const int j = closed ? 0 : 2;
                const Spline2 t = joinC2(s, j, move);
                CAPTURE(closed, uniform, static_cast<int>(move));
                const int L = s.segmentCount(), li = j == 0 ? L - 1 : j - 1;
                const auto c = t.segmentPoints(li), d = t.segmentPoints(j);
                const double hl = t.intervals()[li], hr = t.intervals()[j];
                const Eigen::Vector2d d2l = 6 * (c.col(3) - 2 * c.col(2) + c.col(1)) / (hl * hl);
                const Eigen::Vector2d d2r = 6 * (d.col(2) - 2 * d.col(1) + d.col(0)) / (hr * hr);
                CHECK((d2l - d2r).norm() < 1e-11 * (1 + d2l.norm()));
                for (const auto& r : continuityReport(t)) {
                    if (r.joint != j) continue;
                    CHECK(r.C == 2);
                    CHECK(r.G == 2);
                }
                std::set<int> expected;
                if (move == JoinMove::Joint)
                    expected = {t.pointIndex(li, 2), t.pointIndex(j, 0), t.pointIndex(j, 1)};
                else if (move == JoinMove::RightHandle)
                    expected = {t.pointIndex(j, 1), t.pointIndex(j, 2)};
                else
                    expected = {t.pointIndex(li, 1), t.pointIndex(li, 2)};
                CHECK(movedColumns(s.controlPoints(), t.controlPoints()) == expected);
            }
        }
    }
    CHECK_THROWS_WITH(joinC2(randomSpline(4, false, 1, true), 1, JoinMove::Joint), Catch::Contains("cubic"));
}

TEST_CASE("C0 joins of separate segments", "[joins]")
{
    const auto a = randomPoints<double, 2>(4, 5), b = randomPoints<double, 2>(4, 6);
    {
        PointMatrix<double, 2> l = a, r = b;
        joinC0<double, 2>(l, r, JoinMove::Joint);
        CHECK(l.col(3) == r.col(0));
        CHECK(l.col(3) == ((a.col(3) + b.col(0)) / 2).eval());
        CHECK(l.leftCols(3) == a.leftCols(3));
        CHECK(r.rightCols(3) == b.rightCols(3));
    }
    {
        PointMatrix<double, 2> l = a, r = b;
        joinC0<double, 2>(l, r, JoinMove::RightHandle);
        CHECK(l == a);
        CHECK(r.col(0) == a.col(3));
        CHECK((r.col(1) - r.col(0)).isApprox(b.col(1) - b.col(0), 1e-14)); // the handle travels along
        const auto rep = jointContinuity<double, 2>(l, r, 1.0, 1.0);
        CHECK(rep.C >= 0);
        CHECK(rep.jumps[0] == 0);
    }
    {
        PointMatrix<double, 2> l = a, r = b;
        CHECK(jointContinuity<double, 2>(l, r, 1.0, 1.0).C == -1);
        joinC1<double, 2>(l, r, 2.0, 1.0, JoinMove::LeftHandle);
        CHECK(r == b);
        const auto rep = jointContinuity<double, 2>(l, r, 2.0, 1.0);
        CHECK(rep.C == 1);
    }
}

TEST_CASE("join input validation", "[joins]")
{
    const Spline2 s = randomSpline(3, false, 3, true);
    CHECK_THROWS_WITH(joinC1(s, 0, JoinMove::Joint), Catch::Contains("not an inner joint"));
    CHECK_THROWS_WITH(joinC1(s, 4, JoinMove::Joint), Catch::Contains("not an inner joint"));
    const Spline2 line(1, false, randomPoints<double, 2>(4, 3));
    CHECK_THROWS_WITH(joinC1(line, 1, JoinMove::RightHandle), Catch::Contains("a line has no handles"));
    CHECK_NOTHROW(joinC1(line, 1, JoinMove::Joint));
    PointMatrix<double, 2> p(2, 7);
    p << 0, 1, 1, 1, 2, 3, 4, 0, 1, 1, 1, 0, 0, 0; // left handle c_2 on the joint
    CHECK_THROWS_WITH(joinG1(Spline2(3, false, p), 1, JoinMove::RightHandle), Catch::Contains("coincides"));
}

} // namespace test_joins
