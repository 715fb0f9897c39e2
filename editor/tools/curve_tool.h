#pragma once
// The curve tool: Bezier curves, Bezier splines and de Boor splines. Creation by clicking (C: a
// curve through its control points; Shift+C: a C2 cubic spline through the clicked points, its
// joints in mode C2), degree elevation, splitting at the t slider, inserting and deleting points
// (joints of splines), the de Casteljau construction at t and the curvature comb.

#include "tools/curve_tools.h"
#include "tools/tool.h"

namespace freeform::editor {

class CurveTool final : public Tool {
public:
    using Tool::Tool;

    KeyContext keyContext() const override { return KeyContext::Curve; }
    bool onKey(ToolContext& context, KeyAction action) override;
    bool onPointer(ToolContext& context, const PointerEvent& event) override;
    void update(ToolContext& context, Overlay& overlay) override;
    void reset() override;

    // ---- operations (true on success; else the status line says why)
    /// Ends the creation: the clicked points become a curve (or a C2 spline).
    bool createFromClicks(ToolContext& context);
    /// Starts creating a curve (spline = false) or a C2 spline by clicking.
    void startCreating(bool spline);
    bool elevateSelected(ToolContext& context);
    bool splitSelected(ToolContext& context);
    bool insertAtSelected(ToolContext& context);
    bool deleteSelected(ToolContext& context);

    bool creating() const { return creating_; }
    bool creatingSpline() const { return creatingSpline_; }
    const Points3& newPoints() const { return newPoints_; }

    // ---- settings the panel and the tests change
    double t = 0.5;             // the t slider (global parameter fraction for splines)
    bool construction = false;  // draw the de Casteljau construction at t
    bool comb = false;          // draw curvature combs
    double combScale = 1;       // comb length relative to the automatic scale

private:
    bool onCreateKey(ToolContext& context, KeyAction action);
    void splineOverlays(Overlay& overlay, const BezierSpline<double, 3>& spline, double size) const;

    bool creating_ = false;         // "create" mode: clicks add points ...
    bool creatingSpline_ = false;   // ... of a C2 cubic spline through them (else a curve)
    Points3 newPoints_;             // the points clicked so far
};

} // namespace freeform::editor
