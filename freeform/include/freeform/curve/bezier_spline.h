#pragma once
// BezierSpline<Scalar, Dim>: a chain of L Bézier segments of one degree n, segment i on a global
// parameter interval [T_i, T_(i+1)] of length h_i > 0 (T_0 = 0), open or closed.
//
// Invariants (checked once in the constructor, Error names what is wrong): degree 1..kMaxDegree,
// at least one segment, every coordinate finite, L positive finite interval lengths. Control points
// are stored once, joints shared: an open spline has L*n + 1 points, segment i owns points
// i*n .. i*n + n; a closed spline has L*n points and its last segment ends at point 0. Joint j is
// the point i*n = j*n where segment j starts (open: j = 0..L, the ends included; closed: j = 0..L-1,
// joint 0 being the closing joint). Evaluation is const and check-free; a global parameter outside
// [0, T_L] extrapolates the first or last segment. Derivatives are with respect to the global
// parameter: the k-th derivative of segment i is scaled by h_i^-k. Structural operations
// (splitSegment, removeJoint, elevated, withControlPoints) return new splines. Math: docs/splines.md.

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "freeform/core/bernstein.h"
#include "freeform/core/error.h"
#include "freeform/core/types.h"
#include "freeform/curve/aframe.h"
#include "freeform/curve/bezier_curve.h"

namespace freeform {

template <typename Scalar, int Dim>
class BezierSpline {
public:
    using PointType = Point<Scalar, Dim>;
    using Points = PointMatrix<Scalar, Dim>;
    using Curve = BezierCurve<Scalar, Dim>;
    using Derivatives = Eigen::Matrix<Scalar, Dim, Eigen::Dynamic>;

    /// Segment and local parameter t of a global parameter (see locate()).
    struct Location {
        int segment;
        Scalar t;
    };

    /// Result of removeJoint(): the spline with one segment less and an upper bound of the
    /// parametric distance max_T |merged(T) - this(T)| (from the convex hull of the difference's
    /// control points on each of the two old pieces); 0 up to rounding when the joint was C-infinity.
    struct Merge;

    /// All control points as columns, joints shared (see the header comment); intervals: one
    /// positive length per segment, or empty for all 1.
    BezierSpline(int degree, bool closed, Points points, std::vector<Scalar> intervals = {})
        : degree_(degree), closed_(closed), points_(std::move(points)), intervals_(std::move(intervals))
    {
        if (degree_ < 1 || degree_ > kMaxDegree)
            throw Error("BezierSpline: degree " + std::to_string(degree_) + " is outside 1.." + std::to_string(kMaxDegree));
        const long count = static_cast<long>(points_.cols());
        const bool fits = closed_ ? (count >= degree_ && count % degree_ == 0)
                                  : (count >= degree_ + 1 && (count - 1) % degree_ == 0);
        if (!fits)
            throw Error("BezierSpline: " + std::to_string(count) + " points do not fit degree " + std::to_string(degree_) +
                        (closed_ ? ": a closed spline of L segments has L*degree points"
                                 : ": an open spline of L segments has L*degree + 1 points"));
        requireFinite(points_, "BezierSpline");
        segments_ = static_cast<int>(closed_ ? count / degree_ : (count - 1) / degree_);
        intervals_ = detail::aframeIntervals(intervals_, segments_, "BezierSpline");
        knots_.resize(static_cast<std::size_t>(segments_) + 1);
        knots_[0] = Scalar(0);
        for (int i = 0; i < segments_; ++i) knots_[i + 1] = knots_[i] + intervals_[i];
    }

    /// The C2 cubic spline of de Boor points by the A-frame (curve/aframe.h).
    static BezierSpline fromDeBoor(const Points& deboor, EndCondition end, const std::vector<Scalar>& intervals = {})
    {
        return BezierSpline(3, end == EndCondition::Closed, aframeBezierPoints<Scalar, Dim>(deboor, end, intervals),
                            intervals);
    }

    /// The de Boor points of this spline (cubic, C2) under `end`, which must be Closed exactly
    /// when the spline is closed; Error otherwise or when the spline is not C2 (aframeDeBoorPoints).
    Points deBoorPoints(EndCondition end, Scalar tolerance = aframeDefaultTolerance<Scalar>()) const
    {
        if (degree_ != 3)
            throw Error("BezierSpline::deBoorPoints: de Boor points need a cubic spline, this one has degree " +
                        std::to_string(degree_));
        if ((end == EndCondition::Closed) != closed_)
            throw Error(std::string("BezierSpline::deBoorPoints: a ") + (closed_ ? "closed" : "open") +
                        " spline cannot have the end condition " + toString(end));
        return aframeDeBoorPoints<Scalar, Dim>(points_, end, intervals_, tolerance);
    }

