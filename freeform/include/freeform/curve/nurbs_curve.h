#pragma once
// NurbsCurve<Scalar, Dim>: C(u) = sum w_i P_i N_(i,p)(u) / sum w_i N_(i,p)(u) on the domain
// [u_p, u_(n+1)] of a general knot vector (curve/knot_vector.h; docs/nurbs.md).
//
// Stored as homogeneous control points (w_i P_i, w_i) in Dim + 1 coordinates; a curve whose weights
// are all 1 is polynomial (isRational() false). Invariants, checked once in the constructor with
// freeform::Error naming the knot or point: a valid knot vector, knots = points + degree + 1,
// finite coordinates, positive finite weights.
//
// Algorithms (The NURBS Book; docs/nurbs.md):
//   - evaluate(): span by bisection, the p+1 non-zero basis functions (Cox-de Boor triangle), one
//     homogeneous sum and one division;
//   - derivatives(): basis derivatives (A2.3) on the homogeneous points, then Leibniz's rule;
//   - insertKnot(): Boehm's algorithm, r times; refined(): the Oslo algorithm in blossom form
//     (each new control point is the blossom of the old curve at p consecutive new knots);
//   - split(): Boehm's insertion of the cut up to multiplicity p in one pass (A5.1), rest copied;
//   - bezierPieces(): one rational Bézier piece per non-empty span, points the blossoms at (a^(p-i), b^i);
//   - evaluateMany()/evaluateManyWithDerivative(): the batch path; the spans' Bézier pieces are
//     extracted once in the constructor and turned into Taylor coefficients about the span
//     midpoint (|s - 1/2| <= 1/2 in the local parameter s, so the power form is well conditioned at
//     the degrees NURBS use); each run of parameters inside one span costs one Horner scheme of p
//     steps in Dim + 1 coordinates and one division per point.

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "freeform/core/format.h"
#include "freeform/core/polynomial.h"
#include "freeform/core/quadrature.h"
#include "freeform/curve/batch.h"
#include "freeform/curve/bezier_curve.h"
#include "freeform/curve/knot_vector.h"
#include "freeform/curve/rational_bezier_curve.h"

namespace freeform {

template <typename Scalar, int Dim>
class NurbsCurve {
public:
    using PointType = Point<Scalar, Dim>;
    using Points = PointMatrix<Scalar, Dim>;
    using HPoint = Point<Scalar, Dim + 1>;
    using HPoints = PointMatrix<Scalar, Dim + 1>;
    using Weights = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
    using Knots = KnotVector<Scalar>;
    using Piece = RationalBezierCurve<Scalar, Dim>;

    struct Closest {
        Scalar u;
        PointType point;
        Scalar distance;
    };

    /// degree p, knots (points + p + 1 values), control points (Dim x (n+1)) and weights (n+1
    /// positive values; empty = all 1, a polynomial B-spline).
    NurbsCurve(int degree, std::vector<Scalar> knots, const Points& points, const Weights& weights = Weights())
        : NurbsCurve(Knots(std::move(knots), degree, "NurbsCurve"), homogeneousFrom(points, weights))
    {
    }

    /// From a knot vector and homogeneous points (w P, w) as columns.
    NurbsCurve(Knots knots, HPoints hom) : knots_(std::move(knots)), hom_(std::move(hom))
    {
        if (hom_.cols() != knots_.controlCount())
            throw Error("NurbsCurve: " + std::to_string(knots_.size()) + " knots of degree " +
                        std::to_string(knots_.degree()) + " need " + std::to_string(knots_.controlCount()) +
                        " control points, got " + std::to_string(hom_.cols()));
        requireFinite(hom_, "NurbsCurve");
        rational_ = false;
        for (Eigen::Index i = 0; i < hom_.cols(); ++i) {
            if (!(hom_(Dim, i) > Scalar(0)))
                throw Error("NurbsCurve: weight " + std::to_string(i) + " is not positive");
            if (hom_(Dim, i) != Scalar(1)) rational_ = true;
        }
        extractPieces();
    }

    /// The polynomial Bézier curve as a NURBS (knots 0^(n+1) 1^(n+1)).
    static NurbsCurve fromBezier(const BezierCurve<Scalar, Dim>& c)
    {
        return fromRationalBezier(Piece(c));
    }
    static NurbsCurve fromRationalBezier(const Piece& c)
    {
        const int n = c.degree();
        std::vector<Scalar> k(static_cast<std::size_t>(n + 1), Scalar(0));
        k.resize(static_cast<std::size_t>(2 * n + 2), Scalar(1));
        return NurbsCurve(Knots(std::move(k), n, "NurbsCurve::fromBezier"), c.homogeneous().controlPoints());
    }

    /// The curve in Bézier form from its pieces: piece k (homogeneous points (w P, w), degree p)
    /// over [breaks[k], breaks[k + 1]], every interior breakpoint a knot of multiplicity p. Where
    /// two pieces meet (equal to rounding) the left piece's end is kept. `what` names it in errors.
    static NurbsCurve fromBezierPieces(const std::vector<Scalar>& breaks, int p, const std::vector<HPoints>& pieces,
                                       const std::string& what)
    {
        if (pieces.empty() || breaks.size() != pieces.size() + 1)
            throw Error(what + ": " + std::to_string(pieces.size()) + " Bézier pieces need " + std::to_string(pieces.size() + 1) +
                        " breakpoints, got " + std::to_string(breaks.size()));
        HPoints h(Dim + 1, static_cast<Eigen::Index>(pieces.size()) * p + 1);
        for (std::size_t k = pieces.size(); k-- > 0;) {
            if (pieces[k].cols() != p + 1)
                throw Error(what + ": piece " + std::to_string(k) + " has " + std::to_string(pieces[k].cols()) +
                            " control points, not " + std::to_string(p + 1));
            h.middleCols(static_cast<Eigen::Index>(k) * p, p + 1) = pieces[k];
        }
        return NurbsCurve(Knots(Knots::bezierForm(breaks, p), p, what), std::move(h));
    }

