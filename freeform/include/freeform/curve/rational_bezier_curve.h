#pragma once
// RationalBezierCurve<Scalar, Dim>: f(t) = sum w_i b_i B_i^n(t) / sum w_i B_i^n(t), t in [0, 1]
// (docs/nurbs.md, "Rational Bézier curves").
//
// Stored as the polynomial Bézier curve of its homogeneous points (w_i b_i, w_i) in Dim + 1
// coordinates, so every polynomial algorithm (de Casteljau, split, elevation, hodograph) runs on
// the homogeneous curve and the rational curve is its central projection. Invariants: at least one
// control point, finite coordinates, every weight positive and finite (checked once, in the
// constructor, with freeform::Error naming the point).
//
// Derivatives of any order come from the homogeneous derivatives A^(k) and w^(k) by Leibniz's rule
// on A = w f:  f^(k) = (A^(k) - sum_(i=1..k) C(k,i) w^(i) f^(k-i)) / w.
//
// Conics: ellipseArc()/circleArc() are exact arcs of any sweep up to 180 degrees in one segment
// (quadratic up to 120 degrees, where the middle weight cos(sweep/2) >= 1/2; the degree-elevated
// cubic with positive weights beyond, up to and including the half circle, whose quadratic would
// need the weight 0).

#include <cmath>
#include <numbers>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "freeform/curve/bezier_curve.h"

namespace freeform {

template <typename Scalar, int Dim>
class RationalBezierCurve {
public:
    using PointType = Point<Scalar, Dim>;
    using Points = PointMatrix<Scalar, Dim>;
    using Weights = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
    using Homogeneous = BezierCurve<Scalar, Dim + 1>;
    using HPoints = PointMatrix<Scalar, Dim + 1>;

    /// Control points (Dim x (n+1)) and their weights (n+1 positive values).
    RationalBezierCurve(const Points& points, const Weights& weights)
        : hom_(makeHomogeneous(points, weights, "RationalBezierCurve"))
    {
    }

    /// From homogeneous points (w b, w) as columns; every w must be positive.
    explicit RationalBezierCurve(Homogeneous hom) : hom_(std::move(hom))
    {
        const HPoints& h = hom_.controlPoints();
        for (Eigen::Index i = 0; i < h.cols(); ++i)
            if (!(h(Dim, i) > Scalar(0)))
                throw Error("RationalBezierCurve: weight " + std::to_string(i) + " is not positive");
    }

    /// The polynomial curve as a rational one (all weights 1).
    explicit RationalBezierCurve(const BezierCurve<Scalar, Dim>& curve)
        : RationalBezierCurve(curve.controlPoints(), Weights::Ones(curve.controlPoints().cols()))
    {
    }

    int degree() const { return hom_.degree(); }
    const Homogeneous& homogeneous() const { return hom_; }
    Scalar weight(int i) const { return hom_.controlPoints()(Dim, i); }
    Weights weights() const { return hom_.controlPoints().row(Dim).transpose(); }
    PointType controlPoint(int i) const { return hom_.controlPoints().col(i).template head<Dim>() / weight(i); }
    Points controlPoints() const
    {
        Points p(Dim, hom_.controlPoints().cols());
        for (Eigen::Index i = 0; i < p.cols(); ++i) p.col(i) = controlPoint(static_cast<int>(i));
        return p;
    }

    /// f(t) by de Casteljau on the homogeneous points and one division, carried out in long double
    /// for float and double and rounded once (docs/nurbs.md, "Accuracy of points"): the point is then
    /// the stored representation's exact value to about half an ulp, where plain double de Casteljau
    /// loses a few ulps (a circle's points drift 1.2e-15 of the radius off it at worst, 5e-16 here).
    PointType evaluate(Scalar t) const
    {
        using Wide = std::conditional_t<std::is_floating_point_v<Scalar> && sizeof(Scalar) <= sizeof(double),
                                        long double, Scalar>;
        const HPoints& h = hom_.controlPoints();
        const int n = static_cast<int>(h.cols()) - 1;
        Wide b[kMaxDegree + 1][Dim + 1];
        for (int c = 0; c <= Dim; ++c) b[0][c] = static_cast<Wide>(h(c, 0)); // n >= 0: never empty
        for (int i = 1; i <= n; ++i)
            for (int c = 0; c <= Dim; ++c) b[i][c] = static_cast<Wide>(h(c, i));
        const Wide tt = static_cast<Wide>(t), s = Wide(1) - tt;
        for (int k = 1; k <= n; ++k)
            for (int i = 0; i <= n - k; ++i)
                for (int c = 0; c <= Dim; ++c) b[i][c] = s * b[i][c] + tt * b[i + 1][c];
        PointType p;
        for (int c = 0; c < Dim; ++c) p[c] = static_cast<Scalar>(b[0][c] / b[0][Dim]);
        return p;
    }
    PointType operator()(Scalar t) const { return evaluate(t); }

