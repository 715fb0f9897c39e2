// Rational FFD (NFFD): unit weights give the polynomial FFD bit for bit, uniform weights to
// rounding; the rest lattice is the identity bit for bit whatever the weights; the map against
// the formula p + sum w B d / sum w B with the lattice's own basis weights; the Jacobian against
// central differences; the exact composition with rational Bézier and NURBS curves against
// point-wise deformation and against the polynomial deformCurve.

#include <catch2/catch.hpp>

#include <freeform/volume/deform_rational.h>

#include <random>

#include "support/random.h"

namespace test_rational_ffd {

using namespace freeform;
using freeform::test::randomPoints;

namespace {

Lattice randomLattice(std::array<int, 3> degree, OutsidePolicy policy, std::uint32_t seed)
{
    Eigen::Matrix3d axes;
    axes << 2, 0.3, 0, 0, 1.5, 0.2, 0.1, 0, 1;
    Lattice l = Lattice::identity(degree, Eigen::Vector3d(-1, -0.5, 0.25), axes, policy);
    l.setControlPoints(l.controlPoints() + 0.2 * randomPoints<double, 3>(l.pointCount(), seed));
    return l;
}

Eigen::VectorXd randomWeights(int count, std::uint32_t seed)
{
    return randomPoints<double, 1>(count, seed, 0.3, 3.0).transpose();
}

} // namespace

TEST_CASE("NFFD with unit weights is the polynomial FFD bit for bit; uniform weights to rounding", "[ffd][rational]")
{
    for (OutsidePolicy policy : {OutsidePolicy::Keep, OutsidePolicy::Clamp, OutsidePolicy::Extrapolate}) {
        const Lattice l = randomLattice({2, 3, 1}, policy, 7);
        const RationalLattice unit(l), uniform(l, Eigen::VectorXd::Constant(l.pointCount(), 2.5));
        CHECK(unit.isPolynomial());
        CHECK_FALSE(uniform.isPolynomial());
        Eigen::Matrix3Xd pts = randomPoints<double, 3>(200, 8, -1.5, 2.5);
        Eigen::Matrix3Xd a = pts, b = pts;
        const auto ra = deformPoints(l, a, {0.8, 1});
        const auto rb = deformPoints(unit, b, {0.8, 1});
        CHECK((a.array() == b.array()).all());
        CHECK(ra.minDetJ == rb.minDetJ);
        for (Eigen::Index v = 0; v < pts.cols(); ++v) {
            const auto p = l.deform(pts.col(v), 0.8), q = uniform.deform(pts.col(v), 0.8);
            CHECK((p.point - q.point).norm() <= 1e-14 * 4);
            CHECK((p.jacobian - q.jacobian).norm() <= 1e-13);
            CHECK(p.outside == q.outside);
        }
    }
}

TEST_CASE("the rest lattice with any weights is the identity bit for bit", "[ffd][rational]")
{
    Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
    const Lattice rest = Lattice::identity({3, 2, 2}, Eigen::Vector3d(0, 0, 0), axes);
    const RationalLattice rl(rest, randomWeights(rest.pointCount(), 3));
    Eigen::Matrix3Xd pts = randomPoints<double, 3>(100, 4, 0, 1), moved = pts;
    deformPoints(rl, moved);
    CHECK((moved.array() == pts.array()).all());
}

TEST_CASE("the rational map against the formula and its Jacobian against differences", "[ffd][rational]")
{
    const Lattice l = randomLattice({3, 2, 2}, OutsidePolicy::Extrapolate, 11);
    const Eigen::VectorXd w = randomWeights(l.pointCount(), 12);
    const RationalLattice rl(l, w);
    const Eigen::Matrix3Xd pts = randomPoints<double, 3>(50, 13, -0.5, 1.0);
    for (Eigen::Index v = 0; v < pts.cols(); ++v) {
        const Eigen::Vector3d p = pts.col(v);
        const Eigen::VectorXd b = l.basisWeights(l.toLattice(p));
        const Eigen::Vector3d expected = p + 0.7 * (l.displacements() * w.cwiseProduct(b)) / w.dot(b);
        const auto jet = rl.deform(p, 0.7);
        CHECK((jet.point - expected).norm() <= 1e-14 * 4);
        const double h = 1e-6;
        for (int a = 0; a < 3; ++a) {
            const Eigen::Vector3d e = Eigen::Vector3d::Unit(a) * h;
            const Eigen::Vector3d fd = (rl.deform(p + e, 0.7).point - rl.deform(p - e, 0.7).point) / (2 * h);
            CHECK((fd - jet.jacobian.col(a)).norm() <= 1e-6 * (1 + jet.jacobian.col(a).norm()));
        }
    }
}

TEST_CASE("exact composition of rational Bézier and NURBS curves with a rational lattice", "[ffd][rational][nurbs]")
{
    const Lattice l = randomLattice({2, 1, 2}, OutsidePolicy::Clamp, 21);
    const RationalLattice rl(l, randomWeights(l.pointCount(), 22));
    // A rational cubic inside the box (lattice coordinates in [0.1, 0.9]).
    Eigen::Matrix3Xd stu = randomPoints<double, 3>(4, 23, 0.1, 0.9), pts(3, 4);
    for (int i = 0; i < 4; ++i) pts.col(i) = l.toWorld(stu.col(i));
    const RationalBezierCurve<double, 3> c(pts, randomWeights(4, 24));
    const auto composed = deformCurve(rl, c, 0.9);
    CHECK(composed.degree() == 3 * (1 + 5));
    for (int i = 0; i <= 50; ++i) {
        const double t = i / 50.0;
        CHECK((composed(t) - rl.deform(c(t), 0.9).point).norm() <= 1e-12);
    }
    // A NURBS circle in a plane of the box: per span, with the original breakpoints.
    auto circle = NurbsCurve<double, 3>::circle(Eigen::Vector3d(0, 0, 0), 0.3);
    Eigen::Matrix<double, 4, Eigen::Dynamic> h = circle.homogeneousPoints();
    const Eigen::Vector3d centre = l.toWorld(Eigen::Vector3d(0.5, 0.5, 0.5));
    for (Eigen::Index i = 0; i < h.cols(); ++i) h.col(i).head<3>() += h(3, i) * centre;
    const NurbsCurve<double, 3> moved(circle.knotVector(), h);
    const auto deformed = deformCurve(rl, moved, 1.0);
    CHECK(deformed.breakpoints() == moved.breakpoints());
    CHECK(deformed.degree() == 2 * 6);
    for (int i = 0; i <= 100; ++i) {
        const double u = i / 100.0;
        REQUIRE(Lattice::insideBox(l.toLattice(moved(u))));
        CHECK((deformed(u) - rl.deform(moved(u)).point).norm() <= 1e-12);
    }
    // Unit lattice weights and a polynomial curve: the polynomial exact composition.
    const BezierCurve<double, 3> poly(pts);
    const auto a = deformCurve(RationalLattice(l), RationalBezierCurve<double, 3>(poly), 0.6);
    const auto b = deformCurve(l, poly, 0.6);
    for (int i = 0; i <= 20; ++i) CHECK((a(i / 20.0) - b(i / 20.0)).norm() <= 1e-13);
    CHECK_THROWS_WITH(RationalLattice(l, Eigen::VectorXd::Ones(3)), Catch::Contains("3 weights"));
}

} // namespace test_rational_ffd
