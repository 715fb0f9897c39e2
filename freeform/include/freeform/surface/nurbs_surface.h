#pragma once
// NurbsSurface<Scalar, Dim>: the tensor-product NURBS surface
//     S(u, v) = sum w_ij P_ij N_(i,p)(u) N_(j,q)(v) / sum w_ij N_(i,p)(u) N_(j,q)(v)
// on [u_p, u_(nu)] x [v_q, v_(nv)] of two general knot vectors (curve/knot_vector.h;
// docs/nurbs.md). Control point (i, j), i along u, at column i * countV + j (the BezierSurface
// layout). Stored as homogeneous points (w P, w). Invariants, checked once in the constructor with
// freeform::Error naming the knot vector, knot or point: valid knot vectors, countU * countV points,
// finite coordinates, positive finite weights.
//
// Evaluation: the spans in u and v, the (p+1)(q+1) non-zero basis products and one division;
// jet(): basis derivatives in both directions on the homogeneous points, then Leibniz's rule in two
// variables (surface/rational_bezier_surface.h); evaluateGrid(): the batch path for a grid of
// parameters (basis values tabulated once per grid row and column, one homogeneous sum of
// (q+1) terms per point after a per-row reduction in u); bezierPatches(): Bézier extraction by the
// extraction operators of both knot vectors; removeKnotU/V(), elevatedU/V(), reducedU/V(): the
// curve algorithms of curve/nurbs_curve.h on every column (row) of the net, one decision for all.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "freeform/core/format.h"
#include "freeform/curve/knot_vector.h"
#include "freeform/curve/nurbs_curve.h"
#include "freeform/surface/rational_bezier_surface.h"

namespace freeform {

template <typename Scalar, int Dim>
class NurbsSurface {
public:
    using PointType = Point<Scalar, Dim>;
    using Points = PointMatrix<Scalar, Dim>;
    using HPoint = Point<Scalar, Dim + 1>;
    using HPoints = PointMatrix<Scalar, Dim + 1>;
    using Weights = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
    using Knots = KnotVector<Scalar>;
    using Jet = Eigen::Matrix<Scalar, Dim, Eigen::Dynamic>;
    using Patch = RationalBezierSurface<Scalar, Dim>;

    /// Degrees p (u) and q (v), knot vectors, points Dim x (countU * countV) with countU =
    /// knotsU.size() - p - 1 and countV likewise, weights (same count; empty = all 1).
    NurbsSurface(int p, int q, std::vector<Scalar> knotsU, std::vector<Scalar> knotsV, const Points& points,
                 const Weights& weights = Weights())
        : NurbsSurface(Knots(std::move(knotsU), p, "NurbsSurface (knots in u)"),
                       Knots(std::move(knotsV), q, "NurbsSurface (knots in v)"), points, weights)
    {
    }

    NurbsSurface(Knots ku, Knots kv, const Points& points, const Weights& weights = Weights())
        : ku_(std::move(ku)), kv_(std::move(kv))
    {
        const Eigen::Index expected = static_cast<Eigen::Index>(countU()) * countV();
        if (points.cols() != expected)
            throw Error("NurbsSurface: the knot vectors need " + std::to_string(countU()) + " x " +
                        std::to_string(countV()) + " = " + std::to_string(expected) + " control points, got " +
                        std::to_string(points.cols()));
        if (weights.size() != 0 && weights.size() != expected)
            throw Error("NurbsSurface: " + std::to_string(weights.size()) + " weights for " + std::to_string(expected) +
                        " control points");
        requireFinite(points, "NurbsSurface");
        hom_.resize(Dim + 1, expected);
        for (Eigen::Index i = 0; i < expected; ++i) {
            const Scalar w = weights.size() ? weights[i] : Scalar(1);
            if (!(w > Scalar(0)) || !std::isfinite(static_cast<long double>(w)))
                throw Error("NurbsSurface: weight " + std::to_string(i) + " (point " + std::to_string(i / countV()) +
                            ", " + std::to_string(i % countV()) + ") is not a positive finite number");
            if (w != Scalar(1)) rational_ = true;
            hom_.col(i).template head<Dim>() = w * points.col(i);
            hom_(Dim, i) = w;
        }
    }

