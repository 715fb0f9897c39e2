// The exact NURBS forms of CAD curves and surfaces (brep/exact_forms.h) and the trim
// classification (brep/trimmed_surface.h), against the analytic formulas in long double: circle,
// ellipse and hyperbola arcs at random parameters in the file's parameter, surfaces of revolution
// against the rotation of their meridian, the parameter maps' inverses, and the even-odd
// classification of a square with a round hole against the distance to the exact boundary.

#include <catch2/catch.hpp>

#include <freeform/brep/part.h>
#include <freeform/brep/trimmed_surface.h>
#include <freeform/core/quadrature.h>

#include <cmath>
#include <numbers>
#include <random>

namespace test_exact_forms {

using namespace freeform;
using Catch::Matchers::WithinAbs;

namespace {

using V2 = Eigen::Vector2d;
using V3 = Eigen::Vector3d;
using LD = long double;

/// The plane z = 0 over [0, 4]^2 and the loop of its four sides.
MappedSurface squarePlane() { return exactPlane(V3::Zero(), V3(1, 0, 0), V3(0, 1, 0), 0, 4, 0, 4); }
TrimLoop squareLoop()
{
    TrimLoop outer;
    const V2 corners[4] = {V2(0, 0), V2(4, 0), V2(4, 4), V2(0, 4)};
    for (int i = 0; i < 4; ++i)
        outer.curves.push_back({exactLine<2>(corners[i], corners[(i + 1) % 4] - corners[i], 0, 1), false, -1});
    return outer;
}

} // namespace

TEST_CASE("ellipse and circle arcs equal a cos t, b sin t in the file's parameter", "[brep]")
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> angle(-7, 7), len(0.1, 6);
    for (int trial = 0; trial < 200; ++trial) {
        const double t0 = angle(rng), t1 = t0 + len(rng), a = 0.5 + trial % 7, b = 0.25 + trial % 5;
        const V3 c(1, -2, 3), X = V3(1, 2, 2) / 3, Y = V3(2, 1, -2) / 3;
        const MappedCurve<3> e = exactEllipse<3>(c, X, Y, a, b, t0, t1);
        REQUIRE(e.map.spans == static_cast<int>(std::ceil((t1 - t0) / (std::numbers::pi / 2) * (1 - 1e-12))));
        for (int k = 0; k <= 20; ++k) {
            const double t = t0 + (t1 - t0) * k / 20;
            const V3 p = e.point(t);
            for (int i = 0; i < 3; ++i) {
                const LD want = LD(c[i]) + LD(a) * std::cos(LD(t)) * LD(X[i]) + LD(b) * std::sin(LD(t)) * LD(Y[i]);
                CHECK_THAT(p[i], WithinAbs(double(want), 1e-14 * (a + b + 4)));
            }
            CHECK_THAT(e.map.inverse(e.map(t)), WithinAbs(t, 1e-13));
        }
        // The end points are the NURBS's own end points: the range is the whole domain.
        CHECK(e.map(t0) == Approx(e.nurbs.domainStart()).margin(1e-14));
        CHECK(e.map(t1) == Approx(e.nurbs.domainEnd()).margin(1e-13));
    }
}

TEST_CASE("hyperbola and parabola arcs equal their analytic points", "[brep]")
{
    const V2 c(0.5, -1), X(0.6, 0.8), Y(-0.8, 0.6);
    for (double t0 : {-2.0, -0.3, 0.7}) {
        const double t1 = t0 + 1.9;
        const MappedCurve<2> h = exactHyperbola<2>(c, X, Y, 2.0, 0.75, t0, t1);
        const MappedCurve<2> p = exactParabola<2>(c, X, Y, 0.3, t0, t1);
        for (int k = 0; k <= 16; ++k) {
            const double t = t0 + (t1 - t0) * k / 16;
            const V2 ph = h.point(t), pp = p.point(t);
            for (int i = 0; i < 2; ++i) {
                const LD wh = LD(c[i]) + 2 * std::cosh(LD(t)) * LD(X[i]) + 0.75L * std::sinh(LD(t)) * LD(Y[i]);
                const LD wp = LD(c[i]) + LD(t) * LD(t) / (4 * 0.3L) * LD(X[i]) + LD(t) * LD(Y[i]);
                CHECK_THAT(ph[i], WithinAbs(double(wh), 1e-13));
                CHECK_THAT(pp[i], WithinAbs(double(wp), 1e-13));
            }
        }
    }
}

