#pragma once
// C2 cubic spline interpolation through points, in O(n) (docs/splines.md, "Interpolation").
//
// The unknowns are the derivatives m_i = f'(u_i) at the points; C2 at every inner point gives the
// tridiagonal rows
//     h_i m_(i-1) + 2 (h_(i-1) + h_i) m_i + h_(i-1) m_(i+1) = 3 (h_i d_(i-1) + h_(i-1) d_i),
// with h_i = u_(i+1) - u_i and d_i = (p_(i+1) - p_i) / h_i, closed by the end condition:
//   - Natural: f'' = 0 at both ends (2 m_0 + m_1 = 3 d_0, m_(N-1) + 2 m_N = 3 d_(N-1));
//   - Clamped: m_0 and m_N given (derivatives with respect to the parameter u);
//   - Periodic: the rows wrap around (a cyclic system): the curve closes C2 at p_0.
// The matrix is strictly diagonally dominant, so the Thomas algorithm (no pivoting) is stable and
// the cyclic system is solved by Sherman-Morrison with two Thomas sweeps. Segment i of the result
// is the cubic Hermite piece b_0 = p_i, b_1 = p_i + h_i m_i / 3, b_2 = p_(i+1) - h_i m_(i+1) / 3,
// b_3 = p_(i+1) on an interval of length h_i.
//
// Guarantees: the spline passes through every point exactly (the points are copied as joints), is
// C2 at every inner joint (and at the closing joint when periodic) up to rounding, and reproduces a
// cubic polynomial exactly when sampled at its own parameters with clamped ends given its end
// derivatives. Errors (freeform::Error) name the point or parameter that is wrong.

#include <cmath>
#include <string>
#include <vector>

#include "freeform/core/error.h"
#include "freeform/core/types.h"
#include "freeform/curve/bezier_spline.h"