    /// Closed (periodic) curve through the uniform knots 0..count+2p: the first p control points
    /// are repeated at the end, so the curve is C^(p-1) everywhere, including where it closes.
    static NurbsCurve periodic(int degree, const Points& points, const Weights& weights = Weights())
    {
        requireDegree(degree, "NurbsCurve::periodic");
        const int count = static_cast<int>(points.cols());
        if (count < degree + 1 || degree < 1)
            throw Error("NurbsCurve::periodic: " + std::to_string(count) + " control points are too few for degree " +
                        std::to_string(degree));
        Points p(Dim, count + degree);
        Weights w(count + degree);
        const Weights w0 = weights.size() ? weights : Weights(Weights::Ones(count));
        if (w0.size() != count)
            throw Error("NurbsCurve::periodic: " + std::to_string(w0.size()) + " weights for " + std::to_string(count) +
                        " control points");
        for (int i = 0; i < count + degree; ++i) {
            p.col(i) = points.col(i % count);
            w[i] = w0[i % count];
        }
        std::vector<Scalar> k;
        for (int i = 0; i <= count + 2 * degree; ++i) k.push_back(Scalar(i));
        return NurbsCurve(degree, std::move(k), p, w);
    }

    /// The exact full circle of `radius` about c in the plane of the first two coordinates: a
    /// closed quadratic rational spline of four quarter arcs on [0, 1] (knots 0,0,0, 1/4,1/4,
    /// 1/2,1/2, 3/4,3/4, 1,1,1; weights 1 and sqrt(2)/2).
    static NurbsCurve circle(const PointType& c, Scalar radius)
    {
        static_assert(Dim >= 2, "circle needs at least two dimensions");
        const Scalar s = std::sqrt(Scalar(2)) / 2;
        const int xs[9] = {1, 1, 0, -1, -1, -1, 0, 1, 1}, ys[9] = {0, 1, 1, 1, 0, -1, -1, -1, 0};
        Points p(Dim, 9);
        Weights w(9);
        for (int i = 0; i < 9; ++i) {
            p.col(i) = c;
            p(0, i) += radius * Scalar(xs[i]);
            p(1, i) += radius * Scalar(ys[i]);
            w[i] = i % 2 ? s : Scalar(1);
        }
        const Scalar q = Scalar(1) / 4;
        return NurbsCurve(2, {0, 0, 0, q, q, 2 * q, 2 * q, 3 * q, 3 * q, 1, 1, 1}, p, w);
    }

    int degree() const { return knots_.degree(); }
    const Knots& knotVector() const { return knots_; }
    const std::vector<Scalar>& knots() const { return knots_.knots(); }
    int controlCount() const { return static_cast<int>(hom_.cols()); }
    bool isRational() const { return rational_; }
    const HPoints& homogeneousPoints() const { return hom_; }
    Scalar weight(int i) const { return hom_(Dim, i); }
    Weights weights() const { return hom_.row(Dim).transpose(); }
    PointType controlPoint(int i) const { return hom_.col(i).template head<Dim>() / hom_(Dim, i); }
    Points controlPoints() const
    {
        Points p(Dim, hom_.cols());
        for (int i = 0; i < controlCount(); ++i) p.col(i) = controlPoint(i);
        return p;
    }
    Scalar domainStart() const { return knots_.front(); }
    Scalar domainEnd() const { return knots_.back(); }

    // ---------------------------------------------------------------- evaluation

    /// C(u); u outside the domain is clamped to it (as in the batch path).
    PointType evaluate(Scalar u) const
    {
        const int p = degree();
        u = clampToDomain(u);
        const int span = knots_.findSpan(u);
        Scalar n[kMaxDegree + 1];
        knots_.basisFunctions(span, u, n);
        HPoint h = HPoint::Zero();
        for (int j = 0; j <= p; ++j) h += n[j] * hom_.col(span - p + j);
        return h.template head<Dim>() / h[Dim];
    }
    PointType operator()(Scalar u) const { return evaluate(u); }

    /// u clamped to [domainStart(), domainEnd()] (NaN stays NaN).
    Scalar clampToDomain(Scalar u) const
    {
        return u < domainStart() ? domainStart() : u > domainEnd() ? domainEnd() : u;
    }

    /// Column j is C^(j)(u), j = 0..k (u clamped to the domain; derivatives with respect to u; zero above the degree for a
    /// polynomial curve, generally non-zero for a rational one).
    Eigen::Matrix<Scalar, Dim, Eigen::Dynamic> derivatives(Scalar u, int k) const
    {
        if (k < 0) throw Error("NurbsCurve::derivatives: order " + std::to_string(k) + " is negative");
        const int p = degree();
        u = clampToDomain(u);
        const int span = knots_.findSpan(u);
        std::vector<Scalar> ders(static_cast<std::size_t>((k + 1) * (p + 1)));
        knots_.basisDerivatives(span, u, k, ders.data());
        Eigen::Matrix<Scalar, Dim + 1, Eigen::Dynamic> h(Dim + 1, k + 1);
        h.setZero();
        for (int r = 0; r <= std::min(k, p); ++r)
            for (int j = 0; j <= p; ++j) h.col(r) += ders[static_cast<std::size_t>(r * (p + 1) + j)] * hom_.col(span - p + j);
        return Piece::template projectDerivatives<Scalar, Dim>(h);
    }

