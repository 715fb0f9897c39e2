#pragma once
// Global interpolation and least-squares approximation by NURBS curves of any degree
// (docs/nurbs.md, "Interpolation and approximation"; The NURBS Book, sections 9.2 and 9.4).
//
// Parameters ū_k of the data points: uniform, chord length or centripetal (the Parametrization
// of curve/interpolation.h), or given; all normalised to [0, 1].
//   - interpolateNurbs(): n+1 points, degree p <= n. Without end derivatives the knots are the
//     averages of p consecutive parameters (u_(j+p) = (ū_j + ... + ū_(j+p-1)) / p, j = 1..n-p), which
//     satisfies the Schoenberg-Whitney condition, so the collocation matrix is non-singular. With
//     both end derivatives (p >= 3; derivatives with respect to the normalised parameter) there are
//     n+3 control points and the interior knots are the averages of p-2 consecutive parameters
//     ū_1..ū_(n-1): for p = 3 exactly the data parameters, which is the clamped C2 cubic spline of
//     interpolateCubic() (curve/interpolation.h).
//   - approximateNurbs(): m+1 points by n+1 < m+1 control points; the end points are interpolated
//     and the interior control points minimise sum |C(ū_k) - Q_k|^2 (QR on the collocation
//     matrix, not the normal equations); knots by the spread-out averaging of (9.68)-(9.69).
// The systems are solved densely (LU with partial pivoting / column-pivoted QR): O(n^3), meant for
// the hundreds of points of a design curve. Errors (freeform::Error) name the point or option.
// A degree-p interpolant reproduces any polynomial curve of degree <= p sampled at its parameters.

#include <optional>
#include <string>
#include <vector>

#include "freeform/curve/interpolation.h"
#include "freeform/curve/least_squares.h"
#include "freeform/curve/nurbs_curve.h"

