// BezierCurve: exact values, identities over seeded random control points (degrees 1..20, 2D and
// 3D), numerics at degree 40, and input validation.

#include <catch2/catch.hpp>

#include <freeform/curve/bezier_curve.h>

#include <cmath>
#include <limits>
#include <random>

#include "support/random.h"

namespace test_bezier_curve {

using namespace freeform;
using freeform::test::randomPoints;

using Curve2 = BezierCurve<double, 2>;
using Curve3 = BezierCurve<double, 3>;

namespace {

const Curve2 kArch({{0, 0}, {1, 2}, {3, 2}, {4, 0}});

/// The scale of a curve's values: max |b_i|, for relative tolerances.
template <typename Curve>
double scaleOf(const Curve& c)
{
    return double(c.controlPoints().cwiseAbs().maxCoeff()) + 1e-300;
}

/// f'(t) by Richardson extrapolation of central differences in long double (error O(h^6)).
template <int Dim>
Point<long double, Dim> richardsonDerivative(const BezierCurve<long double, Dim>& f, long double t, long double h)
{
    auto central = [&](long double step) { return ((f(t + step) - f(t - step)) / (2 * step)).eval(); };
    const auto d1 = central(h), d2 = central(h / 2), d4 = central(h / 4);
    const auto r1 = ((4 * d2 - d1) / 3).eval(), r2 = ((4 * d4 - d2) / 3).eval();
    return (16 * r2 - r1) / 15;
}

} // namespace

TEST_CASE("the cubic arch at t = 1/2: hand-computed point and derivatives", "[curve]")
{
    // f(1/2) = (b0 + 3 b1 + 3 b2 + b3) / 8 = (16, 12) / 8.
    CHECK(kArch.evaluate(0.5) == Eigen::Vector2d(2, 1.5));
    CHECK(kArch.bernsteinSum(0.5) == Eigen::Vector2d(2, 1.5));
    const auto d = kArch.derivatives(0.5, 4);
    CHECK(d.col(0) == Eigen::Vector2d(2, 1.5));
    CHECK(d.col(1) == Eigen::Vector2d(4.5, 0));   // 3 ((1,2)/4 + (2,0)/2 + (1,-2)/4)
    CHECK(d.col(2) == Eigen::Vector2d(0, -12));   // 6 ((1,-2) + (-1,-2)) / 2
    CHECK(d.col(3) == Eigen::Vector2d(-12, 0));   // 6 ((-1,-2) - (1,-2))
    CHECK(d.col(4) == Eigen::Vector2d(0, 0));     // above the degree
    // Signed curvature (x'y'' - y'x'') / |f'|^3 = (4.5 * -12) / 4.5^3 = -12 / 20.25 (turning right).
    CHECK(kArch.curvature(0.5) == Approx(-12.0 / 20.25).epsilon(1e-15));
    CHECK(kArch.tangent(0.5) == Eigen::Vector2d(1, 0));
    // t = 1/3: B^3 = (8, 12, 6, 1) / 27, f = (34, 36) / 27.
    CHECK(kArch.evaluate(1.0 / 3).x() == Approx(34.0 / 27).epsilon(1e-15));
    CHECK(kArch.evaluate(1.0 / 3).y() == Approx(36.0 / 27).epsilon(1e-15));
}

TEST_CASE("the hodograph has the forward differences as control points", "[curve]")
{
    const Curve2 h = kArch.derivative();
    REQUIRE(h.degree() == 2);
    CHECK(h.controlPoint(0) == Eigen::Vector2d(3, 6));
    CHECK(h.controlPoint(1) == Eigen::Vector2d(6, 0));
    CHECK(h.controlPoint(2) == Eigen::Vector2d(3, -6));
    const Curve2 h3 = kArch.derivative(3);
    REQUIRE(h3.degree() == 0);
    CHECK(h3.controlPoint(0) == Eigen::Vector2d(-12, 0));
    const Curve2 h5 = kArch.derivative(5);
    CHECK(h5.degree() == 0);
    CHECK(h5.controlPoint(0) == Eigen::Vector2d(0, 0));
}

TEMPLATE_TEST_CASE_SIG("identities over random control points", "[curve][property]", ((int Dim), Dim), 2, 3)
{
    using Curve = BezierCurve<double, Dim>;
    using LCurve = BezierCurve<long double, Dim>;
    using P = Point<double, Dim>;
    for (int n = 1; n <= 20; ++n) {
        const std::uint32_t seed = 1000u * Dim + static_cast<std::uint32_t>(n);
        const Curve f(randomPoints<double, Dim>(n + 1, seed));
        const LCurve fl(f.controlPoints().template cast<long double>());
        const double scale = scaleOf(f);
        const auto& b = f.controlPoints();
        INFO("degree " << n << ", seed " << seed);

        // Endpoint interpolation and endpoint derivatives, exactly.
        CHECK(f(0.0) == P(b.col(0)));
        CHECK(f(1.0) == P(b.col(n)));
        CHECK((f.derivatives(0.0, 1).col(1) - double(n) * (b.col(1) - b.col(0))).norm() <= 1e-14 * n * scale);
        CHECK((f.derivatives(1.0, 1).col(1) - double(n) * (b.col(n) - b.col(n - 1))).norm() <= 1e-14 * n * scale);

        const Curve d1 = f.derivative(1), d2 = f.derivative(2);
        const LCurve dl1 = fl.derivative(1);
        const Curve elevated = f.elevated(2);
        const auto [left, right] = f.split(0.3);
        const Curve rev = f.reversed();
        for (int s = 0; s <= 50; ++s) {
            const double t = s / 50.0;
            INFO("t = " << t);
            const P p = f.deCasteljau(t);
            // de Casteljau equals the Bernstein sum.
            REQUIRE((p - f.bernsteinSum(t)).norm() <= 1e-14 * n * scale);
            // derivatives() agrees with the hodographs.
            const auto jet = f.derivatives(t, 3);
            REQUIRE((jet.col(0) - p).norm() <= 1e-14 * n * scale);
            REQUIRE((jet.col(1) - d1(t)).norm() <= 1e-13 * n * n * scale);
            REQUIRE((jet.col(2) - d2(t)).norm() <= 1e-12 * n * n * n * scale);
            // Elevation keeps the shape; reversal runs backwards.
            REQUIRE((elevated(t) - p).norm() <= 1e-14 * n * scale);
            REQUIRE((rev(1 - t) - p).norm() <= 1e-14 * n * scale);
            // The halves of the split reproduce the curve.
            if (t <= 0.3) REQUIRE((left(t / 0.3) - p).norm() <= 1e-13 * n * scale);
            if (t >= 0.3) REQUIRE((right((t - 0.3) / 0.7) - p).norm() <= 1e-13 * n * scale);
            // The hodograph equals a Richardson-extrapolated finite difference (interior t).
            if (s > 0 && s < 50) {
                const auto fd = richardsonDerivative<Dim>(fl, static_cast<long double>(t), 1e-3L);
                const double err = double((dl1(static_cast<long double>(t)) - fd).norm());
                REQUIRE(err <= 1e-9 * std::pow(double(n), 3) * scale);
            }
        }
    }
}

TEMPLATE_TEST_CASE_SIG("affine invariance and convex hull containment", "[curve][property]", ((int Dim), Dim), 2, 3)
{
    using Curve = BezierCurve<double, Dim>;
    using P = Point<double, Dim>;
    std::mt19937 rng(7);
    std::normal_distribution<double> g;
    for (int n = 1; n <= 20; ++n) {
        const Curve f(randomPoints<double, Dim>(n + 1, 77u + n));
        LinearMap<double, Dim> a;
        for (int r = 0; r < Dim; ++r)
            for (int c = 0; c < Dim; ++c) a(r, c) = g(rng);
        P shift;
        for (int r = 0; r < Dim; ++r) shift[r] = g(rng);
        const Curve image = f.transformed(a, shift);
        // The support function of the hull: for every direction u, u.f(t) <= max_i u.b_i.
        std::vector<P> dirs;
        for (int k = 0; k < 64; ++k) {
            P u;
            for (int r = 0; r < Dim; ++r) u[r] = g(rng);
            dirs.push_back(u.normalized());
        }
        for (int s = 0; s <= 100; ++s) {
            const double t = s / 100.0;
            INFO("degree " << n << ", t = " << t);
            REQUIRE((image(t) - (a * f(t) + shift)).norm() <= 1e-13 * n * (1 + a.norm()));
            const P p = f(t);
            for (const P& u : dirs) {
                const double support = (u.transpose() * f.controlPoints()).maxCoeff();
                REQUIRE(u.dot(p) <= support + 1e-14);
            }
        }
    }
}

TEST_CASE("degree 40 in double agrees with a long double reference to 1e-12", "[curve][numerics]")
{
    for (std::uint32_t seed = 1; seed <= 5; ++seed) {
        // Coordinates in [1, 2]: the curve stays in [1, 2], so a relative error is well defined.
        const auto pts = randomPoints<double, 3>(41, seed, 1.0, 2.0);
        const Curve3 f(pts);
        const BezierCurve<long double, 3> ref(pts.cast<long double>());
        std::vector<double> ts;
        for (int s = 0; s <= 1000; ++s) ts.push_back(s / 1000.0);
        const auto batch = f.evaluateMany(ts);
        for (std::size_t s = 0; s < ts.size(); ++s) {
            const auto exact = ref.deCasteljau(static_cast<long double>(ts[s]));
            const double norm = double(exact.norm());
            INFO("seed " << seed << ", t = " << ts[s]);
            REQUIRE(double((f.deCasteljau(ts[s]).cast<long double>() - exact).norm()) <= 1e-12 * norm);
            REQUIRE(double((f.bernsteinSum(ts[s]).cast<long double>() - exact).norm()) <= 1e-12 * norm);
            REQUIRE(double((batch.col(s).cast<long double>() - exact).norm()) <= 1e-12 * norm);
        }
    }
}

TEMPLATE_TEST_CASE_SIG("the batch path matches de Casteljau within its error bound", "[curve][batch]",
                       ((typename S, int Dim), S, Dim), (float, 2), (float, 3), (double, 2), (double, 3),
                       (long double, 3))
{
    using Curve = BezierCurve<S, Dim>;
    const S eps = std::numeric_limits<S>::epsilon();
    for (int n : {0, 1, 2, 3, 5, 7, 15, 24, 40}) {
        // Mixed signs: compare against the bound ~ n eps sum |b_i| B_i(t), not |f(t)|.
        const auto pts = randomPoints<S, Dim>(n + 1, 500u + n);
        const Curve f(pts);
        const Curve absCurve(pts.cwiseAbs().eval());
        std::vector<S> ts;
        for (int s = 0; s <= 203; ++s) ts.push_back(S(s) / S(203));
        ts.push_back(S(0.5));
        ts.push_back(S(0.5) + eps);
        const auto batch = f.evaluateMany(ts);
        REQUIRE(batch.cols() == static_cast<Eigen::Index>(ts.size()));
        for (std::size_t s = 0; s < ts.size(); ++s) {
            const S bound = S(8) * S(n + 1) * eps * absCurve(ts[s]).norm() + std::numeric_limits<S>::min();
            INFO("degree " << n << ", t = " << ts[s]);
            REQUIRE((batch.col(s) - f.deCasteljau(ts[s])).norm() <= bound);
        }
        // The end points are reproduced exactly.
        CHECK(batch.col(0) == pts.col(0));
        CHECK(batch.col(203) == pts.col(n));
    }
}

TEST_CASE("degree reduction", "[curve]")
{
    SECTION("an elevated curve reduces back exactly")
    {
        for (int n = 1; n <= 12; ++n) {
            const Curve3 f(randomPoints<double, 3>(n + 1, 900u + n));
            const auto r = f.elevated().reduced();
            INFO("degree " << n);
            REQUIRE(r.curve.degree() == n);
            CHECK(r.errorBound <= 1e-12);
            CHECK((r.curve.controlPoints() - f.controlPoints()).cwiseAbs().maxCoeff() <= 1e-12);
        }
    }
    SECTION("the reported bound holds and is not vacuous")
    {
        for (int n = 2; n <= 12; ++n) {
            const Curve2 f(randomPoints<double, 2>(n + 1, 950u + n));
            const auto r = f.reduced();
            double worst = 0;
            for (int s = 0; s <= 2000; ++s) worst = std::max(worst, (r.curve(s / 2000.0) - f(s / 2000.0)).norm());
            INFO("degree " << n);
            CHECK(worst <= r.errorBound * (1 + 1e-12));
            CHECK(worst > 0);
            // End points are kept.
            CHECK(r.curve(0.0) == f(0.0));
            CHECK(r.curve(1.0) == f(1.0));
        }
    }
    CHECK_THROWS_AS(Curve2({{1, 2}}).reduced(), Error);
}

TEST_CASE("tight bounding box", "[curve]")
{
    const auto box = kArch.boundingBox();
    CHECK(box.min().x() == 0);
    CHECK(box.max().x() == 4);
    CHECK(box.min().y() == 0);
    CHECK(box.max().y() == Approx(1.5).epsilon(1e-15)); // the apex, not the control points' 2
    for (int n = 2; n <= 15; ++n) {
        const Curve3 f(randomPoints<double, 3>(n + 1, 40u + n));
        const auto b = f.boundingBox();
        Eigen::AlignedBox3d sampled;
        for (int s = 0; s <= 20000; ++s) sampled.extend(f(s / 20000.0));
        INFO("degree " << n);
        // Contains every sample, and is no larger than the samples by more than sampling error.
        CHECK((b.min() - sampled.min()).maxCoeff() <= 1e-14);
        CHECK((sampled.max() - b.max()).maxCoeff() <= 1e-14);
        CHECK((sampled.min() - b.min()).maxCoeff() <= 1e-6);
        CHECK((b.max() - sampled.max()).maxCoeff() <= 1e-6);
    }
}

TEST_CASE("arc length of known curves and its inverse", "[curve]")
{
    // A straight segment with unevenly spaced control points: length |b3 - b0| = 5.
    const Curve2 line({{0, 0}, {0.3, 0.4}, {2.4, 3.2}, {3, 4}});
    CHECK(line.arcLength(1e-13) == Approx(5.0).epsilon(1e-12));
    // The parabola y = x^2 on [0, 1]: length sqrt(5)/2 + asinh(2)/4.
    const Curve2 parabola({{0, 0}, {0.5, 0}, {1, 1}});
    CHECK(parabola.arcLength(1e-14) == Approx(std::sqrt(5.0) / 2 + std::asinh(2.0) / 4).epsilon(1e-12));
    // Quarter of the length along the line is where x = 0.75 (the parameter is not 1/4).
    const double t = line.parameterAtLength(1.25, 1e-12);
    CHECK(line(t).x() == Approx(0.75).epsilon(1e-10));
    CHECK(t != Approx(0.25).epsilon(1e-3));
    for (double s : {0.1, 0.5, 0.9}) {
        const double target = s * parabola.arcLength(1e-14);
        CHECK(parabola.arcLength(1e-14, 0.0, parabola.parameterAtLength(target, 1e-13)) == Approx(target).epsilon(1e-11));
    }
}

TEST_CASE("closest point is global", "[curve]")
{
    // A U shape: from (0.9, 3) a local method started at t = 0 finds the left arm; the right arm
    // at x = 1 is nearer.
    const Curve2 u({{0, 4}, {0, -2}, {1, -2}, {1, 4}});
    const auto c = u.closestPoint({0.9, 3});
    CHECK(c.point.x() > 0.9);
    CHECK(c.distance == Approx((u(c.t) - Eigen::Vector2d(0.9, 3)).norm()));
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> box(-1.5, 1.5);
    for (int n = 1; n <= 12; ++n) {
        const Curve3 f(randomPoints<double, 3>(n + 1, 300u + n));
        for (int trial = 0; trial < 20; ++trial) {
            const Eigen::Vector3d p(box(rng), box(rng), box(rng));
            const auto best = f.closestPoint(p);
            double brute = std::numeric_limits<double>::infinity();
            for (int s = 0; s <= 4000; ++s) brute = std::min(brute, (f(s / 4000.0) - p).norm());
            INFO("degree " << n << ", trial " << trial);
            REQUIRE(best.distance <= brute + 1e-12);
            REQUIRE(best.distance >= brute - 1e-4); // the dense sample is close to the optimum
            REQUIRE((f(best.t) - best.point).norm() <= 1e-15);
        }
    }
}

TEST_CASE("sampling", "[curve]")
{
    const auto uniform = kArch.sampleUniform(5);
    REQUIRE(uniform.cols() == 5);
    CHECK(uniform.col(0) == Eigen::Vector2d(0, 0));
    CHECK(uniform.col(2) == Eigen::Vector2d(2, 1.5));
    CHECK(uniform.col(4) == Eigen::Vector2d(4, 0));
    CHECK_THROWS_AS(kArch.sampleUniform(1), Error);

    for (double tol : {1e-1, 1e-3, 1e-6}) {
        const Curve3 f(randomPoints<double, 3>(8, 11));
        const auto ts = f.sampleAdaptive(tol);
        REQUIRE(ts.front() == 0.0);
        REQUIRE(ts.back() == 1.0);
        // Every curve point between two samples is within tol of their chord.
        for (std::size_t i = 0; i + 1 < ts.size(); ++i) {
            const Eigen::Vector3d a = f(ts[i]), b = f(ts[i + 1]);
            for (int s = 1; s < 20; ++s) {
                const Eigen::Vector3d p = f(ts[i] + (ts[i + 1] - ts[i]) * s / 20.0);
                const double u = std::clamp((p - a).dot(b - a) / std::max((b - a).squaredNorm(), 1e-300), 0.0, 1.0);
                REQUIRE((p - a - u * (b - a)).norm() <= tol);
            }
        }
        // Finer tolerances need more points (the adaptivity is real).
        if (tol < 1e-1) CHECK(ts.size() > f.sampleAdaptive(tol * 100).size());
    }
}

TEST_CASE("construction validates its input", "[curve][errors]")
{
    CHECK_THROWS_WITH(Curve2(Curve2::Points(2, 0)), Catch::Contains("at least one control point"));
    Curve2::Points p(2, 3);
    p << 0, 1, 2, 0, std::nan(""), 0;
    CHECK_THROWS_WITH(Curve2(p), Catch::Contains("point 1 coordinate 1 is not finite"));
    p(1, 1) = std::numeric_limits<double>::infinity();
    CHECK_THROWS_AS(Curve2(p), Error);
    CHECK_THROWS_WITH(Curve2(Curve2::Points::Zero(2, kMaxDegree + 2)), Catch::Contains("degree 68"));
    CHECK_NOTHROW(Curve2(Curve2::Points::Zero(2, kMaxDegree + 1)));
    CHECK_THROWS_AS(kArch.derivatives(0.5, -1), Error);
    CHECK_THROWS_AS(kArch.elevated(kMaxDegree), Error);
}

TEST_CASE("float and long double instantiations", "[curve]")
{
    const BezierCurve<float, 2> f({{0, 0}, {1, 2}, {3, 2}, {4, 0}});
    CHECK(f(0.5f) == Eigen::Vector2f(2, 1.5f));
    const BezierCurve<long double, 3> g({{0, 0, 0}, {1, 1, 1}});
    CHECK(g(0.25L).x() == 0.25L);
    CHECK(g.arcLength() == Approx(std::sqrt(3.0)).epsilon(1e-15));
}

} // namespace test_bezier_curve
