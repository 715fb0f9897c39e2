#pragma once
// The A-frame construction: the Bézier points of a C2 cubic spline from its de Boor points, and
// back (docs/splines.md, "The A-frame").
//
// Guarantees: aframeBezierPoints() returns a chain of cubic Bézier segments that is C2 at every
// interior joint (and, for Closed, at the closing joint) for any de Boor points and any positive
// intervals; aframeDeBoorPoints() inverts it exactly (up to rounding) and throws Error when the
// given chain is not C2 within its tolerance. Inputs are checked once (point count against the end
// condition, interval count, positive finite lengths) and every message names what is wrong.
//
// The three end conditions, as knot sequences of the cubic B-spline (segment i covers the
// parameter interval of length h_i, i = 0..L-1):
//   - Open: L = count - 3; the knot intervals beyond the ends repeat the end intervals (h_-2 =
//     h_-1 = h_0, h_L = h_(L+1) = h_(L-1)). With all h = 1 this is the uniform B-spline, the
//     classic A-frame: the curve starts at (d_0 + 4 d_1 + d_2)/6.
//   - Clamped: L = count - 3; the knot intervals beyond the ends are 0 (end knots of multiplicity
//     4, the clamped cubic B-spline). The curve starts at d_0 heading for d_1 and ends at d_last
//     coming from d_(last-1): the first two and last two Bézier points are those de Boor points,
//     bit for bit.
//   - Closed: L = count, periodic (h_k = h_(k mod L)). Segment i is built from d_i..d_(i+3)
//     (indices mod count), exactly as segment i of the Open spline over d_0..d_(n-1), d_0, d_1, d_2.
// In every case segment i is the span of d_i, d_(i+1), d_(i+2), d_(i+3) (mod count when closed):
// its inner Bézier points split the leg d_(i+1) d_(i+2) in the ratio h_(i-1) : h_i : h_(i+1), and
// the joint between segments i-1 and i is the point dividing the crossbar in the ratio
// h_(i-1) : h_i (Farin, Curves and Surfaces for CAGD, chapter "C2 cubic spline curves").

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "freeform/core/error.h"
#include "freeform/core/format.h"
#include "freeform/core/types.h"

namespace freeform {

enum class EndCondition { Open, Clamped, Closed };

/// "open" | "clamped" | "closed"; Error naming `what` for anything else.
EndCondition parseEndCondition(const std::string& text, const std::string& what);
std::string toString(EndCondition end);

/// The fewest de Boor points the end condition accepts: 4 for Open and Clamped, 3 for Closed.
inline int aframeMinimumPoints(EndCondition end) { return end == EndCondition::Closed ? 3 : 4; }

/// Number of cubic segments a C2 spline with `deboorCount` de Boor points has under `end`:
/// count - 3 for Open and Clamped, count for Closed; 0 when the count is below the minimum.
inline int aframeSegmentCount(int deboorCount, EndCondition end)
{
    if (deboorCount < aframeMinimumPoints(end)) return 0;
    return end == EndCondition::Closed ? deboorCount : deboorCount - 3;
}

namespace detail {

/// Checks `intervals` (empty or `segments` positive finite lengths) and returns them filled
/// (all 1 when empty).
template <typename Scalar>
std::vector<Scalar> aframeIntervals(const std::vector<Scalar>& intervals, int segments, const std::string& what)
{
    if (intervals.empty()) return std::vector<Scalar>(static_cast<std::size_t>(segments), Scalar(1));
    if (static_cast<int>(intervals.size()) != segments)
        throw Error(what + ": " + std::to_string(intervals.size()) + " intervals for " + std::to_string(segments) +
                    " segments");
    for (std::size_t i = 0; i < intervals.size(); ++i) {
        if (!(intervals[i] > Scalar(0)) || !std::isfinite(static_cast<long double>(intervals[i])))
            throw Error(what + ": interval " + std::to_string(i) + " is not a positive finite length");
    }
    return intervals;
}

/// The knot intervals h_k of the end condition for any k (beyond the ends as documented above).
template <typename Scalar>
struct AframeKnots {
    const std::vector<Scalar>& h;
    EndCondition end;

