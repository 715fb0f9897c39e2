#pragma once
// Adaptive Gauss-Kronrod (7-15) quadrature on an interval, used for arc length.
// The 15-point Kronrod value is returned; the difference to the embedded 7-point Gauss value is the
// error estimate, and an interval is bisected until the estimate falls below its share of the
// requested absolute tolerance.

#include <cmath>
#include <limits>

namespace freeform {

namespace detail {
// Nodes and weights of the Gauss-Kronrod 7-15 rule on [-1, 1] (abscissae of the positive half).
inline constexpr long double kGkNodes[8] = {
    0.991455371120812639206854697526329L, 0.949107912342758524526189684047851L,
    0.864864423359769072789712788640926L, 0.741531185599394439863864773280788L,
    0.586087235467691130294144845693013L, 0.405845151377397166906606412076961L,
    0.207784955007898467600689403773245L, 0.000000000000000000000000000000000L};
inline constexpr long double kKronrodWeights[8] = {
    0.022935322010529224963732008058970L, 0.063092092629978553290700663189204L,
    0.104790010322250183839876322541518L, 0.140653259715525918745189590510238L,
    0.169004726639267902826583426598550L, 0.190350578064785409913256402421014L,
    0.204432940075298892414161999234649L, 0.209482141084727828012999174891714L};
// Gauss weights for the nodes with odd index (1, 3, 5) and the centre (7).
inline constexpr long double kGaussWeights[4] = {
    0.129484966168869693270611432679082L, 0.279705391489276667901467771423780L,
    0.381830050505118944950369775488975L, 0.417959183673469387755102040816327L};

template <typename Scalar, typename F>
Scalar gaussKronrod(const F& f, Scalar a, Scalar b, Scalar tol, int depth)
{
    const Scalar half = (b - a) / 2, centre = (a + b) / 2;
    Scalar kronrod = Scalar(kKronrodWeights[7]) * f(centre);
    Scalar gauss = Scalar(kGaussWeights[3]) * f(centre);
    for (int i = 0; i < 7; ++i) {
        const Scalar dx = half * Scalar(kGkNodes[i]);
        const Scalar sum = f(centre - dx) + f(centre + dx);
        kronrod += Scalar(kKronrodWeights[i]) * sum;
        if (i % 2 == 1) gauss += Scalar(kGaussWeights[i / 2]) * sum;
    }
    kronrod *= half;
    gauss *= half;
    const Scalar floor = std::numeric_limits<Scalar>::epsilon() * 50 * std::abs(kronrod);
    if (std::abs(kronrod - gauss) <= std::max(tol, floor) || depth >= 50) return kronrod;
    return gaussKronrod(f, a, centre, tol / 2, depth + 1) + gaussKronrod(f, centre, b, tol / 2, depth + 1);
}
} // namespace detail

/// Integral of f over [a, b] to an absolute tolerance (estimated) tol.
template <typename Scalar, typename F>
Scalar integrate(const F& f, Scalar a, Scalar b, Scalar tol)
{
    if (a == b) return Scalar(0);
    return detail::gaussKronrod(f, a, b, tol, 0);
}

} // namespace freeform
