#pragma once
// PatchComplex: a set of 3D Bézier patches that meet along shared boundary edges (the Utah teapot,
// the Bézier form of a bicubic spline surface, a closed box).
//
// Guarantees: every patch is a valid BezierSurface<double, 3> (checked when it was built). Two
// patch edges are "shared" when their boundary curves have the same degree and control points
// that agree (exactly, or within a given tolerance) in the same or the opposite order; an edge
// whose control points all coincide is "collapsed" (a pole, as at the teapot's lid) and is shared
// with nothing. Nothing else is assumed: the tessellator and the continuity report find the
// shared edges themselves (sharedEdges()). (The .bpt reader is in io/bpt.h.) Math and conventions: docs/surfaces.md.

#include <array>
#include <string>
#include <vector>

#include "freeform/curve/aframe.h"
#include "freeform/surface/bezier_surface.h"

namespace freeform {

using Patch = BezierSurface<double, 3>;

struct PatchComplex {
    std::vector<Patch> patches;
};

/// The four sides of a patch: U0 is the edge u = 0 (row i = 0, a curve in v), U1 the edge u = 1
/// (row m), V0 the edge v = 0 (column j = 0, a curve in u), V1 the edge v = 1 (column n).
enum class PatchSide { U0 = 0, U1 = 1, V0 = 2, V1 = 3 };

struct PatchEdge {
    int patch = 0;
    PatchSide side = PatchSide::U0;
};

/// The boundary curve of a side, parametrised by v (U0, U1) or u (V0, V1).
BezierCurve<double, 3> edgeCurve(const Patch& patch, PatchSide side);

/// Whether every control point of the side coincides with the first within tolerance.
bool isCollapsedEdge(const Patch& patch, PatchSide side, double tolerance = 0);

/// Two sides whose boundary curves coincide; reversed when b runs opposite to a.
struct SharedEdge {
    PatchEdge a, b;
    bool reversed = false;
    double gap = 0; // largest distance between corresponding control points
};

/// All pairs of sides with the same degree whose control points agree within tolerance
/// (0: bit for bit), forward or reversed. Collapsed sides are left out. A side that matches
/// several others is reported once per match (a non-manifold edge). O(E log E) on the sides.
std::vector<SharedEdge> sharedEdges(const PatchComplex& complex, double tolerance = 0);

/// Continuity across one shared edge (like the joints of a curve):
///   c0: the boundary curves agree within the tolerance (always, for an edge found by sharedEdges);
///   c1: the cross-boundary derivatives agree: the inward derivative of one patch is the negated
///       inward derivative of the other, control point by control point, within tolerance times the
///       larger derivative bound (a parametric C1 join);
///   g1: the tangent planes agree: at 4d + 1 points along the edge (d its degree) the unit normals
///       (limits at collapsed corners) make an angle of at most angleTolerance up to sign, and the
///       patches lie on opposite sides of the edge (no fold).
/// angle is the largest angle found (radians, in [0, pi/2]); gap as in SharedEdge.
struct EdgeContinuity {
    PatchEdge a, b;
    bool reversed = false;
    bool c0 = false, g1 = false, c1 = false;
    double gap = 0, angle = 0;
};

std::vector<EdgeContinuity> edgeContinuity(const PatchComplex& complex, double tolerance = 1e-9,
                                           double angleTolerance = 1e-6);

// The .bpt text format (parseBpt, readBpt, formatBpt): io/bpt.h.

/// The C2 bicubic spline surface with the de Boor points `points` (3 x rows*cols, point (r, c) at
/// column r*cols + c; rows along u, cols along v) as Bézier patches: the tensor-product A-frame
/// (aframeBezierPoints along every row, then along every column of the result). endU applies to
/// the u direction (the rows index), endV to v. Patch (a, b) (segment a in u, b in v) is
/// patches[a * segmentsV + b]; neighbouring patches share their boundary control points exactly,
/// across the seam too when a direction is closed (a torus when both are). Error when a
/// direction has too few points for its end condition.
PatchComplex deboorSurfacePatches(const PointMatrix<double, 3>& points, int rows, int cols, EndCondition endU,
                                  EndCondition endV);

/// Segment counts of deboorSurfacePatches in u and v.
std::array<int, 2> deboorSurfaceSegments(int rows, int cols, EndCondition endU, EndCondition endV);

} // namespace freeform
