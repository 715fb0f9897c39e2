#pragma once
// Tessellation of rational Bézier patches and NURBS surfaces (through their Bézier extraction)
// with a certified bound, on top of the polynomial bound of tessellate.h (docs/surfaces.md,
// "Rational patches"):
//
//   every surface point S(u, v) lies within
//       rationalTessellationErrorBound(patch, nu, nv) = (E_h + rho E_w) / w_min
//   of the point of the mesh triangle at the same (u, v) (the triangle point is the projective
//   image h_lin / w_lin, which sweeps the flat triangle), where, with c the centre of the control
//   box and rho its half diagonal, E_h is the polynomial bound M_uu/(8 nu^2) + M_uv/(4 nu nv) +
//   M_vv/(8 nv^2) of the translated homogeneous numerator sum B_ij w_ij (P_ij - c), E_w the same
//   bound of the weight sum B_ij w_ij, and w_min the smallest control weight.
//
// Crack-free: patch (a, b) of a rows x cols grid (a along u) uses the counts of its column in u
// and of its row in v (the maximum the patches of that column / row ask for), and every vertex on
// a shared side is evaluated once (one vertex of the mesh).

#include <array>
#include <vector>

#include "freeform/mesh/polygon_mesh.h"
#include "freeform/surface/nurbs_surface.h"
#include "freeform/surface/rational_bezier_surface.h"
#include "freeform/tessellate/tessellate.h"

namespace freeform {

using RationalPatch = RationalBezierSurface<double, 3>;

/// (E_h + rho E_w) / w_min for the patch on an nu x nv grid (see above).
double rationalTessellationErrorBound(const RationalPatch& patch, int segmentsU, int segmentsV);

/// The same bound from the whole net alone, without the axes of the frame that follows the patch
/// (tessellate_rational.cpp): at least rationalTessellationErrorBound and cheaper, for a search
/// that asks only whether a bound is within its target.
double rationalWholeNetBound(const RationalPatch& patch, int segmentsU, int segmentsV);

/// Both of the above from one pass over the net (the whole net's bound the same number): for a
/// search that takes the whole net's bound where that is within its target and the other where
/// not, where the first is mostly over it.
struct RationalBounds {
    double wholeNet = 0, framed = 0;
};
RationalBounds rationalBounds(const RationalPatch& patch, int segmentsU, int segmentsV);

/// The grid with the fewest cells whose rational bound is at most tolerance (each count at most
/// maxSegments).
std::array<int, 2> rationalAdaptiveSegments(const RationalPatch& patch, double tolerance, int maxSegments = 4096);

/// The triangle mesh of a rows x cols grid of rational patches (patch (a, b) at a * cols + b, a
/// along u, neighbours sharing their sides exactly, as NurbsSurface::bezierPatches gives them),
/// with analytic normals and (u, v) texture coordinates (global: a + local u, b + local v).
/// options as for tessellate(); report: per patch counts and the largest bound.
PolygonMesh tessellateRational(const std::vector<RationalPatch>& patches, int rows, int cols,
                               const TessellationOptions& options, TessellationReport* report = nullptr);

/// A NURBS surface through its Bézier patches (texture coordinates in the knot domain).
PolygonMesh tessellateNurbs(const NurbsSurface<double, 3>& surface, const TessellationOptions& options,
                            TessellationReport* report = nullptr);

} // namespace freeform