    Scalar operator()(long k) const
    {
        const long count = static_cast<long>(h.size());
        if (end == EndCondition::Closed) {
            // Callers ask for k in -3..count+2; a branch is much cheaper than a division.
            while (k < 0) k += count;
            while (k >= count) k -= count;
            return h[static_cast<std::size_t>(k)];
        }
        if (k >= 0 && k < count) return h[static_cast<std::size_t>(k)];
        if (end == EndCondition::Clamped) return Scalar(0);
        return k < 0 ? h.front() : h.back();
    }
};

} // namespace detail

/// Bézier control points of the C2 cubic spline with de Boor points `deboor` (Dim x count):
/// Dim x (3L+1) for open/clamped, Dim x 3L for closed (the last segment ends at column 0).
/// Column 3i is joint i, columns 3i+1 and 3i+2 the inner points of segment i.
/// intervals: L lengths (empty = all 1). Throws Error on too few points / bad intervals.
template <typename Scalar, int Dim>
PointMatrix<Scalar, Dim> aframeBezierPoints(const PointMatrix<Scalar, Dim>& deboor, EndCondition end,
                                            const std::vector<Scalar>& intervals = {})
{
    const int count = static_cast<int>(deboor.cols());
    if (count < aframeMinimumPoints(end))
        throw Error("aframeBezierPoints: " + std::to_string(count) + " de Boor points are too few for a " +
                    toString(end) + " cubic spline (needs at least " + std::to_string(aframeMinimumPoints(end)) + ")");
    requireFinite(deboor, "aframeBezierPoints");
    const int segments = aframeSegmentCount(count, end);
    const std::vector<Scalar> h = detail::aframeIntervals(intervals, segments, "aframeBezierPoints");
    const detail::AframeKnots<Scalar> H{h, end};
    const bool closed = end == EndCondition::Closed;

    using P = Point<Scalar, Dim>;
    // Leg j runs from de Boor point j to j+1 (mod count when closed) and carries the inner points
    // of segment j-1, splitting it in the ratio H(j-2) : H(j-1) : H(j).
    auto leg = [&](long j, P& first, P& second) {
        const long ja = closed && j >= count ? j - count : j; // j <= count + 1
        const long jb = closed && ja + 1 >= count ? ja + 1 - count : ja + 1;
        const P a = deboor.col(ja);
        const P b = deboor.col(jb);
        const Scalar h0 = H(j - 2), h1 = H(j - 1), h2 = H(j);
        const Scalar s = h0 + h1 + h2;
        first = ((h1 + h2) * a + h0 * b) / s;
        second = (h2 * a + (h0 + h1) * b) / s;
    };

    PointMatrix<Scalar, Dim> out(Dim, closed ? 3 * segments : 3 * segments + 1);
    P prevFirst, prevSecond, first, second;
    leg(0, prevFirst, prevSecond); // leg 0: the segment before segment 0 (phantom unless closed)
    for (long i = 0; i <= segments; ++i) {
        if (closed && i == segments) break;
        leg(i + 1, first, second); // segment i (for i == L: the phantom segment after the end)
        const Scalar hl = H(i - 1), hr = H(i);
        out.col(3 * i) = (hr * prevSecond + hl * first) / (hl + hr);
        if (i < segments) {
            out.col(3 * i + 1) = first;
            out.col(3 * i + 2) = second;
        }
        prevSecond = second;
    }
    if (end == EndCondition::Clamped) {
        // The ratios above give these exactly in real arithmetic (zero-length intervals at the
        // ends); set them so that they hold bit for bit as well.
        out.col(0) = deboor.col(0);
        out.col(1) = deboor.col(1);
        out.col(3 * segments - 1) = deboor.col(count - 2);
        out.col(3 * segments) = deboor.col(count - 1);
    }
    return out;
}

/// Default relative tolerance of aframeDeBoorPoints: 1e-9 in double, 1000 eps in float.
template <typename Scalar>
constexpr Scalar aframeDefaultTolerance()
{
    return std::max(Scalar(1e-9), Scalar(1000) * std::numeric_limits<Scalar>::epsilon());
}

/// The inverse of aframeBezierPoints: the de Boor points of the C2 cubic Bézier spline `bezier`
/// (Dim x (3L+1) for open/clamped, Dim x 3L for closed) under `end`, with intervals as there.
/// Every interior de Boor point is found from both legs that meet at it (the two sides of the
/// A-frame) and averaged; the end points follow from the end joints. The result is then checked:
/// if the A-frame of the recovered points misses a given Bézier point by more than `tolerance`
/// times the diagonal of the control points' bounding box, the chain is not C2 there and Error
/// names the joint and the deviation.
template <typename Scalar, int Dim>
PointMatrix<Scalar, Dim> aframeDeBoorPoints(const PointMatrix<Scalar, Dim>& bezier, EndCondition end,
                                            const std::vector<Scalar>& intervals = {},
                                            Scalar tolerance = aframeDefaultTolerance<Scalar>())
{
    const bool closed = end == EndCondition::Closed;
    const long cols = static_cast<long>(bezier.cols());
    const bool fits = closed ? (cols >= 3 && cols % 3 == 0) : (cols >= 4 && (cols - 1) % 3 == 0);
    if (!fits)
        throw Error("aframeDeBoorPoints: " + std::to_string(cols) + " Bézier points do not form " +
                    (closed ? "a closed cubic spline (3L points, L >= 1)" : "an open cubic spline (3L + 1 points, L >= 1)"));
    requireFinite(bezier, "aframeDeBoorPoints");
    const int segments = static_cast<int>(closed ? cols / 3 : (cols - 1) / 3);
    if (closed && segments < 3)
        throw Error("aframeDeBoorPoints: a closed C2 cubic spline from de Boor points has at least 3 segments, this one has " +
                    std::to_string(segments));
    const std::vector<Scalar> h = detail::aframeIntervals(intervals, segments, "aframeDeBoorPoints");
    const detail::AframeKnots<Scalar> H{h, end};

    using P = Point<Scalar, Dim>;
    const int count = closed ? segments : segments + 3;
    PointMatrix<Scalar, Dim> deboor = PointMatrix<Scalar, Dim>::Zero(Dim, count);
    std::vector<int> estimates(static_cast<std::size_t>(count), 0);
    // Segment i lies on leg i+1: its inner points divide d_(i+1) d_(i+2) as H(i-1) : H(i) : H(i+1),
    // so the leg's ends are the inner points pushed outwards by the neighbouring ratios.
    for (long i = 0; i < segments; ++i) {
        const P first = bezier.col(3 * i + 1), second = bezier.col(3 * i + 2);
        const Scalar a = H(i - 1), b = H(i), c = H(i + 1);
        const P step = second - first;
        const long ia = closed ? (i + 1) % count : i + 1;
        const long ib = closed ? (i + 2) % count : i + 2;
        deboor.col(ia) += first - (a / b) * step;
        deboor.col(ib) += second + (c / b) * step;
        ++estimates[static_cast<std::size_t>(ia)];
        ++estimates[static_cast<std::size_t>(ib)];
    }
    for (int k = 0; k < count; ++k)
        if (estimates[static_cast<std::size_t>(k)] > 1) deboor.col(k) /= Scalar(estimates[static_cast<std::size_t>(k)]);
    if (!closed) {
        const long L = segments;
        // Joint 0 divides (second inner point of leg 0, b_1) as H(-1) : H(0); leg 0 runs d_0 d_1.
        {
            const P joint = bezier.col(0), y = bezier.col(1);
            const Scalar hm2 = H(-2), hm1 = H(-1), h0 = H(0);
            const P x = ((hm1 + h0) * joint - hm1 * y) / h0;
            deboor.col(0) = ((hm2 + hm1 + h0) * x - (hm2 + hm1) * P(deboor.col(1))) / h0;
        }
        // Joint L divides (b_(3L-1), first inner point of leg L+1) as H(L-1) : H(L); leg L+1 runs
        // d_(L+1) d_(L+2).
        {
            const P joint = bezier.col(3 * L), x = bezier.col(3 * L - 1);
            const Scalar hl = H(L - 1), hr = H(L), hr2 = H(L + 1);
            const P y = ((hl + hr) * joint - hr * x) / hl;
            deboor.col(L + 2) = ((hl + hr + hr2) * y - (hr + hr2) * P(deboor.col(L + 1))) / hl;
        }
        if (end == EndCondition::Clamped) { // the same values, bit for bit
            deboor.col(0) = bezier.col(0);
            deboor.col(L + 2) = bezier.col(3 * L);
        }
    }

    // The check: the A-frame of the recovered points must give back every Bézier point.
    const PointMatrix<Scalar, Dim> again = aframeBezierPoints<Scalar, Dim>(deboor, end, h);
    const Scalar size = (bezier.rowwise().maxCoeff() - bezier.rowwise().minCoeff()).norm();
    Scalar worst(0);
    long worstIndex = 0;
    for (long k = 0; k < cols; ++k) {
        const Scalar d = (again.col(k) - bezier.col(k)).norm();
        if (d > worst) {
            worst = d;
            worstIndex = k;
        }
    }
    if (worst > tolerance * size) {
        long joint = (worstIndex + 1) / 3; // b_(3j-1), b_3j, b_(3j+1) belong to joint j
        if (closed) joint %= segments;
        throw Error("aframeDeBoorPoints: the cubic Bézier spline is not C2 at joint " + std::to_string(joint) +
                    ": Bézier point " + std::to_string(worstIndex) + " is " + formatNumber(worst) +
                    " away from the C2 spline of the recovered de Boor points (tolerance " +
                    formatNumber(Scalar(tolerance * size)) + ")");
    }
    return deboor;
}

} // namespace freeform
