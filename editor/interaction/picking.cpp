#include "interaction/picking.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>

#include "scene/scene.h"

namespace freeform::editor {

ViewTransform::ViewTransform(const Eigen::Matrix4d& vp, const Eigen::Vector3d& direction, int w, int h)
    : viewProjection(vp), inverse(vp.inverse()), viewDirection(direction.normalized()), width(std::max(w, 1)),
      height(std::max(h, 1))
{
}

ViewTransform ViewTransform::of(const Scene& scene, int width, int height)
{
    width = std::max(width, 1);
    height = std::max(height, 1);
    // As SceneDrawer::frameInfo: the clipping range encloses the scene's bounds with a margin.
    const Eigen::AlignedBox3d box = scene.bounds();
    const double radius = 0.5 * box.diagonal().norm() * 1.6 + 1e-9;
    double near = 0, far = 0;
    scene.camera.clipPlanes(box.center(), radius, near, far);
    const Eigen::Matrix4d vp = scene.camera.projectionMatrix(double(width) / double(height), near, far) * scene.camera.viewMatrix();
    return ViewTransform(vp, -scene.camera.back(), width, height);
}

std::optional<Eigen::Vector3d> ViewTransform::toPixel(const Eigen::Vector3d& p) const
{
    const Eigen::Vector4d c = viewProjection * p.homogeneous();
    if (!(c.w() > 0)) return std::nullopt;
    const Eigen::Vector3d ndc = c.head<3>() / c.w();
    return Eigen::Vector3d((ndc.x() + 1) * 0.5 * width, (1 - ndc.y()) * 0.5 * height, ndc.z());
}

Eigen::Vector3d ViewTransform::unproject(double x, double y, double z) const
{
    const Eigen::Vector4d ndc(2 * x / width - 1, 1 - 2 * y / height, z, 1);
    const Eigen::Vector4d w = inverse * ndc;
    return w.head<3>() / w.w();
}

void ViewTransform::ray(double x, double y, Eigen::Vector3d& origin, Eigen::Vector3d& direction) const
{
    origin = unproject(x, y, -1);
    direction = (unproject(x, y, 1) - origin).normalized();
}

double ViewTransform::worldPerPixel(const Eigen::Vector3d& p) const
{
    const std::optional<Eigen::Vector3d> q = toPixel(p);
    if (!q) return 0;
    return (unproject(q->x() + 1, q->y(), q->z()) - unproject(q->x(), q->y(), q->z())).norm();
}

std::optional<int> pickPoint(const ViewTransform& view, const Eigen::Matrix3Xd& points, double x, double y, double radius)
{
    std::optional<int> best;
    double bestDistance = radius, bestDepth = std::numeric_limits<double>::infinity();
    for (Eigen::Index k = 0; k < points.cols(); ++k) {
        const std::optional<Eigen::Vector3d> q = view.toPixel(points.col(k));
        if (!q) continue;
        const double d = std::hypot(q->x() - x, q->y() - y);
        if (d > radius) continue;
        if (!best || d < bestDistance || (d == bestDistance && q->z() < bestDepth)) {
            best = static_cast<int>(k);
            bestDistance = d;
            bestDepth = q->z();
        }
    }
    return best;
}

std::vector<int> pointsInBox(const ViewTransform& view, const Eigen::Matrix3Xd& points, double x0, double y0, double x1, double y1)
{
    const double xa = std::min(x0, x1), xb = std::max(x0, x1), ya = std::min(y0, y1), yb = std::max(y0, y1);
    std::vector<int> inside;
    for (Eigen::Index k = 0; k < points.cols(); ++k) {
        const std::optional<Eigen::Vector3d> q = view.toPixel(points.col(k));
        if (q && q->x() >= xa && q->x() <= xb && q->y() >= ya && q->y() <= yb) inside.push_back(static_cast<int>(k));
    }
    return inside;
}

std::optional<MeshHit> rayMeshHit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, const PolygonMesh& mesh)
{
    // Moeller-Trumbore on each triangle of each face's fan; both sides count.
    std::optional<MeshHit> best;
    for (int f = 0; f < mesh.faceCount(); ++f) {
        const int* v = mesh.face(f);
        const Eigen::Vector3d a = mesh.positions.col(v[0]);
        for (int k = 1; k + 1 < mesh.faceSize(f); ++k) {
            const Eigen::Vector3d e1 = mesh.positions.col(v[k]) - a, e2 = mesh.positions.col(v[k + 1]) - a;
            const Eigen::Vector3d p = direction.cross(e2);
            const double det = e1.dot(p);
            if (std::abs(det) < 1e-300) continue;
            const Eigen::Vector3d s = origin - a;
            const double u = s.dot(p) / det;
            if (u < 0 || u > 1) continue;
            const Eigen::Vector3d q = s.cross(e1);
            const double w = direction.dot(q) / det;
            if (w < 0 || u + w > 1) continue;
            const double t = e2.dot(q) / det;
            if (t > 0 && (!best || t < best->distance)) best = MeshHit{f, k, u, w, t};
        }
    }
    return best;
}

std::optional<double> rayMesh(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, const PolygonMesh& mesh)
{
    const auto hit = rayMeshHit(origin, direction, mesh);
    return hit ? std::optional<double>(hit->distance) : std::nullopt;
}

Eigen::Vector3d pointAt(const PolygonMesh& mesh, const Eigen::Matrix3Xd& positions, const MeshHit& hit)
{
    const int* v = mesh.face(hit.face);
    return (1 - hit.b1 - hit.b2) * positions.col(v[0]) + hit.b1 * positions.col(v[hit.k]) + hit.b2 * positions.col(v[hit.k + 1]);
}

std::optional<double> pixelDistanceToPolyline(const ViewTransform& view, const Eigen::Matrix3Xd& polyline, double x, double y)
{
    std::optional<double> best;
    const Eigen::Vector2d c(x, y);
    std::optional<Eigen::Vector3d> previous;
    for (Eigen::Index i = 0; i < polyline.cols(); ++i) {
        const std::optional<Eigen::Vector3d> q = view.toPixel(polyline.col(i));
        if (q && previous) {
            const Eigen::Vector2d a = previous->head<2>(), b = q->head<2>();
            const Eigen::Vector2d ab = b - a;
            const double len2 = ab.squaredNorm();
            const double t = len2 > 0 ? std::clamp((c - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
            const double d = (a + t * ab - c).norm();
            if (!best || d < *best) best = d;
        } else if (q && polyline.cols() == 1) {
            best = (q->head<2>() - c).norm();
        }
        previous = q;
    }
    return best;
}

} // namespace freeform::editor
