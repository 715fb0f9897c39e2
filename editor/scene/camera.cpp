#include "scene/camera.h"

#include <algorithm>
#include <cmath>

#include "freeform/core/error.h"
#include "freeform/core/transform.h"
#include "scene/json_read.h"

namespace freeform::editor {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// The rotation with the given right and up directions (back = right x up).
Eigen::Quaterniond frame(const Eigen::Vector3d& right, const Eigen::Vector3d& up)
{
    Eigen::Matrix3d m;
    m.col(0) = right.normalized();
    m.col(1) = up.normalized();
    m.col(2) = m.col(0).cross(m.col(1));
    return Eigen::Quaterniond(m).normalized();
}

/// A point of the unit arcball for a cursor position (Shoemake): on the sphere inside the unit
/// disc, on its rim outside.
Eigen::Vector3d arcballPoint(const Eigen::Vector2d& p)
{
    const double r2 = p.squaredNorm();
    if (r2 <= 1.0) return {p.x(), p.y(), std::sqrt(1.0 - r2)};
    const Eigen::Vector2d q = p / std::sqrt(r2);
    return {q.x(), q.y(), 0.0};
}

} // namespace

double Camera::halfHeight() const
{
    return distance * std::tan(fovyDegrees * kPi / 360.0);
}

Eigen::Matrix4d Camera::viewMatrix() const
{
    return lookAlong<double>(eye(), -back(), up());
}

Eigen::Matrix4d Camera::projectionMatrix(double aspect, double near, double far) const
{
    if (projection == Projection::Perspective) return perspective<double>(fovyDegrees * kPi / 180.0, aspect, near, far);
    const double h = halfHeight();
    return orthographic<double>(-aspect * h, aspect * h, -h, h, near, far);
}

void Camera::clipPlanes(const Eigen::Vector3d& centre, double radius, double& near, double& far) const
{
    const double depth = (eye() - centre).dot(back()); // distance of the centre in front of the eye
    radius = std::max(radius, 1e-6);
    far = std::max(depth + 1.5 * radius, 1e-3 * radius);
    if (projection == Projection::Orthographic) {
        // An orthographic view may put the eye inside the scene: allow a near plane behind it.
        near = depth - 1.5 * radius;
        if (std::abs(far - near) < 1e-9) far = near + 1e-3;
        return;
    }
    near = std::max(depth - 1.5 * radius, far * 1e-4);
}

void Camera::orbitTurntable(double dx, double dy)
{
    const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
    Eigen::Quaterniond q = Eigen::Quaterniond(Eigen::AngleAxisd(-dx, z)) * orientation;
    // Tilt, clamped so that the view direction never reaches world up or down.
    const Eigen::Vector3d backAfterYaw = q * Eigen::Vector3d::UnitZ();
    const double elevation = std::asin(std::clamp(backAfterYaw.z(), -1.0, 1.0));
    const double limit = 89.5 * kPi / 180.0;
    const double newElevation = std::clamp(elevation + dy, -limit, limit);
    const Eigen::Vector3d r = q * Eigen::Vector3d::UnitX();
    q = Eigen::Quaterniond(Eigen::AngleAxisd(-(newElevation - elevation), r)) * q;
    // Keep the horizon level: right stays horizontal.
    Eigen::Vector3d back = q * Eigen::Vector3d::UnitZ();
    Eigen::Vector3d right = z.cross(back);
    if (right.norm() < 1e-9) right = q * Eigen::Vector3d::UnitX();
    orientation = frame(right, back.cross(right.normalized()));
}

void Camera::orbitArcball(const Eigen::Vector2d& from, const Eigen::Vector2d& to)
{
    const Eigen::Vector3d a = arcballPoint(from), b = arcballPoint(to);
    // Rotating the scene from a to b is rotating the camera from b to a (in camera coordinates).
    const Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(b, a);
    orientation = (orientation * q).normalized();
}

void Camera::pan(double dx, double dy, double height)
{
    const double perPixel = 2.0 * halfHeight() / std::max(height, 1.0);
    target += (-dx * perPixel) * right() + (dy * perPixel) * up();
}

void Camera::zoom(double factor, const Eigen::Vector2d& cursor, double aspect)
{
    factor = std::clamp(factor, 1e-3, 1e3);
    const double h = halfHeight();
    const Eigen::Vector3d underCursor = target + (cursor.x() * aspect * h) * right() + (cursor.y() * h) * up();
    target = underCursor + factor * (target - underCursor);
    distance = std::clamp(distance * factor, 1e-9, 1e12);
}

