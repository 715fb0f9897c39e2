#pragma once
// Continuity analysis of the joints of a Bézier spline (docs/splines.md, "Continuity report").
//
// For a joint between a left segment (interval hl) and a right segment (interval hr), with the
// one-sided derivatives f_L^(k), f_R^(k) taken with respect to the global parameter:
//   - jumps[k] = |f_R^(k) - f_L^(k)| for k = 0..n;
//   - derivative k agrees when jumps[k] <= tolerance * scale_k, where scale_k is the size of the
//     k-th derivative on the two segments: for k >= 1 the largest control point of the two k-th
//     hodographs (an upper bound of |f^(k)| there), for k = 0 the diagonal of the bounding box of
//     both segments' control points (so the test is invariant under translation and scaling);
//   - C is the highest k for which derivatives 0..k all agree (-1 when not even the points meet;
//     C = n means the two pieces are one polynomial: C-infinity);
//   - G is the geometric level: G0 when the points meet, G1 when moreover the unit tangents (the
//     direction of the first derivative that does not vanish, on each side) differ by at most
//     angleTolerance, G2 when moreover the curvature vectors (f'' - (f''.T)T) / |f'|^2 agree within
//     tolerance * max(|kappa_L|, |kappa_R|, 1/diagonal). G2 needs a non-vanishing first derivative on
//     both sides; where it vanishes the report says at most G1.
// Guarantees: the report is a pure function of the control points and intervals; a joint whose
// derivatives agree to rounding is reported at its true level for the defaults, and a joint whose
// k-th derivative differs by more than the tolerance relative to scale_k is reported below k.

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "freeform/core/types.h"
#include "freeform/curve/bezier_curve.h"
#include "freeform/curve/bezier_spline.h"