namespace freeform {

enum class InterpolationEnd { Natural, Clamped, Periodic };
enum class Parametrization { Uniform, Chord, Centripetal };

/// "natural" | "clamped" | "periodic"; Error naming `what` otherwise.
InterpolationEnd parseInterpolationEnd(const std::string& text, const std::string& what);
std::string toString(InterpolationEnd end);
/// "uniform" | "chord" | "centripetal"; Error naming `what` otherwise.
Parametrization parseParametrization(const std::string& text, const std::string& what);
std::string toString(Parametrization param);

template <typename Scalar, int Dim>
struct InterpolationOptions {
    InterpolationEnd end = InterpolationEnd::Natural;
    Parametrization parametrization = Parametrization::Chord;
    /// Given parameter values (strictly increasing) instead of `parametrization`: one per point, and
    /// for Periodic one more, where the curve returns to the first point. Shifted to start at 0.
    std::vector<Scalar> params;
    /// f'(u) at the first and last point, for Clamped.
    Point<Scalar, Dim> startDerivative = Point<Scalar, Dim>::Zero();
    Point<Scalar, Dim> endDerivative = Point<Scalar, Dim>::Zero();
};

/// Solves the tridiagonal system sub[i] x[i-1] + diag[i] x[i] + super[i] x[i+1] = rhs.col(i)
/// (sub[0] and super[n-1] unused) in place of rhs, by the Thomas algorithm; `scratch` needs n
/// values. No pivoting: meant for diagonally dominant systems. rhs has one column per unknown.
template <typename Scalar, typename Rhs>
void solveTridiagonal(const Scalar* sub, const Scalar* diag, const Scalar* super, Rhs& rhs, Scalar* scratch)
{
    const Eigen::Index n = rhs.cols();
    if (n == 0) return;
    Scalar beta = diag[0];
    rhs.col(0) /= beta;
    for (Eigen::Index i = 1; i < n; ++i) {
        scratch[i] = super[i - 1] / beta;
        beta = diag[i] - sub[i] * scratch[i];
        rhs.col(i) = (rhs.col(i) - sub[i] * rhs.col(i - 1)) / beta;
    }
    for (Eigen::Index i = n - 2; i >= 0; --i) rhs.col(i) -= scratch[i + 1] * rhs.col(i + 1);
}

/// The cyclic system: as solveTridiagonal with the corners sub[0] (row 0, column n-1) and
/// super[n-1] (row n-1, column 0); n >= 3. Sherman-Morrison: two Thomas sweeps.
template <typename Scalar, typename Rhs>
void solveCyclicTridiagonal(const Scalar* sub, const Scalar* diag, const Scalar* super, Rhs& rhs)
{
    const Eigen::Index n = rhs.cols();
    const Scalar alpha = super[n - 1], beta = sub[0]; // bottom-left, top-right
    const Scalar gamma = -diag[0];
    std::vector<Scalar> d(diag, diag + n), scratch(static_cast<std::size_t>(n));
    d[0] = diag[0] - gamma;
    d[n - 1] = diag[n - 1] - alpha * beta / gamma;
    solveTridiagonal(sub, d.data(), super, rhs, scratch.data());
    Eigen::Matrix<Scalar, 1, Eigen::Dynamic> z = Eigen::Matrix<Scalar, 1, Eigen::Dynamic>::Zero(n);
    z(0) = gamma;
    z(n - 1) = alpha;
    solveTridiagonal(sub, d.data(), super, z, scratch.data());
    const auto factor = ((rhs.col(0) + (beta / gamma) * rhs.col(n - 1)) / (Scalar(1) + z(0) + beta * z(n - 1) / gamma)).eval();
    for (Eigen::Index i = 0; i < n; ++i) rhs.col(i) -= z(i) * factor;
}

/// Parameter gaps h_i of the points under a parametrization: count-1 gaps, and for `closed` one
/// more from the last point back to the first. Error when a chord or centripetal gap is 0
/// (coincident consecutive points).
template <typename Scalar, int Dim>
std::vector<Scalar> parameterGaps(const PointMatrix<Scalar, Dim>& points, Parametrization param, bool closed)
{
    const Eigen::Index count = points.cols();
    const Eigen::Index gaps = closed ? count : count - 1;
    std::vector<Scalar> h(static_cast<std::size_t>(std::max<Eigen::Index>(gaps, 0)));
    for (Eigen::Index i = 0; i < gaps; ++i) {
        if (param == Parametrization::Uniform) {
            h[i] = Scalar(1);
            continue;
        }
        const Eigen::Index j = (i + 1) % count;
        const Scalar chord = (points.col(j) - points.col(i)).norm();
        if (!(chord > Scalar(0)))
            throw Error("interpolation: points " + std::to_string(i) + " and " + std::to_string(j) +
                        " coincide, so the " + toString(param) + " parameter gap is 0");
        h[i] = param == Parametrization::Chord ? chord : std::sqrt(chord);
    }
    return h;
}

/// The C2 cubic spline through the columns of `points` (see the header comment). Open for Natural
/// and Clamped (N+1 points, N segments), closed for Periodic (a last point equal to the first is
/// dropped; N distinct points, N segments). The intervals of the result are the parameter gaps.
template <typename Scalar, int Dim>
BezierSpline<Scalar, Dim> interpolateCubic(const PointMatrix<Scalar, Dim>& input,
                                           const InterpolationOptions<Scalar, Dim>& options = {})
{
    requireFinite(input, "interpolation");
    const bool periodic = options.end == InterpolationEnd::Periodic;
    Eigen::Index count = input.cols();
    if (periodic && count >= 2 && input.col(count - 1) == input.col(0)) --count;
    const PointMatrix<Scalar, Dim> points = input.leftCols(count);
    const Eigen::Index minimum = periodic ? 3 : 2;
    if (count < minimum)
        throw Error("interpolation: " + std::to_string(count) + (periodic ? " distinct" : "") + " points are too few for " +
                    toString(options.end) + " end conditions (needs at least " + std::to_string(minimum) + ")");

    std::vector<Scalar> h;
    if (!options.params.empty()) {
        const std::size_t expected = static_cast<std::size_t>(periodic ? count + 1 : count);
        if (options.params.size() != expected)
            throw Error("interpolation: " + std::to_string(options.params.size()) + " parameters for " +
                        std::to_string(count) + (periodic ? " distinct points of a periodic spline (needs one per point and one for the return to the first, " : " points (needs ") +
                        std::to_string(expected) + ")");
        h.resize(expected - 1);
        for (std::size_t i = 0; i + 1 < expected; ++i) {
            h[i] = options.params[i + 1] - options.params[i];
            if (!(h[i] > Scalar(0)) || !std::isfinite(static_cast<long double>(h[i])))
                throw Error("interpolation: parameters " + std::to_string(i) + " and " + std::to_string(i + 1) +
                            " are not strictly increasing and finite");
        }
    } else {
        h = parameterGaps<Scalar, Dim>(points, options.parametrization, periodic);
    }

    const Eigen::Index segments = periodic ? count : count - 1;
    const Eigen::Index unknowns = count; // m_0..m_N (open), m_0..m_(N-1) (periodic)
    std::vector<Scalar> sub(static_cast<std::size_t>(unknowns)), diag(sub.size()), super(sub.size());
    PointMatrix<Scalar, Dim> m(Dim, unknowns);
    auto slope = [&](Eigen::Index i) { // d_i
        const Eigen::Index j = i + 1 == count ? 0 : i + 1;
        return Point<Scalar, Dim>((points.col(j) - points.col(i)) / h[i]);
    };
    const Eigen::Index first = periodic ? 0 : 1, last = periodic ? count - 1 : count - 2;
    for (Eigen::Index i = first; i <= last; ++i) {
        const Eigen::Index prev = i == 0 ? segments - 1 : i - 1; // the interval before point i
        const Scalar hp = h[prev], hi = h[i];
        sub[i] = hi;
        diag[i] = Scalar(2) * (hp + hi);
        super[i] = hp;
        m.col(i) = Scalar(3) * (hi * slope(prev) + hp * slope(i));
    }
    if (periodic) {
        solveCyclicTridiagonal(sub.data(), diag.data(), super.data(), m);
    } else {
        const Eigen::Index N = count - 1;
        if (options.end == InterpolationEnd::Clamped) {
            diag[0] = Scalar(1), super[0] = Scalar(0), m.col(0) = options.startDerivative;
            diag[N] = Scalar(1), sub[N] = Scalar(0), m.col(N) = options.endDerivative;
            requireFinite(m.col(0), "interpolation: start derivative");
            requireFinite(m.col(N), "interpolation: end derivative");
        } else {
            diag[0] = Scalar(2), super[0] = Scalar(1), m.col(0) = Scalar(3) * slope(0);
            diag[N] = Scalar(2), sub[N] = Scalar(1), m.col(N) = Scalar(3) * slope(N - 1);
        }
        std::vector<Scalar> scratch(static_cast<std::size_t>(unknowns));
        solveTridiagonal(sub.data(), diag.data(), super.data(), m, scratch.data());
    }

    PointMatrix<Scalar, Dim> b(Dim, periodic ? 3 * segments : 3 * segments + 1);
    const Scalar third = Scalar(1) / Scalar(3);
    for (Eigen::Index i = 0; i < segments; ++i) {
        const Eigen::Index j = i + 1 == count ? 0 : i + 1;
        b.col(3 * i) = points.col(i);
        b.col(3 * i + 1) = points.col(i) + (h[i] * third) * m.col(i);
        b.col(3 * i + 2) = points.col(j) - (h[i] * third) * m.col(j);
    }
    if (!periodic) b.col(3 * segments) = points.col(count - 1);
    return BezierSpline<Scalar, Dim>(3, periodic, std::move(b), std::move(h));
}

} // namespace freeform