    /// The polynomial or rational Bézier patch as a NURBS surface (clamped knots 0 and 1).
    static NurbsSurface fromBezier(const Patch& patch)
    {
        const int m = patch.degreeU(), n = patch.degreeV();
        auto knots = [](int d) {
            std::vector<Scalar> k(static_cast<std::size_t>(d + 1), Scalar(0));
            k.resize(static_cast<std::size_t>(2 * d + 2), Scalar(1));
            return k;
        };
        const HPoints& h = patch.homogeneous().controlPoints();
        Points pts(Dim, h.cols());
        for (Eigen::Index i = 0; i < h.cols(); ++i) pts.col(i) = h.col(i).template head<Dim>() / h(Dim, i);
        return NurbsSurface(m, n, knots(m), knots(n), pts, Weights(h.row(Dim).transpose()));
    }

    /// The surface in Bézier form from its patches: patch (a, b) of degrees (p, q) over
    /// [bu[a], bu[a + 1]] x [bv[b], bv[b + 1]] at index a (bv.size() - 1) + b, its homogeneous point
    /// (i, j) at column i (q + 1) + j. A boundary two patches share (equal to rounding) keeps the
    /// first patch's points. `what` names it in errors.
    static NurbsSurface fromBezierPatches(const std::vector<Scalar>& bu, const std::vector<Scalar>& bv, int p, int q,
                                          const std::vector<HPoints>& patches, const std::string& what)
    {
        const int nu = static_cast<int>(bu.size()) - 1, nv = static_cast<int>(bv.size()) - 1;
        if (nu < 1 || nv < 1 || patches.size() != static_cast<std::size_t>(nu) * static_cast<std::size_t>(nv))
            throw Error(what + ": " + std::to_string(patches.size()) + " Bézier patches do not fill " + std::to_string(std::max(nu, 0)) +
                        " x " + std::to_string(std::max(nv, 0)) + " spans");
        const int cv = nv * q + 1;
        HPoints h(Dim + 1, static_cast<Eigen::Index>(nu * p + 1) * cv);
        for (int a = nu - 1; a >= 0; --a)
            for (int b = nv - 1; b >= 0; --b) {
                const HPoints& c = patches[static_cast<std::size_t>(a * nv + b)];
                if (c.cols() != static_cast<Eigen::Index>(p + 1) * (q + 1))
                    throw Error(what + ": patch (" + std::to_string(a) + ", " + std::to_string(b) + ") has " +
                                std::to_string(c.cols()) + " control points, not " + std::to_string((p + 1) * (q + 1)));
                for (int i = 0; i <= p; ++i)
                    for (int j = 0; j <= q; ++j) h.col((a * p + i) * cv + b * q + j) = c.col(i * (q + 1) + j);
            }
        return NurbsSurface(Knots(Knots::bezierForm(bu, p), p, what + " (knots in u)"),
                            Knots(Knots::bezierForm(bv, q), q, what + " (knots in v)"), std::move(h));
    }