namespace freeform {

template <typename Scalar>
struct ContinuityTolerances {
    /// Relative tolerance for the parametric levels (C) and for G2.
    Scalar relative = std::max(Scalar(1e-9), Scalar(1000) * std::numeric_limits<Scalar>::epsilon());
    /// Largest |T_L - T_R| of the unit tangents for G1 (about the angle in radians).
    Scalar angle = std::max(Scalar(1e-9), Scalar(1000) * std::numeric_limits<Scalar>::epsilon());
};

template <typename Scalar>
struct JointContinuity {
    int joint = 0;                // the joint's index in the spline (0 for a separate pair)
    Scalar t = Scalar(0);         // its global parameter
    int C = -1;                   // parametric continuity, -1..n
    int G = -1;                   // geometric continuity, -1..2
    std::vector<Scalar> jumps;    // |f_R^(k) - f_L^(k)|, k = 0..n
};

/// The continuity of the joint between two segments of one degree (Dim x (n+1) each) on intervals
/// hl and hr; joint and t of the result are 0.
template <typename Scalar, int Dim>
JointContinuity<Scalar> jointContinuity(const PointMatrix<Scalar, Dim>& left, const PointMatrix<Scalar, Dim>& right,
                                        Scalar hl, Scalar hr,
                                        const ContinuityTolerances<Scalar>& tol = ContinuityTolerances<Scalar>())
{
    if (left.cols() != right.cols() || left.cols() < 2)
        throw Error("jointContinuity: the two segments need the same degree of at least 1");
    if (!(hl > Scalar(0)) || !(hr > Scalar(0))) throw Error("jointContinuity: interval lengths must be positive");
    using P = Point<Scalar, Dim>;
    const int n = static_cast<int>(left.cols()) - 1;
    const BezierCurve<Scalar, Dim> cl(left), cr(right);
    Eigen::Matrix<Scalar, Dim, Eigen::Dynamic> dl = cl.derivatives(Scalar(1), n), dr = cr.derivatives(Scalar(0), n);

    std::vector<Scalar> scale(static_cast<std::size_t>(n + 1), Scalar(0));
    {
        PointMatrix<Scalar, Dim> both(Dim, 2 * (n + 1));
        both << left, right;
        scale[0] = (both.rowwise().maxCoeff() - both.rowwise().minCoeff()).norm();
    }
    // k-th hodograph control points: n!/(n-k)! Delta^k b, scaled by h^-k.
    PointMatrix<Scalar, Dim> fl = left, fr = right;
    Scalar factorL(1), factorR(1);
    for (int k = 1; k <= n; ++k) {
        for (int i = 0; i <= n - k; ++i) {
            fl.col(i) = fl.col(i + 1) - fl.col(i);
            fr.col(i) = fr.col(i + 1) - fr.col(i);
        }
        factorL *= Scalar(n - k + 1) / hl;
        factorR *= Scalar(n - k + 1) / hr;
        Scalar largest(0);
        for (int i = 0; i <= n - k; ++i)
            largest = std::max({largest, factorL * fl.col(i).norm(), factorR * fr.col(i).norm()});
        scale[k] = largest;
        // Global-parameter derivatives.
        dl.col(k) /= std::pow(hl, Scalar(k));
        dr.col(k) /= std::pow(hr, Scalar(k));
    }

    JointContinuity<Scalar> out;
    out.jumps.resize(static_cast<std::size_t>(n + 1));
    out.C = -1;
    bool agreeing = true;
    for (int k = 0; k <= n; ++k) {
        out.jumps[k] = (dr.col(k) - dl.col(k)).norm();
        agreeing = agreeing && out.jumps[k] <= tol.relative * scale[k];
        if (agreeing) out.C = k;
    }

    if (out.C < 0) {
        out.G = -1;
        return out;
    }
    out.G = 0;
    auto tangent = [&](const Eigen::Matrix<Scalar, Dim, Eigen::Dynamic>& d, P& t) {
        for (int k = 1; k <= n; ++k) {
            const Scalar len = d.col(k).norm();
            if (len > tol.relative * scale[k] && len > Scalar(0)) {
                t = d.col(k) / len;
                return k;
            }
        }
        return 0;
    };
    P tl = P::Zero(), tr = P::Zero();
    const int kl = tangent(dl, tl), kr = tangent(dr, tr);
    if (kl == 0 || kr == 0 || (tl - tr).norm() > tol.angle) return out;
    out.G = 1;
    if (kl != 1 || kr != 1 || n < 2) {
        // Curvature needs a regular point; a line (n = 1) has none on either side: G2 trivially.
        if (n < 2 && kl == 1 && kr == 1) out.G = 2;
        return out;
    }
    auto curvature = [](const P& d1, const P& d2) {
        const Scalar s2 = d1.squaredNorm();
        const P t = d1 / std::sqrt(s2);
        return P((d2 - d2.dot(t) * t) / s2);
    };
    const P kappaL = curvature(dl.col(1), dl.col(2)), kappaR = curvature(dr.col(1), dr.col(2));
    const Scalar reference =
        std::max({kappaL.norm(), kappaR.norm(), scale[0] > Scalar(0) ? Scalar(1) / scale[0] : Scalar(0)});
    if ((kappaL - kappaR).norm() <= tol.relative * reference) out.G = 2;
    return out;
}

/// Every joint of the spline where two segments meet: joints 1..L-1 of an open spline, and for a
/// closed spline joint 0 (the closing joint, t = 0, listed first) as well.
template <typename Scalar, int Dim>
std::vector<JointContinuity<Scalar>> continuityReport(const BezierSpline<Scalar, Dim>& spline,
                                                      const ContinuityTolerances<Scalar>& tol = ContinuityTolerances<Scalar>())
{
    std::vector<JointContinuity<Scalar>> out;
    const int L = spline.segmentCount();
    for (int j = spline.closed() ? 0 : 1; j < L; ++j) {
        const int li = j == 0 ? L - 1 : j - 1;
        JointContinuity<Scalar> c = jointContinuity<Scalar, Dim>(spline.segmentPoints(li), spline.segmentPoints(j),
                                                                 spline.intervals()[li], spline.intervals()[j], tol);
        c.joint = j;
        c.t = spline.knot(j);
        out.push_back(std::move(c));
    }
    return out;
}

} // namespace freeform