    /// Batch evaluation: C(ts[j]) into out (Dim x count, resized). Fastest on sorted parameters
    /// (one span look-up per run of parameters in the same span).
    void evaluateMany(const Scalar* ts, std::size_t count, Points& out) const
    {
        out.resize(Dim, static_cast<Eigen::Index>(count));
        forRuns(ts, count, [&](int piece, std::size_t start, std::size_t len, const Scalar* s) {
            evalRun(piece, s, len, out.data() + start * Dim, nullptr, 0);
        });
    }
    Points evaluateMany(const std::vector<Scalar>& ts) const
    {
        Points out;
        evaluateMany(ts.data(), ts.size(), out);
        return out;
    }

    /// Batch of positions and first derivatives (with respect to u).
    void evaluateManyWithDerivative(const Scalar* ts, std::size_t count, Points& pos, Points& d1) const
    {
        pos.resize(Dim, static_cast<Eigen::Index>(count));
        d1.resize(Dim, static_cast<Eigen::Index>(count));
        forRuns(ts, count, [&](int piece, std::size_t start, std::size_t len, const Scalar* s) {
            evalRun(piece, s, len, pos.data() + start * Dim, d1.data() + start * Dim, 1);
        });
    }

    // ---------------------------------------------------------------- knots

    /// Boehm's knot insertion of u, `times` times (the multiplicity may not exceed p; u strictly
    /// inside the domain or at an interior knot). The curve is unchanged.
    NurbsCurve insertKnot(Scalar u, int times = 1) const
    {
        const int p = degree();
        if (!(u > domainStart() && u < domainEnd()))
            throw Error("NurbsCurve::insertKnot: " + num(u) + " is not inside the domain (" + num(domainStart()) +
                        ", " + num(domainEnd()) + ")");
        const int s = knots_.multiplicity(u);
        if (times < 0 || s + times > p + 1)
            throw Error("NurbsCurve::insertKnot: inserting " + num(u) + " " + std::to_string(times) +
                        " times would make its multiplicity " + std::to_string(s + times) + ", above degree + 1 = " +
                        std::to_string(p + 1));
        std::vector<Scalar> U = knots();
        HPoints P = hom_;
        for (int t = 0; t < times; ++t) {
            const Knots kv(U, p, "NurbsCurve::insertKnot");
            const int k = kv.findSpan(u); // u_k <= u < u_(k+1)
            const int sm = static_cast<int>(std::count(U.begin(), U.end(), u));
            HPoints Q(Dim + 1, P.cols() + 1);
            for (int i = 0; i <= k - p; ++i) Q.col(i) = P.col(i);
            for (int i = k - sm; i < P.cols(); ++i) Q.col(i + 1) = P.col(i);
            for (int i = k - p + 1; i <= k - sm; ++i) {
                const Scalar a = (u - U[i]) / (U[i + p] - U[i]);
                Q.col(i) = a * P.col(i) + (Scalar(1) - a) * P.col(i - 1);
            }
            U.insert(U.begin() + k + 1, u);
            P = std::move(Q);
        }
        return NurbsCurve(Knots(std::move(U), p, "NurbsCurve::insertKnot"), std::move(P));
    }

    /// Knot refinement by the Oslo algorithm: the new knot vector is the old one with the values in
    /// `extra` added (each inside the domain, multiplicities up to p + 1). The curve is unchanged.
    NurbsCurve refined(std::vector<Scalar> extra) const
    {
        const int p = degree();
        for (Scalar x : extra)
            if (!(x > domainStart() && x < domainEnd()))
                throw Error("NurbsCurve::refined: knot " + num(x) + " is not inside the domain (" + num(domainStart()) +
                            ", " + num(domainEnd()) + ")");
        std::vector<Scalar> tau = knots();
        tau.insert(tau.end(), extra.begin(), extra.end());
        std::sort(tau.begin(), tau.end());
        const Knots kv(tau, p, "NurbsCurve::refined");
        const int count = kv.controlCount();
        HPoints Q(Dim + 1, count);
        Scalar args[kMaxDegree + 1];
        for (int j = 0; j < count; ++j) {
            // A non-empty new span among j..j+p inside the domain; the old span containing it.
            int k = std::max(j, p);
            while (k < std::min(j + p, count - 1) && !(tau[k] < tau[k + 1])) ++k;
            const int mu = knots_.findSpan(tau[k]);
            for (int r = 0; r < p; ++r) args[r] = tau[j + 1 + r];
            Q.col(j) = blossom(mu, args);
        }
        return NurbsCurve(kv, std::move(Q));
    }

    /// One rational Bézier piece per non-empty knot span, in order (Bézier extraction).
    std::vector<Piece> bezierPieces() const
    {
        std::vector<Piece> out;
        for (std::size_t k = 0; k + 1 < breaks_.size(); ++k) out.emplace_back(BezierCurve<Scalar, Dim + 1>(HPoints(homogeneousPiece(k))));
        return out;
    }
    /// Piece k of bezierPieces() as the curve keeps it: its p + 1 homogeneous points, in place.
    auto homogeneousPiece(std::size_t k) const { return pieces_.middleCols(static_cast<Eigen::Index>(k) * (degree() + 1), degree() + 1); }
    /// The distinct knots of the domain: piece k of bezierPieces() is the curve over
    /// [breakpoints()[k], breakpoints()[k+1]], reparametrised to [0, 1].
    const std::vector<Scalar>& breakpoints() const { return breaks_; }

