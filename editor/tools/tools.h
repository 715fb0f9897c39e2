#pragma once
// The editing tools' entry points, called by the application (app/) and the panels (ui/): the
// interaction layer (selection, picking, dragging, gizmo, undo) is generic over control points; the
// tools add what is specific to an object type: curve creation by clicking, point insertion and
// deletion, degree elevation, splitting, the de Casteljau construction, spline joint handle modes,
// curvature combs, patch creation, lattice fitting and live FFD of imported meshes, direct
// manipulation. No ImGui here (the panels live in ui/tool_panels.cpp).
//
// Every change to the document goes through Scene's mutating methods, so undo and redo cover the
// tools without their knowing.

#include <Eigen/Core>

#include <memory>
#include <string>

#include "interaction/selection.h"
#include "scene/overlay.h"
#include "scene/scene.h"

namespace freeform::editor {

/// A pointer event in pixels (origin top left of the view), with the camera ray through it.
struct PointerEvent {
    enum class Type { Move, Press, Release } type = Type::Move;
    int button = 0;                        // 0 left, 1 right, 2 middle
    int mods = 0;                          // GLFW modifier bits
    double x = 0, y = 0;                   // pixels
    Eigen::Vector3d rayOrigin = Eigen::Vector3d::Zero();
    Eigen::Vector3d rayDirection = Eigen::Vector3d::UnitZ(); // unit
};

/// What the tools see of the application for one call.
struct ToolContext {
    Scene& scene;
    Selection& selection;
    int viewWidth = 1, viewHeight = 1;     // pixels
    Eigen::Matrix4d viewProjection = Eigen::Matrix4d::Identity(); // world -> clip
};

/// The state of the tools (modes, t slider, lattice sessions, caches); one per application.
class Tools {
public:
    Tools();
    ~Tools();
    Tools(const Tools&) = delete;
    Tools& operator=(const Tools&) = delete;

    /// A key press (GLFW key code and modifier bits) not taken by the panels; true when a tool
    /// used it (the application then ignores it).
    bool onKey(ToolContext& context, int key, int mods);
    /// A pointer event not taken by the panels; true when a tool took it (e.g. a click that adds a
    /// curve point, or the start of a direct-manipulation drag), so the generic picking and
    /// dragging leave it alone.
    bool onPointer(ToolContext& context, const PointerEvent& event);
    /// Called once per frame before drawing: updates live results (e.g. the deformed mesh after a
    /// lattice point moved) and fills the overlay with construction geometry.
    void update(ToolContext& context, Overlay& overlay);
    /// The scene was replaced (new, open, recovery): drops caches and sessions.
    void reset();

    /// Lines for the help window: "key: what it does", one per line.
    static const char* keyHelp();

    struct State;
    State& state() { return *state_; }     // for the panels (ui/tool_panels.cpp)

private:
    std::unique_ptr<State> state_;
};

} // namespace freeform::editor
