// Exact composition of Bézier patches with a lattice (deformSurface): the composed patch against
// point-wise deformation (the batched kernel and the direct reference), its degrees, the identity
// lattice, a trilinear lattice against a hand computation, the outside policy, the degree limit.

#include <catch2/catch.hpp>

#include <freeform/volume/deform.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "support/random.h"

namespace test_deform_surface {

using freeform::Lattice;
using freeform::OutsidePolicy;
using Points = Lattice::Points;
using Surface = freeform::BezierSurface<double, 3>;

namespace {

/// A sheared, non-orthogonal frame.
const Eigen::Vector3d kOrigin(-1, -0.5, -2);
Eigen::Matrix3d shearedAxes()
{
    Eigen::Matrix3d a;
    a.col(0) = Eigen::Vector3d(2, 0.3, 0);
    a.col(1) = Eigen::Vector3d(0.4, 1.5, 0.1);
    a.col(2) = Eigen::Vector3d(0.2, -0.3, 1.8);
    return a;
}

/// The rest lattice of the sheared frame with every control point moved by a seeded random offset.
Lattice randomLattice(std::array<int, 3> degree, std::uint32_t seed, OutsidePolicy outside = OutsidePolicy::Clamp)
{
    Lattice lat = Lattice::identity(degree, kOrigin, shearedAxes(), outside);
    lat.setControlPoints(lat.controlPoints() + freeform::test::randomPoints<double, 3>(lat.pointCount(), seed, -0.3, 0.3));
    return lat;
}

/// A patch of degrees (p, q) whose control points have lattice coordinates uniform in [lo, hi]^3.
Surface patchInLattice(const Lattice& lat, int p, int q, std::uint32_t seed, double lo, double hi)
{
    const Points stu = freeform::test::randomPoints<double, 3>((p + 1) * (q + 1), seed, lo, hi);
    Points world(3, stu.cols());
    for (Eigen::Index i = 0; i < stu.cols(); ++i) world.col(i) = lat.toWorld(stu.col(i));
    return Surface(p, q, std::move(world));
}

/// The patch sampled on an (n+1) x (n+1) grid, as columns.
Points samples(const Surface& s, int n)
{
    Points out(3, (n + 1) * (n + 1));
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) out.col(i * (n + 1) + j) = s.evaluate(double(i) / n, double(j) / n);
    return out;
}

} // namespace

TEST_CASE("a patch composed with a lattice equals point-wise deformation", "[unit]")
{
    const int n = 24;
    for (const auto& d : {std::array<int, 3>{1, 1, 1}, {2, 1, 3}, {3, 3, 3}}) {
        for (const auto& pq : {std::array<int, 2>{1, 1}, {2, 3}, {3, 3}, {0, 2}}) {
            CAPTURE(d[0], d[1], d[2], pq[0], pq[1]);
            const auto seed = static_cast<std::uint32_t>(10 * pq[0] + pq[1] + 100 * d[1]);
            const Lattice lat = randomLattice(d, seed);
            const Surface patch = patchInLattice(lat, pq[0], pq[1], seed + 7, 0.02, 0.98);
            const double w = 0.8;
            const Surface deformed = freeform::deformSurface(lat, patch, w);
            const int sum = d[0] + d[1] + d[2];
            CHECK(deformed.degreeU() == pq[0] * sum);
            CHECK(deformed.degreeV() == pq[1] * sum);

            // Point-wise: the batched kernel (deformPoints) at the patch's points.
            Points moved = samples(patch, n);
            freeform::DeformOptions options;
            options.strength = w;
            freeform::deformPoints(lat, moved, options);
            double worst = 0;
            for (int i = 0; i <= n; ++i)
                for (int j = 0; j <= n; ++j) {
                    const Eigen::Vector3d exact = moved.col(i * (n + 1) + j);
                    const Eigen::Vector3d composed = deformed.evaluate(double(i) / n, double(j) / n);
                    worst = std::max(worst, (composed - exact).norm() / std::max(1.0, exact.norm()));
                    // And the direct reference evaluation of the lattice map.
                    const Eigen::Vector3d ref = lat.deform(patch.evaluate(double(i) / n, double(j) / n), w).point;
                    CHECK((ref - exact).norm() <= 1e-12 * std::max(1.0, exact.norm()));
                }
            CHECK(worst <= 1e-12);
        }
    }
}

