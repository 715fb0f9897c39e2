#pragma once
// The regular Loop patch as a quartic triangular Bézier patch, and the certified bound of a
// triangular Bézier net (docs/subdivision.md, "Loop cages"). Used by the certified tessellation of
// Loop cages (SubdivisionSurface::tessellate); public so that tests can check both against
// OpenSubdiv's own patch evaluation and against sampling.
//
// A net holds the 15 points b_ijk, i + j + k = 4, of f(s, t) = sum 4!/(i! j! k!) (1-s-t)^i s^j t^k b_ijk
// on the triangle s, t >= 0, s + t <= 1 (corner 0 at (0, 0), corner 1 at (1, 0), corner 2 at (0, 1)),
// stored in the order j = 0..4, k = 0..4-j (index bezierIndex(j, k)).

#include <Eigen/Core>

#include <array>

namespace freeform {

using QuarticTriangleNet = std::array<Eigen::Vector3d, 15>;

constexpr int bezierIndex(int j, int k) { return 5 * j - j * (j - 1) / 2 + k; }

/// The Bézier net of OpenSubdiv's regular Loop patch (Far::PatchDescriptor::LOOP, without boundary
/// bits) from its 12 points in the patch table's order, in the patch's own (s, t)
/// (Far::PatchParam::NormalizeTriangle of the face's (u, v)).
QuarticTriangleNet loopPatchToBezier(const std::array<Eigen::Vector3d, 12>& points);

/// f(s, t) of the net.
Eigen::Vector3d evaluateTriangleNet(const QuarticTriangleNet& net, double s, double t);

/// A bound e such that for every triangle whose three vertices are points f(x_i) with x_i in the
/// net's triangle, the point sum l_i f(x_i) is within e of f(sum l_i x_i) (barycentric l_i): the
/// linear interpolation error of the patch on any such triangle, both ways.
/// min over corners a of 12/8 (max|D_bb| + 2 max|D_bc| + max|D_cc|) (second differences of the net
/// along the sides from a); proof in docs/subdivision.md.
double triangleNetErrorBound(const QuarticTriangleNet& net);

} // namespace freeform