    /// The pieces over [start, u] and [u, end] (u strictly inside the domain); knots of the left
    /// piece end, and of the right one start, with u of multiplicity p + 1.
    std::pair<NurbsCurve, NurbsCurve> split(Scalar u) const
    {
        const int p = degree();
        if (!(u > domainStart() && u < domainEnd()))
            throw Error("NurbsCurve::split: " + num(u) + " is not inside the domain (" + num(domainStart()) + ", " +
                        num(domainEnd()) + ")");
        std::vector<Scalar> U = knots(), left, right;
        HPoints P = hom_, leftRows, rightRows;
        insertRows(U, P, 1, p, u);
        cutRows(U, P, 1, p, u, false, left, leftRows);
        cutRows(U, P, 1, p, u, true, right, rightRows);
        return {NurbsCurve(Knots(std::move(left), p, "NurbsCurve::split"), std::move(leftRows)),
                NurbsCurve(Knots(std::move(right), p, "NurbsCurve::split"), std::move(rightRows))};
    }

    /// Boehm's insertion of u (strictly inside the domain) until its multiplicity is at least p,
    /// in one pass (The NURBS Book, A5.1), on a net of rows on the knots U: row i is the columns
    /// i * width .. i * width + width - 1 of hom (a curve is one column wide; NurbsSurface cuts
    /// every column of its net at once with the same operations, so the same numbers). Only the
    /// p - s - 1 rows around u are new; the others are copied, not recomputed.
    static void insertRows(std::vector<Scalar>& U, HPoints& hom, Eigen::Index width, int p, Scalar u)
    {
        const int s = static_cast<int>(std::count(U.begin(), U.end(), u)), r = p - s;
        if (r <= 0) return;
        const int k = static_cast<int>(std::upper_bound(U.begin(), U.end(), u) - U.begin()) - 1; // U[k] <= u < U[k+1]
        const int n = static_cast<int>(hom.cols() / width) - 1;
        auto row = [width](auto& m, int i) { return m.middleCols(static_cast<Eigen::Index>(i) * width, width); };
        HPoints Q(Dim + 1, static_cast<Eigen::Index>(n + 1 + r) * width), R(Dim + 1, static_cast<Eigen::Index>(p - s + 1) * width);
        for (int i = 0; i <= k - p; ++i) row(Q, i) = row(hom, i);
        for (int i = k - s; i <= n; ++i) row(Q, i + r) = row(hom, i);
        for (int i = 0; i <= p - s; ++i) row(R, i) = row(hom, k - p + i);
        int L = k - p;
        for (int j = 1; j <= r; ++j) {
            L = k - p + j;
            for (int i = 0; i <= p - j - s; ++i) {
                const Scalar alpha = (u - U[static_cast<std::size_t>(L + i)]) /
                                     (U[static_cast<std::size_t>(i + k + 1)] - U[static_cast<std::size_t>(L + i)]);
                row(R, i) = alpha * row(R, i + 1) + (Scalar(1) - alpha) * row(R, i);
            }
            row(Q, L) = row(R, 0);
            row(Q, k + r - j - s) = row(R, p - j - s);
        }
        for (int i = L + 1; i < k - s; ++i) row(Q, i) = row(R, i - L);
        U.insert(U.begin() + k + 1, static_cast<std::size_t>(r), u);
        hom = std::move(Q);
    }

    /// After insertRows(u): the knots and rows before u (or after it, keepRight), u of multiplicity
    /// p + 1 at the cut; the row at u (multiplicity p) ends one piece and starts the other.
    static void cutRows(const std::vector<Scalar>& U, const HPoints& hom, Eigen::Index width, int p, Scalar u, bool keepRight,
                        std::vector<Scalar>& knotsOut, HPoints& rowsOut)
    {
        const int a = static_cast<int>(std::lower_bound(U.begin(), U.end(), u) - U.begin());
        const int s = static_cast<int>(std::count(U.begin(), U.end(), u));
        const Eigen::Index rows = hom.cols() / width, shared = s <= p ? 1 : 0;
        if (keepRight) {
            knotsOut.assign(static_cast<std::size_t>(p + 1), u);
            knotsOut.insert(knotsOut.end(), U.begin() + a + s, U.end());
            rowsOut = hom.rightCols((rows - a + shared) * width);
        } else {
            knotsOut.assign(U.begin(), U.begin() + a);
            knotsOut.insert(knotsOut.end(), static_cast<std::size_t>(p + 1), u);
            rowsOut = hom.leftCols(static_cast<Eigen::Index>(a) * width);
        }
    }

    /// The same curve run backwards on the same domain: D(u) = C(a + b - u).
    NurbsCurve reversed() const
    {
        const std::vector<Scalar>& U = knots();
        const Scalar ab = domainStart() + domainEnd();
        std::vector<Scalar> R(U.size());
        for (std::size_t i = 0; i < U.size(); ++i) R[i] = ab - U[U.size() - 1 - i];
        return NurbsCurve(Knots(std::move(R), degree(), "NurbsCurve::reversed"), HPoints(hom_.rowwise().reverse()));
    }

