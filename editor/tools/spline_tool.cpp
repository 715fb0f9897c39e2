#include "tools/spline_tool.h"

#include <algorithm>

#include "freeform/core/error.h"
#include "freeform/curve/interpolation.h"
#include "tools/tool_util.h"

namespace freeform::editor {

using namespace tool_util;

namespace {

/// The cubic spline with the joints of `d` (same intervals) that is C2 at every inner joint: the
/// C2 interpolant of the joints, with the end derivatives of `d` (open) or periodic (closed). Unlike
/// making joints C2 one after the other, no joint moves and the handles stay near the old ones.
BezierSplineData c2ThroughJoints(const BezierSplineData& d)
{
    const Eigen::Index L = d.closed ? d.points.cols() / 3 : (d.points.cols() - 1) / 3;
    Points3 joints(3, L + 1);
    for (Eigen::Index j = 0; j <= L; ++j) joints.col(j) = d.points.col((3 * j) % d.points.cols());
    InterpolationOptions<double, 3> options;
    options.params.assign(1, 0.0);
    for (Eigen::Index i = 0; i < L; ++i)
        options.params.push_back(options.params.back() + (d.intervals.empty() ? 1.0 : d.intervals[static_cast<std::size_t>(i)]));
    if (d.closed) {
        options.end = InterpolationEnd::Periodic;
    } else {
        const double h0 = options.params[1] - options.params[0], hL = options.params.back() - options.params[static_cast<std::size_t>(L - 1)];
        options.end = InterpolationEnd::Clamped;
        options.startDerivative = 3 * (d.points.col(1) - d.points.col(0)) / h0;
        options.endDerivative = 3 * (d.points.col(3 * L) - d.points.col(3 * L - 1)) / hL;
    }
    const BezierSpline<double, 3> spline = interpolateCubic<double, 3>(joints, options);
    BezierSplineData out = d;
    out.points = spline.controlPoints();
    return out;
}

} // namespace

bool SplineTool::onKey(ToolContext& c, KeyAction action)
{
    JointMode mode;
    switch (action) {
    case KeyAction::JointFree: mode = JointMode::Free; break;
    case KeyAction::JointAligned: mode = JointMode::Aligned; break;
    case KeyAction::JointMirrored: mode = JointMode::Mirrored; break;
    case KeyAction::JointC2: mode = JointMode::C2; break;
    default: return false;
    }
    int item = -1;
    const DocumentObject* object = selectedObject(c, item);
    if (!object || !std::holds_alternative<BezierSplineData>(object->data) || c.selection.points.empty()) return false;
    return setJointMode(c, mode), true;
}

bool SplineTool::onPointer(ToolContext& c, const PointerEvent& e)
{
    Scene& scene = c.scene;
    if (dragItem_ >= 0) {
        if (e.type == PointerEvent::Type::Release) {
            dragItem_ = -1;
            scene.endMerge();
            return true;
        }
        if (e.type != PointerEvent::Type::Move) return true;
        const auto hit = rayPlane(e, dragPlanePoint_, dragPlaneNormal_);
        if (!hit || dragItem_ >= scene.itemCount()) return true;
        try {
            DocumentObject next = dragObject_;
            Points3 deboor = dragDeBoor_;
            deboor.col(dragIndex_) = *hit + dragOffset_;
            next.data = splineFromDeBoor(std::get<BezierSplineData>(dragObject_.data), deboor);
            scene.replaceObject(dragItem_, next, "move de Boor point");
            modeSnapshot_ = std::get<BezierSplineData>(next.data);
        } catch (const Error& err) {
            status() = err.what();
        }
        return true;
    }
    if (e.type != PointerEvent::Type::Press || e.button != 0 || e.mods != 0) return false;
    // A de Boor point of the selected all-C2 spline.
    int item = -1;
    const DocumentObject* object = selectedObject(c, item);
    const auto* d = object ? std::get_if<BezierSplineData>(&object->data) : nullptr;
    if (!d || !allC2(*d, jointModes(scene, item))) return false;
    try {
        const Points3 deboor = splineDeBoorPoints(*d);
        int best = -1;
        double bestDistance = 9.0; // pixels
        for (Eigen::Index i = 0; i < deboor.cols(); ++i) {
            const auto px = toPixel(c, deboor.col(i));
            if (!px) continue;
            const double dist = (*px - Eigen::Vector2d(e.x, e.y)).norm();
            if (dist < bestDistance) bestDistance = dist, best = static_cast<int>(i);
        }
        if (best < 0) return false;
        dragItem_ = item;
        dragIndex_ = best;
        dragDeBoor_ = deboor;
        dragObject_ = *object;
        dragPlanePoint_ = deboor.col(best);
        dragPlaneNormal_ = scene.camera.back();
        const auto on = rayPlane(e, dragPlanePoint_, dragPlaneNormal_);
        dragOffset_ = on ? Eigen::Vector3d(dragPlanePoint_ - *on) : Eigen::Vector3d::Zero();
        scene.beginMerge();
        return true;
    } catch (const Error&) {
        return false; // not C2 within tolerance: no de Boor points to grab
    }
}

void SplineTool::trackJointModes(ToolContext& c)
{
    int item = -1;
    const DocumentObject* object = selectedObject(c, item);
    const auto* d = object ? std::get_if<BezierSplineData>(&object->data) : nullptr;
    if (!d) {
        modeItem_ = -1;
        modeSnapshot_.reset();
        return;
    }
    if (item != modeItem_ || !modeSnapshot_) {
        modeItem_ = item;
        modeSnapshot_ = *d;
        return;
    }
    if (modeSnapshot_->points.cols() != d->points.cols() || modeSnapshot_->degree != d->degree) {
        modeSnapshot_ = *d;
        return;
    }
    std::vector<int> moved;
    for (Eigen::Index k = 0; k < d->points.cols(); ++k)
        if (d->points.col(k) != modeSnapshot_->points.col(k)) moved.push_back(static_cast<int>(k));
    if (moved.empty()) return;
    // Undo and redo restore states of the document as they were: enforcing the modes on them would
    // be an edit of its own that clears the redo steps (a record always empties them, so a redo
    // step left means the last change was an undo or a redo).
    if (c.scene.history().canRedo()) {
        modeSnapshot_ = *d;
        return;
    }
    const std::vector<JointMode> modes = jointModes(c.scene, item);
    BezierSplineData enforced = enforceJointModes(*modeSnapshot_, *d, modes, moved);
    // Re-enforcing a mode that already holds moves points by rounding only: no edit for that.
    const double scale = std::max(1.0, d->points.cwiseAbs().maxCoeff());
    if ((enforced.points - d->points).cwiseAbs().maxCoeff() > 1e-12 * scale) {
        DocumentObject next = *object;
        next.data = enforced;
        try {
            // One change since the last look (a typed coordinate, a frame of a drag): the modes
            // complete that change, in its undo step. Several: a step of their own.
            if (c.scene.changeCount() == lastChange_ + 1) c.scene.amendObject(item, next);
            else c.scene.replaceObject(item, next, "handle mode");
        } catch (const Error& e) {
            status() = e.what();
        }
    }
    modeSnapshot_ = std::get<BezierSplineData>(c.scene.object(item).data);
}

void SplineTool::update(ToolContext& c, Overlay& o)
{
    if (dragItem_ < 0) trackJointModes(c);
    lastChange_ = c.scene.changeCount();
    int item = -1;
    const DocumentObject* object = selectedObject(c, item);
    const auto* d = object ? std::get_if<BezierSplineData>(&object->data) : nullptr;
    if (!d || !allC2(*d, jointModes(c.scene, item))) return;
    try {
        const Points3 deboor = splineDeBoorPoints(*d);
        drawPolyline(o, deboor, kDeBoor * 0.8f, d->closed);
        for (Eigen::Index i = 0; i < deboor.cols(); ++i) o.addPoint(f3(deboor.col(i)), kDeBoor);
    } catch (const Error&) {
        // A spline that is not C2 within tolerance shows no de Boor points.
    }
}

void SplineTool::reset()
{
    modeItem_ = -1;
    modeSnapshot_.reset();
    lastChange_ = -1;
    dragItem_ = dragIndex_ = -1;
}

bool SplineTool::setJointMode(ToolContext& c, JointMode mode, int joint)
{
    int item = -1;
    const DocumentObject* object = selectedObject(c, item);
    const auto* d = object ? std::get_if<BezierSplineData>(&object->data) : nullptr;
    if (!d) {
        status() = "handle modes are for bezier_spline joints";
        return false;
    }
    const int k = selectedPoint(c);
    if (joint < 0) {
        if (k < 0) {
            status() = "select a joint or a handle of the spline";
            return false;
        }
        joint = jointOfPoint(*d, k);
    }
    if (!isInnerJoint(*d, joint)) {
        status() = "joint " + std::to_string(joint) + " is an end of the spline: it has no handle mode";
        return false;
    }
    // Keep the selected handle (or the left one) and adjust the opposite one.
    const int side = k >= 0 ? sideOfPoint(*d, joint, k) : -1;
    try {
        DocumentObject next = *object;
        ObjectSettings settings = c.scene.item(item).settings;
        settings.joints = jointModes(c.scene, item);
        settings.joints[static_cast<std::size_t>(joint)] = mode;
        // The joint gets its mode keeping the chosen side; what that moved may belong to the
        // neighbouring joints (C2 moves two points on a side), so every joint's mode is enforced
        // again with the points of this joint and what it moved held in place.
        const BezierSplineData applied = applyJointMode(*d, joint, mode, side > 0 ? +1 : -1);
        std::vector<int> held;
        for (Eigen::Index k = 0; k < applied.points.cols(); ++k)
            if (applied.points.col(k) != d->points.col(k)) held.push_back(static_cast<int>(k));
        const int column = jointColumn(applied, joint);
        const auto total = static_cast<int>(applied.points.cols());
        for (int offset = -1; offset <= 1; ++offset) held.push_back(applied.closed ? ((column + offset) % total + total) % total : column + offset);
        const BezierSplineData enforced = enforceJointModes(applied, applied, settings.joints, held);
        // Modes that already hold are not re-applied (that would move points by rounding only).
        const double scale = std::max(1.0, applied.points.cwiseAbs().maxCoeff());
        next.data = (enforced.points - applied.points).cwiseAbs().maxCoeff() > 1e-12 * scale ? enforced : applied;
        c.scene.beginMerge();
        c.scene.setSettings(item, settings, "handle mode");
        c.scene.replaceObject(item, next, "handle mode");
        c.scene.endMerge();
        modeSnapshot_ = std::get<BezierSplineData>(c.scene.object(item).data);
        status() = std::string("joint ") + std::to_string(joint) + ": " + toString(mode);
        return true;
    } catch (const Error& e) {
        c.scene.endMerge();
        status() = e.what();
        return false;
    }
}

bool SplineTool::setAllJointModes(ToolContext& c, JointMode mode)
{
    int item = -1;
    const DocumentObject* object = selectedObject(c, item);
    const auto* d = object ? std::get_if<BezierSplineData>(&object->data) : nullptr;
    if (!d) {
        status() = "handle modes are for bezier_spline joints";
        return false;
    }
    try {
        BezierSplineData data = *d;
        ObjectSettings settings = c.scene.item(item).settings;
        settings.joints = jointModes(c.scene, item);
        if (mode == JointMode::C2 && data.degree != 3)
            throw Error("C2 handle mode: the spline must be cubic (elevate or use a deboor_spline)");
        for (int j = 0; j < static_cast<int>(settings.joints.size()); ++j)
            if (isInnerJoint(data, j)) settings.joints[static_cast<std::size_t>(j)] = mode;
        if (mode == JointMode::C2) data = c2ThroughJoints(data);
        // Aligned and mirrored: every joint at once, no side preferred: the joints stay, and the
        // handles change least (aligned: along the bisector of the two handle directions).
        else if (mode != JointMode::Free) data = enforceJointModes(data, data, settings.joints, {});
        DocumentObject next = *object;
        next.data = data;
        c.scene.beginMerge();
        c.scene.setSettings(item, settings, "handle modes");
        c.scene.replaceObject(item, next, "handle modes");
        c.scene.endMerge();
        modeSnapshot_ = data;
        status().clear();
        return true;
    } catch (const Error& e) {
        c.scene.endMerge();
        status() = e.what();
        return false;
    }
}

} // namespace freeform::editor
