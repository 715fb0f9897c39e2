#pragma once
// Triangulation of polygons and of polygon meshes.
//
// A polygon (3 x n corners, n >= 3) is projected onto its best-fit plane: the plane through the
// centroid with Newell's normal 1/2 sum (p_i - p_0) x (p_i+1 - p_0), which is the exact plane of a
// planar polygon and, for a nearly planar one, keeps the sense in which the corners run. A convex
// polygon is fanned from corner 0; any other is cut by ear clipping (an ear: a convex corner whose
// triangle with its two neighbours holds no other remaining corner). The result always has n - 2
// triangles, each counter-clockwise like the polygon, made of corner indices; for a simple polygon
// they tile it exactly (their areas sum to its area and none leaves it). A polygon that is not simple
// (self-intersecting) or degenerate (all corners on a line) still gets n - 2 triangles, clipped at the
// most convex corner when no ear exists, but they may overlap. Math: docs/meshes.md.

#include <Eigen/Core>

#include <array>
#include <vector>

#include "freeform/mesh/polygon_mesh.h"

namespace freeform {

/// Triangles of one polygon as corner indices 0..n-1 (n - 2 of them). Error for fewer than three
/// corners or a non-finite corner.
std::vector<std::array<int, 3>> triangulatePolygon(const Eigen::Matrix<double, 3, Eigen::Dynamic>& corners);

/// The same for a polygon already in the plane (counter-clockwise or clockwise; triangles follow it).
std::vector<std::array<int, 3>> triangulatePolygon2(const Eigen::Matrix<double, 2, Eigen::Dynamic>& corners);

/// Every face of the mesh triangulated; vertices and their attributes are kept as they are.
/// triangleFace (when given) receives, for each output triangle, the face it came from.
PolygonMesh triangulate(const PolygonMesh& mesh, std::vector<int>* triangleFace = nullptr);

} // namespace freeform
