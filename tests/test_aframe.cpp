// The A-frame (curve/aframe.h): C2 at every joint for random de Boor polygons under all three end
// conditions and uniform / non-uniform intervals, agreement with an independent de Boor algorithm
// on the documented knot sequences (long double), the hand-computed uniform formulas, the inverse
// (round trip and refusal of non-C2 chains), and input validation.

#include <catch2/catch.hpp>

#include <freeform/curve/aframe.h>
#include <freeform/curve/bezier_spline.h>
#include <freeform/curve/continuity.h>

#include <random>
#include <vector>

#include "support/random.h"

namespace test_aframe {

using namespace freeform;
using freeform::test::randomPoints;

namespace {

const EndCondition kEnds[] = {EndCondition::Open, EndCondition::Clamped, EndCondition::Closed};

std::vector<double> randomIntervals(int count, std::uint32_t seed, bool uniform)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.1, 4.0);
    std::vector<double> h(static_cast<std::size_t>(count), 1.0);
    if (!uniform)
        for (double& x : h) x = u(rng);
    return h;
}

/// The documented knot interval h_k for any k (independent of the library's helper).
double knotInterval(const std::vector<double>& h, EndCondition end, long k)
{
    const long L = static_cast<long>(h.size());
    if (end == EndCondition::Closed) return h[static_cast<std::size_t>(((k % L) + L) % L)];
    if (k >= 0 && k < L) return h[static_cast<std::size_t>(k)];
    if (end == EndCondition::Clamped) return 0.0;
    return k < 0 ? h.front() : h.back();
}

/// The spline by de Boor's algorithm on the full knot vector, in long double: for Closed the open
/// spline of d_0..d_(N-1), d_0, d_1, d_2 with periodic knots. T is the global parameter in [0, sum h].
template <int Dim>
Eigen::Matrix<long double, Dim, 1> deBoorEvaluate(const PointMatrix<double, Dim>& d, EndCondition end,
                                                  const std::vector<double>& h, long double T)
{
    std::vector<Eigen::Matrix<long double, Dim, 1>> P;
    for (Eigen::Index i = 0; i < d.cols(); ++i) P.push_back(d.col(i).template cast<long double>());
    if (end == EndCondition::Closed)
        for (int i = 0; i < 3; ++i) P.push_back(d.col(i).template cast<long double>());
    const long M = static_cast<long>(P.size()), L = static_cast<long>(h.size());
    // Knots t_0..t_(M+3): t_3 = 0 starts the domain, t_(3+i) - t_(2+i) = h_(i-1).
    std::vector<long double> t(static_cast<std::size_t>(M + 4));
    t[3] = 0;
    for (long k = 2; k >= 0; --k) t[k] = t[k + 1] - knotInterval(h, end, k - 3);
    for (long k = 4; k < M + 4; ++k) t[k] = t[k - 1] + knotInterval(h, end, k - 4);
    REQUIRE(t[static_cast<std::size_t>(3 + L)] > 0);
    long r = 3;
    while (r + 1 < 3 + L && T >= t[static_cast<std::size_t>(r + 1)]) ++r;
    std::vector<Eigen::Matrix<long double, Dim, 1>> w(P.begin() + (r - 3), P.begin() + (r + 1));
    for (int k = 1; k <= 3; ++k) {
        for (long j = r; j >= r - 3 + k; --j) {
            const long double a = (T - t[j]) / (t[j + 4 - k] - t[j]);
            w[j - (r - 3)] = (1 - a) * w[j - 1 - (r - 3)] + a * w[j - (r - 3)];
        }
    }
    return w[3];
}

} // namespace

TEST_CASE("uniform open A-frame: the hand formulas of docs/math.md (A-frame)", "[aframe]")
{
    PointMatrix<double, 2> d(2, 4);
    d << 0, 6, 12, 18, 0, 6, -6, 0;
    const PointMatrix<double, 2> b = aframeBezierPoints<double, 2>(d, EndCondition::Open);
    REQUIRE(b.cols() == 4);
    // b0 = (a0 + 4 a1 + a2)/6, b1 = (2 a1 + a2)/3, b2 = (a1 + 2 a2)/3, b3 = (a1 + 4 a2 + a3)/6.
    CHECK(b(0, 0) == Approx(6).epsilon(1e-15));
    CHECK(b(1, 0) == Approx(3).epsilon(1e-15));
    CHECK(b(0, 1) == Approx(8).epsilon(1e-15));
    CHECK(b(1, 1) == Approx(2).epsilon(1e-15));
    CHECK(b(0, 2) == Approx(10).epsilon(1e-15));
    CHECK(b(1, 2) == Approx(-2).epsilon(1e-15));
    CHECK(b(0, 3) == Approx(12).epsilon(1e-15));
    CHECK(b(1, 3) == Approx(-3).epsilon(1e-15));
}

