#pragma once
// The spline tool: the joint handle modes of Bezier splines (free, aligned G1, mirrored C1, C2;
// keys 1-4 and the joints table), enforced again at every joint after every change of the
// spline's points (enforceJointModes, tools/curve_tools.h; docs/editor.md), and
// the de Boor points of an all-C2 cubic spline, drawn and dragged (the spline stays C2).
// Curve operations common to all curve types (insert, delete, split ...) are the curve tool's.

#include <optional>

#include "tools/curve_tools.h"
#include "tools/tool.h"

namespace freeform::editor {

class SplineTool final : public Tool {
public:
    using Tool::Tool;

    KeyContext keyContext() const override { return KeyContext::Spline; }
    bool onKey(ToolContext& context, KeyAction action) override;
    bool onPointer(ToolContext& context, const PointerEvent& event) override;
    /// Enforces the joint modes after a change of the selected spline's points (a drag, a typed
    /// coordinate), then draws the de Boor points of an all-C2 spline.
    void update(ToolContext& context, Overlay& overlay) override;
    void reset() override;

    /// Sets the mode of the joint of the selected point (or of `joint` >= 0) and applies it at once.
    bool setJointMode(ToolContext& context, JointMode mode, int joint = -1);
    /// All inner joints to `mode`. For C2 on a cubic spline the joints stay where they are and the
    /// handles become those of the C2 interpolant of the joints on the spline's own intervals (the
    /// end tangents kept; closed: periodic); aligned and mirrored are applied to all joints at once
    /// (enforceJointModes with nothing moved: the joints stay, the handles change least, no side
    /// preferred).
    bool setAllJointModes(ToolContext& context, JointMode mode);

    bool dragging() const { return dragItem_ >= 0; }

private:
    void trackJointModes(ToolContext& context);

    int modeItem_ = -1;                           // the spline item whose modes are tracked ...
    std::optional<BezierSplineData> modeSnapshot_; // ... and its data as last seen
    long lastChange_ = -1;                        // Scene::changeCount at the last update

    // A de Boor point being dragged.
    int dragItem_ = -1, dragIndex_ = -1;
    Eigen::Vector3d dragPlanePoint_ = Eigen::Vector3d::Zero(), dragPlaneNormal_ = Eigen::Vector3d::UnitZ();
    Eigen::Vector3d dragOffset_ = Eigen::Vector3d::Zero();
    Points3 dragDeBoor_;
    DocumentObject dragObject_;                   // the object at the start of the drag
};

} // namespace freeform::editor