    /// The exact sphere of `radius` about c (3D): a full circle in u (four quarter arcs, u in
    /// [0, 1], counter-clockwise about z from +x) times a half circle from the south pole to the
    /// north pole in v (two quarter arcs, v in [0, 1]); degree (2, 2), 9 x 5 control points.
    static NurbsSurface sphere(const PointType& c, Scalar radius)
        requires(Dim == 3)
    {
        const Scalar s = std::sqrt(Scalar(2)) / 2;
        const int cx[9] = {1, 1, 0, -1, -1, -1, 0, 1, 1}, cy[9] = {0, 1, 1, 1, 0, -1, -1, -1, 0};
        const int px[5] = {0, 1, 1, 1, 0}, pz[5] = {-1, -1, 0, 1, 1};
        Points pts(3, 45);
        Weights w(45);
        for (int i = 0; i < 9; ++i)
            for (int j = 0; j < 5; ++j) {
                pts.col(i * 5 + j) = c + radius * PointType(Scalar(cx[i] * px[j]), Scalar(cy[i] * px[j]), Scalar(pz[j]));
                w[i * 5 + j] = (i % 2 ? s : Scalar(1)) * (j % 2 ? s : Scalar(1));
            }
        const Scalar q = Scalar(1) / 4, h = Scalar(1) / 2;
        return NurbsSurface(2, 2, {0, 0, 0, q, q, 2 * q, 2 * q, 3 * q, 3 * q, 1, 1, 1}, {0, 0, 0, h, h, 1, 1, 1}, pts, w);
    }

    int degreeU() const { return ku_.degree(); }
    int degreeV() const { return kv_.degree(); }
    int countU() const { return ku_.controlCount(); }
    int countV() const { return kv_.controlCount(); }
    const Knots& knotsU() const { return ku_; }
    const Knots& knotsV() const { return kv_; }
    bool isRational() const { return rational_; }
    const HPoints& homogeneousPoints() const { return hom_; }
    int index(int i, int j) const { return i * countV() + j; }
    Scalar weight(int i, int j) const { return hom_(Dim, index(i, j)); }
    PointType controlPoint(int i, int j) const
    {
        return hom_.col(index(i, j)).template head<Dim>() / weight(i, j);
    }
    Points controlPoints() const
    {
        Points p(Dim, hom_.cols());
        for (Eigen::Index k = 0; k < hom_.cols(); ++k) p.col(k) = hom_.col(k).template head<Dim>() / hom_(Dim, k);
        return p;
    }
    Weights weights() const { return hom_.row(Dim).transpose(); }

    /// S(u, v); parameters outside the domain are clamped to it.
    PointType evaluate(Scalar u, Scalar v) const
    {
        const int p = degreeU(), q = degreeV();
        u = clampU(u);
        v = clampV(v);
        const int su = ku_.findSpan(u), sv = kv_.findSpan(v);
        Scalar nu[kMaxDegree + 1], nv[kMaxDegree + 1];
        ku_.basisFunctions(su, u, nu);
        kv_.basisFunctions(sv, v, nv);
        HPoint h = HPoint::Zero();
        for (int a = 0; a <= p; ++a) {
            HPoint row = HPoint::Zero();
            const int base = (su - p + a) * countV() + sv - q;
            for (int b = 0; b <= q; ++b) row += nv[b] * hom_.col(base + b);
            h += nu[a] * row;
        }
        return h.template head<Dim>() / h[Dim];
    }
    PointType operator()(Scalar u, Scalar v) const { return evaluate(u, v); }

    /// Position and every partial derivative of total order <= order, columns by
    /// BezierSurface::jetIndex (f, f_u, f_v, f_uu, f_uv, f_vv, ...), derivatives with respect to u, v.
    Jet jet(Scalar u, Scalar v, int order) const
    {
        if (order < 0) throw Error("NurbsSurface::jet: order " + std::to_string(order) + " is negative");
        const int p = degreeU(), q = degreeV();
        u = clampU(u);
        v = clampV(v);
        const int su = ku_.findSpan(u), sv = kv_.findSpan(v);
        std::vector<Scalar> du(static_cast<std::size_t>((order + 1) * (p + 1))), dv(static_cast<std::size_t>((order + 1) * (q + 1)));
        ku_.basisDerivatives(su, u, order, du.data());
        kv_.basisDerivatives(sv, v, order, dv.data());
        Eigen::Matrix<Scalar, Dim + 1, Eigen::Dynamic> h(Dim + 1, (order + 1) * (order + 2) / 2);
        h.setZero();
        for (int t = 0; t <= order; ++t)
            for (int l = 0; l <= t; ++l) {
                const int k = t - l;
                HPoint sum = HPoint::Zero();
                for (int a = 0; a <= p; ++a) {
                    HPoint row = HPoint::Zero();
                    const int base = (su - p + a) * countV() + sv - q;
                    for (int b = 0; b <= q; ++b) row += dv[static_cast<std::size_t>(l * (q + 1) + b)] * hom_.col(base + b);
                    sum += du[static_cast<std::size_t>(k * (p + 1) + a)] * row;
                }
                h.col(t * (t + 1) / 2 + l) = sum;
            }
        return projectSurfaceJet<Scalar, Dim>(h, order);
    }

