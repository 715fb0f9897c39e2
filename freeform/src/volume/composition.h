#pragma once
// The exact composition of a lattice with one rational Bézier piece, as the homogeneous Bernstein
// coefficients of the result, without the library's degree cap (kMaxDegree): what deformCurve and
// deformSurface (volume/deform_rational.h) wrap in their classes, and what brep/part_deform.cpp
// degree-reduces when a face or edge of a part would rise above the cap. Private to the library.

#include <Eigen/Core>

#include "freeform/volume/deform_rational.h"

namespace freeform::detail {

/// What a composition multiplies a piece's degrees by: l+m+n for a polynomial lattice (its
/// denominator W^(l+m+n) cancels one factor W), 1 + l+m+n for a rational one.
inline int degreeFactor(const RationalLattice& lattice)
{
    const auto& d = lattice.lattice().degrees();
    return d[0] + d[1] + d[2] + (lattice.isPolynomial() ? 0 : 1);
}

/// 4 x (d + 1): (w p, w) of the composed piece, degree d (1 + l+m+n), d (l+m+n) for a polynomial
/// lattice. Error when the strength is not finite.
Eigen::Matrix<double, 4, Eigen::Dynamic> composePiece(const RationalLattice& lattice,
                                                      const RationalBezierCurve<double, 3>& curve, double strength);

/// A composed patch: degrees (du, dv), coefficient (i, j) of (w p, w) at column i (dv + 1) + j.
struct HomogeneousPatch {
    int du = 0, dv = 0;
    Eigen::Matrix<double, 4, Eigen::Dynamic> points;
};

/// The patch through the lattice by tensor Bernstein products in long double (every patch, unit
/// weights included: deformSurface takes volume/deform.h's polynomial path for those up to
/// kMaxDegree). Error when the strength is not finite or a composed weight is not positive.
HomogeneousPatch composePatch(const RationalLattice& lattice, const RationalBezierSurface<double, 3>& surface,
                              double strength);

} // namespace freeform::detail