    /// Result of removeKnot() and reduced(): the new curve and the error the operation reports.
    struct Approximation;

    /// Removes one occurrence of the interior knot u (The NURBS Book, A5.8, in homogeneous
    /// coordinates). The result always has one knot and one control point less; `error` is the
    /// mismatch of the two estimates of the changed control points, which bounds max |new - old|
    /// over the curve for a polynomial curve (for a rational one it bounds the homogeneous curves'
    /// difference). 0 up to rounding when u is removable (for example after insertKnot(u)).
    Approximation removeKnot(Scalar u) const;

    /// The same curve with degree p + times: Bézier extraction, elevation of every piece, and knot
    /// removal back to the original continuity (each interior knot's multiplicity grows by times).
    /// The result is clamped on the same domain.
    NurbsCurve elevated(int times = 1) const;

    /// Degree p - 1 (p >= 2): every piece reduced (BezierCurve::reduced on the homogeneous piece, ends
    /// kept), joined C0, then interior knots removed towards the original multiplicities while the
    /// accumulated error stays within `tolerance`. `error` bounds max |new - old| for polynomial
    /// curves (homogeneous for rational ones).
    Approximation reduced(Scalar tolerance = Scalar(0)) const;

    // ---------------------------------------------------------------- measures

    /// Tight axis-aligned bounding box over the domain: the ends of every Bézier piece and its
    /// points where a coordinate's derivative vanishes (roots of (A_k' w - A_k w') in Bernstein form).
    Box<Scalar, Dim> boundingBox() const
    {
        Box<Scalar, Dim> box(evaluate(domainStart()));
        for (const Piece& piece : bezierPieces()) {
            box.extend(piece.evaluate(Scalar(1)));
            const int n = piece.degree();
            if (n < 1) continue;
            const HPoints& h = piece.homogeneous().controlPoints();
            const HPoints d = piece.homogeneous().derivative(1).controlPoints();
            std::vector<Scalar> w(static_cast<std::size_t>(n + 1)), wd(static_cast<std::size_t>(n));
            for (int i = 0; i <= n; ++i) w[i] = h(Dim, i);
            for (int i = 0; i < n; ++i) wd[i] = d(Dim, i);
            for (int k = 0; k < Dim; ++k) {
                std::vector<Scalar> a(static_cast<std::size_t>(n + 1)), ad(static_cast<std::size_t>(n));
                for (int i = 0; i <= n; ++i) a[i] = h(k, i);
                for (int i = 0; i < n; ++i) ad[i] = d(k, i);
                std::vector<Scalar> num1 = bernsteinPolyProduct(ad, w), num2 = bernsteinPolyProduct(a, wd);
                for (std::size_t i = 0; i < num1.size(); ++i) num1[i] -= num2[i];
                for (Scalar t : bernsteinPolyRoots(num1)) box.extend(piece.evaluate(t));
            }
        }
        return box;
    }

    /// Arc length over the domain (or [a, b] inside it), adaptive Gauss-Kronrod per knot span.
    Scalar arcLength(Scalar tolerance = Scalar(1e-10)) const { return arcLength(tolerance, domainStart(), domainEnd()); }
    Scalar arcLength(Scalar tolerance, Scalar a, Scalar b) const
    {
        if (a > b) std::swap(a, b);
        Scalar total(0);
        const Scalar share = tolerance / Scalar(breaks_.size());
        for (std::size_t k = 0; k + 1 < breaks_.size(); ++k) {
            const Scalar lo = std::max(a, breaks_[k]), hi = std::min(b, breaks_[k + 1]);
            if (!(lo < hi)) continue;
            total += integrate<Scalar>([&](Scalar u) { return derivatives(u, 1).col(1).norm(); }, lo, hi, share);
        }
        return total;
    }

    /// The point of the curve closest to p, globally. On each knot span the rational piece
    /// C = A / w has (C - p) . C' = 0 exactly where the polynomial (A - p w) . (A' w - A w') of
    /// degree 3p - 1 vanishes (multiply by w^3 > 0); all its roots in the span are found in
    /// Bernstein form (core/polynomial.h) and compared with the breakpoints, as
    /// BezierCurve::closestPoint does for one polynomial piece.
    Closest closestPoint(const PointType& p) const
    {
        Closest best{domainStart(), evaluate(domainStart()), (evaluate(domainStart()) - p).norm()};
        auto consider = [&](Scalar u) {
            const PointType q = evaluate(u);
            const Scalar d = (q - p).norm();
            if (d < best.distance) best = {u, q, d};
        };
        const int n = degree();
        for (std::size_t k = 0; k + 1 < breaks_.size(); ++k) {
            const Scalar a = breaks_[k], b = breaks_[k + 1];
            consider(b);
            if (n == 0) continue;
            const auto H = pieces_.middleCols(static_cast<Eigen::Index>(k) * (n + 1), n + 1);
            std::vector<Scalar> w(n + 1), dw(n);
            for (int i = 0; i <= n; ++i) w[i] = H(Dim, i);
            for (int i = 0; i < n; ++i) dw[i] = Scalar(n) * (w[i + 1] - w[i]);
            std::vector<Scalar> g(static_cast<std::size_t>(3 * n), Scalar(0));
            for (int c = 0; c < Dim; ++c) {
                std::vector<Scalar> A(n + 1), offset(n + 1), dA(n);
                for (int i = 0; i <= n; ++i) {
                    A[i] = H(c, i);
                    offset[i] = H(c, i) - p[c] * w[i];
                }
                for (int i = 0; i < n; ++i) dA[i] = Scalar(n) * (A[i + 1] - A[i]);
                std::vector<Scalar> tangent = bernsteinPolyProduct(dA, w);
                const std::vector<Scalar> correction = bernsteinPolyProduct(A, dw);
                for (std::size_t i = 0; i < tangent.size(); ++i) tangent[i] -= correction[i];
                const std::vector<Scalar> prod = bernsteinPolyProduct(offset, tangent);
                for (std::size_t i = 0; i < g.size(); ++i) g[i] += prod[i];
            }
            for (Scalar t : bernsteinPolyRoots(g)) consider(std::clamp(a + (b - a) * t, a, b));
        }
        return best;
    }