    /// Unit normal S_u x S_v / |S_u x S_v| (3D); zero where the partials are parallel (poles).
    PointType normal(Scalar u, Scalar v) const
        requires(Dim == 3)
    {
        const Jet d = jet(u, v, 1);
        const PointType c = PointType(d.col(1)).cross(PointType(d.col(2)));
        const Scalar len = c.norm();
        return len > Scalar(0) ? PointType(c / len) : PointType::Zero();
    }

    /// The batch path: positions on the grid us x vs (point (iu, iv) at column iu * vs.size() + iv),
    /// and when du/dv are given the partials S_u and S_v there too.
    void evaluateGrid(const std::vector<Scalar>& us, const std::vector<Scalar>& vs, Points& positions,
                      Points* du = nullptr, Points* dv = nullptr) const
    {
        const int p = degreeU(), q = degreeV();
        const int order = (du || dv) ? 1 : 0;
        const std::size_t nu = us.size(), nv = vs.size();
        positions.resize(Dim, static_cast<Eigen::Index>(nu * nv));
        if (du) du->resize(Dim, static_cast<Eigen::Index>(nu * nv));
        if (dv) dv->resize(Dim, static_cast<Eigen::Index>(nu * nv));
        // Tabulate the v basis (and first derivatives) once per column.
        const int Q = q + 1;
        std::vector<int> spanV(nv);
        std::vector<Scalar> basisV(nv * static_cast<std::size_t>(Q * (order + 1)));
        for (std::size_t j = 0; j < nv; ++j) {
            const Scalar v = clampV(vs[j]);
            spanV[j] = kv_.findSpan(v);
            Scalar* out = basisV.data() + j * static_cast<std::size_t>(Q * (order + 1));
            if (order == 0) kv_.basisFunctions(spanV[j], v, out);
            else kv_.basisDerivatives(spanV[j], v, 1, out);
        }
        // Per row u: reduce the (p+1) rows of homogeneous points to one row (and its u-derivative).
        HPoints row(Dim + 1, countV()), rowU(Dim + 1, countV());
        std::vector<Scalar> basisU(static_cast<std::size_t>((p + 1) * (order + 1)));
        for (std::size_t i = 0; i < nu; ++i) {
            const Scalar u = clampU(us[i]);
            const int su = ku_.findSpan(u);
            if (order == 0) ku_.basisFunctions(su, u, basisU.data());
            else ku_.basisDerivatives(su, u, 1, basisU.data());
            row.setZero();
            if (order) rowU.setZero();
            for (int a = 0; a <= p; ++a) {
                const auto block = hom_.middleCols((su - p + a) * countV(), countV());
                row.noalias() += basisU[a] * block;
                if (order) rowU.noalias() += basisU[static_cast<std::size_t>(p + 1 + a)] * block;
            }
            for (std::size_t j = 0; j < nv; ++j) {
                const Scalar* b = basisV.data() + j * static_cast<std::size_t>(Q * (order + 1));
                const int first = spanV[j] - q;
                HPoint h = HPoint::Zero();
                for (int k = 0; k <= q; ++k) h += b[k] * row.col(first + k);
                const Scalar inv = Scalar(1) / h[Dim];
                const PointType s = h.template head<Dim>() * inv;
                const Eigen::Index col = static_cast<Eigen::Index>(i * nv + j);
                positions.col(col) = s;
                if (!order) continue;
                HPoint hu = HPoint::Zero(), hv = HPoint::Zero();
                for (int k = 0; k <= q; ++k) {
                    hu += b[k] * rowU.col(first + k);
                    hv += b[Q + k] * row.col(first + k);
                }
                if (du) du->col(col) = (hu.template head<Dim>() - hu[Dim] * s) * inv;
                if (dv) dv->col(col) = (hv.template head<Dim>() - hv[Dim] * s) * inv;
            }
        }
    }

