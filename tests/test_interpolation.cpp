// C2 cubic interpolation (curve/interpolation.h): cubic polynomials reproduced exactly with
// clamped ends, passing through every point, C2 at every joint (the closing one of periodic
// splines included), natural ends with zero second derivative, the tridiagonal solvers against a
// dense LU, and input validation.

#include <catch2/catch.hpp>

#include <freeform/curve/continuity.h>
#include <freeform/curve/interpolation.h>

#include <Eigen/LU>

#include <cmath>
#include <random>

#include "support/random.h"

namespace test_interpolation {

using namespace freeform;
using freeform::test::randomPoints;

namespace {

const Parametrization kParams[] = {Parametrization::Uniform, Parametrization::Chord, Parametrization::Centripetal};
const InterpolationEnd kEnds[] = {InterpolationEnd::Natural, InterpolationEnd::Clamped, InterpolationEnd::Periodic};

/// Second derivatives on both sides of joint j, from the control points.
template <int Dim>
std::pair<Point<double, Dim>, Point<double, Dim>> secondDerivatives(const BezierSpline<double, Dim>& s, int j)
{
    const int L = s.segmentCount(), li = j == 0 ? L - 1 : j - 1;
    const auto c = s.segmentPoints(li), d = s.segmentPoints(j);
    const double hl = s.intervals()[li], hr = s.intervals()[j];
    return {6 * (c.col(3) - 2 * c.col(2) + c.col(1)) / (hl * hl), 6 * (d.col(2) - 2 * d.col(1) + d.col(0)) / (hr * hr)};
}

} // namespace

TEST_CASE("clamped interpolation reproduces a cubic polynomial exactly", "[interpolation]")
{
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-2, 2), gap(0.2, 1.5);
    for (int trial = 0; trial < 10; ++trial) {
        // q(u) = a0 + a1 u + a2 u^2 + a3 u^3 in 3D.
        Eigen::Matrix<double, 3, 4> a;
        for (int k = 0; k < 12; ++k) a(k) = u(rng);
        auto q = [&](double x) { return Eigen::Vector3d(a.col(0) + x * (a.col(1) + x * (a.col(2) + x * a.col(3)))); };
        auto dq = [&](double x) { return Eigen::Vector3d(a.col(1) + x * (2 * a.col(2) + 3 * x * a.col(3))); };
        const int count = 3 + trial;
        std::vector<double> params{u(rng)};
        for (int i = 1; i < count; ++i) params.push_back(params.back() + gap(rng));
        PointMatrix<double, 3> pts(3, count);
        for (int i = 0; i < count; ++i) pts.col(i) = q(params[i]);
        InterpolationOptions<double, 3> opt;
        opt.end = InterpolationEnd::Clamped;
        opt.params = params;
        opt.startDerivative = dq(params.front());
        opt.endDerivative = dq(params.back());
        const auto s = interpolateCubic(pts, opt);
        CAPTURE(trial);
        REQUIRE(s.segmentCount() == count - 1);
        for (int k = 0; k <= 100; ++k) {
            const double x = params.front() + (params.back() - params.front()) * k / 100;
            const double T = x - params.front();
            CHECK((s.evaluate(T) - q(x)).norm() < 1e-12 * (1 + q(x).norm()));
            CHECK((s.derivatives(T, 1).col(1) - dq(x)).norm() < 1e-11 * (1 + dq(x).norm()));
        }
    }
}

TEST_CASE("the interpolant passes through every point and is C2 at every joint", "[interpolation]")
{
    for (const InterpolationEnd end : kEnds) {
        for (const Parametrization param : kParams) {
            for (std::uint32_t seed = 1; seed <= 5; ++seed) {
                const int count = 3 + static_cast<int>(seed) * 3;
                const auto pts = randomPoints<double, 2>(count, seed);
                InterpolationOptions<double, 2> opt;
                opt.end = end;
                opt.parametrization = param;
                opt.startDerivative = Eigen::Vector2d(1, -2);
                opt.endDerivative = Eigen::Vector2d(0.5, 3);
                const auto s = interpolateCubic(pts, opt);
                CAPTURE(toString(end), toString(param), seed);
                const bool periodic = end == InterpolationEnd::Periodic;
                REQUIRE(s.closed() == periodic);
                REQUIRE(s.segmentCount() == (periodic ? count : count - 1));
                for (int i = 0; i < count; ++i) CHECK(s.evaluate(s.knot(i)) == pts.col(i));
                // Parameter gaps as documented.
                for (int i = 0; i < s.segmentCount(); ++i) {
                    const double chord = (pts.col((i + 1) % count) - pts.col(i)).norm();
                    const double expected = param == Parametrization::Uniform ? 1.0
                                          : param == Parametrization::Chord ? chord : std::sqrt(chord);
                    CHECK(s.intervals()[i] == expected);
                }
                for (int j = periodic ? 0 : 1; j < s.segmentCount(); ++j) {
                    const auto [l, r] = secondDerivatives(s, j);
                    CHECK((l - r).norm() < 1e-11 * (1 + l.norm()));
                }
                for (const auto& joint : continuityReport(s)) CHECK(joint.C >= 2);
                if (end == InterpolationEnd::Natural) {
                    CHECK(s.derivatives(0, 2).col(2).norm() < 1e-11);
                    CHECK(s.derivatives(s.domainEnd(), 2).col(2).norm() < 1e-10);
                }
                if (end == InterpolationEnd::Clamped) {
                    CHECK((s.derivatives(0, 1).col(1) - opt.startDerivative).norm() < 1e-13);
                    CHECK((s.derivatives(s.domainEnd(), 1).col(1) - opt.endDerivative).norm() < 1e-12);
                }
            }
        }
    }
}

