#pragma once
// The editing tools as one set, the application's entry point (app/) and the panels' (ui/): one
// object per tool (tools/tool.h), each owning its state (its panel is ui/'s); the set dispatches keys
// (through the keymap, interaction/keymap.h), pointer events and the per-frame update to them in a
// fixed order and holds the status line they share. The interaction layer (selection, picking,
// dragging, gizmo) is generic over control points; the tools add what is specific to an object
// type. The deformed mesh of a lattice is not a tool's: the scene derives it (scene/derived.h).
//
// Where a new tool goes: a class deriving from Tool in tools/<name>_tool.{h,cpp}, its panel as
// drawPanel(<Tool>&, ToolContext&) in ui/tool_panels.{h,cpp} (called from drawToolPanels), its keys
// as a KeyContext with entries in interaction/keymap.cpp, and one line in Tools' constructor.

#include <memory>
#include <string>
#include <vector>

#include "tools/cage_tool.h"
#include "tools/curve_tool.h"
#include "tools/lattice_tool.h"
#include "tools/nurbs_tool.h"
#include "tools/patch_tool.h"
#include "tools/spline_tool.h"
#include "tools/tool.h"
#include "tools/tool_util.h"

namespace freeform::editor {

class Tools {
public:
    Tools();
    Tools(const Tools&) = delete;
    Tools& operator=(const Tools&) = delete;

    /// A key press (GLFW key code and modifier bits) not taken by the panels: the tools' keymap
    /// contexts are looked up in turn (creation first), and the first tool that uses its action
    /// takes the key (true; the application then ignores it).
    bool onKey(ToolContext& context, int key, int mods);
    /// A pointer event not taken by the panels; true when a tool took it (e.g. a click that adds a
    /// curve point, or the start of a de Boor or direct-manipulation drag), so the generic picking
    /// and dragging leave it alone.
    bool onPointer(ToolContext& context, const PointerEvent& event);
    /// Called once per frame before drawing: each tool's follow-up (joint modes) and overlay.
    void update(ToolContext& context, Overlay& overlay);
    /// The scene was replaced (new, open, recovery): every tool starts afresh.
    void reset();

    CurveTool& curve() { return curve_; }
    SplineTool& spline() { return spline_; }
    PatchTool& patch() { return patch_; }
    LatticeTool& lattice() { return lattice_; }
    NurbsTool& nurbs() { return nurbs_; }
    CageTool& cage() { return cage_; }
    /// The tools in dispatch order.
    const std::vector<Tool*>& all() const { return all_; }

    /// The status line: the last operation's error or result.
    std::string& message() { return message_; }

private:
    std::string message_;
    CurveTool curve_{message_};
    SplineTool spline_{message_};
    PatchTool patch_{message_};
    LatticeTool lattice_{message_};
    NurbsTool nurbs_{message_};
    CageTool cage_{message_};
    std::vector<Tool*> all_;
};

} // namespace freeform::editor