    /// Bézier extraction: one rational Bézier patch per pair of non-empty knot spans, patch
    /// (ku, kv) at index ku * (spans in v) + kv, over [breakpointsU[ku], ..+1] x [breakpointsV[kv], ..+1].
    std::vector<Patch> bezierPatches() const
    {
        const int p = degreeU(), q = degreeV();
        std::vector<int> spansU, spansV;
        for (int i = p; i < countU(); ++i) if (ku_[i] < ku_[i + 1]) spansU.push_back(i);
        for (int j = q; j < countV(); ++j) if (kv_[j] < kv_[j + 1]) spansV.push_back(j);
        std::vector<Patch> out;
        for (int su : spansU) {
            const auto eu = ku_.extractionOperator(su);
            for (int sv : spansV) {
                const auto ev = kv_.extractionOperator(sv);
                HPoints h(Dim + 1, (p + 1) * (q + 1));
                h.setZero();
                for (int a = 0; a <= p; ++a)
                    for (int b = 0; b <= q; ++b) {
                        HPoint sum = HPoint::Zero();
                        for (int i = 0; i <= p; ++i) {
                            if (eu(a, i) == Scalar(0)) continue;
                            HPoint r = HPoint::Zero();
                            for (int j = 0; j <= q; ++j) r += ev(b, j) * hom_.col((su - p + i) * countV() + sv - q + j);
                            sum += eu(a, i) * r;
                        }
                        h.col(a * (q + 1) + b) = sum;
                    }
                out.emplace_back(BezierSurface<Scalar, Dim + 1>(p, q, std::move(h)));
            }
        }
        return out;
    }

    /// Knot refinement in u (or v): every value of `extra` (inside the domain) added to that knot
    /// vector, by the Oslo algorithm of NurbsCurve::refined applied to every column (row) of the
    /// homogeneous net. The surface is unchanged.
    NurbsSurface refinedU(const std::vector<Scalar>& extra) const
    {
        for (Scalar x : extra)
            if (!(x > ku_.front() && x < ku_.back()))
                throw Error("NurbsCurve::refined: knot " + formatNumber(x) + " is not inside the domain (" +
                            formatNumber(ku_.front()) + ", " + formatNumber(ku_.back()) + ")");
        std::vector<Scalar> tau = ku_.knots();
        tau.insert(tau.end(), extra.begin(), extra.end());
        std::sort(tau.begin(), tau.end());
        Knots k(std::move(tau), degreeU(), "NurbsCurve::refined");
        HPoints h = refinedRows(ku_, hom_, countV(), k);
        return NurbsSurface(std::move(k), kv_, std::move(h));
    }
    NurbsSurface refinedV(const std::vector<Scalar>& extra) const { return transposed().refinedU(extra).transposed(); }

    /// Result of removeKnotU/V() and reducedU/V(): the new surface and the error the operation
    /// reports. The error is the largest of the per-row curve errors (NurbsCurve::removeKnot,
    /// reduced); since S(u, v) = sum_j N_j(v) C_j(u) with basis functions summing to 1, it bounds
    /// max |new - old| over the surface for a polynomial surface (the homogeneous surfaces' difference
    /// for a rational one).
    struct Approximation {
        NurbsSurface surface;
        Scalar error;
    };

