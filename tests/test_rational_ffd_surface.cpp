// Exact FFD of rational Bézier patches and NURBS surfaces (volume/deform_rational.h): the composed
// surface against the lattice applied point by point to the original surface's points (rational
// and polynomial lattices, 1e-12 relative), the polynomial NURBS path against the polynomial
// deformSurface of the independently extracted patches (bit for bit), uniform lattice weights
// against unit ones, an affine lattice against the affine map itself, normals against cof(J) n,
// and the breakpoints and degrees of the result.

#include <catch2/catch.hpp>

#include <freeform/volume/deform_rational.h>

#include <cmath>

#include "support/random.h"

namespace test_rational_ffd_surface {

using namespace freeform;
using freeform::test::randomPoints;

namespace {

Lattice randomLattice(std::array<int, 3> degree, std::uint32_t seed, double amount = 0.2)
{
    Eigen::Matrix3d axes;
    axes << 2, 0.3, 0, 0, 1.5, 0.2, 0.1, 0, 1;
    Lattice l = Lattice::identity(degree, Eigen::Vector3d(-1, -0.5, 0.25), axes, OutsidePolicy::Clamp);
    l.setControlPoints(l.controlPoints() + amount * randomPoints<double, 3>(l.pointCount(), seed));
    return l;
}

Eigen::VectorXd randomWeights(int count, std::uint32_t seed)
{
    return randomPoints<double, 1>(count, seed, 0.3, 3.0).transpose();
}

/// Points given in lattice coordinates (inside the box) mapped to world space.
Eigen::Matrix3Xd insideBox(const Lattice& l, int count, std::uint32_t seed)
{
    const Eigen::Matrix3Xd stu = randomPoints<double, 3>(count, seed, 0.1, 0.9);
    Eigen::Matrix3Xd pts(3, count);
    for (int i = 0; i < count; ++i) pts.col(i) = l.toWorld(stu.col(i));
    return pts;
}

/// The NURBS sphere of radius 0.35 about the centre of the lattice box (inside it).
NurbsSurface<double, 3> sphereIn(const Lattice& l)
{
    return NurbsSurface<double, 3>::sphere(l.toWorld(Eigen::Vector3d(0.5, 0.5, 0.5)), 0.35);
}

/// A clamped cubic-by-quadratic B-spline surface (weights as given, empty = polynomial) with a
/// double interior knot in u, control points inside the lattice box.
NurbsSurface<double, 3> splineIn(const Lattice& l, const Eigen::VectorXd& weights, std::uint32_t seed)
{
    const std::vector<double> ku{0, 0, 0, 0, 0.3, 0.6, 0.6, 1, 1, 1, 1}, kv{-1, -1, -1, 0.5, 2, 2, 2};
    return NurbsSurface<double, 3>(3, 2, ku, kv, insideBox(l, 7 * 4, seed), weights);
}

double relative(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
    return (a - b).norm() / std::max(1.0, b.norm());
}

} // namespace

TEST_CASE("rational Bézier patch through a rational lattice equals the point-wise NFFD", "[ffd][rational][surface]")
{
    const Lattice l = randomLattice({1, 2, 1}, 31);
    const RationalLattice rl(l, randomWeights(l.pointCount(), 32));
    const RationalBezierSurface<double, 3> patch(2, 1, insideBox(l, 6, 33), randomWeights(6, 34));
    const auto composed = deformSurface(rl, patch, 0.85);
    CHECK(composed.degreeU() == 2 * (1 + 4));
    CHECK(composed.degreeV() == 1 * (1 + 4));
    double worst = 0;
    for (int i = 0; i <= 30; ++i)
        for (int j = 0; j <= 30; ++j) {
            const double u = i / 30.0, v = j / 30.0;
            REQUIRE(Lattice::insideBox(l.toLattice(patch(u, v))));
            worst = std::max(worst, relative(composed(u, v), rl.deform(patch(u, v), 0.85).point));
        }
    CHECK(worst <= 1e-12);
    // The polynomial lattice: degrees (m L, n L), against Lattice::deform point by point.
    const auto poly = deformSurface(RationalLattice(l), patch, 0.85);
    CHECK(poly.degreeU() == 2 * 4);
    CHECK(poly.degreeV() == 1 * 4);
    worst = 0;
    for (int i = 0; i <= 30; ++i)
        for (int j = 0; j <= 30; ++j) {
            const double u = i / 30.0, v = j / 30.0;
            worst = std::max(worst, relative(poly(u, v), l.deform(patch(u, v), 0.85).point));
        }
    CHECK(worst <= 1e-12);
}

TEST_CASE("NURBS sphere through rational and polynomial lattices: point-wise map, breakpoints, degrees",
          "[ffd][rational][surface][nurbs]")
{
    const Lattice l = randomLattice({2, 1, 1}, 41);
    const RationalLattice rl(l, randomWeights(l.pointCount(), 42));
    const auto sphere = sphereIn(l);
    for (const bool rational : {true, false}) {
        INFO("rational lattice " << rational);
        const RationalLattice lat = rational ? rl : RationalLattice(l);
        const auto moved = deformSurface(lat, sphere, 0.9);
        const int factor = rational ? 1 + 4 : 4;
        CHECK(moved.degreeU() == 2 * factor);
        CHECK(moved.degreeV() == 2 * factor);
        CHECK(moved.knotsU().breakpoints() == sphere.knotsU().breakpoints());
        CHECK(moved.knotsV().breakpoints() == sphere.knotsV().breakpoints());
        CHECK(moved.isRational());
        double worst = 0;
        for (int i = 0; i <= 40; ++i)
            for (int j = 0; j <= 40; ++j) {
                const double u = i / 40.0, v = j / 40.0;
                const Eigen::Vector3d p = sphere(u, v);
                REQUIRE(Lattice::insideBox(l.toLattice(p)));
                worst = std::max(worst, relative(moved(u, v), lat.deform(p, 0.9).point));
            }
        CHECK(worst <= 1e-12);
    }
}

TEST_CASE("NURBS surface with unit lattice weights is the polynomial FFD bit for bit", "[ffd][rational][surface][nurbs]")
{
    const Lattice l = randomLattice({2, 2, 1}, 51);
    const auto surface = splineIn(l, Eigen::VectorXd(), 52);
    REQUIRE_FALSE(surface.isRational());
    const auto moved = deformSurface(RationalLattice(l), surface, 0.7);
    CHECK_FALSE(moved.isRational());
    CHECK(moved.degreeU() == 3 * 5);
    CHECK(moved.degreeV() == 2 * 5);
    // The polynomial deformSurface of volume/deform.h on each extracted patch, placed by hand.
    const auto patches = surface.bezierPatches();
    const int nv = static_cast<int>(surface.knotsV().breakpoints().size()) - 1;
    REQUIRE(patches.size() == static_cast<std::size_t>(3 * nv));
    bool same = true;
    for (std::size_t k = 0; k < patches.size(); ++k) {
        const int pu = static_cast<int>(k) / nv, pv = static_cast<int>(k) % nv;
        const BezierSurface<double, 3> poly(3, 2, patches[k].homogeneous().controlPoints().topRows<3>());
        const BezierSurface<double, 3> expected = deformSurface(l, poly, 0.7);
        for (int a = 0; a <= 15; ++a)
            for (int b = 0; b <= 10; ++b) {
                // Shared boundaries hold the first patch's points.
                if ((pu > 0 && a == 0) || (pv > 0 && b == 0)) continue;
                const Eigen::Vector3d got = moved.controlPoint(pu * 15 + a, pv * 10 + b);
                same = same && (got.array() == expected.controlPoint(a, b).array()).all();
            }
    }
    CHECK(same);
    // Uniform lattice weights (the rational path, one degree of W more) give the same surface to rounding.
    const RationalLattice uniform(l, Eigen::VectorXd::Constant(l.pointCount(), 2.5));
    const auto viaRational = deformSurface(uniform, surface, 0.7);
    CHECK(viaRational.degreeU() == 3 * 6);
    double worst = 0;
    for (int i = 0; i <= 30; ++i)
        for (int j = 0; j <= 30; ++j) {
            const double u = i / 30.0, v = -1 + 3 * j / 30.0;
            worst = std::max(worst, relative(viaRational(u, v), moved(u, v)));
            worst = std::max(worst, relative(moved(u, v), l.deform(surface(u, v), 0.7).point));
        }
    CHECK(worst <= 1e-12);
}

TEST_CASE("an affine lattice maps rational patches and NURBS surfaces by the affine map", "[ffd][rational][surface][nurbs]")
{
    Eigen::Matrix3d axes;
    axes << 2, 0.3, 0, 0, 1.5, 0.2, 0.1, 0, 1;
    Lattice l = Lattice::identity({2, 1, 3}, Eigen::Vector3d(-1, -0.5, 0.25), axes, OutsidePolicy::Keep);
    Eigen::Matrix3d m;
    m << 1.2, 0.1, -0.3, 0.05, 0.9, 0.2, -0.1, 0.3, 1.1;
    const Eigen::Vector3d t(0.4, -0.2, 0.7);
    const Lattice::Points rest = l.controlPoints();
    l.setControlPoints((m * rest).colwise() + t);
    const auto sphere = sphereIn(l);
    const auto weighted = splineIn(l, randomWeights(28, 61), 62);
    for (const auto* s : {&sphere, &weighted}) {
        const auto moved = deformSurface(RationalLattice(l), *s, 1.0);
        double worst = 0;
        for (int i = 0; i <= 30; ++i)
            for (int j = 0; j <= 30; ++j) {
                const double u = s->knotsU().front() + (s->knotsU().back() - s->knotsU().front()) * i / 30.0;
                const double v = s->knotsV().front() + (s->knotsV().back() - s->knotsV().front()) * j / 30.0;
                worst = std::max(worst, relative(moved(u, v), m * (*s)(u, v) + t));
            }
        CHECK(worst <= 1e-13);
    }
    const RationalBezierSurface<double, 3> patch(1, 2, insideBox(l, 6, 63), randomWeights(6, 64));
    const auto composed = deformSurface(RationalLattice(l), patch, 1.0);
    double worst = 0;
    for (int i = 0; i <= 20; ++i)
        for (int j = 0; j <= 20; ++j) worst = std::max(worst, relative(composed(i / 20.0, j / 20.0), m * patch(i / 20.0, j / 20.0) + t));
    CHECK(worst <= 1e-13);
}

TEST_CASE("normals of the composed surface are cof(J) times the original normals", "[ffd][rational][surface][nurbs]")
{
    const Lattice l = randomLattice({2, 1, 2}, 71, 0.1);
    const RationalLattice rl(l, randomWeights(l.pointCount(), 72));
    const auto surface = splineIn(l, randomWeights(28, 73), 74);
    const auto moved = deformSurface(rl, surface, 1.0);
    double worst = 0;
    for (int i = 1; i < 20; ++i)
        for (int j = 1; j < 20; ++j) {
            const double u = i / 20.0, v = -1 + 3 * j / 20.0;
            const auto jet = rl.deform(surface(u, v), 1.0);
            const Eigen::Vector3d expected = transformNormal(jet.jacobian, surface.normal(u, v));
            worst = std::max(worst, (moved.normal(u, v) - expected).norm());
        }
    CHECK(worst <= 1e-9);
}

TEST_CASE("surface composition errors name the degrees", "[ffd][rational][surface]")
{
    const Lattice l = randomLattice({3, 3, 3}, 81);
    const RationalBezierSurface<double, 3> patch(3, 3, insideBox(l, 16, 82), randomWeights(16, 83));
    const RationalBezierSurface<double, 3> high(7, 1, insideBox(l, 16, 85), randomWeights(16, 86));
    CHECK_THROWS_WITH(deformSurface(RationalLattice(l, randomWeights(l.pointCount(), 84)), high),
                      Catch::Contains("(70, 10)") && Catch::Contains("above 67"));
    const auto ok = deformSurface(RationalLattice(l), patch);
    CHECK(ok.degreeU() == 27);
    CHECK_THROWS_WITH(deformSurface(RationalLattice(l), patch, std::nan("")), Catch::Contains("strength"));
}

} // namespace test_rational_ffd_surface
