// RationalBezierCurve: exact conics (points on the circle and ellipse), derivatives against the
// quotient rule in long double and finite differences, split / elevation / standard form keeping
// the point set, and validation.

#include <catch2/catch.hpp>

#include <freeform/curve/rational_bezier_curve.h>

#include <cmath>
#include <numbers>

#include "support/random.h"

namespace test_rational_bezier {

using namespace freeform;
using freeform::test::randomPoints;
using RB2 = RationalBezierCurve<double, 2>;

TEST_CASE("circular arcs of any sweep up to 180 degrees lie on the circle", "[rational][conic]")
{
    const Eigen::Vector2d c(1, 2);
    for (double deg : {1.0, 30.0, 90.0, 119.0, 120.0, 121.0, 150.0, 179.9, 180.0, -180.0, -45.0}) {
        const double sweep = deg * std::numbers::pi / 180;
        const auto arc = RB2::circleArc(c, 3.0, 0.4, sweep);
        CAPTURE(deg);
        CHECK(arc.degree() == (std::abs(deg) <= 120 ? 2 : 3));
        for (int i = 0; i < arc.degree() + 1; ++i) CHECK(arc.weight(i) > 0);
        double worst = 0;
        for (int i = 0; i <= 200; ++i) worst = std::max(worst, std::abs((arc(i / 200.0) - c).norm() - 3.0) / 3.0);
        CHECK(worst <= 1e-15);
        CHECK((arc(0) - (c + 3.0 * Eigen::Vector2d(std::cos(0.4), std::sin(0.4)))).norm() <= 1e-15 * 4);
        CHECK((arc(1) - (c + 3.0 * Eigen::Vector2d(std::cos(0.4 + sweep), std::sin(0.4 + sweep)))).norm() <= 1e-15 * 4);
        // The angle runs monotonically from start to start + sweep, through the middle at t = 1/2
        // (symmetric weights).
        const Eigen::Vector2d m = arc(0.5) - c;
        CHECK(std::atan2(m.y(), m.x()) == Approx(std::remainder(0.4 + sweep / 2, 2 * std::numbers::pi)).margin(1e-14));
        CHECK(arc.arcLength(1e-13) == Approx(3.0 * std::abs(sweep)).epsilon(1e-12));
    }
    CHECK_THROWS_WITH(RB2::circleArc(c, 1, 0, 3.5), Catch::Contains("sweep"));
}

TEST_CASE("circle points to 1e-15 of the radius for every whole-degree sweep, distance in long double", "[rational][conic]")
{
    // The point's distance from the centre measured in long double (the double subtraction and
    // norm would add their own roundings): what remains is the point's own error. Plain double de
    // Casteljau reached 1.2e-15 here (sweep 165 degrees); the long double evaluation rounds once.
    const Eigen::Vector2d c(1, 2);
    double worst = 0;
    for (int deg = -180; deg <= 180; ++deg) {
        if (deg == 0) continue;
        const auto arc = RB2::circleArc(c, 3.0, 0.4, deg * std::numbers::pi / 180);
        for (int i = 0; i <= 400; ++i) {
            const Eigen::Vector2d p = arc(i / 400.0);
            const long double dx = static_cast<long double>(p.x()) - c.x(), dy = static_cast<long double>(p.y()) - c.y();
            worst = std::max(worst, static_cast<double>(std::abs(std::sqrt(dx * dx + dy * dy) - 3.0L) / 3.0L));
        }
    }
    CHECK(worst <= 1e-15);
}

TEST_CASE("an elliptic arc in 3D satisfies the ellipse equation", "[rational][conic]")
{
    using RB3 = RationalBezierCurve<double, 3>;
    const Eigen::Vector3d c(0, 1, 2), a(2, 0, 0), b(0, 0.5, 0.5);
    const auto arc = RB3::ellipseArc(c, a, b, -0.3, 2.5);
    for (int i = 0; i <= 100; ++i) {
        const Eigen::Vector3d q = arc(i / 100.0) - c;
        const double x = q.dot(a) / a.squaredNorm(), y = q.dot(b) / b.squaredNorm();
        CHECK(std::abs(x * x + y * y - 1) <= 1e-15 * 4);
        CHECK((q - x * a - y * b).norm() <= 1e-15); // in the plane of the axes
    }
}

TEST_CASE("rational derivatives against the quotient rule in long double and finite differences", "[rational]")
{
    for (int n = 1; n <= 9; ++n) {
        const auto pts = randomPoints<double, 3>(n + 1, 10u + n);
        const auto wr = randomPoints<double, 1>(n + 1, 20u + n, 0.2, 4.0);
        const Eigen::VectorXd w = wr.transpose();
        const RationalBezierCurve<double, 3> c(pts, w);
        for (double t : {0.0, 0.2, 0.5, 0.77, 1.0}) {
            // Reference: A(t), w(t) and their derivatives from the Bernstein derivative formula in long double.
            using LD = long double;
            const int K = 4;
            std::vector<Eigen::Matrix<LD, 3, 1>> A(K + 1, Eigen::Matrix<LD, 3, 1>::Zero());
            std::vector<LD> W(K + 1, 0);
            for (int k = 0; k <= K; ++k) {
                std::vector<LD> out(n + 1), scratch(n + 1);
                bernsteinDerivativeAll<LD>(n, k, t, out.data(), scratch.data());
                for (int i = 0; i <= n; ++i) {
                    A[k] += out[i] * LD(w[i]) * pts.col(i).cast<LD>();
                    W[k] += out[i] * LD(w[i]);
                }
            }
            std::vector<Eigen::Matrix<LD, 3, 1>> f(K + 1);
            // Quotient rule written out (not Leibniz): f' = (A' w - A w') / w^2, f'' from f = A / w
            // via f'' = (A'' - 2 w' f' - w'' f) / w only as a cross-check of order 2.
            f[0] = A[0] / W[0];
            f[1] = (A[1] * W[0] - A[0] * W[1]) / (W[0] * W[0]);
            f[2] = (A[2] * W[0] * W[0] - A[0] * W[2] * W[0] - 2 * A[1] * W[1] * W[0] + 2 * A[0] * W[1] * W[1]) /
                   (W[0] * W[0] * W[0]);
            const auto d = c.derivatives(t, 2);
            CAPTURE(n, t);
            for (int k = 0; k <= 2; ++k)
                CHECK(double((d.col(k).cast<LD>() - f[k]).cwiseAbs().maxCoeff()) <= 1e-12 * (1 + double(f[k].norm())));
            if (t > 0 && t < 1) {
                const double h = 1e-5;
                const Eigen::Vector3d fd = (c(t + h) - c(t - h)) / (2 * h);
                CHECK((fd - d.col(1)).norm() <= 1e-6 * (1 + d.col(1).norm()));
            }
        }
    }
}

TEST_CASE("split, elevation, reversal and standard form keep the point set", "[rational]")
{
    const auto pts = randomPoints<double, 2>(5, 3);
    Eigen::VectorXd w(5);
    w << 2.0, 0.5, 1.5, 3.0, 0.7;
    const RB2 c(pts, w);
    const auto [l, r] = c.split(0.3);
    const RB2 e = c.elevated(2), rev = c.reversed(), std_ = c.standardForm();
    CHECK(std_.weight(0) == 1.0);
    CHECK(std_.weight(4) == 1.0);
    for (int i = 0; i <= 50; ++i) {
        const double t = i / 50.0;
        CHECK((e(t) - c(t)).norm() <= 1e-14);
        CHECK((rev(1 - t) - c(t)).norm() <= 1e-14);
        if (t <= 0.3) CHECK((l(t / 0.3) - c(t)).norm() <= 1e-14);
        else CHECK((r((t - 0.3) / 0.7) - c(t)).norm() <= 1e-14);
        // Standard form: the point c(t) is std_(s) with s = t / (t + c (1 - t)), c = (w_n / w_0)^(1/n)... found by the
        // closed-form inverse of the Möbius map t = k s / ((1 - s) + k s), k = (w_0 / w_n)^(1/4).
        const double k = std::pow(w[0] / w[4], 0.25);
        const double s = t / (t + k * (1 - t));
        CHECK((std_(s) - c(t)).norm() <= 1e-14);
    }
    Eigen::VectorXd bad = w;
    bad[2] = 0;
    CHECK_THROWS_WITH(RB2(pts, bad), Catch::Contains("weight 2"));
    CHECK_THROWS_WITH(RB2(pts, Eigen::VectorXd::Ones(4)), Catch::Contains("4 weights for 5"));
}

TEST_CASE("the batch path agrees with de Casteljau", "[rational][batch]")
{
    const auto pts = randomPoints<double, 3>(8, 5);
    const Eigen::VectorXd w = randomPoints<double, 1>(8, 6, 0.3, 2.0).transpose();
    const RationalBezierCurve<double, 3> c(pts, w);
    std::vector<double> ts;
    for (int i = 0; i <= 37; ++i) ts.push_back(i / 37.0);
    PointMatrix<double, 3> out;
    c.evaluateMany(ts.data(), ts.size(), out);
    for (std::size_t i = 0; i < ts.size(); ++i) CHECK((out.col(i) - c(ts[i])).norm() <= 1e-14);
}

} // namespace test_rational_bezier