    /// Removes one occurrence of the interior knot u from the u knot vector: NurbsCurve::removeKnot
    /// (The NURBS Book, A5.8, homogeneous) on every column of the net (the curves in u, one per v
    /// index). One knot and one row of control points less.
    Approximation removeKnotU(Scalar u) const
    {
        auto curves = curvesU();
        Scalar error(0);
        for (auto& c : curves) {
            auto r = c.removeKnot(u);
            error = std::max(error, r.error);
            c = std::move(r.curve);
        }
        return {fromCurvesU(curves, kv_), error};
    }
    /// The same in v (every row of the net).
    Approximation removeKnotV(Scalar v) const
    {
        auto t = transposed().removeKnotU(v);
        return {t.surface.transposed(), t.error};
    }

    /// Degree p + times in u (q + times in v): NurbsCurve::elevated on every column (row) of the
    /// net; every interior knot's multiplicity grows by times. The surface is unchanged.
    NurbsSurface elevatedU(int times = 1) const
    {
        auto curves = curvesU();
        for (auto& c : curves) c = c.elevated(times);
        return fromCurvesU(curves, kv_);
    }
    NurbsSurface elevatedV(int times = 1) const { return transposed().elevatedU(times).transposed(); }

    /// Degree p - 1 in u (p >= 2), as NurbsCurve::reduced but with one decision for the whole net:
    /// every column's Bézier pieces reduced (ends kept) and joined C0, then the interior knots
    /// removed towards their original multiplicities, a removal taken (in every column) only while
    /// the accumulated error stays within `tolerance`. `error` bounds max |new - old| as above.
    Approximation reducedU(Scalar tolerance = Scalar(0)) const
    {
        const int p = degreeU();
        if (p < 2) throw Error("NurbsSurface::reducedU: degree " + std::to_string(p) + " in u cannot be reduced (needs 2 or more)");
        const std::vector<Scalar> br = ku_.breakpoints();
        for (std::size_t k = 1; k + 1 < br.size(); ++k)
            if (ku_.multiplicity(br[k]) > p)
                throw Error("NurbsSurface::reducedU: the surface is broken at knot " +
                            formatNumber(br[k]) + " in u");
        std::vector<NurbsCurve<Scalar, Dim>> curves;
        Scalar error(0);
        for (const auto& c : curvesU()) {
            std::vector<HPoints> pieces;
            for (const auto& piece : c.bezierPieces()) {
                const auto red = piece.homogeneous().reduced();
                for (Eigen::Index i = 0; i < red.curve.controlPoints().cols(); ++i)
                    if (!(red.curve.controlPoints()(Dim, i) > Scalar(0)))
                        throw Error("NurbsSurface::reducedU: a reduced weight is not positive");
                pieces.push_back(red.curve.controlPoints());
                error = std::max(error, red.errorBound);
            }
            curves.push_back(detail::joinPieces<Scalar, Dim>(pieces, br, std::vector<bool>(br.size(), false), p - 1));
        }
        for (std::size_t k = 1; k + 1 < br.size(); ++k) {
            const int target = std::max(ku_.multiplicity(br[k]), 1);
            for (int r = 0; r < (p - 1) - target; ++r) {
                std::vector<NurbsCurve<Scalar, Dim>> next;
                Scalar e(0);
                for (const auto& c : curves) {
                    auto removed = c.removeKnot(br[k]);
                    e = std::max(e, removed.error);
                    next.push_back(std::move(removed.curve));
                }
                if (error + e > tolerance) break;
                error += e;
                curves = std::move(next);
            }
        }
        return {fromCurvesU(curves, kv_), error};
    }
    Approximation reducedV(Scalar tolerance = Scalar(0)) const
    {
        auto t = transposed().reducedU(tolerance);
        return {t.surface.transposed(), t.error};
    }