TEST_CASE("clamped ends start and end at the end de Boor points, tangent to the end legs", "[aframe]")
{
    const auto d = randomPoints<double, 3>(7, 11);
    const auto h = randomIntervals(4, 12, false);
    const auto b = aframeBezierPoints<double, 3>(d, EndCondition::Clamped, h);
    REQUIRE(b.cols() == 13);
    CHECK(b.col(0) == d.col(0));
    CHECK(b.col(1) == d.col(1));
    CHECK(b.col(12) == d.col(6));
    CHECK(b.col(11) == d.col(5));
}

TEST_CASE("random de Boor polygons give C2 splines, and C3 is reported false", "[aframe]")
{
    for (const EndCondition end : kEnds) {
        for (const bool uniform : {true, false}) {
            for (std::uint32_t seed = 1; seed <= 12; ++seed) {
                const int count = 5 + static_cast<int>(seed % 9);
                const int L = aframeSegmentCount(count, end);
                const auto d = randomPoints<double, 2>(count, seed * 31 + (uniform ? 0 : 7));
                const auto h = randomIntervals(L, seed, uniform);
                CAPTURE(toString(end), uniform, seed, count);
                const auto spline = BezierSpline<double, 2>::fromDeBoor(d, end, h);
                REQUIRE(spline.segmentCount() == L);
                REQUIRE(spline.closed() == (end == EndCondition::Closed));
                // Independent check from the control points: C1 and C2 with the interval ratios.
                for (int j = end == EndCondition::Closed ? 0 : 1; j < L; ++j) {
                    const int li = j == 0 ? L - 1 : j - 1;
                    const auto c = spline.segmentPoints(li), e = spline.segmentPoints(j);
                    const double hl = h[li], hr = h[j];
                    const Eigen::Vector2d d1l = 3 * (c.col(3) - c.col(2)) / hl, d1r = 3 * (e.col(1) - e.col(0)) / hr;
                    const Eigen::Vector2d d2l = 6 * (c.col(3) - 2 * c.col(2) + c.col(1)) / (hl * hl);
                    const Eigen::Vector2d d2r = 6 * (e.col(2) - 2 * e.col(1) + e.col(0)) / (hr * hr);
                    const double s1 = std::max(d1l.norm(), d1r.norm()) + 1, s2 = std::max(d2l.norm(), d2r.norm()) + 1;
                    CHECK((d1l - d1r).norm() < 1e-12 * s1);
                    CHECK((d2l - d2r).norm() < 1e-12 * s2);
                }
                for (const auto& joint : continuityReport(spline)) {
                    CAPTURE(joint.joint);
                    CHECK(joint.C == 2);
                    CHECK(joint.G == 2);
                    CHECK(joint.jumps[3] > 1e-6);
                }
            }
        }
    }
}

TEST_CASE("the A-frame agrees with de Boor's algorithm on the documented knot sequences", "[aframe]")
{
    for (const EndCondition end : kEnds) {
        for (const bool uniform : {true, false}) {
            for (std::uint32_t seed = 1; seed <= 6; ++seed) {
                const int count = 4 + static_cast<int>(seed);
                const int L = aframeSegmentCount(count, end);
                const auto d = randomPoints<double, 3>(count, seed + 100);
                const auto h = randomIntervals(L, seed + 200, uniform);
                CAPTURE(toString(end), uniform, seed);
                const auto spline = BezierSpline<double, 3>::fromDeBoor(d, end, h);
                for (int k = 0; k <= 40; ++k) {
                    const double T = spline.domainEnd() * k / 40;
                    const auto expected = deBoorEvaluate<3>(d, end, h, T);
                    CHECK((spline.evaluate(T).cast<long double>() - expected).norm() < 1e-13L);
                }
            }
        }
    }
}

