#pragma once
// Homogeneous 4x4 transforms for drawing geometry: model transforms (translation, scaling, rotation
// about any unit axis), the camera (look-at), the projections (perspective frustum, orthographic)
// and the viewport, plus the normal matrix. Formulas: docs/math.md ("Transforms and projection").
//
// Conventions (those of OpenGL): column vectors, right-handed eye space with the camera at the
// origin looking down -z, projections map the view volume to the cube [-1,1]^3 (near plane to
// z = -1), the viewport maps x, y in [-1,1] to pixels with y pointing up from the bottom row and
// z to the depth range [0, 1]. Every function validates its arguments (a zero axis, a degenerate
// frustum, a view direction parallel to "up") and throws freeform::Error naming the argument; the
// results are plain Eigen matrices. No graphics API is involved: the editor uploads these matrices.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include <cmath>
#include <string>

#include "freeform/core/error.h"

namespace freeform {

template <typename Scalar>
using Matrix4 = Eigen::Matrix<Scalar, 4, 4>;
template <typename Scalar>
using Matrix3 = Eigen::Matrix<Scalar, 3, 3>;
template <typename Scalar>
using Vector3 = Eigen::Matrix<Scalar, 3, 1>;

/// x -> x + t.
template <typename Scalar>
Matrix4<Scalar> translation(const Vector3<Scalar>& t)
{
    Matrix4<Scalar> m = Matrix4<Scalar>::Identity();
    m.template topRightCorner<3, 1>() = t;
    return m;
}

/// x -> diag(s) x.
template <typename Scalar>
Matrix4<Scalar> scaling(const Vector3<Scalar>& s)
{
    Matrix4<Scalar> m = Matrix4<Scalar>::Identity();
    m(0, 0) = s.x();
    m(1, 1) = s.y();
    m(2, 2) = s.z();
    return m;
}

/// The 3x3 rotation by `angle` radians about the axis direction (normalised here; counter-clockwise
/// seen from the tip of the axis): R = cos(a) I + (1 - cos(a)) n n^T + sin(a) X_n, with X_n the
/// cross-product matrix of n (X_n v = n x v). Error for a zero or non-finite axis.
template <typename Scalar>
Matrix3<Scalar> rotationMatrix(const Vector3<Scalar>& axis, Scalar angle)
{
    const Scalar length = axis.norm();
    if (!(length > Scalar(0)) || !std::isfinite(static_cast<double>(length)))
        throw Error("rotation: the axis must be a finite non-zero vector");
    const Vector3<Scalar> n = axis / length;
    Matrix3<Scalar> cross;
    cross << Scalar(0), -n.z(), n.y(),
             n.z(), Scalar(0), -n.x(),
             -n.y(), n.x(), Scalar(0);
    using std::cos;
    using std::sin;
    const Scalar c = cos(angle), s = sin(angle);
    return c * Matrix3<Scalar>::Identity() + (Scalar(1) - c) * (n * n.transpose()) + s * cross;
}

/// The homogeneous rotation about an axis through the origin (see rotationMatrix).
template <typename Scalar>
Matrix4<Scalar> rotation(const Vector3<Scalar>& axis, Scalar angle)
{
    Matrix4<Scalar> m = Matrix4<Scalar>::Identity();
    m.template topLeftCorner<3, 3>() = rotationMatrix(axis, angle);
    return m;
}

/// The view matrix of a camera at `eye` looking along `direction` with `up` as the upward hint:
/// d = direction/|direction|, r = d x up normalised, u = r x d, and the matrix is the inverse of
/// the camera frame [r u -d eye] (so r, u, -d become the eye-space x, y, z axes and eye the origin).
/// Error when direction is zero or parallel to up.
template <typename Scalar>
Matrix4<Scalar> lookAlong(const Vector3<Scalar>& eye, const Vector3<Scalar>& direction, const Vector3<Scalar>& up)
{
    const Scalar dl = direction.norm();
    if (!(dl > Scalar(0))) throw Error("lookAt: the view direction is zero (eye and target coincide)");
    const Vector3<Scalar> d = direction / dl;
    Vector3<Scalar> r = d.cross(up);
    const Scalar rl = r.norm();
    if (!(rl > Scalar(1e-12) * (up.norm() + Scalar(1e-300)))) throw Error("lookAt: the view direction is parallel to up");
    r /= rl;
    const Vector3<Scalar> u = r.cross(d);
    // Inverse of the orthonormal frame: rotation transposed, translation -R^T eye.
    Matrix4<Scalar> m = Matrix4<Scalar>::Identity();
    m.template block<1, 3>(0, 0) = r.transpose();
    m.template block<1, 3>(1, 0) = u.transpose();
    m.template block<1, 3>(2, 0) = -d.transpose();
    m(0, 3) = -r.dot(eye);
    m(1, 3) = -u.dot(eye);
    m(2, 3) = d.dot(eye);
    return m;
}

/// The view matrix of a camera at `eye` looking at `target` (see lookAlong).
template <typename Scalar>
Matrix4<Scalar> lookAt(const Vector3<Scalar>& eye, const Vector3<Scalar>& target, const Vector3<Scalar>& up)
{
    return lookAlong<Scalar>(eye, target - eye, up);
}

/// The perspective projection of the frustum with the near-plane rectangle [l,r] x [b,t] at
/// distance n and the far plane at f (docs/math.md, "Transforms and projection"). Error unless l != r, b != t, 0 < n < f.
template <typename Scalar>
Matrix4<Scalar> frustum(Scalar l, Scalar r, Scalar b, Scalar t, Scalar n, Scalar f)
{
    if (!(r != l) || !(t != b)) throw Error("frustum: left/right and bottom/top must differ");
    if (!(n > Scalar(0)) || !(f > n)) throw Error("frustum: needs 0 < near < far");
    Matrix4<Scalar> m = Matrix4<Scalar>::Zero();
    m(0, 0) = Scalar(2) * n / (r - l);
    m(0, 2) = (r + l) / (r - l);
    m(1, 1) = Scalar(2) * n / (t - b);
    m(1, 2) = (t + b) / (t - b);
    m(2, 2) = -(f + n) / (f - n);
    m(2, 3) = Scalar(-2) * f * n / (f - n);
    m(3, 2) = Scalar(-1);
    return m;
}

/// The symmetric frustum with vertical field of view fovy (radians, in (0, pi)) and
/// aspect = width/height: t = n tan(fovy/2), r = aspect t.
template <typename Scalar>
Matrix4<Scalar> perspective(Scalar fovy, Scalar aspect, Scalar n, Scalar f)
{
    using std::tan;
    if (!(fovy > Scalar(0)) || !(fovy < Scalar(3.14159265358979323846)))
        throw Error("perspective: the field of view must lie in (0, pi)");
    if (!(aspect > Scalar(0))) throw Error("perspective: the aspect ratio must be positive");
    const Scalar t = n * tan(fovy / Scalar(2));
    return frustum<Scalar>(-aspect * t, aspect * t, -t, t, n, f);
}

/// The orthographic projection of the box [l,r] x [b,t] x [-n,-f] (eye space) to [-1,1]^3.
/// Error unless l != r, b != t, n != f.
template <typename Scalar>
Matrix4<Scalar> orthographic(Scalar l, Scalar r, Scalar b, Scalar t, Scalar n, Scalar f)
{
    if (!(r != l) || !(t != b) || !(f != n)) throw Error("orthographic: left/right, bottom/top and near/far must differ");
    Matrix4<Scalar> m = Matrix4<Scalar>::Identity();
    m(0, 0) = Scalar(2) / (r - l);
    m(0, 3) = -(r + l) / (r - l);
    m(1, 1) = Scalar(2) / (t - b);
    m(1, 3) = -(t + b) / (t - b);
    m(2, 2) = Scalar(-2) / (f - n);
    m(2, 3) = -(f + n) / (f - n);
    return m;
}

/// Normalised device coordinates to window coordinates for the viewport at pixel (x, y) (lower
/// left corner) of the given size: x_w = x + (x_ndc + 1) w/2, y_w = y + (y_ndc + 1) h/2,
/// z_w = (z_ndc + 1)/2 (depth 0 at the near plane, 1 at the far plane). Pixel (i, j) covers
/// [i, i+1) x [j, j+1), its centre is (i + 1/2, j + 1/2).
template <typename Scalar>
Matrix4<Scalar> viewport(Scalar x, Scalar y, Scalar width, Scalar height)
{
    if (!(width > Scalar(0)) || !(height > Scalar(0))) throw Error("viewport: width and height must be positive");
    Matrix4<Scalar> m = Matrix4<Scalar>::Identity();
    m(0, 0) = width / Scalar(2);
    m(0, 3) = x + width / Scalar(2);
    m(1, 1) = height / Scalar(2);
    m(1, 3) = y + height / Scalar(2);
    m(2, 2) = Scalar(0.5);
    m(2, 3) = Scalar(0.5);
    return m;
}

/// The matrix that transforms normals under the model(-view) transform m: the inverse transpose of
/// its linear 3x3 part (normals then need renormalising). Error when that part is singular.
template <typename Scalar>
Matrix3<Scalar> normalMatrix(const Matrix4<Scalar>& m)
{
    const Matrix3<Scalar> a = m.template topLeftCorner<3, 3>();
    Matrix3<Scalar> inverse;
    bool invertible = false;
    Scalar det(0);
    a.computeInverseAndDetWithCheck(inverse, det, invertible, Scalar(0));
    if (!invertible || !std::isfinite(static_cast<double>(det)))
        throw Error("normalMatrix: the linear part of the transform is singular");
    return inverse.transpose();
}

/// Applies a 4x4 transform to the point p (w = 1) and divides by the resulting w: with
/// m = viewport * projection * view * model this gives window coordinates (pixels, depth).
template <typename Scalar>
Vector3<Scalar> transformPoint(const Matrix4<Scalar>& m, const Vector3<Scalar>& p)
{
    const Eigen::Matrix<Scalar, 4, 1> h = m * Eigen::Matrix<Scalar, 4, 1>(p.x(), p.y(), p.z(), Scalar(1));
    return h.template head<3>() / h.w();
}

} // namespace freeform
