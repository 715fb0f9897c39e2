#pragma once
// Face and vertex normals of a polygon mesh.
//
// A face's area vector is Newell's 1/2 sum (p_i - p_0) x (p_i+1 - p_0): for a triangle (a, b, c) it is
// (b - a) x (c - a) / 2, for a planar polygon its length is the area and its direction the normal seen
// counter-clockwise, and for a slightly non-planar one it is the normal of the best-fitting plane in
// Newell's sense. Face normals are the unit area vectors; a vertex normal is the unit sum of the
// incident face normals weighted by 1, the face area or the interior angle at the vertex. Where no
// direction is defined (a face of zero area, a vertex without faces or whose weighted normals cancel)
// the result is the zero vector, never NaN. Math: docs/meshes.md.

#include <Eigen/Core>

#include <string>

#include "freeform/mesh/polygon_mesh.h"

namespace freeform {

enum class NormalWeighting { Uniform, Area, Angle };

/// "uniform", "area" or "angle"; Error naming `what` otherwise.
NormalWeighting parseNormalWeighting(const std::string& text, const std::string& what);
std::string toString(NormalWeighting weighting);

/// 3 x F area vectors (see above). Validates the mesh (Error).
Eigen::Matrix<double, 3, Eigen::Dynamic> faceAreaVectors(const PolygonMesh& mesh);

/// 3 x F unit face normals; zero for faces of zero area. Validates the mesh (Error).
Eigen::Matrix<double, 3, Eigen::Dynamic> faceNormals(const PolygonMesh& mesh);

/// 3 x V unit vertex normals: normalise(sum over the corners at v of w * n_face), w = 1, the face's
/// area or the corner's interior angle; zero where undefined. Validates the mesh (Error).
Eigen::Matrix<double, 3, Eigen::Dynamic> vertexNormals(const PolygonMesh& mesh,
                                                       NormalWeighting weighting = NormalWeighting::Angle);

} // namespace freeform