    /// f at every t in ts (Dim x count, resized): the polynomial batch path on the homogeneous
    /// curve, then one division per point.
    void evaluateMany(const Scalar* ts, std::size_t count, Points& out) const
    {
        HPoints h;
        hom_.evaluateMany(ts, count, h);
        out.resize(Dim, static_cast<Eigen::Index>(count));
        for (Eigen::Index j = 0; j < h.cols(); ++j) out.col(j) = h.col(j).template head<Dim>() / h(Dim, j);
    }

    /// Column j is f^(j)(t), j = 0..k (Leibniz on the homogeneous derivatives).
    Eigen::Matrix<Scalar, Dim, Eigen::Dynamic> derivatives(Scalar t, int k) const
    {
        if (k < 0) throw Error("RationalBezierCurve::derivatives: order " + std::to_string(k) + " is negative");
        return projectDerivatives<Scalar, Dim>(hom_.derivatives(t, k));
    }

    /// The pieces over [0, t] and [t, 1] (homogeneous de Casteljau).
    std::pair<RationalBezierCurve, RationalBezierCurve> split(Scalar t) const
    {
        auto [a, b] = hom_.split(t);
        return {RationalBezierCurve(std::move(a)), RationalBezierCurve(std::move(b))};
    }

    /// The same curve of degree n + times (elevation of the homogeneous curve).
    RationalBezierCurve elevated(int times = 1) const { return RationalBezierCurve(hom_.elevated(times)); }

    RationalBezierCurve reversed() const { return RationalBezierCurve(hom_.reversed()); }

    /// The same curve with w_0 = w_n = 1 (standard form): the Möbius reparametrisation
    /// t = c s / ((1 - s) + c s) scales w_i by c^i; c = (w_0 / w_n)^(1/n), then all weights by 1/w_0.
    /// The point set is unchanged; the parametrisation changes unless w_0 = w_n already.
    RationalBezierCurve standardForm() const
    {
        const int n = degree();
        HPoints h = hom_.controlPoints();
        if (n == 0) return RationalBezierCurve(Homogeneous(HPoints(h / h(Dim, 0))));
        const Scalar c = std::pow(h(Dim, 0) / h(Dim, n), Scalar(1) / Scalar(n));
        Scalar f = Scalar(1) / h(Dim, 0);
        for (int i = 0; i <= n; ++i) {
            h.col(i) *= f;
            f *= c;
        }
        h(Dim, 0) = Scalar(1);
        h(Dim, n) = Scalar(1);
        return RationalBezierCurve(Homogeneous(std::move(h)));
    }

    /// Unit tangent (zero where f' vanishes).
    PointType tangent(Scalar t) const
    {
        const PointType d = derivatives(t, 1).col(1);
        const Scalar len = d.norm();
        return len > Scalar(0) ? PointType(d / len) : PointType::Zero();
    }

    /// Arc length over [a, b] to the absolute tolerance.
    Scalar arcLength(Scalar tolerance = Scalar(1e-10), Scalar a = Scalar(0), Scalar b = Scalar(1)) const
    {
        return integrate<Scalar>([&](Scalar t) { return derivatives(t, 1).col(1).norm(); }, a, b, tolerance);
    }

    /// Bounding box of the control points (contains the curve: convex hull property, weights > 0).
    Box<Scalar, Dim> controlBox() const
    {
        Box<Scalar, Dim> box(controlPoint(0));
        for (int i = 1; i <= degree(); ++i) box.extend(controlPoint(i));
        return box;
    }