TEST_CASE("periodic interpolation of a circle is C2 everywhere, the closing joint included", "[interpolation]")
{
    const int count = 24;
    PointMatrix<double, 2> pts(2, count);
    for (int i = 0; i < count; ++i) {
        const double a = 2 * M_PI * i / count;
        pts.col(i) = Eigen::Vector2d(3 * std::cos(a), 3 * std::sin(a));
    }
    InterpolationOptions<double, 2> opt;
    opt.end = InterpolationEnd::Periodic;
    const auto s = interpolateCubic(pts, opt);
    const auto report = continuityReport(s);
    REQUIRE(report.size() == static_cast<std::size_t>(count));
    CHECK(report[0].joint == 0);
    for (const auto& j : report) {
        CHECK(j.C == 2);
        CHECK(j.G == 2);
    }
    // Close to the circle between the points (cubic splines are O(h^4) accurate).
    for (int k = 0; k < 500; ++k) CHECK(std::abs(s.evaluate(s.domainEnd() * k / 500).norm() - 3) < 1e-4);
    // By symmetry the speed is the same at every point.
    for (int i = 1; i < count; ++i)
        CHECK(s.derivatives(s.knot(i), 1).col(1).norm() == Approx(s.derivatives(0, 1).col(1).norm()).epsilon(1e-12));
    // Repeating the first point at the end changes nothing.
    PointMatrix<double, 2> repeated(2, count + 1);
    repeated << pts, pts.col(0);
    CHECK(interpolateCubic(repeated, opt).controlPoints() == s.controlPoints());
}

TEST_CASE("Thomas and Sherman-Morrison solvers against a dense LU", "[interpolation]")
{
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> u(-1, 1);
    for (const int n : {3, 4, 7, 30}) {
        std::vector<double> sub(n), diag(n), super(n);
        Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n), Ac = A;
        for (int i = 0; i < n; ++i) {
            sub[i] = u(rng), super[i] = u(rng), diag[i] = 2.5 + u(rng);
            A(i, i) = Ac(i, i) = diag[i];
            if (i > 0) A(i, i - 1) = Ac(i, i - 1) = sub[i];
            if (i + 1 < n) A(i, i + 1) = Ac(i, i + 1) = super[i];
        }
        Ac(0, n - 1) += sub[0];
        Ac(n - 1, 0) += super[n - 1];
        const Eigen::Matrix<double, 2, Eigen::Dynamic> rhs = randomPoints<double, 2>(n, 3);
        Eigen::Matrix<double, 2, Eigen::Dynamic> x = rhs;
        std::vector<double> scratch(n);
        solveTridiagonal(sub.data(), diag.data(), super.data(), x, scratch.data());
        const Eigen::MatrixXd expected = A.lu().solve(Eigen::MatrixXd(rhs.transpose()));
        CHECK((Eigen::MatrixXd(x.transpose()) - expected).cwiseAbs().maxCoeff() < 1e-13);
        Eigen::Matrix<double, 2, Eigen::Dynamic> y = rhs;
        solveCyclicTridiagonal(sub.data(), diag.data(), super.data(), y);
        const Eigen::MatrixXd expectedCyclic = Ac.lu().solve(Eigen::MatrixXd(rhs.transpose()));
        CHECK((Eigen::MatrixXd(y.transpose()) - expectedCyclic).cwiseAbs().maxCoeff() < 1e-13);
    }
}

TEST_CASE("interpolation input validation", "[interpolation]")
{
    PointMatrix<double, 2> pts(2, 3);
    pts << 0, 1, 1, 0, 0, 0;
    InterpolationOptions<double, 2> opt;
    CHECK_THROWS_WITH(interpolateCubic(pts, opt), Catch::Contains("points 1 and 2 coincide"));
    opt.parametrization = Parametrization::Uniform;
    CHECK_NOTHROW(interpolateCubic(pts, opt));
    opt.params = {0, 1};
    CHECK_THROWS_WITH(interpolateCubic(pts, opt), Catch::Contains("2 parameters for 3 points"));
    opt.params = {0, 1, 1};
    CHECK_THROWS_WITH(interpolateCubic(pts, opt), Catch::Contains("not strictly increasing"));
    opt.params = {};
    CHECK_THROWS_WITH((interpolateCubic(PointMatrix<double, 2>(pts.leftCols(1)), opt)), Catch::Contains("too few"));
    opt.end = InterpolationEnd::Periodic;
    PointMatrix<double, 2> two(2, 3);
    two << 0, 1, 0, 0, 1, 0;
    CHECK_THROWS_WITH(interpolateCubic(two, opt), Catch::Contains("2 distinct points are too few"));
    CHECK_THROWS_WITH(parseInterpolationEnd("free", "--end"), Catch::Contains("unknown end condition \"free\""));
    CHECK_THROWS_WITH(parseParametrization("arc", "--param"), Catch::Contains("unknown parametrization"));
    CHECK(parseParametrization("centripetal", "x") == Parametrization::Centripetal);
}

} // namespace test_interpolation
