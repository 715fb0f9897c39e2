// core/transform.h: every matrix against values computed by hand (written out in the comments),
// identities that hold for any input (rotations are orthogonal, normals stay perpendicular to
// tangents), a known point that lands on a known pixel, and the argument checks.

#include <catch2/catch.hpp>

#include <freeform/core/transform.h>

#include <cmath>

#include "support/random.h"

namespace test_transform {

using namespace freeform;
using Catch::Matchers::WithinAbs;

namespace {

constexpr double kPi = 3.14159265358979323846;

void requireNear(const Eigen::MatrixXd& actual, const Eigen::MatrixXd& expected, double tolerance = 1e-14)
{
    INFO("actual:\n" << actual << "\nexpected:\n" << expected);
    REQUIRE(actual.rows() == expected.rows());
    REQUIRE(actual.cols() == expected.cols());
    REQUIRE((actual - expected).cwiseAbs().maxCoeff() <= tolerance);
}

} // namespace

TEST_CASE("translation and scaling move and stretch points", "[transform]")
{
    const Eigen::Vector3d p(1, -2, 3);
    requireNear(transformPoint<double>(translation<double>({10, 20, 30}), p), Eigen::Vector3d(11, 18, 33));
    requireNear(transformPoint<double>(scaling<double>({2, 3, -1}), p), Eigen::Vector3d(2, -6, -3));
}

TEST_CASE("rotation about an axis follows cos I + (1 - cos) n n^T + sin X_n", "[transform]")
{
    SECTION("a quarter turn about z takes x to y and y to -x")
    {
        Eigen::Matrix3d expected;
        expected << 0, -1, 0,
                    1, 0, 0,
                    0, 0, 1;
        requireNear(rotationMatrix<double>({0, 0, 1}, kPi / 2), expected);
        // The axis need not be unit length.
        requireNear(rotationMatrix<double>({0, 0, 7}, kPi / 2), expected);
    }
    SECTION("a third of a turn about (1,1,1) permutes the axes x -> y -> z -> x")
    {
        Eigen::Matrix3d expected;
        expected << 0, 0, 1,
                    1, 0, 0,
                    0, 1, 0;
        requireNear(rotationMatrix<double>({1, 1, 1}, 2 * kPi / 3), expected, 1e-15);
    }
    SECTION("a half turn about x flips y and z")
    {
        const Eigen::Matrix4d m = rotation<double>({1, 0, 0}, kPi);
        requireNear(transformPoint<double>(m, {1, 2, 3}), Eigen::Vector3d(1, -2, -3), 1e-15);
    }
    SECTION("any rotation is orthogonal with determinant 1 and keeps its axis")
    {
        const auto axes = test::randomPoints<double, 3>(20, 7);
        for (int i = 0; i < axes.cols(); ++i) {
            const double angle = 0.3 * i - 2.5;
            const Eigen::Matrix3d r = rotationMatrix<double>(axes.col(i), angle);
            CAPTURE(i, angle);
            requireNear(r * r.transpose(), Eigen::Matrix3d::Identity(), 1e-15);
            REQUIRE_THAT(r.determinant(), WithinAbs(1.0, 1e-15));
            requireNear(r * axes.col(i), axes.col(i), 1e-15);
        }
    }
    REQUIRE_THROWS_WITH(rotationMatrix<double>({0, 0, 0}, 1.0), Catch::Contains("axis"));
}

TEST_CASE("lookAt builds the inverse of the camera frame [r u -d c]", "[transform]")
{
    SECTION("camera on the z axis looking at the origin: a translation by -5 along z")
    {
        requireNear(lookAt<double>({0, 0, 5}, {0, 0, 0}, {0, 1, 0}), translation<double>({0, 0, -5}));
    }
    SECTION("camera on the x axis, z up: d = -x, r = d x z = y, u = r x d = z")
    {
        // Rows r = (0,1,0), u = (0,0,1), -d = (1,0,0); translation (-r.c, -u.c, d.c) = (0, 0, -3).
        Eigen::Matrix4d expected;
        expected << 0, 1, 0, 0,
                    0, 0, 1, 0,
                    1, 0, 0, -3,
                    0, 0, 0, 1;
        const Eigen::Matrix4d view = lookAt<double>({3, 0, 0}, {0, 0, 0}, {0, 0, 1});
        requireNear(view, expected);
        // The eye goes to the origin, the target to (0, 0, -distance), up to eye-space y.
        requireNear(transformPoint<double>(view, {3, 0, 0}), Eigen::Vector3d::Zero());
        requireNear(transformPoint<double>(view, {0, 0, 0}), Eigen::Vector3d(0, 0, -3));
        requireNear(transformPoint<double>(view, {3, 0, 1}), Eigen::Vector3d(0, 1, 0));
    }
    SECTION("an up hint that is not perpendicular is straightened")
    {
        requireNear(lookAt<double>({0, 0, 5}, {0, 0, 0}, {0, 1, 1}), translation<double>({0, 0, -5}));
    }
    REQUIRE_THROWS_WITH(lookAt<double>({0, 0, 5}, {0, 0, 0}, {0, 0, 1}), Catch::Contains("parallel"));
    REQUIRE_THROWS_WITH(lookAt<double>({1, 1, 1}, {1, 1, 1}, {0, 0, 1}), Catch::Contains("zero"));
}

TEST_CASE("frustum and perspective map the view volume to [-1,1]^3", "[transform]")
{
    SECTION("the frustum l=-1 r=1 b=-1 t=1 n=1 f=3, entry by entry")
    {
        // 2n/(r-l) = 1, 2n/(t-b) = 1, -(f+n)/(f-n) = -2, -2fn/(f-n) = -3.
        Eigen::Matrix4d expected;
        expected << 1, 0, 0, 0,
                    0, 1, 0, 0,
                    0, 0, -2, -3,
                    0, 0, -1, 0;
        const Eigen::Matrix4d m = frustum<double>(-1, 1, -1, 1, 1, 3);
        requireNear(m, expected);
        // Near plane to z = -1, far plane to z = +1, the corners of the near rectangle to +-1.
        requireNear(transformPoint<double>(m, {0, 0, -1}), Eigen::Vector3d(0, 0, -1));
        requireNear(transformPoint<double>(m, {0, 0, -3}), Eigen::Vector3d(0, 0, 1));
        requireNear(transformPoint<double>(m, {1, -1, -1}), Eigen::Vector3d(1, -1, -1));
        requireNear(transformPoint<double>(m, {3, 3, -3}), Eigen::Vector3d(1, 1, 1));
    }
    SECTION("an off-centre frustum shifts x and y with (r+l)/(r-l) and (t+b)/(t-b)")
    {
        const Eigen::Matrix4d m = frustum<double>(0, 2, 1, 2, 1, 10);
        REQUIRE(m(0, 0) == 1.0);   // 2/2
        REQUIRE(m(0, 2) == 1.0);   // 2/2
        REQUIRE(m(1, 1) == 2.0);   // 2/1
        REQUIRE(m(1, 2) == 3.0);   // 3/1
        requireNear(transformPoint<double>(m, {0, 1, -1}), Eigen::Vector3d(-1, -1, -1));
        requireNear(transformPoint<double>(m, {2, 2, -1}), Eigen::Vector3d(1, 1, -1));
    }
    SECTION("perspective with a 90 degree field of view and aspect 2: t = n, r = 2n")
    {
        const Eigen::Matrix4d m = perspective<double>(kPi / 2, 2.0, 1.0, 10.0);
        requireNear(m, frustum<double>(-2, 2, -1, 1, 1, 10), 1e-15);
        REQUIRE_THAT(m(0, 0), WithinAbs(0.5, 1e-15));
        REQUIRE_THAT(m(1, 1), WithinAbs(1.0, 1e-15));
    }
    REQUIRE_THROWS(frustum<double>(-1, 1, -1, 1, 0, 3));
    REQUIRE_THROWS(frustum<double>(-1, 1, -1, 1, 3, 3));
    REQUIRE_THROWS(frustum<double>(1, 1, -1, 1, 1, 3));
    REQUIRE_THROWS(perspective<double>(0.0, 1.0, 1.0, 2.0));
    REQUIRE_THROWS(perspective<double>(1.0, -1.0, 1.0, 2.0));
}

TEST_CASE("orthographic maps a box to [-1,1]^3", "[transform]")
{
    // l=-2 r=2 b=-1 t=1 n=1 f=5: 2/(r-l) = 0.5, 2/(t-b) = 1, -2/(f-n) = -0.5, -(f+n)/(f-n) = -1.5.
    Eigen::Matrix4d expected;
    expected << 0.5, 0, 0, 0,
                0, 1, 0, 0,
                0, 0, -0.5, -1.5,
                0, 0, 0, 1;
    const Eigen::Matrix4d m = orthographic<double>(-2, 2, -1, 1, 1, 5);
    requireNear(m, expected);
    requireNear(transformPoint<double>(m, {-2, -1, -1}), Eigen::Vector3d(-1, -1, -1));
    requireNear(transformPoint<double>(m, {2, 1, -5}), Eigen::Vector3d(1, 1, 1));
    REQUIRE_THROWS(orthographic<double>(-1, 1, 2, 2, 1, 5));
}

TEST_CASE("viewport maps [-1,1]^2 to pixels and depth to [0,1]", "[transform]")
{
    const Eigen::Matrix4d m = viewport<double>(0, 0, 640, 480);
    requireNear(transformPoint<double>(m, {-1, -1, -1}), Eigen::Vector3d(0, 0, 0));
    requireNear(transformPoint<double>(m, {1, 1, 1}), Eigen::Vector3d(640, 480, 1));
    requireNear(transformPoint<double>(m, {0, 0, 0}), Eigen::Vector3d(320, 240, 0.5));
    const Eigen::Matrix4d shifted = viewport<double>(10, 20, 100, 50);
    requireNear(transformPoint<double>(shifted, {-1, 1, 0}), Eigen::Vector3d(10, 70, 0.5));
    REQUIRE_THROWS(viewport<double>(0, 0, 0, 480));
}

TEST_CASE("a known point projects to a known pixel", "[transform]")
{
    // Camera at (0,0,10) looking at the origin, y up; 90 degree vertical field of view on a 640x480
    // viewport (aspect 4/3), near 1, far 100. The point (5, 7.5, 0) is at eye-space (5, 7.5, -10):
    //   x_ndc = (1/(aspect tan 45)) 5 / 10 = 0.75 * 0.5 = 0.375 -> x_w = 320 + 0.375 * 320 = 440
    //   y_ndc = 7.5 / 10 = 0.75                            -> y_w = 240 + 0.75 * 240 = 420
    //   depth = (1/n - 1/z)/(1/n - 1/f) = (1 - 1/10)/(1 - 1/100) = 10/11.
    const Eigen::Matrix4d full = viewport<double>(0, 0, 640, 480) * perspective<double>(kPi / 2, 640.0 / 480.0, 1, 100) *
                                 lookAt<double>({0, 0, 10}, {0, 0, 0}, {0, 1, 0});
    const Eigen::Vector3d pixel = transformPoint<double>(full, {5, 7.5, 0});
    REQUIRE_THAT(pixel.x(), WithinAbs(440.0, 1e-12));
    REQUIRE_THAT(pixel.y(), WithinAbs(420.0, 1e-12));
    REQUIRE_THAT(pixel.z(), WithinAbs(10.0 / 11.0, 1e-15));
    // The look-at target lands in the centre of the viewport.
    requireNear(transformPoint<double>(full, {0, 0, 0}).head<2>(), Eigen::Vector2d(320, 240), 1e-12);

    // The same point through an orthographic camera of half-height 10 (half-width 40/3):
    // x_w = 320 + 5/(40/3) * 320 = 440, y_w = 240 + 7.5/10 * 240 = 420.
    const Eigen::Matrix4d ortho = viewport<double>(0, 0, 640, 480) * orthographic<double>(-40.0 / 3, 40.0 / 3, -10, 10, 1, 100) *
                                  lookAt<double>({0, 0, 10}, {0, 0, 0}, {0, 1, 0});
    const Eigen::Vector3d p2 = transformPoint<double>(ortho, {5, 7.5, 0});
    REQUIRE_THAT(p2.x(), WithinAbs(440.0, 1e-12));
    REQUIRE_THAT(p2.y(), WithinAbs(420.0, 1e-12)); // 240 + (7.5/10) * 240
    REQUIRE_THAT(p2.z(), WithinAbs((10.0 - 1.0) / 99.0, 1e-15)); // linear depth: (d - n)/(f - n)
}

TEST_CASE("normalMatrix is the inverse transpose and keeps normals perpendicular", "[transform]")
{
    SECTION("a scaling by (2, 1, 4) scales normals by (1/2, 1, 1/4)")
    {
        requireNear(normalMatrix<double>(scaling<double>({2, 1, 4})), Eigen::Vector3d(0.5, 1, 0.25).asDiagonal().toDenseMatrix());
    }
    SECTION("a rotation with a translation: the normal matrix is the rotation itself")
    {
        const Eigen::Matrix4d m = translation<double>({1, 2, 3}) * rotation<double>({0, 1, 1}, 0.7);
        requireNear(normalMatrix<double>(m), m.topLeftCorner<3, 3>(), 1e-15);
    }
    SECTION("under a shear the transformed normal is perpendicular to the transformed tangents")
    {
        Eigen::Matrix4d shear = Eigen::Matrix4d::Identity();
        shear(0, 1) = 1.5;
        shear(2, 0) = -0.25;
        // The plane x + y + z = 0 has normal (1,1,1) and tangents (1,-1,0), (1,0,-1).
        const Eigen::Vector3d n = normalMatrix<double>(shear) * Eigen::Vector3d(1, 1, 1);
        const Eigen::Matrix3d a = shear.topLeftCorner<3, 3>();
        REQUIRE_THAT(n.dot(a * Eigen::Vector3d(1, -1, 0)), WithinAbs(0.0, 1e-15));
        REQUIRE_THAT(n.dot(a * Eigen::Vector3d(1, 0, -1)), WithinAbs(0.0, 1e-15));
        // ... while transforming the normal like a point would not be.
        REQUIRE(std::abs((a * Eigen::Vector3d(1, 1, 1)).dot(a * Eigen::Vector3d(1, -1, 0))) > 0.5);
    }
    REQUIRE_THROWS_WITH(normalMatrix<double>(scaling<double>({1, 0, 1})), Catch::Contains("singular"));
}

TEST_CASE("the float versions agree with double", "[transform]")
{
    const Eigen::Matrix4f f = perspective<float>(1.0f, 1.5f, 0.1f, 50.0f) * lookAt<float>({1, 2, 3}, {0, 0, 0}, {0, 0, 1});
    const Eigen::Matrix4d d = perspective<double>(1.0, 1.5, 0.1, 50.0) * lookAt<double>({1, 2, 3}, {0, 0, 0}, {0, 0, 1});
    REQUIRE((f.cast<double>() - d).cwiseAbs().maxCoeff() < 1e-5);
}

} // namespace test_transform
