#pragma once
// Helpers the tool classes share (no ImGui): the selected object, ray and pixel geometry, overlay
// drawing, and the spline joint modes as the scene stores them.

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "freeform/curve/bezier_curve.h"
#include "tools/curve_tools.h"
#include "tools/tool.h"

namespace freeform::editor {

/// Item index of the item named `name`, or -1.
int findItem(const Scene& scene, const std::string& name);
/// The mesh file behind an imported mesh item (relative paths resolved against the document).
std::string meshFilePath(const Scene& scene, int meshItem);
/// The joint modes of a spline item, one per joint (missing ones free).
std::vector<JointMode> jointModes(const Scene& scene, int item);

namespace tool_util {

inline Vec3f f3(const Eigen::Vector3d& p) { return p.cast<float>(); }
/// The ray of a pointer event meets the plane (point, normal); nothing when parallel or behind.
std::optional<Eigen::Vector3d> rayPlane(const PointerEvent& e, const Eigen::Vector3d& point, const Eigen::Vector3d& normal);
/// Pixel of a world point under the context's view-projection (nothing behind the eye).
std::optional<Eigen::Vector2d> toPixel(const ToolContext& c, const Eigen::Vector3d& p);
/// The selected document object (nullptr for none or a mesh); `item` its index.
const DocumentObject* selectedObject(const ToolContext& c, int& item);
/// The last selected control point, or -1.
int selectedPoint(const ToolContext& c);
/// The diagonal of the scene's bounds (1 when empty).
double sceneSize(const Scene& scene);
/// Whether every inner joint of a cubic spline is in C2 mode (then its de Boor points are edited).
bool allC2(const BezierSplineData& s, const std::vector<JointMode>& modes);

void drawPolyline(Overlay& o, const Points3& p, const Vec3f& color, bool closed = false);
/// A triangular construction (de Casteljau, de Boor): levels[0] is the control polygon (not drawn),
/// every further level's polygon and points faded with depth, the last level's point (the curve
/// point) in kCurvePoint. The colours are defined below.
void drawConstructionLevels(Overlay& o, const std::vector<Points3>& levels);
/// The curvature comb (curvatureComb, tools/curve_tools.h) of a curve's jets (columns: point, first
/// and second derivative), its longest tooth `scale` x 0.15 x the scene's `size`, in kComb.
void drawComb(Overlay& o, const std::vector<Eigen::Matrix3d>& jets, double size, double scale);

inline const Vec3f kConstruction{1.0f, 0.75f, 0.2f};
inline const Vec3f kCurvePoint{1.0f, 0.3f, 0.2f};
inline const Vec3f kDeBoor{0.3f, 0.85f, 1.0f};
inline const Vec3f kComb{0.6f, 0.9f, 0.4f};
inline const Vec3f kCreate{1.0f, 1.0f, 1.0f};

} // namespace tool_util

} // namespace freeform::editor
