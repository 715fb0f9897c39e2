#pragma once
// Joins: make the joint between a left segment c_0..c_n (on an interval of length hl) and a right
// segment d_0..d_n (length hr) C0, C1, G1 or, for cubics, C2, by moving as few control points as
// the chosen variant allows. docs/splines.md ("Joins") has the formulas and figures.
//
// Variants (JoinMove), the ones a drawing program offers:
//   - Joint: keep the handles, move the joint point. C0: the midpoint of c_n and d_0. C1: the ratio
//     point c_n = d_0 = (hr c_(n-1) + hl d_1) / (hl + hr) (the seed's (c_(n-1) + d_1)/2 for equal
//     intervals). G1: the point of the segment c_(n-1) d_1 nearest to the old joint (the midpoint
//     when that nearest point is an end of the segment, which would collapse a handle). C2 (cubic):
//     keep the outer handles c_1, d_2, take the de Boor point a as the mean of the two A-frame
//     apexes, then c_2, d_1 and the joint are the ratio points of the A-frame (moves c_2, c_3 = d_0,
//     d_1).
//   - RightHandle: keep the left segment (and so the joint c_n) and move the right side. C0: d_0
//     goes to c_n and d_1 travels with it (n >= 2). C1: d_1 = c_n + (hr/hl)(c_n - c_(n-1)) (the
//     mirrored handle, scaled by the interval ratio). G1: d_1 turns onto the ray from c_(n-1)
//     through c_n keeping its length |d_1 - d_0|. C2: C1 as above, then d_2 = d_1 + (hr/hl)(d_1 - a)
//     with a = c_2 + (hr/hl)(c_2 - c_1) the left A-frame apex.
//   - LeftHandle: the mirror image (keep the right segment, move c_n, c_(n-1), c_(n-2)).
// The joint is shared by both segments afterwards (c_n = d_0). Guarantees: the requested
// continuity holds up to rounding; points not named above keep their values exactly. The spline
// overloads return a new spline (interior joints of open splines, any joint of closed splines of
// at least two segments); a BezierSpline is C0 by construction, so joinC0 exists for separate
// segments only.

#include <algorithm>
#include <string>

#include "freeform/core/error.h"
#include "freeform/core/types.h"
#include "freeform/curve/bezier_spline.h"

