#pragma once
// Screen-space geometry of the view: world points to pixels and pixels to rays, and the picking
// built on them (nearest control point within a radius, box selection, rays against triangles,
// distance to a projected polyline). Pixels are window coordinates with the origin at the top left
// of the view, x to the right, y down; a pixel's centre is at (i + 0.5, j + 0.5), the cursor's
// position is continuous. Pure functions of their arguments: no GL, no ImGui.

#include <Eigen/Core>

#include <optional>
#include <vector>

#include "freeform/mesh/polygon_mesh.h"

namespace freeform::editor {

class Scene;

/// The camera of a view of width x height pixels, in double precision.
struct ViewTransform {
    Eigen::Matrix4d viewProjection = Eigen::Matrix4d::Identity(); // world -> clip
    Eigen::Matrix4d inverse = Eigen::Matrix4d::Identity();        // clip -> world
    Eigen::Vector3d viewDirection = -Eigen::Vector3d::UnitZ();     // unit, from the eye into the scene
    int width = 1, height = 1;

    ViewTransform() = default;
    ViewTransform(const Eigen::Matrix4d& viewProjection, const Eigen::Vector3d& viewDirection, int width, int height);
    /// The scene's camera with the near and far planes the drawer uses (SceneDrawer::frameInfo).
    static ViewTransform of(const Scene& scene, int width, int height);

    /// Pixel position (x, y) and normalised depth z in [-1, 1]; nothing when p lies behind the eye.
    std::optional<Eigen::Vector3d> toPixel(const Eigen::Vector3d& p) const;
    /// The world point at pixel (x, y) and normalised depth z.
    Eigen::Vector3d unproject(double x, double y, double z) const;
    /// The ray through pixel (x, y): origin on the near plane, unit direction.
    void ray(double x, double y, Eigen::Vector3d& origin, Eigen::Vector3d& direction) const;
    /// World length of one pixel at the depth of p (along the view plane through p).
    double worldPerPixel(const Eigen::Vector3d& p) const;
};

/// The column of `points` (3 x N) whose projection is nearest to (x, y), if within `radius`
/// pixels; ties go to the point nearer the eye. Points behind the eye are never picked.
std::optional<int> pickPoint(const ViewTransform& view, const Eigen::Matrix3Xd& points, double x, double y, double radius);

/// The columns whose projections lie inside the rectangle with corners (x0, y0), (x1, y1).
std::vector<int> pointsInBox(const ViewTransform& view, const Eigen::Matrix3Xd& points, double x0, double y0, double x1,
                             double y1);

/// Where a ray meets a mesh: the face, the fan triangle (corners 0, k, k + 1 of the face), the
/// barycentric coordinates (b1, b2) of corners k and k + 1, and the ray parameter t.
struct MeshHit {
    int face = -1, k = 1;
    double b1 = 0, b2 = 0, distance = 0;
};
/// The nearest hit with t > 0 of origin + t direction on the triangles of the mesh (faces are
/// fanned; both sides count), or nothing.
std::optional<MeshHit> rayMeshHit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, const PolygonMesh& mesh);
/// rayMeshHit's t alone.
std::optional<double> rayMesh(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, const PolygonMesh& mesh);
/// The point of the hit's fan triangle at its barycentric coordinates, on `positions` (the mesh's
/// own, or another set for the same faces, e.g. the rest positions of a deformed mesh).
Eigen::Vector3d pointAt(const PolygonMesh& mesh, const Eigen::Matrix3Xd& positions, const MeshHit& hit);

/// The distance in pixels from (x, y) to the projected polyline (3 x P points), or nothing when
/// no segment is in front of the eye.
std::optional<double> pixelDistanceToPolyline(const ViewTransform& view, const Eigen::Matrix3Xd& polyline, double x, double y);

} // namespace freeform::editor