    /// The same surface with u and v exchanged: S^T(v, u) = S(u, v).
    NurbsSurface transposed() const
    {
        HPoints h(Dim + 1, hom_.cols());
        for (int i = 0; i < countU(); ++i)
            for (int j = 0; j < countV(); ++j) h.col(j * countU() + i) = hom_.col(index(i, j));
        return NurbsSurface(kv_, ku_, std::move(h));
    }

    /// From knot vectors and homogeneous points (w P, w), point (i, j) at column i * countV + j.
    NurbsSurface(Knots ku, Knots kv, HPoints hom) : ku_(std::move(ku)), kv_(std::move(kv)), hom_(std::move(hom))
    {
        if (hom_.cols() != static_cast<Eigen::Index>(countU()) * countV())
            throw Error("NurbsSurface: the knot vectors need " + std::to_string(countU()) + " x " +
                        std::to_string(countV()) + " control points, got " + std::to_string(hom_.cols()));
        requireFinite(hom_, "NurbsSurface");
        for (Eigen::Index i = 0; i < hom_.cols(); ++i) {
            if (!(hom_(Dim, i) > Scalar(0))) throw Error("NurbsSurface: weight " + std::to_string(i) + " is not positive");
            if (hom_(Dim, i) != Scalar(1)) rational_ = true;
        }
    }

    /// The isocurve v = const as a NURBS curve in u, and u = const as one in v.
    NurbsCurve<Scalar, Dim> curveAtV(Scalar v) const
    {
        const int q = degreeV();
        v = clampV(v);
        const int sv = kv_.findSpan(v);
        Scalar nv[kMaxDegree + 1];
        kv_.basisFunctions(sv, v, nv);
        HPoints c(Dim + 1, countU());
        c.setZero();
        for (int i = 0; i < countU(); ++i)
            for (int b = 0; b <= q; ++b) c.col(i) += nv[b] * hom_.col(i * countV() + sv - q + b);
        return NurbsCurve<Scalar, Dim>(ku_, std::move(c));
    }
    NurbsCurve<Scalar, Dim> curveAtU(Scalar u) const
    {
        const int p = degreeU();
        u = clampU(u);
        const int su = ku_.findSpan(u);
        Scalar nu[kMaxDegree + 1];
        ku_.basisFunctions(su, u, nu);
        HPoints c(Dim + 1, countV());
        c.setZero();
        for (int a = 0; a <= p; ++a) c += nu[a] * hom_.middleCols((su - p + a) * countV(), countV());
        return NurbsCurve<Scalar, Dim>(kv_, std::move(c));
    }

    /// Box of the control points (contains the surface).
    /// The surface over [a, b] of its u (or v) domain, by knot insertion at a and b (NurbsCurve::split
    /// on every column): the same points at the same parameters there. An end outside the domain
    /// (or on its end) leaves that end as it is.
    NurbsSurface restrictedU(Scalar a, Scalar b) const
    {
        Knots k = ku_;
        HPoints h = hom_;
        if (a > k.front() && a < k.back()) cutU(k, h, countV(), a, true);
        if (b > k.front() && b < k.back()) cutU(k, h, countV(), b, false);
        return NurbsSurface(std::move(k), kv_, std::move(h));
    }
    NurbsSurface restrictedV(Scalar a, Scalar b) const { return transposed().restrictedU(a, b).transposed(); }

    Box<Scalar, Dim> controlBox() const
    {
        const Points p = controlPoints();
        return Box<Scalar, Dim>(PointType(p.rowwise().minCoeff()), PointType(p.rowwise().maxCoeff()));
    }