    /// Exact elliptic arc c + cos(theta) a + sin(theta) b for theta from `start` over `sweep`
    /// (radians, |sweep| <= pi, sign = direction). Quadratic for |sweep| <= 2 pi / 3, cubic beyond.
    static RationalBezierCurve ellipseArc(const PointType& c, const PointType& a, const PointType& b, Scalar start,
                                          Scalar sweep)
    {
        const Scalar pi = std::numbers::pi_v<Scalar>;
        if (!(std::abs(sweep) <= pi) || sweep == Scalar(0))
            throw Error("RationalBezierCurve::ellipseArc: sweep " + std::to_string(static_cast<long double>(sweep)) +
                        " is not in [-pi, pi] \\ {0}");
        const Scalar half = sweep / 2, mid = start + half;
        const Scalar w = std::cos(half);
        auto at = [&](Scalar angle, Scalar scale) -> PointType {
            return c + scale * (std::cos(angle) * a + std::sin(angle) * b);
        };
        // Homogeneous quadratic: (p0, 1), (w * apex, w) with w * apex = w c + (cos mid a + sin mid b).
        HPoints h(Dim + 1, 3);
        h.col(0).template head<Dim>() = at(start, 1);
        h.col(1).template head<Dim>() = w * c + (std::cos(mid) * a + std::sin(mid) * b);
        h.col(2).template head<Dim>() = at(start + sweep, 1);
        h(Dim, 0) = Scalar(1);
        h(Dim, 1) = w;
        h(Dim, 2) = Scalar(1);
        const Homogeneous quad(std::move(h));
        if (std::abs(sweep) <= 2 * pi / 3) return RationalBezierCurve(std::move(quad));
        return RationalBezierCurve(quad.elevated(1));
    }

    /// Exact circular arc in the plane of the first two coordinates (Dim >= 2).
    static RationalBezierCurve circleArc(const PointType& c, Scalar radius, Scalar start, Scalar sweep)
    {
        static_assert(Dim >= 2, "circleArc needs at least two dimensions");
        PointType a = PointType::Zero(), b = PointType::Zero();
        a[0] = radius;
        b[1] = radius;
        return ellipseArc(c, a, b, start, sweep);
    }

private:
    static Homogeneous makeHomogeneous(const Points& points, const Weights& weights, std::string_view what)
    {
        if (points.cols() < 1) throw Error(std::string(what) + ": needs at least one control point");
        if (weights.size() != points.cols())
            throw Error(std::string(what) + ": " + std::to_string(weights.size()) + " weights for " + std::to_string(points.cols()) +
                        " control points");
        requireFinite(points, what);
        HPoints h(Dim + 1, points.cols());
        for (Eigen::Index i = 0; i < points.cols(); ++i) {
            if (!(weights[i] > Scalar(0)) || !std::isfinite(static_cast<long double>(weights[i])))
                throw Error(std::string(what) + ": weight " + std::to_string(i) + " is not a positive finite number");
            h.col(i).template head<Dim>() = weights[i] * points.col(i);
            h(Dim, i) = weights[i];
        }
        return Homogeneous(std::move(h));
    }

    Homogeneous hom_;

public:
    /// Columns j = 0..k of homogeneous derivatives (A^(j), w^(j)) to the rational derivatives
    /// f^(j) (Leibniz: f^(j) = (A^(j) - sum_(i=1..j) C(j,i) w^(i) f^(j-i)) / w).
    template <typename S, int D>
    static Eigen::Matrix<S, D, Eigen::Dynamic> projectDerivatives(const Eigen::Matrix<S, D + 1, Eigen::Dynamic>& h)
    {
        const Eigen::Index k = h.cols() - 1;
        Eigen::Matrix<S, D, Eigen::Dynamic> f(D, k + 1);
        const S w = h(D, 0);
        for (Eigen::Index j = 0; j <= k; ++j) {
            Point<S, D> v = h.col(j).template head<D>();
            for (Eigen::Index i = 1; i <= j; ++i)
                v -= S(binomialWide(static_cast<int>(j), static_cast<int>(i))) * h(D, i) * f.col(j - i);
            f.col(j) = v / w;
        }
        return f;
    }
};

extern template class RationalBezierCurve<double, 2>;
extern template class RationalBezierCurve<double, 3>;
#ifndef FREEFORM_DOUBLE_ONLY_INSTANTIATIONS // float and long double (docs/development.md)
extern template class RationalBezierCurve<float, 2>;
extern template class RationalBezierCurve<float, 3>;
extern template class RationalBezierCurve<long double, 2>;
extern template class RationalBezierCurve<long double, 3>;
#endif

} // namespace freeform