    /// Bounding box of the control points (contains the curve).
    Box<Scalar, Dim> controlBox() const
    {
        Box<Scalar, Dim> box(controlPoint(0));
        for (int i = 1; i < controlCount(); ++i) box.extend(controlPoint(i));
        return box;
    }

    /// The blossom of the polynomial (homogeneous) piece on knot span `span` at args[0..p-1]
    /// (de Boor's algorithm with a different argument at each level).
    HPoint blossom(int span, const Scalar* args) const
    {
        const int p = degree();
        const std::vector<Scalar>& U = knots();
        HPoint d[kMaxDegree + 1];
        for (int j = 0; j <= p; ++j) d[j] = hom_.col(span - p + j);
        for (int r = 1; r <= p; ++r) {
            const Scalar x = args[r - 1];
            for (int j = p; j >= r; --j) {
                const int i = span - p + j;
                const Scalar a = (x - U[i]) / (U[i + p + 1 - r] - U[i]);
                d[j] = (Scalar(1) - a) * d[j - 1] + a * d[j];
            }
        }
        return d[p];
    }

private:
    static std::string num(Scalar x) { return formatNumber(x); }

    static HPoints homogeneousFrom(const Points& points, const Weights& weights)
    {
        if (weights.size() != 0 && weights.size() != points.cols())
            throw Error("NurbsCurve: " + std::to_string(weights.size()) + " weights for " + std::to_string(points.cols()) +
                        " control points");
        requireFinite(points, "NurbsCurve");
        HPoints h(Dim + 1, points.cols());
        for (Eigen::Index i = 0; i < points.cols(); ++i) {
            const Scalar w = weights.size() ? weights[i] : Scalar(1);
            if (!(w > Scalar(0)) || !std::isfinite(static_cast<long double>(w)))
                throw Error("NurbsCurve: weight " + std::to_string(i) + " is not a positive finite number");
            h.col(i).template head<Dim>() = w * points.col(i);
            h(Dim, i) = w;
        }
        return h;
    }

    void extractPieces()
    {
        const int p = degree();
        breaks_ = knots_.breakpoints();
        const int count = static_cast<int>(breaks_.size()) - 1;
        pieces_.resize(Dim + 1, count * (p + 1));
        spanOf_.resize(static_cast<std::size_t>(count));
        Scalar args[kMaxDegree + 1];
        for (int k = 0; k < count; ++k) {
            const Scalar a = breaks_[k], b = breaks_[k + 1];
            const int span = knots_.findSpan(a);
            spanOf_[k] = span;
            for (int i = 0; i <= p; ++i) {
                for (int r = 0; r < p; ++r) args[r] = r < p - i ? a : b;
                pieces_.col(k * (p + 1) + i) = blossom(span, args);
            }
        }
        // Taylor coefficients of each homogeneous piece about s = 1/2: c_j = A^(j)(1/2) / j!.
        taylor_.resize(Dim + 1, count * (p + 1));
        for (int k = 0; k < count; ++k) {
            const BezierCurve<Scalar, Dim + 1> piece(HPoints(pieces_.middleCols(k * (p + 1), p + 1)));
            const auto d = piece.derivatives(Scalar(0.5), p);
            Scalar fact(1);
            for (int j = 0; j <= p; ++j) {
                if (j > 0) fact *= Scalar(j);
                taylor_.col(k * (p + 1) + j) = d.col(j) / fact;
            }
        }
    }

    /// Calls f(piece, start, length, local parameters) for each run of consecutive parameters in one
    /// piece; the local parameters s = (u - a) / (b - a) are clamped to [0, 1] (parameters outside
    /// the domain evaluate the end pieces' ends; a NaN gives NaN).
    template <typename F>
    void forRuns(const Scalar* ts, std::size_t count, const F& f) const
    {
        std::vector<Scalar> local(count);
        const int pieces = static_cast<int>(breaks_.size()) - 1;
        std::size_t start = 0;
        while (start < count) {
            const Scalar u0 = ts[start];
            int k = 0;
            if (!(u0 < breaks_.back())) k = pieces - 1;
            else if (u0 > breaks_.front())
                k = static_cast<int>(std::upper_bound(breaks_.begin(), breaks_.end(), u0) - breaks_.begin()) - 1;
            const Scalar a = breaks_[k], b = breaks_[k + 1];
            const Scalar inv = Scalar(1) / (b - a);
            const bool first = k == 0, last = k == pieces - 1;
            std::size_t end = start;
            do { // the first parameter always belongs to piece k (NaN included)
                local[end] = std::clamp((ts[end] - a) * inv, Scalar(0), Scalar(1));
                ++end;
            } while (end < count && (ts[end] >= a || first) && (ts[end] < b || last) && ts[end] == ts[end]);
            f(k, start, end - start, local.data() + start);
            start = end;
        }
    }