TEST_CASE("through the identity lattice a patch is only degree-elevated", "[unit]")
{
    const Lattice id = Lattice::identity({2, 3, 1}, kOrigin, shearedAxes());
    const Surface patch = patchInLattice(id, 2, 1, 5, 0.1, 0.9);
    const Surface same = freeform::deformSurface(id, patch);
    REQUIRE(same.degreeU() == 12);
    REQUIRE(same.degreeV() == 6);
    const Surface elevated = patch.elevatedU(10).elevatedV(5);
    CHECK((same.controlPoints() - elevated.controlPoints()).cwiseAbs().maxCoeff() <= 1e-14);
    // Strength 0 leaves a moved lattice without effect as well.
    const Lattice moved = randomLattice({2, 3, 1}, 9);
    const Surface none = freeform::deformSurface(moved, patch, 0.0);
    CHECK((none.controlPoints() - elevated.controlPoints()).cwiseAbs().maxCoeff() <= 1e-14);
}

TEST_CASE("a trilinear lattice on a patch, against a hand computation", "[unit]")
{
    // The unit cube, one corner (1,1,1) moved by d: the map is x + s t u d. The bilinear patch
    // f(u, v) = (u, u, v) (a flat quadrilateral on the diagonal plane s = t) moves by u^2 v d, whose
    // Bernstein coefficients in degrees (3, 3) are C(i,2)/C(3,2) * j/3 = i(i-1)/6 * j/3; the patch
    // itself, elevated, has the control points (i/3, i/3, j/3).
    Lattice lat = Lattice::identity({1, 1, 1}, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity());
    const Eigen::Vector3d d(0.25, -0.5, 1.0);
    lat.setControlPoint(1, 1, 1, Eigen::Vector3d(1, 1, 1) + d);
    Points pts(3, 4);
    pts.col(0) = Eigen::Vector3d(0, 0, 0); // (0, 0)
    pts.col(1) = Eigen::Vector3d(0, 0, 1); // (0, 1)
    pts.col(2) = Eigen::Vector3d(1, 1, 0); // (1, 0)
    pts.col(3) = Eigen::Vector3d(1, 1, 1); // (1, 1)
    const Surface deformed = freeform::deformSurface(lat, Surface(1, 1, pts));
    REQUIRE(deformed.degreeU() == 3);
    REQUIRE(deformed.degreeV() == 3);
    for (int i = 0; i <= 3; ++i)
        for (int j = 0; j <= 3; ++j) {
            CAPTURE(i, j);
            const Eigen::Vector3d expected =
                Eigen::Vector3d(i / 3.0, i / 3.0, j / 3.0) + (i * (i - 1) / 6.0) * (j / 3.0) * d;
            CHECK((deformed.controlPoint(i, j) - expected).norm() <= 1e-15);
        }
}

TEST_CASE("outside the box: the composition is the polynomial continued", "[unit]")
{
    // Under extrapolate the composed patch equals point-wise deformation everywhere; under clamp it
    // differs where the patch leaves the box (the documented behaviour), and agrees inside it.
    const Lattice ext = randomLattice({2, 2, 2}, 3, OutsidePolicy::Extrapolate);
    Lattice clamp = ext;
    clamp.setOutside(OutsidePolicy::Clamp);
    const Surface patch = patchInLattice(ext, 2, 2, 11, -0.3, 1.3);
    const Surface deformed = freeform::deformSurface(ext, patch);
    const Surface deformedClamp = freeform::deformSurface(clamp, patch);
    CHECK(deformed.controlPoints() == deformedClamp.controlPoints()); // the policy does not enter
    int outside = 0, inside = 0;
    for (int i = 0; i <= 20; ++i)
        for (int j = 0; j <= 20; ++j) {
            const Eigen::Vector3d x = patch.evaluate(i / 20.0, j / 20.0);
            const Eigen::Vector3d composed = deformed.evaluate(i / 20.0, j / 20.0);
            const Eigen::Vector3d extrapolated = ext.deform(x).point;
            CHECK((composed - extrapolated).norm() <= 1e-12 * std::max(1.0, extrapolated.norm()));
            const Eigen::Vector3d clamped = clamp.deform(x).point;
            if (Lattice::insideBox(ext.toLattice(x))) {
                ++inside;
                CHECK((composed - clamped).norm() <= 1e-12 * std::max(1.0, clamped.norm()));
            } else if ((composed - clamped).norm() > 1e-6) {
                ++outside;
            }
        }
    CHECK(inside > 0);
    CHECK(outside > 0);
}

TEST_CASE("deformSurface rejects degrees above the limit and a non-finite strength", "[unit]")
{
    const Lattice lat = randomLattice({3, 3, 3}, 1);
    const Surface small = patchInLattice(lat, 7, 1, 2, 0.1, 0.9); // 7 * 9 = 63: allowed
    CHECK(freeform::deformSurface(lat, small).degreeU() == 63);
    const Surface big = patchInLattice(lat, 1, 8, 2, 0.1, 0.9); // 8 * 9 = 72 > 67
    CHECK_THROWS_AS(freeform::deformSurface(lat, big), freeform::Error);
    CHECK_THROWS_AS(freeform::deformSurface(lat, small, std::nan("")), freeform::Error);
}

} // namespace test_deform_surface