TEST_CASE("a surface of revolution is its meridian rotated about the axis", "[brep]")
{
    // Torus: meridian circle of radius r about (R, 0, 0) in the xz plane, turned about z; and a
    // rotated frame (axis (1, 2, 2) / 3) with a B-spline-like line meridian (a cone).
    const double R = 3, r = 0.75;
    const MappedCurve<3> meridian = exactEllipse<3>(V3(R, 0, 0), V3(1, 0, 0), V3(0, 0, 1), r, r, -1.0, 2.5);
    const MappedSurface torus = exactRevolution(meridian, V3::Zero(), V3(0, 0, 1), 0.3, 5.9);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.3, 5.9), v(-1.0, 2.5);
    for (int k = 0; k < 300; ++k) {
        const double uu = u(rng), vv = v(rng);
        const V3 p = torus.point(uu, vv);
        const LD rho = R + r * std::cos(LD(vv));
        CHECK_THAT(p.x(), WithinAbs(double(rho * std::cos(LD(uu))), 1e-14));
        CHECK_THAT(p.y(), WithinAbs(double(rho * std::sin(LD(uu))), 1e-14));
        CHECK_THAT(p.z(), WithinAbs(double(r * std::sin(LD(vv))), 1e-14));
        // S_u x S_v = rho r (cos v cos u, cos v sin u, sin v): away from the tube's centre circle.
        const V3 centre(R * std::cos(uu), R * std::sin(uu), 0);
        CHECK(torus.normal(uu, vv).dot((p - centre).normalized()) == Approx(1).margin(1e-12));
    }
    const V3 axis = V3(1, 2, 2) / 3, origin(0.5, 0.5, -1);
    const V3 radial = V3(2, 1, -2) / 3;
    const MappedSurface cone = exactRevolution(exactLine<3>(origin + 2 * radial, 0.5 * radial + axis, -1, 3), origin,
                                               axis, 0, 2 * std::numbers::pi);
    for (int k = 0; k < 100; ++k) {
        const double uu = 2 * std::numbers::pi * k / 100, vv = -1 + 0.04 * k;
        const V3 q = origin + 2 * radial + vv * (0.5 * radial + axis) - origin; // the meridian point
        const V3 want = origin + axis * q.dot(axis) + std::cos(uu) * (q - axis * q.dot(axis)) +
                        std::sin(uu) * axis.cross(q);
        CHECK((cone.point(uu, vv) - want).norm() < 1e-14 * 8);
    }
}

TEST_CASE("the trim classification of a square with a round hole is exact off the flatness band", "[brep]")
{
    // The plane z = 0 over [0, 4]^2; the outer loop four lines, the hole a circle of radius 1 about
    // (2, 2) given as two half circles (one reversed), as a file would.
    const MappedSurface plane = squarePlane();
    const TrimLoop outer = squareLoop();
    TrimLoop hole;
    hole.curves.push_back({exactEllipse<2>(V2(2, 2), V2(1, 0), V2(0, 1), 1, 1, 0, std::numbers::pi), false, -1});
    // The second half, stored from 2 pi back to pi and traversed reversed.
    hole.curves.push_back({exactEllipse<2>(V2(2, 2), V2(1, 0), V2(0, -1), 1, 1, 0, std::numbers::pi), true, -1});
    const TrimmedSurface face(plane, Box<double, 2>(V2(0, 0), V2(4, 4)), {outer, hole}, 1e-6);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> x(-0.5, 4.5);
    int inside = 0, outside = 0;
    for (int k = 0; k < 20000; ++k) {
        const V2 p(x(rng), x(rng));
        const double toHole = (p - V2(2, 2)).norm() - 1; // > 0 outside the hole
        const double toSquare = std::min({p.x(), p.y(), 4 - p.x(), 4 - p.y()}); // > 0 inside the square
        const double signedDistance = std::min(toHole, toSquare);
        const TrimClass c = face.classify(p);
        if (std::abs(signedDistance) > 3e-6) {
            CHECK(c == (signedDistance > 0 ? TrimClass::Inside : TrimClass::Outside));
        } else {
            CHECK(c == TrimClass::Boundary);
        }
        inside += c == TrimClass::Inside;
        outside += c == TrimClass::Outside;
    }
    CHECK(inside > 8000);
    CHECK(outside > 4000);
    // Points on the hole's circle are Boundary.
    for (int k = 0; k < 64; ++k) {
        const double a = 2 * std::numbers::pi * k / 64;
        CHECK(face.classify(V2(2 + std::cos(a), 2 + std::sin(a))) == TrimClass::Boundary);
    }
    // The certified polygon stays within the flatness: every vertex of the hole's polygon lies on the circle.
    for (const V2& q : face.polygons()[1]) CHECK(std::abs((q - V2(2, 2)).norm() - 1) < 1e-12);
}

