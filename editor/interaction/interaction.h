#pragma once
// The generic editing of control points with pointer and keys, for every object type: picking
// (nearest point on screen within a radius, the selected item's points first), shift-click to
// toggle, Ctrl+drag box selection, select all / none, hover highlight, clicking a curve or surface
// to select its item, dragging points in the view plane or through the translate gizmo along an
// axis or in a plane, G (grab) with X/Y/Z constraints, snapping to the grid, proportional ("soft")
// editing. Every move goes through Scene::setControlPoints inside beginMerge/endMerge, so one drag
// is one undo step; Escape (or the right button) during a drag takes it back.
//
// The application calls press/move/release/click/key with pixel coordinates of the view (origin
// top left) and a ViewTransform of the current camera; fillOverlay draws the highlights, the
// gizmo, the soft radius and the selection box. No GL, no ImGui: tests drive it directly.

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "interaction/manipulation.h"
#include "interaction/picking.h"
#include "interaction/selection.h"
#include "scene/overlay.h"
#include "scene/scene.h"

namespace freeform::editor {

/// The editing options the panels and keys change.
struct EditSettings {
    bool snap = false;          // Shift+Tab: the grabbed point lands on the grid
    bool soft = false;          // O: proportional editing
    double softRadius = 0;      // world units; 0: a quarter of the scene's diagonal when first used
    bool gizmo = true;          // Shift+G: the translate gizmo on the selected points
    double pickSlack = 4;       // pixels beyond the drawn point radius that still pick it
};

class Interaction {
public:
    explicit Interaction(EditSettings& settings) : settings_(settings) {}

    /// A button went down at (x, y). True when the interaction took it (a point, the gizmo, a box,
    /// a grab being confirmed or cancelled); false leaves it to the camera (and, when the pointer
    /// does not move before the release, to click()).
    bool press(Scene& scene, Selection& selection, const ViewTransform& view, int button, int mods, double x, double y);
    /// The pointer moved: drags the points or the box, or updates the hover highlight.
    void move(Scene& scene, Selection& selection, const ViewTransform& view, double x, double y);
    /// A button went up: ends a drag (one undo step) or a box selection.
    void release(Scene& scene, Selection& selection, const ViewTransform& view, int button, int mods, double x, double y);
    /// A click on empty space (no point there, the pointer did not move): selects the curve or
    /// surface under it, or clears the selected points (and then the item).
    void click(Scene& scene, Selection& selection, const ViewTransform& view, int mods, double x, double y);
    /// A key (GLFW code and modifier bits); true when taken. (x, y): the pointer, for G.
    bool key(Scene& scene, Selection& selection, const ViewTransform& view, int key, int mods, double x, double y);
    /// True while a drag or grab owns the keys (X/Y/Z, Enter, Escape) before anyone else.
    bool busy() const { return mode_ == Mode::Drag || mode_ == Mode::Grab; }
    /// Ends any gesture, keeping what it did (the scene is about to be replaced or undone).
    void finish(Scene& scene);
    /// Ends any gesture and takes it back.
    void cancel(Scene& scene);

    /// Selected points, hover, gizmo, soft radius, selection box.
    void fillOverlay(const Scene& scene, const Selection& selection, const ViewTransform& view, Overlay& overlay) const;

    /// The pick radius in pixels for points drawn `pointSize` pixels wide.
    double pickRadius(const Scene& scene) const;
    /// The item and control point under (x, y): the selected item's points first, then those of
    /// the other visible items whose points are drawn (View > points).
    std::optional<std::pair<int, int>> pickControlPoint(const Scene& scene, const Selection& selection,
                                                        const ViewTransform& view, double x, double y) const;
    /// The item whose curve or surface is under (x, y), nearest first.
    std::optional<int> pickItem(const Scene& scene, const ViewTransform& view, double x, double y) const;
    /// The centroid of the selected points (the gizmo's place).
    std::optional<Eigen::Vector3d> selectionCentre(const Scene& scene, const Selection& selection) const;
    /// The soft radius, initialised from the scene when still 0.
    double softRadius(const Scene& scene) const;

    /// Which constraint a running drag or grab uses (View otherwise).
    Constraint constraint() const { return constraint_; }

private:
    enum class Mode { None, Drag, Grab, Box };
    void startMove(Scene& scene, const Selection& selection, Constraint constraint, int grabPoint, double x, double y);
    void applyMove(Scene& scene, const ViewTransform& view, double x, double y);
    void setConstraint(Scene& scene, const ViewTransform& view, Constraint c);

    EditSettings& settings_;
    Mode mode_ = Mode::None;
    Constraint constraint_ = Constraint::View;
    double startX_ = 0, startY_ = 0, x_ = 0, y_ = 0;
    bool boxAdd_ = false;
    int item_ = -1;
    int grabIndex_ = -1;                 // column of moving_ that snaps exactly (-1: none)
    Eigen::Vector3d grab_ = Eigen::Vector3d::Zero();
    std::vector<int> moving_;            // control points that move (selected, and soft neighbours)
    Eigen::Matrix3Xd start_;             // their positions when the gesture began
    std::vector<double> weights_;        // 1 selected, falloff for soft neighbours
    Eigen::Vector3d lastDelta_ = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
    double step_ = 0;                    // grid step frozen for the gesture
    bool moved_ = false;                 // the gesture has changed the points (a click does not)
    int activePoint_ = -1;               // the point last clicked (G grabs it)
    std::optional<Constraint> gizmoHover_;
};

} // namespace freeform::editor
