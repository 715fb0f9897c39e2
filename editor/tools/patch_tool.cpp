#include "tools/patch_tool.h"

#include <algorithm>

#include "freeform/core/error.h"
#include "tools/tool_util.h"

namespace freeform::editor {

using namespace tool_util;

bool PatchTool::onKey(ToolContext& c, KeyAction action)
{
    if (action != KeyAction::CreatePatch) return false;
    return createPatch(c), true;
}

void PatchTool::reset()
{
    degree[0] = degree[1] = 3;
    edges_.clear();
    edgePatchNames_.clear();
}

bool PatchTool::createPatch(ToolContext& c)
{
    const int m = std::clamp(degree[0], 1, 20), n = std::clamp(degree[1], 1, 20);
    const Eigen::AlignedBox3d box = c.scene.bounds();
    const Eigen::Vector3d centre = box.center();
    const double half = 0.25 * sceneSize(c.scene);
    const Eigen::Vector3d right = c.scene.camera.right(), up = c.scene.camera.up();
    BezierSurfaceData d;
    d.degree = {m, n};
    d.points.resize(3, (m + 1) * (n + 1));
    for (int i = 0; i <= m; ++i)
        for (int j = 0; j <= n; ++j)
            d.points.col(i * (n + 1) + j) = centre + half * ((2.0 * i / m - 1) * up + (2.0 * j / n - 1) * right);
    try {
        c.selection.selectItem(c.scene.addObject({"patch", d, ""}, "create patch"));
        return true;
    } catch (const Error& e) {
        status() = e.what();
        return false;
    }
}

bool PatchTool::computeEdgeContinuity(ToolContext& c)
{
    return computeEdges(c, true);
}

void PatchTool::update(ToolContext& c, Overlay&)
{
    if (!edges_.empty() && c.scene.changeCount() != edgesChange_) computeEdges(c, false);
}

bool PatchTool::computeEdges(ToolContext& c, bool report)
{
    edgesChange_ = c.scene.changeCount();
    PatchComplex complex;
    edgePatchNames_.clear();
    for (int i = 0; i < c.scene.itemCount(); ++i) {
        if (c.scene.item(i).kind != SceneItem::Kind::DocumentObject) continue;
        if (const auto* d = std::get_if<BezierSurfaceData>(&c.scene.object(i).data)) {
            complex.patches.emplace_back(d->degree[0], d->degree[1], Points3(d->points));
            edgePatchNames_.push_back(c.scene.item(i).name);
        }
    }
    try {
        edges_ = edgeContinuity(complex);
        if (report)
            status() = std::to_string(edges_.size()) + (edges_.size() == 1 ? " shared edge" : " shared edges") + " between " + std::to_string(complex.patches.size()) + " patches";
        return true;
    } catch (const Error& e) {
        edges_.clear();
        if (report) status() = e.what();
        return false;
    }
}

} // namespace freeform::editor
