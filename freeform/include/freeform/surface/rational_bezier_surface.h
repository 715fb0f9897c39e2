#pragma once
// RationalBezierSurface<Scalar, Dim>: the tensor-product patch
//     f(u, v) = sum w_ij b_ij B_i^m(u) B_j^n(v) / sum w_ij B_i^m(u) B_j^n(v),   (u, v) in [0, 1]^2
// (docs/nurbs.md, "Rational patches"), stored as the polynomial BezierSurface of its homogeneous
// points (w b, w) in Dim + 1 coordinates. Points (i, j) at column i*(n+1) + j, as BezierSurface.
// Invariants (checked once, freeform::Error naming the point): finite coordinates, positive
// finite weights.
//
// Partial derivatives come from the homogeneous jet by Leibniz's rule in two variables (The NURBS
// Book, eq. 4.20): with A = w f,
//     f^(k,l) = (A^(k,l) - sum_(i,j) != (0,0), i<=k, j<=l  C(k,i) C(l,j) w^(i,j) f^(k-i,l-j)) / w.

#include <string>
#include <utility>

#include "freeform/surface/bezier_surface.h"

namespace freeform {

/// Homogeneous jet (columns by BezierSurface::jetIndex, Dim + 1 rows) to the rational jet.
template <typename Scalar, int Dim>
Eigen::Matrix<Scalar, Dim, Eigen::Dynamic> projectSurfaceJet(const Eigen::Matrix<Scalar, Dim + 1, Eigen::Dynamic>& h,
                                                             int order)
{
    auto idx = [](int a, int b) { return (a + b) * (a + b + 1) / 2 + b; };
    Eigen::Matrix<Scalar, Dim, Eigen::Dynamic> f(Dim, h.cols());
    const Scalar w = h(Dim, 0);
    for (int t = 0; t <= order; ++t)
        for (int l = 0; l <= t; ++l) {
            const int k = t - l;
            Point<Scalar, Dim> v = h.col(idx(k, l)).template head<Dim>();
            for (int i = 0; i <= k; ++i)
                for (int j = 0; j <= l; ++j) {
                    if (i == 0 && j == 0) continue;
                    v -= Scalar(binomial(k, i) * binomial(l, j)) * h(Dim, idx(i, j)) * f.col(idx(k - i, l - j));
                }
            f.col(idx(k, l)) = v / w;
        }
    return f;
}

template <typename Scalar, int Dim>
class RationalBezierSurface {
public:
    using PointType = Point<Scalar, Dim>;
    using Points = PointMatrix<Scalar, Dim>;
    using Weights = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
    using Homogeneous = BezierSurface<Scalar, Dim + 1>;
    using HPoints = PointMatrix<Scalar, Dim + 1>;
    using Jet = Eigen::Matrix<Scalar, Dim, Eigen::Dynamic>;

    /// Degrees m, n; points Dim x (m+1)(n+1) and as many positive weights.
    RationalBezierSurface(int m, int n, const Points& points, const Weights& weights)
        : hom_(m, n, homogeneousFrom(m, n, points, weights))
    {
    }

    /// From a homogeneous patch (every weight positive).
    explicit RationalBezierSurface(Homogeneous hom) : hom_(std::move(hom))
    {
        const HPoints& h = hom_.controlPoints();
        for (Eigen::Index i = 0; i < h.cols(); ++i)
            if (!(h(Dim, i) > Scalar(0)))
                throw Error("RationalBezierSurface: weight " + std::to_string(i) + " is not positive");
    }

    /// The polynomial patch with all weights 1.
    explicit RationalBezierSurface(const BezierSurface<Scalar, Dim>& s)
        : RationalBezierSurface(s.degreeU(), s.degreeV(), s.controlPoints(), Weights::Ones(s.controlPoints().cols()))
    {
    }

    int degreeU() const { return hom_.degreeU(); }
    int degreeV() const { return hom_.degreeV(); }
    const Homogeneous& homogeneous() const { return hom_; }
    Scalar weight(int i, int j) const { return hom_.controlPoint(i, j)[Dim]; }
    PointType controlPoint(int i, int j) const
    {
        const Point<Scalar, Dim + 1> h = hom_.controlPoint(i, j);
        return h.template head<Dim>() / h[Dim];
    }

    PointType evaluate(Scalar u, Scalar v) const
    {
        const Point<Scalar, Dim + 1> h = hom_.evaluate(u, v);
        return h.template head<Dim>() / h[Dim];
    }
    PointType operator()(Scalar u, Scalar v) const { return evaluate(u, v); }

    /// Position and every partial derivative of total order <= order (columns by
    /// BezierSurface::jetIndex).
    Jet jet(Scalar u, Scalar v, int order) const
    {
        return projectSurfaceJet<Scalar, Dim>(hom_.jet(u, v, order), order);
    }