    // ---------------------------------------------------------------- structure

    int degree() const { return degree_; }
    bool closed() const { return closed_; }
    int segmentCount() const { return segments_; }
    /// Joints: L + 1 for an open spline (both ends included), L for a closed one.
    int jointCount() const { return closed_ ? segments_ : segments_ + 1; }
    const Points& controlPoints() const { return points_; }
    const std::vector<Scalar>& intervals() const { return intervals_; }
    /// T_j, the global parameter of joint j (j = 0..L; T_L is the end of the domain).
    Scalar knot(int j) const { return knots_[static_cast<std::size_t>(j)]; }
    const std::vector<Scalar>& knots() const { return knots_; }
    Scalar domainEnd() const { return knots_.back(); }

    /// Column of control point k (0..n) of segment i.
    int pointIndex(int segment, int k) const
    {
        const int index = segment * degree_ + k;
        return (closed_ && index == segments_ * degree_) ? 0 : index;
    }

    /// Control points of segment i (Dim x (n+1)).
    Points segmentPoints(int i) const
    {
        Points p(Dim, degree_ + 1);
        for (int k = 0; k <= degree_; ++k) p.col(k) = points_.col(pointIndex(i, k));
        return p;
    }

    /// Segment i as a curve on its own parameter t in [0, 1] (t = (T - T_i) / h_i).
    Curve segment(int i) const { return Curve(segmentPoints(i)); }

    // ---------------------------------------------------------------- evaluation

    /// The segment of T (binary search over the knots; a joint belongs to the segment it starts,
    /// the end of the domain to the last segment) and the local parameter there.
    Location locate(Scalar T) const
    {
        const auto it = std::upper_bound(knots_.begin(), knots_.end(), T);
        int i = static_cast<int>(it - knots_.begin()) - 1;
        i = std::clamp(i, 0, segments_ - 1);
        if (i == segments_ - 1 && T == knots_.back()) return {i, Scalar(1)};
        return {i, (T - knots_[i]) / intervals_[i]};
    }

    PointType evaluate(Scalar T) const
    {
        const Location at = locate(T);
        return segment(at.segment).evaluate(at.t);
    }
    PointType operator()(Scalar T) const { return evaluate(T); }

    /// Column j is the j-th derivative with respect to T (j = 0..k).
    Derivatives derivatives(Scalar T, int k) const
    {
        const Location at = locate(T);
        return scaled(segment(at.segment).derivatives(at.t, k), at.segment);
    }

    /// One-sided derivatives 0..k at joint j from the segment that ends there (the left side).
    /// Error for joint 0 of an open spline (nothing ends there).
    Derivatives leftDerivatives(int joint, int k) const
    {
        requireJoint(joint, "leftDerivatives");
        if (!closed_ && joint == 0) throw Error("BezierSpline::leftDerivatives: joint 0 of an open spline has no left side");
        const int i = joint == 0 ? segments_ - 1 : joint - 1;
        return scaled(segment(i).derivatives(Scalar(1), k), i);
    }

    /// One-sided derivatives 0..k at joint j from the segment that starts there (the right side).
    /// Error for the last joint of an open spline.
    Derivatives rightDerivatives(int joint, int k) const
    {
        requireJoint(joint, "rightDerivatives");
        if (!closed_ && joint == segments_)
            throw Error("BezierSpline::rightDerivatives: the last joint of an open spline has no right side");
        return scaled(segment(joint).derivatives(Scalar(0), k), joint);
    }

    // ---------------------------------------------------------------- structural operations

    /// The same spline with other control points (same degree, closedness and intervals).
    BezierSpline withControlPoints(Points points) const { return BezierSpline(degree_, closed_, std::move(points), intervals_); }