    /// Evaluates piece k at len local parameters s; positions to pos, and when order 1 the first
    /// derivatives (with respect to u) to d1. Horner on the piece's Taylor coefficients about its
    /// midpoint (|s - 1/2| <= 1/2), fully unrolled for degrees up to 7.
    void evalRun(int k, const Scalar* s, std::size_t len, Scalar* pos, Scalar* d1, int order) const
    {
        const int p = degree();
        const Scalar* c = taylor_.data() + static_cast<std::size_t>(k * (p + 1) * (Dim + 1));
        const Scalar invH = Scalar(1) / (breaks_[k + 1] - breaks_[k]);
        switch (p) {
        case 1: return hornerRun<1>(c, s, len, pos, d1, order, invH);
        case 2: return hornerRun<2>(c, s, len, pos, d1, order, invH);
        case 3: return hornerRun<3>(c, s, len, pos, d1, order, invH);
        case 4: return hornerRun<4>(c, s, len, pos, d1, order, invH);
        case 5: return hornerRun<5>(c, s, len, pos, d1, order, invH);
        case 6: return hornerRun<6>(c, s, len, pos, d1, order, invH);
        case 7: return hornerRun<7>(c, s, len, pos, d1, order, invH);
        default: return hornerRun<-1>(c, s, len, pos, d1, order, invH);
        }
    }

    template <int P>
    void hornerRun(const Scalar* c, const Scalar* s, std::size_t len, Scalar* pos, Scalar* d1, int order,
                   Scalar invH) const
    {
        constexpr int H = Dim + 1;
        const int p = P > 0 ? P : degree();
        for (std::size_t j = 0; j < len; ++j) {
            const Scalar x = s[j] - Scalar(0.5);
            Scalar acc[H], dacc[H];
            for (int d = 0; d < H; ++d) {
                acc[d] = c[p * H + d];
                dacc[d] = Scalar(0);
            }
            for (int i = p - 1; i >= 0; --i)
                for (int d = 0; d < H; ++d) {
                    dacc[d] = dacc[d] * x + acc[d];
                    acc[d] = acc[d] * x + c[i * H + d];
                }
            const Scalar inv = Scalar(1) / acc[Dim];
            for (int d = 0; d < Dim; ++d) pos[j * Dim + d] = acc[d] * inv;
            if (order)
                for (int d = 0; d < Dim; ++d)
                    d1[j * Dim + d] = (dacc[d] - dacc[Dim] * pos[j * Dim + d]) * inv * invH;
        }
    }

