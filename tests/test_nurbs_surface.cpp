// NurbsSurface and RationalBezierSurface against independent computations: the exact sphere
// (radius to 1e-14), a long-double Cox-de Boor tensor sum on random knot vectors with multiple
// knots, partial derivatives by the two-variable quotient rule in long double and by finite
// differences, the grid batch path, Bézier extraction and isocurves, and validation.

#include <catch2/catch.hpp>

#include <freeform/curve/nurbs_curve.h>
#include <freeform/surface/nurbs_surface.h>

#include <cmath>
#include <random>

#include "support/cox_de_boor.h"
#include "support/random.h"

namespace test_nurbs_surface {

using namespace freeform;
using namespace freeform::test;
using Surface = NurbsSurface<double, 3>;

namespace {

Surface randomSurface(int p, int q, bool clamped, bool rational, std::uint32_t seed)
{
    std::mt19937 rng(seed);
    const int cu = p + 1 + static_cast<int>(rng() % 4), cv = q + 1 + static_cast<int>(rng() % 4);
    auto ku = randomKnots(p, cu, clamped, rng), kv = randomKnots(q, cv, clamped, rng);
    Eigen::VectorXd w = Eigen::VectorXd::Ones(cu * cv);
    if (rational) {
        std::uniform_real_distribution<double> uw(0.3, 3.0);
        for (int i = 0; i < cu * cv; ++i) w[i] = uw(rng);
    }
    return Surface(p, q, ku, kv, randomPoints<double, 3>(cu * cv, seed + 1), w);
}

/// Homogeneous partial (k, l) of the surface at (u, v) in long double: the tensor Cox-de Boor sum.
Eigen::Matrix<LD, 4, 1> homogeneousPartial(const Surface& s, int k, int l, LD u, LD v)
{
    std::vector<LD> U(s.knotsU().knots().begin(), s.knotsU().knots().end());
    std::vector<LD> V(s.knotsV().knots().begin(), s.knotsV().knots().end());
    const int p = s.degreeU(), q = s.degreeV();
    const int su = referenceSpan(U, p, s.countU() - 1, u), sv = referenceSpan(V, q, s.countV() - 1, v);
    Eigen::Matrix<LD, 4, 1> h = Eigen::Matrix<LD, 4, 1>::Zero();
    for (int i = 0; i < s.countU(); ++i) {
        const LD bu = coxDeBoorDerivative(U, i, p, k, u, su);
        if (bu == 0) continue;
        for (int j = 0; j < s.countV(); ++j) {
            const LD bv = coxDeBoorDerivative(V, j, q, l, v, sv);
            h += bu * bv * s.homogeneousPoints().col(s.index(i, j)).cast<LD>();
        }
    }
    return h;
}

} // namespace

TEST_CASE("the NURBS sphere: every point at the radius, normals radial", "[nurbs][surface][conic]")
{
    const Eigen::Vector3d c(1, -2, 0.5);
    const Surface s = Surface::sphere(c, 1.0);
    double worst = 0, worstNormal = 0;
    std::vector<double> g;
    for (int i = 0; i <= 60; ++i) g.push_back(i / 60.0);
    Surface::Points grid, du, dv;
    s.evaluateGrid(g, g, grid, &du, &dv);
    for (int i = 0; i <= 60; ++i)
        for (int j = 0; j <= 60; ++j) {
            const Eigen::Vector3d q = s(g[i], g[j]);
            worst = std::max(worst, std::abs((q - c).norm() - 1.0));
            worst = std::max(worst, std::abs((grid.col(i * 61 + j) - c).norm() - 1.0));
            if (j > 0 && j < 60) worstNormal = std::max(worstNormal, (s.normal(g[i], g[j]) - (q - c).normalized()).norm());
        }
    CHECK(worst <= 1e-14);
    CHECK(worstNormal <= 1e-13);
    // Poles and the equator where they must be.
    CHECK((s(0.3, 0.0) - (c + Eigen::Vector3d(0, 0, -1))).norm() <= 1e-15);
    CHECK((s(0.3, 1.0) - (c + Eigen::Vector3d(0, 0, 1))).norm() <= 1e-15);
    CHECK((s(0.25, 0.5) - (c + Eigen::Vector3d(0, 1, 0))).norm() <= 1e-15);
    // Extraction: 4 x 2 rational biquadratic patches, each on the sphere.
    const auto patches = s.bezierPatches();
    REQUIRE(patches.size() == 8);
    for (const auto& patch : patches)
        for (double u : {0.0, 0.3, 0.8})
            for (double v : {0.1, 0.5, 1.0}) CHECK(std::abs((patch(u, v) - c).norm() - 1.0) <= 1e-14);
}

TEST_CASE("evaluation and partials against long double Cox-de Boor and the quotient rule", "[nurbs][surface]")
{
    for (int p = 1; p <= 5; ++p)
        for (int q : {1, 2, 3})
            for (int variant = 0; variant < 4; ++variant) {
                const Surface s = randomSurface(p, q, variant & 1, variant & 2, 100u * p + 10u * q + variant);
                std::mt19937 rng(p * 31 + q + variant);
                std::uniform_real_distribution<double> uu(s.knotsU().front(), s.knotsU().back()),
                    vv(s.knotsV().front(), s.knotsV().back());
                for (int n = 0; n < 12; ++n) {
                    const double u = n == 0 ? s.knotsU().front() : uu(rng), v = n == 1 ? s.knotsV().back() : vv(rng);
                    CAPTURE(p, q, variant, u, v);
                    using V4 = Eigen::Matrix<LD, 4, 1>;
                    const V4 A = homogeneousPartial(s, 0, 0, u, v), Au = homogeneousPartial(s, 1, 0, u, v),
                             Av = homogeneousPartial(s, 0, 1, u, v), Auv = homogeneousPartial(s, 1, 1, u, v),
                             Auu = homogeneousPartial(s, 2, 0, u, v);
                    const Eigen::Matrix<LD, 3, 1> S = A.head<3>() / A[3];
                    const Eigen::Matrix<LD, 3, 1> Su = (Au.head<3>() - Au[3] * S) / A[3];
                    const Eigen::Matrix<LD, 3, 1> Sv = (Av.head<3>() - Av[3] * S) / A[3];
                    const Eigen::Matrix<LD, 3, 1> Suv = (Auv.head<3>() - Auv[3] * S - Au[3] * Sv - Av[3] * Su) / A[3];
                    const Eigen::Matrix<LD, 3, 1> Suu = (Auu.head<3>() - Auu[3] * S - 2 * Au[3] * Su) / A[3];
                    const Eigen::Vector3d f = s(u, v);
                    CHECK(double((f.cast<LD>() - S).cwiseAbs().maxCoeff()) <= 1e-14);
                    const auto jet = s.jet(u, v, 2);
                    auto close = [](const Eigen::Vector3d& a, const Eigen::Matrix<LD, 3, 1>& b) {
                        return double((a.cast<LD>() - b).cwiseAbs().maxCoeff()) <= 1e-11 * (1 + double(b.norm()));
                    };
                    CHECK(close(jet.col(0), S));
                    CHECK(close(jet.col(1), Su));
                    CHECK(close(jet.col(2), Sv));
                    CHECK(close(jet.col(3), Suu));
                    CHECK(close(jet.col(4), Suv));
                    // The grid path at this one parameter pair.
                    Surface::Points pos, gu, gv;
                    s.evaluateGrid({u}, {v}, pos, &gu, &gv);
                    CHECK(close(pos.col(0), S));
                    CHECK(close(gu.col(0), Su));
                    CHECK(close(gv.col(0), Sv));
                }
            }
}

TEST_CASE("S_v against central differences; extraction and isocurves keep the surface", "[nurbs][surface]")
{
    for (int p = 1; p <= 4; ++p) {
        const Surface s = randomSurface(p, p + 1, true, true, 4242u + p);
        const auto patches = s.bezierPatches();
        const auto bu = s.knotsU().breakpoints(), bv = s.knotsV().breakpoints();
        REQUIRE(patches.size() == (bu.size() - 1) * (bv.size() - 1));
        for (std::size_t a = 0; a + 1 < bu.size(); ++a)
            for (std::size_t b = 0; b + 1 < bv.size(); ++b) {
                const auto& patch = patches[a * (bv.size() - 1) + b];
                for (double x : {0.0, 0.37, 1.0})
                    for (double y : {0.0, 0.61, 1.0}) {
                        const double u = bu[a] + x * (bu[a + 1] - bu[a]), v = bv[b] + y * (bv[b + 1] - bv[b]);
                        CHECK((patch(x, y) - s(u, v)).norm() <= 1e-13);
                    }
                const double u = (bu[a] + bu[a + 1]) / 2, v = (bv[b] + bv[b + 1]) / 2, h = 1e-6 * (bv[b + 1] - bv[b]);
                const Eigen::Vector3d fd = (s(u, v + h) - s(u, v - h)) / (2 * h);
                const Eigen::Vector3d sv = s.jet(u, v, 1).col(2);
                CHECK((fd - sv).norm() <= 1e-6 * (1 + sv.norm()));
                CHECK((s.curveAtV(v)(u) - s(u, v)).norm() <= 1e-14);
                CHECK((s.curveAtU(u)(v) - s(u, v)).norm() <= 1e-14);
            }
    }
}

TEST_CASE("rational Bézier patches: NURBS round trip, weights, validation", "[rational][surface]")
{
    const auto pts = randomPoints<double, 3>(12, 9);
    Eigen::VectorXd w = randomPoints<double, 1>(12, 10, 0.5, 2.0).transpose();
    const RationalBezierSurface<double, 3> patch(2, 3, pts, w);
    const Surface s = Surface::fromBezier(patch);
    const auto [l, r] = patch.splitU(0.4);
    for (double u : {0.0, 0.2, 0.5, 1.0})
        for (double v : {0.0, 0.3, 1.0}) {
            CHECK((s(u, v) - patch(u, v)).norm() <= 1e-15 * 4);
            CHECK((patch.elevatedV(2)(u, v) - patch(u, v)).norm() <= 1e-14);
            CHECK((patch.transposed()(v, u) - patch(u, v)).norm() <= 1e-15 * 4);
            CHECK(((u <= 0.4 ? l(u / 0.4, v) : r((u - 0.4) / 0.6, v)) - patch(u, v)).norm() <= 1e-14);
        }
    w[5] = -1;
    CHECK_THROWS_WITH((RationalBezierSurface<double, 3>(2, 3, pts, w)), Catch::Contains("weight 5"));
    CHECK_THROWS_WITH((Surface(2, 2, {0, 0, 0, 1, 1, 1}, {0, 0, 0, 1, 1, 1}, randomPoints<double, 3>(8, 1))),
                      Catch::Contains("3 x 3 = 9 control points, got 8"));
    CHECK_THROWS_WITH((Surface(2, 2, {0, 0, 0, 1, 1, 1}, {0, 0, 0, 0.5, 0.2, 1, 1, 1}, randomPoints<double, 3>(15, 1))),
                      Catch::Contains("knots in v") && Catch::Contains("knot 4"));
}

TEST_CASE("surface knot refinement in u and v keeps the surface", "[nurbs][surface]")
{
    for (int p = 1; p <= 4; ++p) {
        const Surface s = randomSurface(p, 5 - p, p % 2, true, 600u + p);
        const double a = s.knotsU().front(), b = s.knotsU().back(), c = s.knotsV().front(), d = s.knotsV().back();
        const Surface r = s.refinedU({a + 0.3 * (b - a), a + 0.3 * (b - a), a + 0.8 * (b - a)}).refinedV({c + 0.55 * (d - c)});
        CHECK(r.countU() == s.countU() + 3);
        CHECK(r.countV() == s.countV() + 1);
        for (int i = 0; i <= 10; ++i)
            for (int j = 0; j <= 10; ++j) {
                const double u = a + (b - a) * i / 10.0, v = c + (d - c) * j / 10.0;
                CHECK((r(u, v) - s(u, v)).norm() <= 1e-13);
            }
    }
}

TEST_CASE("a surface restricted to a parameter box is the same surface there", "[nurbs][surface]")
{
    for (int p = 1; p <= 4; ++p) {
        const Surface s = randomSurface(p, 5 - p, p % 2, true, 700u + p);
        const double a = s.knotsU().front(), b = s.knotsU().back(), c = s.knotsV().front(), d = s.knotsV().back();
        const double a0 = a + 0.21 * (b - a), a1 = a + 0.77 * (b - a), c0 = c + 0.4 * (d - c);
        const Surface r = s.restrictedU(a0, a1).restrictedV(c0, d + 1); // d + 1: v keeps its end
        CHECK(r.knotsU().front() == a0);
        CHECK(r.knotsU().back() == a1);
        CHECK(r.knotsV().front() == c0);
        CHECK(r.knotsV().back() == d);
        for (int i = 0; i <= 10; ++i)
            for (int j = 0; j <= 10; ++j) {
                const double u = a0 + (a1 - a0) * i / 10.0, v = c0 + (d - c0) * j / 10.0;
                CHECK((r(u, v) - s(u, v)).norm() <= 1e-13);
            }
        // The restricted net's box holds the surface there and lies within the whole net's box.
        CHECK(s.controlBox().contains(r.controlBox()));
    }
}

TEST_CASE("refinement and restriction of the net equal the column curves' bit for bit", "[nurbs][surface]")
{
    // The surface refines and cuts all columns at once; NurbsCurve::refined and split do it column
    // by column. The same operations: every number equal, not just close.
    using Curve = NurbsCurve<double, 3>;
    for (int p = 1; p <= 5; ++p) {
        const Surface s = randomSurface(p, 2, p % 2, true, 800u + p);
        const double a = s.knotsU().front(), b = s.knotsU().back();
        const std::vector<double> extra{a + 0.3 * (b - a), a + 0.3 * (b - a), a + 0.8 * (b - a)};
        const double a0 = a + 0.21 * (b - a), a1 = a + 0.77 * (b - a);
        const Surface refined = s.refinedU(extra), restricted = s.restrictedU(a0, a1), right = s.restrictedU(a0, b);
        for (int j = 0; j < s.countV(); ++j) {
            Curve::HPoints column(4, s.countU());
            for (int i = 0; i < s.countU(); ++i) column.col(i) = s.homogeneousPoints().col(s.index(i, j));
            const Curve c(s.knotsU(), column);
            const Curve cr = c.refined(extra), cut = c.split(a0).second.split(a1).first, tail = c.split(a0).second;
            INFO("p = " << p << ", column " << j);
            REQUIRE(refined.countU() == cr.controlCount());
            REQUIRE(restricted.countU() == cut.controlCount());
            REQUIRE(right.countU() == tail.controlCount());
            CHECK(refined.knotsU().knots() == cr.knots());
            CHECK(restricted.knotsU().knots() == cut.knots());
            CHECK(right.knotsU().knots() == tail.knots());
            for (int i = 0; i < cr.controlCount(); ++i) CHECK(refined.homogeneousPoints().col(refined.index(i, j)) == cr.homogeneousPoints().col(i));
            for (int i = 0; i < cut.controlCount(); ++i)
                CHECK(restricted.homogeneousPoints().col(restricted.index(i, j)) == cut.homogeneousPoints().col(i));
            for (int i = 0; i < tail.controlCount(); ++i)
                CHECK(right.homogeneousPoints().col(right.index(i, j)) == tail.homogeneousPoints().col(i));
        }
    }
}

TEST_CASE("fromBezierPatches joins a grid of patches in Bézier form", "[nurbs]")
{
    // 2 x 1 bilinear patches over [0, 1] x [0, 2] and [1, 4] x [0, 2]: the plane z = x + y,
    // points (x, y, x + y) with weight 1, the second patch's corners at x = 1 and 4.
    auto patch = [](double x0, double x1) {
        Surface::HPoints h(4, 4);
        int k = 0;
        for (double x : {x0, x1})
            for (double y : {0.0, 2.0}) h.col(k++) << x, y, x + y, 1;
        return h;
    };
    const Surface s = Surface::fromBezierPatches({0, 1, 4}, {0, 2}, 1, 1, {patch(0, 1), patch(1, 4)}, "plane");
    CHECK(s.knotsU().knots() == std::vector<double>{0, 0, 1, 4, 4});
    CHECK(s.knotsV().knots() == std::vector<double>{0, 0, 2, 2});
    REQUIRE(s.countU() == 3);
    REQUIRE(s.countV() == 2);
    for (double u : {0.25, 1.0, 2.5})
        for (double v : {0.0, 1.5}) {
            // Patch parameters map to x linearly: x = u on [0, 1], x = 1 + (u - 1) on [1, 4].
            const Eigen::Vector3d p = s.evaluate(u, v);
            CHECK((p - Eigen::Vector3d(u, v, u + v)).norm() <= 1e-14);
        }
    CHECK_THROWS_WITH(Surface::fromBezierPatches({0, 1, 4}, {0, 2}, 1, 1, {patch(0, 1)}, "plane"),
                      Catch::Contains("plane: 1 Bézier patches do not fill 2 x 1 spans"));
    CHECK_THROWS_WITH(Surface::fromBezierPatches({0, 1, 4}, {0, 2}, 2, 1, {patch(0, 1), patch(1, 4)}, "plane"),
                      Catch::Contains("patch (1, 0) has 4 control points, not 6"));
}

} // namespace test_nurbs_surface