    Scalar clampU(Scalar u) const { return u < ku_.front() ? ku_.front() : u > ku_.back() ? ku_.back() : u; }
    Scalar clampV(Scalar v) const { return v < kv_.front() ? kv_.front() : v > kv_.back() ? kv_.back() : v; }

private:
    /// The net's columns as curves in u (one per v index j).
    std::vector<NurbsCurve<Scalar, Dim>> curvesU() const
    {
        std::vector<NurbsCurve<Scalar, Dim>> cols;
        for (int j = 0; j < countV(); ++j) {
            HPoints c(Dim + 1, countU());
            for (int i = 0; i < countU(); ++i) c.col(i) = hom_.col(index(i, j));
            cols.push_back(NurbsCurve<Scalar, Dim>(ku_, std::move(c)));
        }
        return cols;
    }
    /// The Oslo refinement of NurbsCurve::refined on every column of a net at once: row i of the
    /// net (along u) is columns i * nv .. i * nv + nv - 1 of hom, on knots k; `refined` holds k's
    /// knots and more. Column by column the same operations as the curve's, so the same numbers,
    /// without a NurbsCurve (and its Bézier pieces) per column.
    static HPoints refinedRows(const Knots& k, const HPoints& hom, int nv, const Knots& refined)
    {
        const int p = k.degree(), count = refined.controlCount();
        const std::vector<Scalar>& tau = refined.knots();
        HPoints out(Dim + 1, static_cast<Eigen::Index>(count) * nv);
        std::vector<HPoints> d(static_cast<std::size_t>(p + 1));
        for (int j = 0; j < count; ++j) {
            // A non-empty new span among j..j+p inside the domain; the old span containing it.
            int s = std::max(j, p);
            while (s < std::min(j + p, count - 1) && !(tau[s] < tau[s + 1])) ++s;
            const int mu = k.findSpan(tau[s]);
            for (int i = 0; i <= p; ++i) d[static_cast<std::size_t>(i)] = hom.middleCols((mu - p + i) * nv, nv);
            for (int r = 1; r <= p; ++r) { // the blossom at tau[j + 1], ..., tau[j + p]
                const Scalar x = tau[j + r];
                for (int i = p; i >= r; --i) {
                    const int g = mu - p + i;
                    const Scalar alpha = (x - k[g]) / (k[g + p + 1 - r] - k[g]);
                    d[static_cast<std::size_t>(i)] =
                        (Scalar(1) - alpha) * d[static_cast<std::size_t>(i - 1)] + alpha * d[static_cast<std::size_t>(i)];
                }
            }
            out.middleCols(static_cast<Eigen::Index>(j) * nv, nv) = d[static_cast<std::size_t>(p)];
        }
        return out;
    }

    /// NurbsCurve::split at u on every column of the net (rows along u, nv wide): the knots and
    /// rows after u (keepRight) or before it, by the curve's insertRows and cutRows.
    static void cutU(Knots& k, HPoints& hom, int nv, Scalar u, bool keepRight)
    {
        using Curve = NurbsCurve<Scalar, Dim>;
        const int p = k.degree();
        std::vector<Scalar> U = k.knots(), out;
        Curve::insertRows(U, hom, nv, p, u);
        HPoints rows;
        Curve::cutRows(U, hom, nv, p, u, keepRight, out, rows);
        hom = std::move(rows);
        k = Knots(std::move(out), p, "NurbsCurve::split");
    }

    /// The surface whose column j is cols[j] (all on one knot vector in u), knots kv in v.
    static NurbsSurface fromCurvesU(const std::vector<NurbsCurve<Scalar, Dim>>& cols, const Knots& kv)
    {
        const int nu = cols.front().controlCount(), nv = static_cast<int>(cols.size());
        HPoints h(Dim + 1, nu * nv);
        for (int i = 0; i < nu; ++i)
            for (int j = 0; j < nv; ++j) h.col(i * nv + j) = cols[static_cast<std::size_t>(j)].homogeneousPoints().col(i);
        return NurbsSurface(cols.front().knotVector(), kv, std::move(h));
    }

    Knots ku_, kv_;
    HPoints hom_;
    bool rational_ = false;
};

extern template class NurbsSurface<double, 3>;
#ifndef FREEFORM_DOUBLE_ONLY_INSTANTIATIONS // float and long double (docs/development.md)
extern template class NurbsSurface<float, 3>;
extern template class NurbsSurface<long double, 3>;
#endif

} // namespace freeform