    Knots knots_;
    HPoints hom_;
    bool rational_ = false;
    std::vector<Scalar> breaks_;
    std::vector<int> spanOf_;
    HPoints pieces_;                 // Bézier pieces, (p+1) homogeneous points each
    HPoints taylor_;                 // their Taylor coefficients about the span midpoints
};

template <typename Scalar, int Dim>
struct NurbsCurve<Scalar, Dim>::Approximation {
    NurbsCurve curve;
    Scalar error;
};

template <typename Scalar, int Dim>
typename NurbsCurve<Scalar, Dim>::Approximation NurbsCurve<Scalar, Dim>::removeKnot(Scalar u) const
{
    const int p = degree();
    const std::vector<Scalar>& U = knots();
    if (!(u > domainStart() && u < domainEnd()))
        throw Error("NurbsCurve::removeKnot: " + num(u) + " is not an interior knot");
    const int s = knots_.multiplicity(u);
    if (s == 0) throw Error("NurbsCurve::removeKnot: " + num(u) + " is not a knot");
    const int r = static_cast<int>(std::upper_bound(U.begin(), U.end(), u) - U.begin()) - 1; // last index of u
    const int first = r - p, last = r - s;
    const int n = controlCount() - 1;
    std::vector<HPoint> temp(static_cast<std::size_t>(last - first + 3));
    HPoints P = hom_;
    temp[0] = first - 1 >= 0 ? HPoint(P.col(first - 1)) : HPoint::Zero();
    temp[static_cast<std::size_t>(last - first + 2)] = last + 1 <= n ? HPoint(P.col(last + 1)) : HPoint::Zero();
    int i = first, j = last, ii = 1, jj = last - first + 1;
    while (j - i > 0) {
        const Scalar ai = (u - U[i]) / (U[i + p + 1] - U[i]);
        const Scalar aj = (u - U[j]) / (U[j + p + 1] - U[j]);
        temp[ii] = (P.col(i) - (Scalar(1) - ai) * temp[ii - 1]) / ai;
        temp[jj] = (P.col(j) - aj * temp[jj + 1]) / (Scalar(1) - aj);
        ++i; ++ii; --j; --jj;
    }
    Scalar error;
    if (j - i < 0) {
        error = (temp[ii - 1] - temp[jj + 1]).norm();
    } else {
        const Scalar ai = (u - U[i]) / (U[i + p + 1] - U[i]);
        error = (HPoint(P.col(i)) - (ai * temp[ii + 1] + (Scalar(1) - ai) * temp[ii - 1])).norm();
    }
    i = first;
    j = last;
    while (j - i > 0) {
        P.col(i) = temp[i - first + 1];
        P.col(j) = temp[j - first + 1];
        ++i;
        --j;
    }
    const int fout = (2 * r - s - p) / 2;
    HPoints Q(Dim + 1, n);
    Q.leftCols(fout) = P.leftCols(fout);
    Q.rightCols(n - fout) = P.rightCols(n - fout);
    std::vector<Scalar> V = U;
    V.erase(V.begin() + r);
    for (Eigen::Index c = 0; c < Q.cols(); ++c)
        if (!(Q(Dim, c) > Scalar(0)))
            throw Error("NurbsCurve::removeKnot: removing " + num(u) + " would give a non-positive weight");
    return {NurbsCurve(Knots(std::move(V), p, "NurbsCurve::removeKnot"), std::move(Q)), error};
}

namespace detail {
/// Joins homogeneous Bézier pieces of degree d over the breakpoints into a NURBS in Bézier form:
/// shared joints (interior multiplicity d) except where `broken[k]` (multiplicity d + 1).
template <typename Scalar, int Dim>
NurbsCurve<Scalar, Dim> joinPieces(const std::vector<PointMatrix<Scalar, Dim + 1>>& pieces, const std::vector<Scalar>& br,
                                   const std::vector<bool>& broken, int d)
{
    std::vector<Scalar> knots(static_cast<std::size_t>(d + 1), br.front());
    std::vector<Point<Scalar, Dim + 1>> pts;
    for (std::size_t k = 0; k < pieces.size(); ++k) {
        for (int i = (k == 0 || broken[k]) ? 0 : 1; i <= d; ++i) pts.push_back(pieces[k].col(i));
        if (k + 1 < pieces.size())
            knots.insert(knots.end(), static_cast<std::size_t>(broken[k + 1] ? d + 1 : d), br[k + 1]);
    }
    knots.insert(knots.end(), static_cast<std::size_t>(d + 1), br.back());
    PointMatrix<Scalar, Dim + 1> h(Dim + 1, static_cast<Eigen::Index>(pts.size()));
    for (std::size_t i = 0; i < pts.size(); ++i) h.col(static_cast<Eigen::Index>(i)) = pts[i];
    return NurbsCurve<Scalar, Dim>(KnotVector<Scalar>(std::move(knots), d, "NurbsCurve (Bézier form)"), std::move(h));
}
} // namespace detail

template <typename Scalar, int Dim>
NurbsCurve<Scalar, Dim> NurbsCurve<Scalar, Dim>::elevated(int times) const
{
    if (times < 0) throw Error("NurbsCurve::elevated: count " + std::to_string(times) + " is negative");
    const int p = degree();
    requireDegree(p + times, "NurbsCurve::elevated");
    if (times == 0) return *this;
    std::vector<HPoints> pieces;
    for (const Piece& piece : bezierPieces()) pieces.push_back(piece.homogeneous().elevated(times).controlPoints());
    std::vector<bool> broken(breaks_.size(), false);
    std::vector<int> mult(breaks_.size(), 0);
    for (std::size_t k = 1; k + 1 < breaks_.size(); ++k) {
        mult[k] = knots_.multiplicity(breaks_[k]);
        broken[k] = mult[k] > p;
    }
    NurbsCurve c = detail::joinPieces<Scalar, Dim>(pieces, breaks_, broken, p + times);
    for (std::size_t k = 1; k + 1 < breaks_.size(); ++k)
        for (int r = 0; r < p - mult[k]; ++r) c = c.removeKnot(breaks_[k]).curve;
    return c;
}

template <typename Scalar, int Dim>
typename NurbsCurve<Scalar, Dim>::Approximation NurbsCurve<Scalar, Dim>::reduced(Scalar tolerance) const
{
    const int p = degree();
    if (p < 2) throw Error("NurbsCurve::reduced: degree " + std::to_string(p) + " cannot be reduced (needs 2 or more)");
    for (std::size_t k = 1; k + 1 < breaks_.size(); ++k)
        if (knots_.multiplicity(breaks_[k]) > p)
            throw Error("NurbsCurve::reduced: the curve is broken at knot " + num(breaks_[k]));
    std::vector<HPoints> pieces;
    Scalar error(0);
    for (const Piece& piece : bezierPieces()) {
        const auto red = piece.homogeneous().reduced();
        pieces.push_back(red.curve.controlPoints());
        error = std::max(error, red.errorBound);
    }
    for (const HPoints& h : pieces)
        for (Eigen::Index i = 0; i < h.cols(); ++i)
            if (!(h(Dim, i) > Scalar(0))) throw Error("NurbsCurve::reduced: a reduced weight is not positive");
    NurbsCurve c = detail::joinPieces<Scalar, Dim>(pieces, breaks_, std::vector<bool>(breaks_.size(), false), p - 1);
    for (std::size_t k = 1; k + 1 < breaks_.size(); ++k) {
        const int target = std::max(knots_.multiplicity(breaks_[k]), 1);
        for (int r = 0; r < (p - 1) - target; ++r) {
            const auto removed = c.removeKnot(breaks_[k]);
            if (error + removed.error > tolerance) break;
            error += removed.error;
            c = removed.curve;
        }
    }
    return {std::move(c), error};
}

extern template class NurbsCurve<double, 2>;
extern template class NurbsCurve<double, 3>;
#ifndef FREEFORM_DOUBLE_ONLY_INSTANTIATIONS // float and long double (docs/development.md)
extern template class NurbsCurve<float, 2>;
extern template class NurbsCurve<float, 3>;
extern template class NurbsCurve<long double, 2>;
extern template class NurbsCurve<long double, 3>;
#endif

} // namespace freeform
