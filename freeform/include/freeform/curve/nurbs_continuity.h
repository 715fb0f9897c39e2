#pragma once
// Continuity of a NURBS curve at every interior knot, from the geometry (docs/nurbs.md,
// "Continuity"). A knot of multiplicity s guarantees C^(p-s); the curve may be smoother (a knot
// inserted into a smooth curve changes nothing), so the report measures the one-sided derivatives
// of the two Bézier pieces that meet there (curve/continuity.h, with derivatives with respect to
// the curve's own parameter u):
//   - polynomial curves: exactly jointContinuity() of curve/continuity.h on the two pieces'
//     control points and span lengths, so the report agrees with the existing `continuity` for
//     every spline both can represent;
//   - rational curves: the same levels from the rational one-sided derivatives (Leibniz on the
//     homogeneous pieces), derivative k agreeing when its jump is at most tolerance times the larger
//     of the two one-sided |f^(k)| (and, for k = 0, the diagonal of the two pieces' control boxes).
// The closing joint of a closed curve is not reported (a NURBS curve does not know it is closed).

#include <algorithm>
#include <cmath>
#include <vector>

#include "freeform/curve/continuity.h"
#include "freeform/curve/nurbs_curve.h"

namespace freeform {

/// One entry per interior breakpoint k = 1..(pieces-1): joint = k, t = the knot value.
template <typename Scalar, int Dim>
std::vector<JointContinuity<Scalar>> continuityReport(const NurbsCurve<Scalar, Dim>& curve,
                                                      const ContinuityTolerances<Scalar>& tol = ContinuityTolerances<Scalar>())
{
    using P = Point<Scalar, Dim>;
    const auto pieces = curve.bezierPieces();
    const auto& br = curve.breakpoints();
    const int n = curve.degree();
    std::vector<JointContinuity<Scalar>> out;
    for (std::size_t j = 1; j < pieces.size(); ++j) {
        const Scalar hl = br[j] - br[j - 1], hr = br[j + 1] - br[j];
        JointContinuity<Scalar> c;
        if (!curve.isRational() || n < 1) {
            c = jointContinuity<Scalar, Dim>(pieces[j - 1].controlPoints(), pieces[j].controlPoints(), hl, hr, tol);
        } else {
            auto dl = pieces[j - 1].derivatives(Scalar(1), n), dr = pieces[j].derivatives(Scalar(0), n);
            for (int k = 1; k <= n; ++k) {
                dl.col(k) /= std::pow(hl, Scalar(k));
                dr.col(k) /= std::pow(hr, Scalar(k));
            }
            Box<Scalar, Dim> box = pieces[j - 1].controlBox();
            box.extend(pieces[j].controlBox());
            const Scalar diagonal = box.diagonal().norm();
            std::vector<Scalar> scale(static_cast<std::size_t>(n + 1));
            scale[0] = diagonal;
            for (int k = 1; k <= n; ++k) scale[k] = std::max(dl.col(k).norm(), dr.col(k).norm());
            c.jumps.resize(static_cast<std::size_t>(n + 1));
            bool agreeing = true;
            for (int k = 0; k <= n; ++k) {
                c.jumps[k] = (dr.col(k) - dl.col(k)).norm();
                agreeing = agreeing && c.jumps[k] <= tol.relative * scale[k];
                if (agreeing) c.C = k;
            }
            if (c.C >= 0) {
                c.G = 0;
                auto tangent = [&](const auto& d, P& t) {
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
                if (kl != 0 && kr != 0 && (tl - tr).norm() <= tol.angle) {
                    c.G = 1;
                    if (kl == 1 && kr == 1 && n >= 2) {
                        auto curvature = [](const P& d1, const P& d2) {
                            const Scalar s2 = d1.squaredNorm();
                            const P t = d1 / std::sqrt(s2);
                            return P((d2 - d2.dot(t) * t) / s2);
                        };
                        const P kl2 = curvature(dl.col(1), dl.col(2)), kr2 = curvature(dr.col(1), dr.col(2));
                        const Scalar reference = std::max({kl2.norm(), kr2.norm(), diagonal > 0 ? Scalar(1) / diagonal : Scalar(0)});
                        if ((kl2 - kr2).norm() <= tol.relative * reference) c.G = 2;
                    }
                }
            }
        }
        c.joint = static_cast<int>(j);
        c.t = br[j];
        out.push_back(std::move(c));
    }
    return out;
}

} // namespace freeform