void Camera::fit(const Eigen::AlignedBox3d& box, double aspect)
{
    target = box.center();
    aspect = std::max(aspect, 1e-6);
    const double tanY = std::tan(fovyDegrees * kPi / 360.0), tanX = tanY * aspect;
    const Eigen::Matrix3d toCamera = orientation.toRotationMatrix().transpose();
    double needed = 1e-9;
    for (int k = 0; k < 8; ++k) {
        const Eigen::Vector3d corner = toCamera * (box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(k)) - target);
        // Perspective: |x| <= (d - z) tan(fovx/2) and |y| <= (d - z) tan(fovy/2) for the camera at
        // distance d on the +z axis. Orthographic: the half-height d tan(fovy/2) must cover |y| and
        // |x|/aspect.
        if (projection == Projection::Perspective)
            needed = std::max({needed, corner.z() + std::abs(corner.x()) / tanX, corner.z() + std::abs(corner.y()) / tanY});
        else
            needed = std::max({needed, std::abs(corner.x()) / tanX, std::abs(corner.y()) / tanY});
    }
    distance = 1.05 * needed; // orthographic: clipPlanes lets the near plane lie behind the eye
}

void Camera::setView(const std::string& name)
{
    using V = Eigen::Vector3d;
    if (name == "front") orientation = frame(V(1, 0, 0), V(0, 0, 1));        // looking along +y
    else if (name == "back") orientation = frame(V(-1, 0, 0), V(0, 0, 1));   // along -y
    else if (name == "left") orientation = frame(V(0, -1, 0), V(0, 0, 1));   // along +x
    else if (name == "right") orientation = frame(V(0, 1, 0), V(0, 0, 1));   // along -x
    else if (name == "top") orientation = frame(V(1, 0, 0), V(0, 1, 0));     // along -z
    else if (name == "bottom") orientation = frame(V(1, 0, 0), V(0, -1, 0)); // along +z
    else if (name == "iso") {
        const V back = V(1, -1, 1).normalized();                              // from front-right-above
        const V right = V(0, 0, 1).cross(back).normalized();
        orientation = frame(right, back.cross(right));
    } else {
        throw Error("unknown view \"" + name + "\" (front, back, left, right, top, bottom, iso)");
    }
}

Json Camera::toJson() const
{
    Json j;
    j["target"] = json::array(target);
    j["distance"] = distance;
    j["orientation"] = Json::array({orientation.w(), orientation.x(), orientation.y(), orientation.z()});
    j["fovy"] = fovyDegrees;
    j["projection"] = projection == Projection::Perspective ? "perspective" : "orthographic";
    j["orbit"] = orbit == OrbitMode::Turntable ? "turntable" : "arcball";
    return j;
}

Camera Camera::fromJson(const Json& j)
{
    const std::string path = "editor.camera";
    json::requireObject(j, path);
    Camera c;
    json::readVector(j, "target", path, c.target);
    json::read(j, "distance", path, c.distance);
    if (!(c.distance > 0)) json::fail(path + ".distance", "must be positive");
    Eigen::Vector4d q(1, 0, 0, 0);
    json::readVector(j, "orientation", path, q);
    if (!(q.norm() > 1e-6)) json::fail(path + ".orientation", "is not a rotation (w, x, y, z)");
    if (std::abs(q.norm() - 1.0) > 1e-12) q.normalize();
    c.orientation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
    json::read(j, "fovy", path, c.fovyDegrees);
    if (!(c.fovyDegrees > 0 && c.fovyDegrees < 180)) json::fail(path + ".fovy", "must lie between 0 and 180 degrees");
    c.projection = json::choice(j, "projection", path, {"perspective", "orthographic"}, 0) == 0 ? Projection::Perspective
                                                                                               : Projection::Orthographic;
    c.orbit = json::choice(j, "orbit", path, {"turntable", "arcball"}, 0) == 0 ? OrbitMode::Turntable : OrbitMode::Arcball;
    for (const auto& [key, value] : j.items())
        if (key != "target" && key != "distance" && key != "orientation" && key != "fovy" && key != "projection" &&
            key != "orbit")
            json::fail(path + "." + key, "unknown field");
    return c;
}

bool Camera::operator==(const Camera& o) const
{
    return target == o.target && distance == o.distance && orientation.coeffs() == o.orientation.coeffs() &&
           fovyDegrees == o.fovyDegrees && projection == o.projection && orbit == o.orbit;
}

} // namespace freeform::editor
