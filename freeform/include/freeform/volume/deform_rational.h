#pragma once
// Rational free-form deformation (NFFD): a Lattice whose control points carry weights
// (docs/nurbs.md, "Rational FFD"), and the exact composition of an FFD with rational Bézier and
// NURBS curves.
//
// The map is the lattice's displacement form with rational blending,
//     p' = p + w_s N(s,t,u) / D(s,t,u),   N = sum w_ijk B_ijk (P_ijk - R_ijk),  D = sum w_ijk B_ijk,
// (w_s the strength), so the rest lattice still maps every point to itself bit for bit whatever
// the weights, a larger weight pulls the deformation towards its control point, and the outside
// policy of the lattice applies as in volume/deform.h. With every weight 1 the polynomial path of
// Lattice::deform is used, so unit weights give the polynomial FFD bit for bit; any other uniform
// weight gives it to rounding (the weights cancel). The Jacobian is
//     J = I + w_s sum_a ((N_a - D_a N / D) / D) dual_a        (a = s, t, u; quotient rule),
// with normals mapped by cof(J) as for polynomial lattices (transformNormal()).
//
// Exact composition: for a rational Bézier curve A(t)/W(t) of degree d whose lattice coordinates
// are (S_a(t) / W(t)), B_i^l(S/W) = C(l,i) S^i (W - S)^(l-i) / W^l, so
//     p'(t) = (A D~ + w_s W N~) / (W D~)
// with N~, D~ the numerator and denominator above composed in homogeneous form: a rational Bézier
// curve of degree d (1 + l + m + n). For a polynomial lattice (every weight 1) D~ = W^(l+m+n)
// identically, so p'(t) = (A W^(L-1) + w_s N~) / W^L, L = l+m+n: degree d L, as for surfaces. Products of Bernstein polynomials are formed in long double
// (core/polynomial.h). A NURBS curve is composed per knot span through its Bézier extraction; the
// result is a NURBS of that degree with the original breakpoints (interior knots of full
// multiplicity). Both equal the point-wise map wherever the curve lies in the lattice box (and
// everywhere under the extrapolate policy).
//
// Surfaces (docs/ffd.md, "Documents"): a rational Bézier patch A(u,v)/W(u,v) of degrees (m, n)
// composes the same way with tensor Bernstein products in two variables:
//   - rational lattice (some weight != 1): p' = (A D~ + w_s W N~) / (W D~), degrees
//     (m (1 + L), n (1 + L)), L = l+m+n of the lattice;
//   - polynomial lattice (every weight 1, D~ = W^L identically): p' = (A W^(L-1) + w_s N~) / W^L,
//     degrees (m L, n L) as for polynomial patches; a patch whose weights are all 1 takes the
//     polynomial deformSurface of volume/deform.h, so the result is that patch bit for bit.
// A NURBS surface is composed patch by patch through its Bézier extraction (bezierPatches()); the
// result is a NURBS surface of those degrees with the original breakpoints in u and v (interior
// knots of full multiplicity, C0 joints in the net; the geometry keeps the smoothness the map gives
// it). The normal of the composed surface is cof(J) times the original normal (chain rule), so
// surface normals map as for polynomial lattices.

#include <Eigen/Core>

#include "freeform/curve/nurbs_curve.h"
#include "freeform/surface/nurbs_surface.h"
#include "freeform/surface/rational_bezier_surface.h"
#include "freeform/mesh/polygon_mesh.h"
#include "freeform/volume/deform.h"
#include "freeform/volume/lattice.h"

namespace freeform {

/// A lattice with one positive weight per control point (same order as Lattice::controlPoints()).
class RationalLattice {
public:
    /// Error when the weight count differs from the point count or a weight is not positive and finite.
    RationalLattice(Lattice lattice, Eigen::VectorXd weights);
    /// Every weight 1.
    explicit RationalLattice(Lattice lattice);

    const Lattice& lattice() const { return lattice_; }
    const Eigen::VectorXd& weights() const { return weights_; }
    double weight(int i, int j, int k) const { return weights_[lattice_.index(i, j, k)]; }
    /// True when every weight is exactly 1 (the polynomial path is taken).
    bool isPolynomial() const { return unit_; }

    /// The map and its Jacobian at a world point (outside policy applied), see the header comment.
    Lattice::PointJet deform(const Eigen::Vector3d& p, double strength = 1) const;

private:
    Lattice lattice_;
    Eigen::VectorXd weights_;
    bool unit_ = true;
};

/// Deforms points (3 x V) in place; the report covers det J (as deformPoints of volume/deform.h).
DeformReport deformPoints(const RationalLattice& lattice, Eigen::Matrix<double, 3, Eigen::Dynamic>& points,
                          const DeformOptions& options = {});

/// Deforms a mesh in place: positions, and normals by cof(J) when the mesh has them.
DeformReport deformMesh(const RationalLattice& lattice, PolygonMesh& mesh, const DeformOptions& options = {});

/// The rational Bézier curve pushed through the (rational) lattice exactly: degree d (1 + l+m+n),
/// d (l+m+n) for a polynomial lattice.
/// Error when the degree would exceed kMaxDegree or the strength is not finite.
RationalBezierCurve<double, 3> deformCurve(const RationalLattice& lattice, const RationalBezierCurve<double, 3>& curve,
                                           double strength = 1);

/// The NURBS curve pushed through the lattice exactly, span by span: a NURBS of degree
/// p (1 + l+m+n) (p (l+m+n) for a polynomial lattice) with the curve's breakpoints.
NurbsCurve<double, 3> deformCurve(const RationalLattice& lattice, const NurbsCurve<double, 3>& curve,
                                  double strength = 1);

/// The rational Bézier patch pushed through the lattice exactly (see the header comment for the
/// degrees). Error when a degree would exceed kMaxDegree, the strength is not finite, or (rational
/// lattice, patch outside the box) a composed weight is not positive.
RationalBezierSurface<double, 3> deformSurface(const RationalLattice& lattice,
                                               const RationalBezierSurface<double, 3>& surface, double strength = 1);

/// The NURBS surface pushed through the lattice exactly, patch by patch: a NURBS surface with the
/// original breakpoints in u and v, degrees as for its patches.
NurbsSurface<double, 3> deformSurface(const RationalLattice& lattice, const NurbsSurface<double, 3>& surface,
                                      double strength = 1);

} // namespace freeform
