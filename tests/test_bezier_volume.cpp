// BezierVolume: evaluation against a long-double Bernstein sum, derivatives against finite
// differences and the derivative volumes, linear precision, elevation, subdivision, errors.

#include <catch2/catch.hpp>

#include <freeform/volume/bezier_volume.h>

#include <cmath>

#include "support/random.h"

namespace test_bezier_volume {

using freeform::BezierVolume;
using Volume = BezierVolume<double>;
using Points = Volume::Points;

namespace {

long double bernsteinLd(int n, int i, long double t)
{
    long double c = 1;
    for (int r = 1; r <= i; ++r) c = c * (n - i + r) / r;
    return c * std::pow(t, static_cast<long double>(i)) * std::pow(1 - t, static_cast<long double>(n - i));
}

/// The triple Bernstein sum written out, in long double: the independent reference.
Eigen::Vector3d referenceValue(const Volume& v, double s, double t, double u)
{
    const int l = v.degree(0), m = v.degree(1), n = v.degree(2);
    long double acc[3] = {0, 0, 0};
    for (int i = 0; i <= l; ++i)
        for (int j = 0; j <= m; ++j)
            for (int k = 0; k <= n; ++k) {
                const long double w = bernsteinLd(l, i, s) * bernsteinLd(m, j, t) * bernsteinLd(n, k, u);
                for (int x = 0; x < 3; ++x) acc[x] += w * v.controlPoint(i, j, k)[x];
            }
    return Eigen::Vector3d(double(acc[0]), double(acc[1]), double(acc[2]));
}

Volume randomVolume(int l, int m, int n, std::uint32_t seed)
{
    return Volume(l, m, n, freeform::test::randomPoints<double, 3>((l + 1) * (m + 1) * (n + 1), seed));
}

const double kParams[][3] = {{0, 0, 0}, {1, 1, 1}, {0.5, 0.5, 0.5}, {0.1, 0.7, 0.3}, {0.9, 0.05, 0.6}, {1, 0.25, 0}};

} // namespace

TEST_CASE("a volume evaluates to the triple Bernstein sum", "[unit]")
{
    const int degrees[][3] = {{1, 1, 1}, {2, 3, 1}, {3, 3, 3}, {0, 2, 4}, {5, 1, 2}};
    std::uint32_t seed = 1;
    for (const auto& d : degrees) {
        const Volume v = randomVolume(d[0], d[1], d[2], seed++);
        for (const auto& p : kParams) {
            CAPTURE(d[0], d[1], d[2], p[0], p[1], p[2]);
            const Eigen::Vector3d ref = referenceValue(v, p[0], p[1], p[2]);
            CHECK((v.evaluate(p[0], p[1], p[2]) - ref).norm() < 1e-14);
            CHECK((v.derivatives(p[0], p[1], p[2]).point - ref).norm() < 1e-14);
        }
    }
}

TEST_CASE("corners interpolate the corner control points exactly", "[unit]")
{
    const Volume v = randomVolume(2, 3, 2, 7);
    CHECK(v.evaluate(0, 0, 0) == v.controlPoint(0, 0, 0));
    CHECK(v.evaluate(1, 0, 0) == v.controlPoint(2, 0, 0));
    CHECK(v.evaluate(0, 1, 0) == v.controlPoint(0, 3, 0));
    CHECK(v.evaluate(0, 0, 1) == v.controlPoint(0, 0, 2));
    CHECK(v.evaluate(1, 1, 1) == v.controlPoint(2, 3, 2));
    // Index order: (i, j, k) at i*(m+1)*(n+1) + j*(n+1) + k.
    CHECK(v.index(1, 2, 1) == 1 * 12 + 2 * 3 + 1);
    CHECK(v.controlPoint(1, 2, 1) == v.controlPoints().col(19));
}

TEST_CASE("partial derivatives agree with central differences and the derivative volumes", "[unit]")
{
    const Volume v = randomVolume(3, 2, 4, 11);
    const Volume dvs = v.derivative(0), dvt = v.derivative(1), dvu = v.derivative(2);
    CHECK(dvs.degrees() == std::array<int, 3>{2, 2, 4});
    CHECK(dvt.degrees() == std::array<int, 3>{3, 1, 4});
    CHECK(dvu.degrees() == std::array<int, 3>{3, 2, 3});
    const double h = 1e-5;
    for (const auto& p : {std::array<double, 3>{0.3, 0.4, 0.5}, {0.1, 0.9, 0.2}, {0.7, 0.5, 0.8}}) {
        const auto jet = v.derivatives(p[0], p[1], p[2]);
        const Eigen::Vector3d fs = (v.evaluate(p[0] + h, p[1], p[2]) - v.evaluate(p[0] - h, p[1], p[2])) / (2 * h);
        const Eigen::Vector3d ft = (v.evaluate(p[0], p[1] + h, p[2]) - v.evaluate(p[0], p[1] - h, p[2])) / (2 * h);
        const Eigen::Vector3d fu = (v.evaluate(p[0], p[1], p[2] + h) - v.evaluate(p[0], p[1], p[2] - h)) / (2 * h);
        CHECK((jet.ds - fs).norm() < 1e-8);
        CHECK((jet.dt - ft).norm() < 1e-8);
        CHECK((jet.du - fu).norm() < 1e-8);
        CHECK((jet.ds - dvs.evaluate(p[0], p[1], p[2])).norm() < 1e-13);
        CHECK((jet.dt - dvt.evaluate(p[0], p[1], p[2])).norm() < 1e-13);
        CHECK((jet.du - dvu.evaluate(p[0], p[1], p[2])).norm() < 1e-13);
        const Eigen::Matrix3d j = v.jacobian(p[0], p[1], p[2]);
        CHECK(j.col(0) == jet.ds);
        CHECK(j.col(2) == jet.du);
    }
    // Degree 0 along an axis: the derivative there is the zero volume.
    const Volume flat = randomVolume(0, 1, 1, 3);
    CHECK(flat.derivative(0).controlPoints().isZero(0.0));
    CHECK(flat.derivative(0).degree(0) == 0);
}

TEST_CASE("linear precision: the lattice (i/l, j/m, k/n) is the identity map", "[unit]")
{
    for (const auto& d : {std::array<int, 3>{1, 1, 1}, {2, 3, 4}, {3, 3, 3}, {6, 1, 2}}) {
        Points p(3, (d[0] + 1) * (d[1] + 1) * (d[2] + 1));
        for (int i = 0; i <= d[0]; ++i)
            for (int j = 0; j <= d[1]; ++j)
                for (int k = 0; k <= d[2]; ++k)
                    p.col((i * (d[1] + 1) + j) * (d[2] + 1) + k) =
                        Eigen::Vector3d(double(i) / d[0], double(j) / d[1], double(k) / d[2]);
        const Volume v(d[0], d[1], d[2], p);
        for (const auto& q : kParams) {
            const Eigen::Vector3d x(q[0], q[1], q[2]);
            CHECK((v.evaluate(q[0], q[1], q[2]) - x).norm() < 1e-15);
            CHECK((v.jacobian(q[0], q[1], q[2]) - Eigen::Matrix3d::Identity()).norm() < 1e-13);
        }
    }
}

TEST_CASE("degree elevation leaves the map unchanged", "[unit]")
{
    const Volume v = randomVolume(2, 1, 3, 21);
    const Volume e = v.elevated(1, 2, 0);
    CHECK(e.degrees() == std::array<int, 3>{3, 3, 3});
    const Volume e2 = v.elevated(2, 3);
    CHECK(e2.degrees() == std::array<int, 3>{2, 1, 6});
    for (const auto& p : kParams) {
        const Eigen::Vector3d ref = referenceValue(v, p[0], p[1], p[2]);
        CHECK((e.evaluate(p[0], p[1], p[2]) - ref).norm() < 1e-14);
        CHECK((e2.evaluate(p[0], p[1], p[2]) - ref).norm() < 1e-14);
        CHECK((e.jacobian(p[0], p[1], p[2]) - v.jacobian(p[0], p[1], p[2])).norm() < 1e-12);
    }
    CHECK_THROWS_AS(v.elevated(0, -1), freeform::Error);
    CHECK_THROWS_AS(v.elevated(3, 1), freeform::Error);
}

TEST_CASE("subdivision: the pieces reproduce the volume on their parameter ranges", "[unit]")
{
    const Volume v = randomVolume(3, 2, 2, 31);
    for (int axis = 0; axis < 3; ++axis) {
        const double at = 0.3;
        const auto [lo, hi] = v.split(axis, at);
        for (const auto& p : kParams) {
            double q[3] = {p[0], p[1], p[2]}, a[3] = {p[0], p[1], p[2]}, b[3] = {p[0], p[1], p[2]};
            a[axis] = at * q[axis];
            b[axis] = at + (1 - at) * q[axis];
            CHECK((lo.evaluate(q[0], q[1], q[2]) - referenceValue(v, a[0], a[1], a[2])).norm() < 1e-14);
            CHECK((hi.evaluate(q[0], q[1], q[2]) - referenceValue(v, b[0], b[1], b[2])).norm() < 1e-14);
        }
    }
    const Volume sub = v.subVolume(0.2, 0.6, 0.1, 0.5, 0.5, 1.0);
    for (const auto& p : kParams) {
        const double s = 0.2 + 0.4 * p[0], t = 0.1 + 0.4 * p[1], u = 0.5 + 0.5 * p[2];
        CHECK((sub.evaluate(p[0], p[1], p[2]) - referenceValue(v, s, t, u)).norm() < 1e-14);
    }
}

TEST_CASE("affine images commute with evaluation", "[unit]")
{
    const Volume v = randomVolume(2, 2, 1, 41);
    Eigen::Matrix3d a;
    a << 1, 2, 0, -1, 0.5, 3, 0, 1, 1;
    const Eigen::Vector3d b(0.5, -2, 1);
    const Volume w = v.transformed(a, b);
    for (const auto& p : kParams)
        CHECK((w.evaluate(p[0], p[1], p[2]) - (a * v.evaluate(p[0], p[1], p[2]) + b)).norm() < 1e-14);
}

TEST_CASE("a volume rejects bad input with a message", "[unit]")
{
    using Catch::Matchers::Contains;
    CHECK_THROWS_WITH(Volume(1, 1, 1, Points::Zero(3, 7)), Contains("need 8 control points, found 7"));
    CHECK_THROWS_WITH(Volume(-1, 1, 1, Points::Zero(3, 0)), Contains("degree l"));
    Points p = Points::Zero(3, 8);
    p(1, 5) = std::nan("");
    CHECK_THROWS_WITH(Volume(1, 1, 1, p), Contains("point 5 coordinate 1 is not finite"));
    const Volume v(1, 1, 1, Points::Zero(3, 8));
    CHECK_THROWS_WITH(v.derivative(3), Contains("axis 3"));
}

} // namespace test_bezier_volume
