#include "tools/tool_util.h"

#include <cmath>
#include <filesystem>

namespace freeform::editor {

int findItem(const Scene& scene, const std::string& name)
{
    return scene.indexOf(name);
}

std::string meshFilePath(const Scene& scene, int meshItem)
{
    const std::filesystem::path p(scene.item(meshItem).meshPath);
    if (p.is_absolute() || scene.path().empty()) return p.string();
    return (std::filesystem::path(scene.path()).parent_path() / p).string();
}

std::vector<JointMode> jointModes(const Scene& scene, int item)
{
    std::vector<JointMode> modes = scene.item(item).settings.joints;
    if (const auto* d = std::get_if<BezierSplineData>(&scene.object(item).data)) {
        const auto L = d->closed ? d->points.cols() / d->degree : (d->points.cols() - 1) / d->degree;
        modes.resize(static_cast<std::size_t>(d->closed ? L : L + 1), JointMode::Free);
    }
    return modes;
}

namespace tool_util {

std::optional<Eigen::Vector3d> rayPlane(const PointerEvent& e, const Eigen::Vector3d& point, const Eigen::Vector3d& normal)
{
    const double d = e.rayDirection.dot(normal);
    if (std::abs(d) < 1e-12) return std::nullopt;
    const double s = (point - e.rayOrigin).dot(normal) / d;
    if (s < 0) return std::nullopt;
    return Eigen::Vector3d(e.rayOrigin + s * e.rayDirection);
}

std::optional<Eigen::Vector2d> toPixel(const ToolContext& c, const Eigen::Vector3d& p)
{
    const Eigen::Vector4d q = c.viewProjection * Eigen::Vector4d(p.x(), p.y(), p.z(), 1.0);
    if (q.w() <= 0) return std::nullopt;
    return Eigen::Vector2d((q.x() / q.w() * 0.5 + 0.5) * c.viewWidth, (0.5 - q.y() / q.w() * 0.5) * c.viewHeight);
}

const DocumentObject* selectedObject(const ToolContext& c, int& item)
{
    item = c.selection.item;
    if (item < 0 || item >= c.scene.itemCount() || c.scene.item(item).kind != SceneItem::Kind::DocumentObject) return nullptr;
    return &c.scene.object(item);
}

int selectedPoint(const ToolContext& c) { return c.selection.points.empty() ? -1 : c.selection.points.back(); }

double sceneSize(const Scene& scene)
{
    const double d = scene.bounds().diagonal().norm();
    return d > 0 ? d : 1.0;
}

bool allC2(const BezierSplineData& s, const std::vector<JointMode>& modes)
{
    if (s.degree != 3) return false;
    bool any = false;
    const int L = static_cast<int>(s.closed ? s.points.cols() / 3 : (s.points.cols() - 1) / 3);
    for (int j = 0; j <= L; ++j) {
        if (!isInnerJoint(s, j)) continue;
        any = true;
        if (j >= static_cast<int>(modes.size()) || modes[static_cast<std::size_t>(j)] != JointMode::C2) return false;
    }
    return any;
}

void drawPolyline(Overlay& o, const Points3& p, const Vec3f& color, bool closed)
{
    for (Eigen::Index i = 0; i + 1 < p.cols(); ++i) o.addLine(f3(p.col(i)), f3(p.col(i + 1)), color, true);
    if (closed && p.cols() > 2) o.addLine(f3(p.col(p.cols() - 1)), f3(p.col(0)), color, true);
}

void drawComb(Overlay& o, const std::vector<Eigen::Matrix3d>& jets, double size, double scale)
{
    double kmax = 0;
    for (const auto& j : jets) {
        const double s2 = j.col(1).squaredNorm();
        if (s2 > 0) kmax = std::max(kmax, j.col(1).cross(j.col(2)).norm() / (s2 * std::sqrt(s2)));
    }
    if (!(kmax > 0)) return;
    const Points3 comb = curvatureComb(jets, scale * 0.15 * size / kmax);
    for (Eigen::Index i = 0; i < comb.cols(); i += 2) {
        o.addLine(f3(comb.col(i)), f3(comb.col(i + 1)), kComb * 0.7f, true);
        if (i + 3 < comb.cols()) o.addLine(f3(comb.col(i + 1)), f3(comb.col(i + 3)), kComb, true);
    }
}

void drawConstructionLevels(Overlay& o, const std::vector<Points3>& levels)
{
    for (std::size_t r = 1; r < levels.size(); ++r) {
        const float fade = 1.0f - 0.5f * static_cast<float>(r) / static_cast<float>(levels.size());
        drawPolyline(o, levels[r], kConstruction * fade);
        for (Eigen::Index i = 0; i < levels[r].cols(); ++i)
            o.addPoint(f3(levels[r].col(i)), r + 1 == levels.size() ? kCurvePoint : Vec3f(kConstruction * fade));
    }
}

} // namespace tool_util

} // namespace freeform::editor