namespace freeform {

template <typename Scalar, int Dim>
struct NurbsFitOptions {
    Parametrization parametrization = Parametrization::Chord;
    /// Given parameters (strictly increasing, one per point), normalised to [0, 1]; overrides
    /// `parametrization`.
    std::vector<Scalar> params;
    /// Interpolation only: C'(0) and C'(1) with respect to the normalised parameter (both or neither).
    std::optional<Point<Scalar, Dim>> startDerivative, endDerivative;
};

namespace detail {

/// ū_k in [0, 1] for the points under the options (Error names the offending points).
template <typename Scalar, int Dim>
std::vector<Scalar> fitParameters(const PointMatrix<Scalar, Dim>& points, const NurbsFitOptions<Scalar, Dim>& options,
                                  const std::string& what)
{
    const Eigen::Index count = points.cols();
    std::vector<Scalar> u(static_cast<std::size_t>(count));
    if (!options.params.empty()) {
        if (static_cast<Eigen::Index>(options.params.size()) != count)
            throw Error(what + ": " + std::to_string(options.params.size()) + " parameters for " +
                        std::to_string(count) + " points");
        for (Eigen::Index i = 1; i < count; ++i)
            if (!(options.params[i] > options.params[i - 1]) || !std::isfinite(static_cast<long double>(options.params[i])))
                throw Error(what + ": parameters " + std::to_string(i - 1) + " and " + std::to_string(i) +
                            " are not strictly increasing and finite");
        for (Eigen::Index i = 0; i < count; ++i)
            u[i] = (options.params[i] - options.params.front()) / (options.params.back() - options.params.front());
    } else {
        const std::vector<Scalar> h = parameterGaps<Scalar, Dim>(points, options.parametrization, false);
        Scalar total(0);
        for (Scalar x : h) total += x;
        u[0] = Scalar(0);
        Scalar run(0);
        for (Eigen::Index i = 1; i < count; ++i) {
            run += h[i - 1];
            u[i] = run / total;
        }
    }
    u.back() = Scalar(1);
    return u;
}

/// Row of the collocation matrix: the derivative of order `order` of every basis function at u.
template <typename Scalar>
void collocationRow(const KnotVector<Scalar>& kv, Scalar u, int order, Scalar* row)
{
    const int p = kv.degree();
    const int span = kv.findSpan(u);
    std::vector<Scalar> ders(static_cast<std::size_t>((order + 1) * (p + 1)));
    kv.basisDerivatives(span, u, order, ders.data());
    for (int i = 0; i < kv.controlCount(); ++i) row[i] = Scalar(0);
    for (int j = 0; j <= p; ++j) row[span - p + j] = ders[static_cast<std::size_t>(order * (p + 1) + j)];
}

} // namespace detail

/// The degree-p B-spline curve through every column of `points` (see the header comment).
template <typename Scalar, int Dim>
NurbsCurve<Scalar, Dim> interpolateNurbs(const PointMatrix<Scalar, Dim>& points, int degree,
                                         const NurbsFitOptions<Scalar, Dim>& options = {})
{
    const std::string what = "interpolateNurbs";
    requireDegree(degree, what);
    requireFinite(points, what);
    const int n = static_cast<int>(points.cols()) - 1;
    const bool ends = options.startDerivative.has_value() || options.endDerivative.has_value();
    if (ends && !(options.startDerivative && options.endDerivative))
        throw Error(what + ": give both end derivatives or neither");
    if (degree < 1) throw Error(what + ": degree must be at least 1");
    if (ends && degree < 3) throw Error(what + ": end derivatives need degree 3 or more");
    if (n < (ends ? 1 : degree))
        throw Error(what + ": " + std::to_string(n + 1) + " points are too few for degree " + std::to_string(degree));
    const std::vector<Scalar> ub = detail::fitParameters<Scalar, Dim>(points, options, what);
    const int p = degree;
    const int count = ends ? n + 3 : n + 1;
    std::vector<Scalar> knots(static_cast<std::size_t>(p + 1), Scalar(0));
    if (!ends) {
        for (int j = 1; j <= n - p; ++j) {
            Scalar s(0);
            for (int i = j; i < j + p; ++i) s += ub[i];
            knots.push_back(s / Scalar(p));
        }
    } else {
        const int window = p - 2;
        for (int j = 1; j + window - 1 <= n - 1; ++j) {
            Scalar s(0);
            for (int i = j; i < j + window; ++i) s += ub[i];
            knots.push_back(s / Scalar(window));
        }
    }
    knots.resize(knots.size() + static_cast<std::size_t>(p + 1), Scalar(1));
    const KnotVector<Scalar> kv(knots, p, what);
    if (kv.controlCount() != count) throw Error(what + ": internal knot count mismatch");
    using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
    Matrix a = Matrix::Zero(count, count), rhs(count, Dim);
    std::vector<Scalar> row(static_cast<std::size_t>(count));
    int r = 0;
    auto addRow = [&](Scalar u, int order, const Point<Scalar, Dim>& value) {
        detail::collocationRow(kv, u, order, row.data());
        for (int i = 0; i < count; ++i) a(r, i) = row[i];
        rhs.row(r) = value.transpose();
        ++r;
    };
    addRow(ub[0], 0, points.col(0));
    if (ends) addRow(Scalar(0), 1, *options.startDerivative);
    for (int k = 1; k < n; ++k) addRow(ub[k], 0, points.col(k));
    if (ends) addRow(Scalar(1), 1, *options.endDerivative);
    addRow(ub[n], 0, points.col(n));
    const Matrix x = detail::linearSolve<Scalar>(a, rhs);
    PointMatrix<Scalar, Dim> ctrl = x.transpose();
    requireFinite(ctrl, what + " (singular system)");
    return NurbsCurve<Scalar, Dim>(p, kv.knots(), ctrl);
}

/// The degree-p B-spline with `controlCount` control points closest in least squares to the
/// columns of `points`, through the first and the last (see the header comment).
template <typename Scalar, int Dim>
NurbsCurve<Scalar, Dim> approximateNurbs(const PointMatrix<Scalar, Dim>& points, int degree, int controlCount,
                                         const NurbsFitOptions<Scalar, Dim>& options = {})
{
    const std::string what = "approximateNurbs";
    requireDegree(degree, what);
    requireFinite(points, what);
    const int m = static_cast<int>(points.cols()) - 1, n = controlCount - 1, p = degree;
    if (p < 1) throw Error(what + ": degree must be at least 1");
    if (n < p || n >= m)
        throw Error(what + ": " + std::to_string(controlCount) + " control points for " + std::to_string(m + 1) +
                    " points of degree " + std::to_string(p) + " (needs degree + 1 <= control points < points)");
    if (options.startDerivative || options.endDerivative)
        throw Error(what + ": end derivatives are for interpolation only");
    const std::vector<Scalar> ub = detail::fitParameters<Scalar, Dim>(points, options, what);
    std::vector<Scalar> knots(static_cast<std::size_t>(p + 1), Scalar(0));
    const Scalar d = Scalar(m + 1) / Scalar(n - p + 1);
    for (int j = 1; j <= n - p; ++j) {
        const Scalar jd = Scalar(j) * d;
        const int i = static_cast<int>(jd);
        const Scalar alpha = jd - Scalar(i);
        knots.push_back((Scalar(1) - alpha) * ub[i - 1] + alpha * ub[i]);
    }
    knots.resize(knots.size() + static_cast<std::size_t>(p + 1), Scalar(1));
    const KnotVector<Scalar> kv(knots, p, what);
    using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
    // Unknowns P_1..P_(n-1); rows k = 1..m-1; the fixed ends move to the right-hand side.
    Matrix a(m - 1, std::max(n - 1, 0)), rhs(m - 1, Dim);
    std::vector<Scalar> row(static_cast<std::size_t>(n + 1));
    for (int k = 1; k < m; ++k) {
        detail::collocationRow(kv, ub[k], 0, row.data());
        for (int i = 1; i < n; ++i) a(k - 1, i - 1) = row[i];
        rhs.row(k - 1) = (points.col(k) - row[0] * points.col(0) - row[n] * points.col(m)).transpose();
    }
    PointMatrix<Scalar, Dim> ctrl(Dim, n + 1);
    ctrl.col(0) = points.col(0);
    ctrl.col(n) = points.col(m);
    if (n >= 2) ctrl.middleCols(1, n - 1) = detail::leastSquaresSolve<Scalar, Eigen::Dynamic>(a, rhs).transpose();
    requireFinite(ctrl, what + " (singular system)");
    return NurbsCurve<Scalar, Dim>(p, kv.knots(), ctrl);
}

} // namespace freeform