namespace freeform {

enum class JoinMove { Joint, LeftHandle, RightHandle };

namespace detail {

template <typename Scalar, int Dim>
void requirePair(const PointMatrix<Scalar, Dim>& left, const PointMatrix<Scalar, Dim>& right, int minDegree,
                 JoinMove move, const char* what)
{
    if (left.cols() != right.cols() || left.cols() < 2)
        throw Error(std::string(what) + ": the two segments need the same degree of at least 1");
    const int n = static_cast<int>(left.cols()) - 1;
    if (n < minDegree)
        throw Error(std::string(what) + ": needs degree " + std::to_string(minDegree) + " or more, the segments have " +
                    std::to_string(n));
    if (move != JoinMove::Joint && n < 2)
        throw Error(std::string(what) + ": moving a handle needs degree 2 or more (a line has no handles)");
}

template <typename Scalar>
void requireIntervals(Scalar hl, Scalar hr, const char* what)
{
    if (!(hl > Scalar(0)) || !(hr > Scalar(0)))
        throw Error(std::string(what) + ": interval lengths must be positive");
}

} // namespace detail

/// C0 for separate segments (see the header comment for what moves).
template <typename Scalar, int Dim>
void joinC0(PointMatrix<Scalar, Dim>& left, PointMatrix<Scalar, Dim>& right, JoinMove move)
{
    detail::requirePair(left, right, 1, move, "joinC0");
    const int n = static_cast<int>(left.cols()) - 1;
    if (move == JoinMove::Joint) {
        const Point<Scalar, Dim> m = (left.col(n) + right.col(0)) / Scalar(2);
        left.col(n) = m;
        right.col(0) = m;
    } else if (move == JoinMove::RightHandle) {
        const Point<Scalar, Dim> shift = left.col(n) - right.col(0);
        right.col(0) = left.col(n);
        right.col(1) += shift;
    } else {
        const Point<Scalar, Dim> shift = right.col(0) - left.col(n);
        left.col(n) = right.col(0);
        left.col(n - 1) += shift;
    }
}

/// C1 with respect to the global parameter (intervals hl, hr); C0 is made as well.
template <typename Scalar, int Dim>
void joinC1(PointMatrix<Scalar, Dim>& left, PointMatrix<Scalar, Dim>& right, Scalar hl, Scalar hr, JoinMove move)
{
    detail::requirePair(left, right, 1, move, "joinC1");
    detail::requireIntervals(hl, hr, "joinC1");
    const int n = static_cast<int>(left.cols()) - 1;
    if (move == JoinMove::Joint) {
        const Point<Scalar, Dim> j = (hr * left.col(n - 1) + hl * right.col(1)) / (hl + hr);
        left.col(n) = j;
        right.col(0) = j;
    } else if (move == JoinMove::RightHandle) {
        const Point<Scalar, Dim> j = left.col(n);
        right.col(0) = j;
        right.col(1) = j + (hr / hl) * (j - left.col(n - 1));
    } else {
        const Point<Scalar, Dim> j = right.col(0);
        left.col(n) = j;
        left.col(n - 1) = j - (hl / hr) * (right.col(1) - j);
    }
}

/// G1: the handles c_(n-1), d_1 and the joint on one line, the handles on opposite sides.
/// Error when the kept handle coincides with the joint (no direction to align to).
template <typename Scalar, int Dim>
void joinG1(PointMatrix<Scalar, Dim>& left, PointMatrix<Scalar, Dim>& right, JoinMove move)
{
    detail::requirePair(left, right, 1, move, "joinG1");
    const int n = static_cast<int>(left.cols()) - 1;
    using P = Point<Scalar, Dim>;
    if (move == JoinMove::Joint) {
        const P a = left.col(n - 1), b = right.col(1), old = (left.col(n) + right.col(0)) / Scalar(2);
        const P ab = b - a;
        const Scalar len2 = ab.squaredNorm();
        Scalar u = len2 > Scalar(0) ? (old - a).dot(ab) / len2 : Scalar(0);
        if (!(u > Scalar(0) && u < Scalar(1))) u = Scalar(0.5); // an end would collapse a handle
        const P j = a + u * ab;
        left.col(n) = j;
        right.col(0) = j;
        return;
    }
    const bool keepLeft = move == JoinMove::RightHandle;
    const P j = keepLeft ? P(left.col(n)) : P(right.col(0));
    const P kept = keepLeft ? P(left.col(n - 1)) : P(right.col(1));
    const P moved = keepLeft ? P(right.col(1)) : P(left.col(n - 1));
    const P oldJoint = keepLeft ? P(right.col(0)) : P(left.col(n));
    const P dir = j - kept;
    const Scalar dirLen = dir.norm();
    if (dirLen == Scalar(0))
        throw Error("joinG1: the kept handle coincides with the joint, there is no tangent to align to");
    Scalar length = (moved - oldJoint).norm();
    if (length == Scalar(0)) length = dirLen; // a collapsed handle gets the kept handle's length
    const P handle = j + (length / dirLen) * dir;
    if (keepLeft) {
        right.col(0) = j;
        right.col(1) = handle;
    } else {
        left.col(n) = j;
        left.col(n - 1) = handle;
    }
}

/// C2 of two cubics (the A-frame condition with the interval ratio); C1 and C0 are made as well.
template <typename Scalar, int Dim>
void joinC2(PointMatrix<Scalar, Dim>& left, PointMatrix<Scalar, Dim>& right, Scalar hl, Scalar hr, JoinMove move)
{
    if (left.cols() != 4 || right.cols() != 4) throw Error("joinC2: C2 joins are for cubic segments");
    detail::requireIntervals(hl, hr, "joinC2");
    using P = Point<Scalar, Dim>;
    const Scalar s = hl + hr;
    if (move == JoinMove::Joint) {
        const P c1 = left.col(1), d2 = right.col(2);
        const P aLeft = left.col(2) + (hr / hl) * (left.col(2) - left.col(1));
        const P aRight = right.col(1) - (hl / hr) * (right.col(2) - right.col(1));
        const P a = (aLeft + aRight) / Scalar(2);
        const P c2 = (hr * c1 + hl * a) / s;
        const P d1 = (hr * a + hl * d2) / s;
        const P j = (hr * c2 + hl * d1) / s;
        left.col(2) = c2;
        left.col(3) = j;
        right.col(0) = j;
        right.col(1) = d1;
    } else if (move == JoinMove::RightHandle) {
        const P j = left.col(3);
        const P a = left.col(2) + (hr / hl) * (left.col(2) - left.col(1));
        const P d1 = j + (hr / hl) * (j - left.col(2));
        right.col(0) = j;
        right.col(1) = d1;
        right.col(2) = d1 + (hr / hl) * (d1 - a);
    } else {
        const P j = right.col(0);
        const P a = right.col(1) - (hl / hr) * (right.col(2) - right.col(1));
        const P c2 = j - (hl / hr) * (right.col(1) - j);
        left.col(3) = j;
        left.col(2) = c2;
        left.col(1) = c2 - (hl / hr) * (a - c2);
    }
}

namespace detail {

template <typename Scalar, int Dim, typename Op>
BezierSpline<Scalar, Dim> joinSpline(const BezierSpline<Scalar, Dim>& spline, int joint, const char* what, Op op)
{
    const int L = spline.segmentCount();
    const bool ok = spline.closed() ? (L >= 2 && joint >= 0 && joint < L) : (joint >= 1 && joint <= L - 1);
    if (!ok)
        throw Error(std::string(what) + ": joint " + std::to_string(joint) + " is not an inner joint of the spline (" +
                    (spline.closed() ? (L >= 2 ? "0.." + std::to_string(L - 1) : std::string("one closed segment has none"))
                                     : (L >= 2 ? "1.." + std::to_string(L - 1) : std::string("one segment has none"))) +
                    ")");
    const int li = joint == 0 ? L - 1 : joint - 1, ri = joint;
    PointMatrix<Scalar, Dim> left = spline.segmentPoints(li), right = spline.segmentPoints(ri);
    op(left, right, spline.intervals()[li], spline.intervals()[ri]);
    PointMatrix<Scalar, Dim> points = spline.controlPoints();
    const int n = spline.degree();
    for (int k = 0; k <= n; ++k) points.col(spline.pointIndex(li, k)) = left.col(k);
    for (int k = 0; k <= n; ++k) points.col(spline.pointIndex(ri, k)) = right.col(k);
    return spline.withControlPoints(std::move(points));
}

} // namespace detail

/// Joint `joint` of the spline made C1 (see JoinMove for what moves).
template <typename Scalar, int Dim>
BezierSpline<Scalar, Dim> joinC1(const BezierSpline<Scalar, Dim>& spline, int joint, JoinMove move)
{
    return detail::joinSpline(spline, joint, "joinC1", [&](auto& l, auto& r, Scalar hl, Scalar hr) {
        joinC1<Scalar, Dim>(l, r, hl, hr, move);
    });
}

/// Joint `joint` of the spline made G1.
template <typename Scalar, int Dim>
BezierSpline<Scalar, Dim> joinG1(const BezierSpline<Scalar, Dim>& spline, int joint, JoinMove move)
{
    return detail::joinSpline(spline, joint, "joinG1", [&](auto& l, auto& r, Scalar, Scalar) {
        joinG1<Scalar, Dim>(l, r, move);
    });
}

/// Joint `joint` of a cubic spline made C2.
template <typename Scalar, int Dim>
BezierSpline<Scalar, Dim> joinC2(const BezierSpline<Scalar, Dim>& spline, int joint, JoinMove move)
{
    if (spline.degree() != 3)
        throw Error("joinC2: C2 joins are for cubic splines, this one has degree " + std::to_string(spline.degree()));
    return detail::joinSpline(spline, joint, "joinC2", [&](auto& l, auto& r, Scalar hl, Scalar hr) {
        joinC2<Scalar, Dim>(l, r, hl, hr, move);
    });
}

} // namespace freeform