    /// Segment i split at local t in (0, 1) into two segments on intervals t h_i and (1-t) h_i: the
    /// curve and its parametrisation are unchanged, and the new joint is C-infinity.
    BezierSpline splitSegment(int i, Scalar t) const
    {
        if (i < 0 || i >= segments_)
            throw Error("BezierSpline::splitSegment: segment " + std::to_string(i) + " is outside 0.." +
                        std::to_string(segments_ - 1));
        if (!(t > Scalar(0) && t < Scalar(1)))
            throw Error("BezierSpline::splitSegment: t must lie strictly inside (0, 1)");
        const auto halves = segment(i).split(t);
        const int n = degree_;
        const bool wraps = closed_ && i == segments_ - 1; // the segment ends at point 0
        Points p(Dim, points_.cols() + n + (wraps ? 1 : 0));
        p.leftCols(i * n) = points_.leftCols(i * n);
        p.middleCols(i * n, n + 1) = halves.first.controlPoints();
        p.middleCols(i * n + n, n + 1) = halves.second.controlPoints();
        // The points from segment i's end joint on (the joint itself again, same value).
        const long rest = points_.cols() - (static_cast<long>(i) * n + n);
        if (rest > 0) p.rightCols(rest) = points_.rightCols(rest);
        if (wraps) p.conservativeResize(Eigen::NoChange, p.cols() - 1);
        std::vector<Scalar> h = intervals_;
        h[i] = intervals_[i] * t;
        h.insert(h.begin() + i + 1, intervals_[i] - h[i]);
        return BezierSpline(n, closed_, std::move(p), std::move(h));
    }

    /// Joint j removed: segments j-1 and j become one segment on the sum of their intervals.
    /// Kept exactly: the outer end points and the derivatives of orders 1..r at them, r = (n-1)/2
    /// (rounded down), so continuity of order r with the neighbours survives; for even n the one
    /// control point left free is chosen so that the merged segment still passes through the removed
    /// joint at the same parameter. Open splines: j = 1..L-1; closed: j = 0..L-1 with L >= 2 (removing
    /// joint 0 moves the start to old joint 1, so the merged segment becomes the last one).
    Merge removeJoint(int joint) const;

    /// Every segment degree-elevated `times` times (the curve is unchanged).
    BezierSpline elevated(int times = 1) const
    {
        if (times < 0) throw Error("BezierSpline::elevated: count " + std::to_string(times) + " is negative");
        const int m = degree_ + times;
        requireDegree(m, "BezierSpline::elevated");
        Points p(Dim, closed_ ? segments_ * m : segments_ * m + 1);
        for (int i = 0; i < segments_; ++i) {
            const Points q = segment(i).elevated(times).controlPoints();
            const int keep = (closed_ && i == segments_ - 1) ? m : m + 1;
            p.middleCols(i * m, keep) = q.leftCols(keep);
        }
        return BezierSpline(m, closed_, std::move(p), intervals_);
    }

    // ---------------------------------------------------------------- sampling

    /// A polyline of `perSegment` >= 1 pieces per segment at uniform local parameters:
    /// Dim x (L*perSegment + 1); a closed spline's polyline ends at its first point again.
    Points sample(int perSegment) const
    {
        if (perSegment < 1)
            throw Error("BezierSpline::sample: " + std::to_string(perSegment) + " pieces per segment is below 1");
        Points out(Dim, segments_ * perSegment + 1);
        std::vector<Scalar> ts(static_cast<std::size_t>(perSegment));
        for (int k = 0; k < perSegment; ++k) ts[k] = Scalar(k) / Scalar(perSegment);
        Points piece;
        for (int i = 0; i < segments_; ++i) {
            segment(i).evaluateMany(ts.data(), ts.size(), piece);
            out.middleCols(i * perSegment, perSegment) = piece;
        }
        out.col(out.cols() - 1) = points_.col(pointIndex(segments_ - 1, degree_));
        return out;
    }

    /// Global parameters (sorted, 0 .. T_L) of a polyline within `tolerance` of the spline
    /// (BezierCurve::sampleAdaptive on every segment).
    std::vector<Scalar> sampleAdaptive(Scalar tolerance) const
    {
        std::vector<Scalar> out{Scalar(0)};
        for (int i = 0; i < segments_; ++i) {
            const std::vector<Scalar> ts = segment(i).sampleAdaptive(tolerance);
            for (std::size_t k = 1; k < ts.size(); ++k)
                out.push_back(k + 1 == ts.size() ? knots_[i + 1] : knots_[i] + ts[k] * intervals_[i]);
        }
        return out;
    }

private:
    void requireJoint(int joint, const char* what) const
    {
        if (joint < 0 || joint >= jointCount())
            throw Error(std::string("BezierSpline::") + what + ": joint " + std::to_string(joint) + " is outside 0.." +
                        std::to_string(jointCount() - 1));
    }

    Derivatives scaled(Derivatives d, int i) const
    {
        const Scalar inv = Scalar(1) / intervals_[i];
        Scalar f(1);
        for (Eigen::Index j = 1; j < d.cols(); ++j) {
            f *= inv;
            d.col(j) *= f;
        }
        return d;
    }