TEST_CASE("closed splines are segment i of the open spline over the wrapped polygon", "[aframe]")
{
    const auto d = randomPoints<double, 2>(6, 5);
    PointMatrix<double, 2> wrapped(2, 9);
    wrapped << d, d.leftCols(3);
    const auto closed = aframeBezierPoints<double, 2>(d, EndCondition::Closed);
    const auto open = aframeBezierPoints<double, 2>(wrapped, EndCondition::Open);
    REQUIRE(closed.cols() == 18);
    REQUIRE(open.cols() == 19);
    CHECK((closed - open.leftCols(18)).cwiseAbs().maxCoeff() < 1e-15);
    CHECK((open.col(18) - closed.col(0)).norm() < 1e-15);
}

TEST_CASE("round trip de Boor -> Bézier -> de Boor gives back the input", "[aframe]")
{
    for (const EndCondition end : kEnds) {
        for (const bool uniform : {true, false}) {
            for (std::uint32_t seed = 1; seed <= 10; ++seed) {
                const int count = 4 + static_cast<int>(seed);
                const int L = aframeSegmentCount(count, end);
                const auto d = randomPoints<double, 2>(count, seed + 300);
                const auto h = randomIntervals(L, seed + 400, uniform);
                CAPTURE(toString(end), uniform, seed);
                const auto b = aframeBezierPoints<double, 2>(d, end, h);
                const auto back = aframeDeBoorPoints<double, 2>(b, end, h);
                REQUIRE(back.cols() == d.cols());
                CHECK((back - d).cwiseAbs().maxCoeff() < 1e-12);
            }
        }
    }
}

TEST_CASE("the inverse refuses a chain that is not C2", "[aframe]")
{
    const auto d = randomPoints<double, 2>(8, 77);
    for (const EndCondition end : kEnds) {
        PointMatrix<double, 2> b = aframeBezierPoints<double, 2>(d, end);
        b(0, 7) += 1e-3; // the inner point after joint 2: C1 and C2 break there
        CAPTURE(toString(end));
        CHECK_THROWS_WITH((aframeDeBoorPoints<double, 2>(b, end)), Catch::Contains("not C2 at joint 2"));
        // A deviation far below the tolerance is accepted.
        b(0, 7) -= 1e-3 - 1e-14;
        CHECK_NOTHROW((aframeDeBoorPoints<double, 2>(b, end)));
    }
}

TEST_CASE("A-frame input validation", "[aframe]")
{
    const auto d3 = randomPoints<double, 2>(3, 1);
    CHECK_THROWS_WITH((aframeBezierPoints<double, 2>(d3, EndCondition::Open)), Catch::Contains("too few"));
    CHECK_THROWS_WITH((aframeBezierPoints<double, 2>(d3, EndCondition::Clamped)), Catch::Contains("at least 4"));
    CHECK(aframeBezierPoints<double, 2>(d3, EndCondition::Closed).cols() == 9);
    const auto d5 = randomPoints<double, 2>(5, 2);
    CHECK_THROWS_WITH((aframeBezierPoints<double, 2>(d5, EndCondition::Open, {1.0})), Catch::Contains("1 intervals for 2 segments"));
    CHECK_THROWS_WITH((aframeBezierPoints<double, 2>(d5, EndCondition::Open, {1.0, 0.0})), Catch::Contains("interval 1"));
    CHECK_THROWS_WITH((aframeBezierPoints<double, 2>(d5, EndCondition::Open, {-1.0, 1.0})), Catch::Contains("interval 0"));
    CHECK_THROWS_WITH(parseEndCondition("loose", "doc"), Catch::Contains("unknown end condition \"loose\""));
    CHECK(parseEndCondition("clamped", "x") == EndCondition::Clamped);
    CHECK(toString(EndCondition::Closed) == "closed");
    CHECK(aframeSegmentCount(7, EndCondition::Open) == 4);
    CHECK(aframeSegmentCount(7, EndCondition::Closed) == 7);
    CHECK(aframeSegmentCount(2, EndCondition::Closed) == 0);
    CHECK_THROWS_WITH((aframeDeBoorPoints<double, 2>(randomPoints<double, 2>(6, 3), EndCondition::Open)),
                      Catch::Contains("do not form"));
}

TEST_CASE("float A-frame is C2 to float precision", "[aframe]")
{
    const auto d = randomPoints<float, 2>(9, 8);
    const auto spline = BezierSpline<float, 2>::fromDeBoor(d, EndCondition::Clamped);
    for (const auto& joint : continuityReport(spline)) CHECK(joint.C == 2);
    CHECK((spline.deBoorPoints(EndCondition::Clamped) - d).cwiseAbs().maxCoeff() < 1e-5f);
}

} // namespace test_aframe