TEST_CASE("the parameter maps' slopes equal central differences", "[brep]")
{
    for (const ParameterMap& m : {ParameterMap::halfAngle(-1, 4.5), ParameterMap::halfAngle(0.2, 0.9),
                                  ParameterMap::exponential(), ParameterMap::identity()}) {
        for (double t = -0.9; t < 0.85; t += 0.0731) {
            const double h = 1e-5;
            const double fd = (m(t + h) - m(t - h)) / (2 * h);
            CHECK(m.derivative(t) == Approx(fd).epsilon(1e-8));
            CHECK(m.derivative(t) > 0);
        }
    }
}

TEST_CASE("the area of trimmed planes, a torus and a sphere zone equals the closed forms", "[brep]")
{
    // The square [0, 4]^2 with a round hole of radius 1: 16 - pi.
    const MappedSurface plane = squarePlane();
    const TrimLoop outer = squareLoop();
    TrimLoop hole;
    hole.curves.push_back({exactEllipse<2>(V2(2, 2), V2(1, 0), V2(0, 1), 1, 1, 0, 2 * std::numbers::pi), true, -1});
    const TrimmedSurface holed(plane, Box<double, 2>(V2(0, 0), V2(4, 4)), {outer, hole});
    CHECK(holed.area() == Approx(16 - std::numbers::pi).epsilon(1e-12));
    // No loops: the whole box of a torus patch, (u1 - u0) r (R (v1 - v0) + r (sin v1 - sin v0)).
    const double R = 3, r = 0.75;
    const MappedSurface torus =
        exactRevolution(exactEllipse<3>(V3(R, 0, 0), V3(1, 0, 0), V3(0, 0, 1), r, r, -1.0, 2.5), V3::Zero(),
                        V3(0, 0, 1), 0.3, 5.9);
    const TrimmedSurface patch(torus, Box<double, 2>(V2(0.3, -1.0), V2(5.9, 2.5)), {});
    const double want = 5.6 * r * (R * 3.5 + r * (std::sin(2.5) - std::sin(-1.0)));
    CHECK(patch.area() == Approx(want).epsilon(1e-11));
    // A sphere zone trimmed by a circle in its parameter plane, against the same integral done by
    // hand: the disc |(u, v) - (1, 0.2)| < 0.5 of the unit sphere has area, the integral over the
    // disc of cos v du dv = the integral of 2 sqrt(0.25 - (v - 0.2)^2) cos v dv; with
    // v = 0.2 + 0.5 sin a, that of 0.5 cos^2 a cos(0.2 + 0.5 sin a) over [-pi/2, pi/2].
    const MappedSurface sphere = exactRevolution(exactEllipse<3>(V3::Zero(), V3(1, 0, 0), V3(0, 0, 1), 1, 1, -1.5, 1.5),
                                                 V3::Zero(), V3(0, 0, 1), 0, 3);
    TrimLoop disc;
    disc.curves.push_back({exactEllipse<2>(V2(1, 0.2), V2(1, 0), V2(0, 1), 0.5, 0.5, 0, 2 * std::numbers::pi), false, -1});
    const TrimmedSurface zone(sphere, Box<double, 2>(V2(0, -1.5), V2(3, 1.5)), {disc});
    const double byHand = integrate<double>(
        [](double a) { return 0.5 * std::cos(a) * std::cos(a) * std::cos(0.2 + 0.5 * std::sin(a)); },
        -std::numbers::pi / 2, std::numbers::pi / 2, 1e-15);
    CHECK(zone.area() == Approx(byHand).epsilon(1e-11));
}

TEST_CASE("a periodic parameter map reduces into its period; maps refuse empty ranges", "[brep]")
{
    const ParameterMap m = ParameterMap::periodic(1, 2);
    CHECK(m(1.5) == 1.5);
    CHECK_THAT(m(3.5), WithinAbs(1.5, 1e-15));
    CHECK_THAT(m(-0.5), WithinAbs(1.5, 1e-15));
    CHECK_THROWS_WITH(exactLine<2>(V2(0, 0), V2(1, 0), 1, 1), Catch::Contains("is empty"));
    CHECK_THROWS_WITH(exactEllipse<3>(V3::Zero(), V3::UnitX(), V3::UnitY(), 1, 1, 2, 1), Catch::Contains("is empty"));
}

} // namespace test_exact_forms