    /// Unit normal f_u x f_v / |f_u x f_v| (3D); zero where the partials are parallel.
    PointType normal(Scalar u, Scalar v) const
        requires(Dim == 3)
    {
        const Jet d = jet(u, v, 1);
        const PointType c = PointType(d.col(1)).cross(PointType(d.col(2)));
        const Scalar len = c.norm();
        return len > Scalar(0) ? PointType(c / len) : PointType::Zero();
    }

    /// (Inside [0, 1] the pieces' weights are convex combinations of positive ones: not checked
    /// again. Outside, extrapolated, they are.)
    std::pair<RationalBezierSurface, RationalBezierSurface> splitU(Scalar t) const
    {
        auto [a, b] = hom_.splitU(t);
        if (!(t >= Scalar(0) && t <= Scalar(1))) return {RationalBezierSurface(std::move(a)), RationalBezierSurface(std::move(b))};
        return {RationalBezierSurface(std::move(a), Unchecked{}), RationalBezierSurface(std::move(b), Unchecked{})};
    }
    std::pair<RationalBezierSurface, RationalBezierSurface> splitV(Scalar t) const
    {
        auto [a, b] = hom_.splitV(t);
        if (!(t >= Scalar(0) && t <= Scalar(1))) return {RationalBezierSurface(std::move(a)), RationalBezierSurface(std::move(b))};
        return {RationalBezierSurface(std::move(a), Unchecked{}), RationalBezierSurface(std::move(b), Unchecked{})};
    }
    /// BezierSurface::pieceU and pieceV on the homogeneous net (0 <= a < b <= 1, unchecked).
    RationalBezierSurface pieceU(Scalar a, Scalar b) const { return RationalBezierSurface(hom_.pieceU(a, b), Unchecked{}); }
    RationalBezierSurface pieceV(Scalar a, Scalar b) const { return RationalBezierSurface(hom_.pieceV(a, b), Unchecked{}); }
    /// BezierSurface::splitOffU and splitOffV on the homogeneous net (0 <= t <= 1): splitU(t)'s
    /// pieces to the bit, the first into `left` and the second in place of this patch.
    void splitOffU(Scalar t, RationalBezierSurface& left) { hom_.splitOffU(t, left.hom_); }
    void splitOffV(Scalar t, RationalBezierSurface& left) { hom_.splitOffV(t, left.hom_); }
    /// pieceU and pieceV written into `out` (its storage kept where it has this net's size).
    void pieceUInto(Scalar a, Scalar b, RationalBezierSurface& out) const { hom_.pieceUInto(a, b, out.hom_); }
    void pieceVInto(Scalar a, Scalar b, RationalBezierSurface& out) const { hom_.pieceVInto(a, b, out.hom_); }
    RationalBezierSurface elevatedU(int times = 1) const { return RationalBezierSurface(hom_.elevatedU(times)); }
    RationalBezierSurface elevatedV(int times = 1) const { return RationalBezierSurface(hom_.elevatedV(times)); }
    RationalBezierSurface transposed() const { return RationalBezierSurface(hom_.transposed()); }

    /// Box of the control points (contains the patch: weights are positive).
    Box<Scalar, Dim> controlBox() const
    {
        Box<Scalar, Dim> box(controlPoint(0, 0));
        for (int i = 0; i <= degreeU(); ++i)
            for (int j = 0; j <= degreeV(); ++j) box.extend(controlPoint(i, j));
        return box;
    }

private:
    struct Unchecked {};
    RationalBezierSurface(Homogeneous hom, Unchecked) : hom_(std::move(hom)) {}

    static HPoints homogeneousFrom(int m, int n, const Points& points, const Weights& weights)
    {
        const Eigen::Index expected = static_cast<Eigen::Index>(m + 1) * (n + 1);
        if (points.cols() != expected || weights.size() != expected)
            throw Error("RationalBezierSurface: degree (" + std::to_string(m) + ", " + std::to_string(n) + ") needs " +
                        std::to_string(expected) + " control points and weights, found " +
                        std::to_string(points.cols()) + " and " + std::to_string(weights.size()));
        requireFinite(points, "RationalBezierSurface");
        HPoints h(Dim + 1, expected);
        for (Eigen::Index i = 0; i < expected; ++i) {
            if (!(weights[i] > Scalar(0)) || !std::isfinite(static_cast<long double>(weights[i])))
                throw Error("RationalBezierSurface: weight " + std::to_string(i) + " is not a positive finite number");
            h.col(i).template head<Dim>() = weights[i] * points.col(i);
            h(Dim, i) = weights[i];
        }
        return h;
    }

    Homogeneous hom_;
};

extern template class RationalBezierSurface<double, 3>;
#ifndef FREEFORM_DOUBLE_ONLY_INSTANTIATIONS // float and long double (docs/development.md)
extern template class RationalBezierSurface<float, 3>;
extern template class RationalBezierSurface<long double, 3>;
#endif

} // namespace freeform
