#pragma once
// The editor camera: it looks at `target` from `distance` along the -z axis of its orientation
// (a rotation whose columns are the camera's right, up and backward directions in world
// coordinates). World "up" is +z (the teapot's). All matrices come from core/transform.h.
//
// Invariants: distance > 0, orientation a unit quaternion, 0 < fovy < 180 degrees. Every
// operation keeps them. The camera is saved in the document's "editor" member (docs/format.md).

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <string>

#include <nlohmann/json.hpp>

namespace freeform::editor {

using Json = nlohmann::ordered_json;

enum class Projection { Perspective, Orthographic };
enum class OrbitMode { Turntable, Arcball };

class Camera {
public:
    Eigen::Vector3d target = Eigen::Vector3d::Zero();
    double distance = 10.0;
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
    double fovyDegrees = 35.0;
    Projection projection = Projection::Perspective;
    OrbitMode orbit = OrbitMode::Turntable;

    Eigen::Vector3d right() const { return orientation * Eigen::Vector3d::UnitX(); }
    Eigen::Vector3d up() const { return orientation * Eigen::Vector3d::UnitY(); }
    Eigen::Vector3d back() const { return orientation * Eigen::Vector3d::UnitZ(); }
    Eigen::Vector3d eye() const { return target + distance * back(); }

    /// Half the height of the visible rectangle in the plane through the target.
    double halfHeight() const;

    Eigen::Matrix4d viewMatrix() const;
    /// The projection for a viewport of aspect width/height, near and far planes from `near`/`far`
    /// (positive distances from the eye; the orthographic box uses the same planes).
    Eigen::Matrix4d projectionMatrix(double aspect, double near, double far) const;
    /// Near and far planes that enclose the sphere (centre, radius) with a margin, near > 0.
    void clipPlanes(const Eigen::Vector3d& centre, double radius, double& near, double& far) const;

    /// Turntable orbit: turn about world z by dx and tilt about the camera's right axis by dy
    /// (radians), never past the poles.
    void orbitTurntable(double dx, double dy);
    /// Arcball orbit from one cursor position to another, both in normalised device coordinates.
    void orbitArcball(const Eigen::Vector2d& from, const Eigen::Vector2d& to);
    /// Moves target and eye by (dx, dy) pixels of a viewport `height` pixels high.
    void pan(double dx, double dy, double height);
    /// Multiplies the distance by `factor`, keeping the point under the cursor (normalised device
    /// coordinates, aspect width/height) in the target plane where it is.
    void zoom(double factor, const Eigen::Vector2d& cursor, double aspect);
    /// Looks at the centre of the box from the current direction and moves to the nearest distance
    /// at which all eight corners lie inside the view of this aspect (with a 5% margin).
    void fit(const Eigen::AlignedBox3d& box, double aspect);
    /// One of front, back, left, right, top, bottom, iso (Error otherwise); keeps target and distance.
    void setView(const std::string& name);

    Json toJson() const;
    /// Reads what toJson writes; Error naming the field on a wrong type or value.
    static Camera fromJson(const Json& json);

    bool operator==(const Camera& other) const;
};

} // namespace freeform::editor
