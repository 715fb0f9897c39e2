#pragma once
// The interface of one editing tool (curves, spline joints, patches, lattices, subdivision cages): like a polyscope
// structure, a tool owns its state, handles the keys of its keymap context (interaction/keymap.h)
// and the pointer events it wants, fills the overlay with its construction geometry each frame, and
// exposes the state and operations its panel uses. Tools (tools/tools.h) holds one of each and
// dispatches to them in a fixed order. No ImGui in tools/: the panels are functions of ui/
// (ui/tool_panels.h), so tools/ compiles and links without ImGui or ui/.
//
// Every change to the document goes through Scene's mutating methods, so undo and redo cover the
// tools without their knowing; an operation that fails leaves the document as it was and says why
// in the status line.

#include <Eigen/Core>

#include <string>

#include "interaction/keymap.h"
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

class Tool {
public:
    /// `status`: the tool set's status line (the last operation's error or result, shown under
    /// the panels), shared by all tools.
    explicit Tool(std::string& status) : status_(status) {}
    virtual ~Tool() = default;
    Tool(const Tool&) = delete;
    Tool& operator=(const Tool&) = delete;

    /// The keymap context whose actions this tool handles.
    virtual KeyContext keyContext() const = 0;
    /// An action of its context (looked up in the keymap); true when the tool used it (else the
    /// key goes on to the next handler: e.g. 1 with no spline point selected is the front view).
    virtual bool onKey(ToolContext& context, KeyAction action) = 0;
    /// A pointer event not taken by the panels; true when the tool took it.
    virtual bool onPointer(ToolContext&, const PointerEvent&) { return false; }
    /// Once per frame before drawing: follow-up of changes, and the overlay.
    virtual void update(ToolContext&, Overlay&) {}
    /// The scene was replaced (new, open, recovery): drops state tied to it.
    virtual void reset() = 0;
    /// The status line shared by the tool set (the panels write a failed edit's error there).
    std::string& status() { return status_; }

private:
    std::string& status_;
};

} // namespace freeform::editor