    /// The first r+1 control points of the polynomial of `p` (degree n) re-expressed over [0, lambda]:
    /// the k-th forward difference at the start scales by lambda^k.
    static Points extendedStart(const Points& p, int r, Scalar lambda)
    {
        Points diff = p.leftCols(r + 1); // diff.col(k) = Delta^k p_0 after the loop
        for (int level = 1; level <= r; ++level)
            for (int k = r; k >= level; --k) diff.col(k) = diff.col(k) - diff.col(k - 1);
        Scalar f(1);
        for (int k = 1; k <= r; ++k) {
            f *= lambda;
            diff.col(k) *= f;
        }
        Points out(Dim, r + 1);
        for (int k = 0; k <= r; ++k) {
            PointType q = PointType::Zero();
            for (int j = 0; j <= k; ++j) q += Scalar(binomial(k, j)) * diff.col(j);
            out.col(k) = q;
        }
        return out;
    }

    int degree_;
    bool closed_;
    Points points_;
    std::vector<Scalar> intervals_;
    std::vector<Scalar> knots_;
    int segments_ = 0;
};

template <typename Scalar, int Dim>
struct BezierSpline<Scalar, Dim>::Merge {
    BezierSpline spline;
    Scalar errorBound;
};

template <typename Scalar, int Dim>
typename BezierSpline<Scalar, Dim>::Merge BezierSpline<Scalar, Dim>::removeJoint(int joint) const
{
    const int L = segments_, n = degree_;
    if (closed_ ? (L < 2 || joint < 0 || joint >= L) : (joint < 1 || joint > L - 1))
        throw Error("BezierSpline::removeJoint: joint " + std::to_string(joint) + " is not an inner joint (" +
                    (closed_ ? (L < 2 ? std::string("a closed spline of one segment has none")
                                      : "0.." + std::to_string(L - 1))
                             : (L < 2 ? std::string("a spline of one segment has none")
                                      : "1.." + std::to_string(L - 1))) +
                    ")");
    const int li = joint == 0 ? L - 1 : joint - 1, ri = joint;
    const Points left = segmentPoints(li), right = segmentPoints(ri);
    const Scalar hl = intervals_[li], hr = intervals_[ri], h = hl + hr;
    const Scalar tau = hl / h;
    const int r = (n - 1) / 2;

    Points merged(Dim, n + 1);
    merged.leftCols(r + 1) = extendedStart(left, r, h / hl);
    const Points reversedRight = right.rowwise().reverse();
    merged.rightCols(r + 1) = extendedStart(reversedRight, r, h / hr).rowwise().reverse();
    if (n % 2 == 0) {
        // The middle point m = n/2: make the merged curve pass through the joint at tau.
        Scalar basis[kMaxDegree + 1];
        bernsteinAll(n, tau, basis);
        PointType rest = left.col(n);
        for (int k = 0; k <= n; ++k)
            if (k != n / 2) rest -= basis[k] * merged.col(k);
        merged.col(n / 2) = rest / basis[n / 2];
    }

    // Error bound: the merged curve over [0, tau] and [tau, 1] against the old pieces.
    const auto halves = Curve(merged).split(tau);
    Scalar bound(0);
    for (int k = 0; k <= n; ++k) {
        bound = std::max(bound, (halves.first.controlPoint(k) - left.col(k)).norm());
        bound = std::max(bound, (halves.second.controlPoint(k) - right.col(k)).norm());
    }

    // Assemble: segments in order with (li, ri) replaced by the merged one.
    std::vector<Points> pieces;
    std::vector<Scalar> h2;
    if (joint == 0) {
        for (int i = 1; i < L - 1; ++i) {
            pieces.push_back(segmentPoints(i));
            h2.push_back(intervals_[i]);
        }
        pieces.push_back(merged);
        h2.push_back(h);
    } else {
        for (int i = 0; i < L; ++i) {
            if (i == li) {
                pieces.push_back(merged);
                h2.push_back(h);
            } else if (i != ri) {
                pieces.push_back(segmentPoints(i));
                h2.push_back(intervals_[i]);
            }
        }
    }
    const int L2 = static_cast<int>(pieces.size());
    Points p(Dim, closed_ ? L2 * n : L2 * n + 1);
    for (int i = 0; i < L2; ++i) {
        const int keep = (closed_ && i == L2 - 1) ? n : n + 1;
        p.middleCols(i * n, keep) = pieces[i].leftCols(keep);
    }
    return {BezierSpline(n, closed_, std::move(p), std::move(h2)), bound};
}

} // namespace freeform
