#pragma once
// The tooltip audit behind the replay event "tooltip_audit" (docs/editor.md, "Replaying input"):
// a test hook that proves "every control has a tooltip" (test_render_tooltips). The pointer is
// moved over a grid of points covering every panel shown (a step of half a line height, every
// scroll position of the panels and of their scrolling children), one ImGui frame per point
// (the panels only: nothing is drawn, nothing is clicked). Where ImGui reports a hovered item
// (its HoveredId: buttons, checkboxes, combos, sliders, drag and input fields, colour edits,
// selectables, menu items, headers, tree nodes, table headers; plain text is no item), a tooltip
// window must be open in that frame. The window's own chrome (title bar buttons, scrollbars,
// resize grips and borders, table column borders) is not a control of the panels and is skipped.
// Each item hovered is named by its ID path (window, then the labels and IDs pushed, as ImGui's
// stack tool finds them; a label of more than about 55 characters is cut there by ImGui and ends in "..."
// here: find such items by their tooltip text). Every dropdown (combo) hovered is opened by a click and its list swept
// the same way, so that each choice needs its own tooltip. Nothing here runs unless a replay asks
// for it.

#include <functional>
#include <string>
#include <vector>

namespace freeform::editor {

struct TooltipAuditItem {
    std::string window;    // the top-level window (panel, menu, dialog) it was found in
    std::string path;      // its ID path, e.g. Properties > "tessellation" (labels quoted, numbers as pushed)
    float x = 0, y = 0;    // the first point where it was hovered (window pixels)
    bool scrolled = false; // found while the sweep had scrolled a panel (x, y then need that scroll)
    int hovered = 0;       // how many points of the grid hovered it
    bool tooltip = false;  // a tooltip was open at every one of them
    std::string text;      // the tooltip text the panels reported at the first point (may be "" if drawn by ImGui itself)
    std::string dropdown;  // a choice in an open dropdown: that dropdown's ID path ("" for every other item)
};

/// A dropdown (combo) the sweep opened: clicked where it was hovered, its open list swept like a
/// window (each choice must have its own tooltip), then closed again.
struct TooltipAuditDropdown {
    std::string window; // the top-level window it is in
    std::string path;   // its ID path
    bool opened = false; // the click opened its list
    int choices = 0;     // the choices hovered in the open list
};

struct TooltipAudit {
    int points = 0;                   // grid points visited
    float step = 0;                   // their spacing in pixels
    std::vector<std::string> windows; // the top-level windows swept
    std::vector<TooltipAuditItem> items;
    std::vector<TooltipAuditDropdown> dropdowns;
};

/// Runs the sweep. `frame(hook)` must build one ImGui frame of the panels (NewFrame, then
/// `hook()` when it is set, then the panels, then Render), with the pointer where io.MousePos
/// says; `shownTooltip` is the tooltip text the panels report for the last frame. `step` <= 0:
/// half of ImGui's line height with spacing. The pointer and the scroll positions are put back
/// afterwards. Needs a current ImGui context that has rendered at least one frame.
/// `windows`: only the top-level windows of these names (empty: every one shown).
/// `dropdowns`: the IDs of the dropdowns the panels drew in the last frame (UiState::dropdowns):
/// each one hovered is opened by a click (a press and a release where it was hovered), its list
/// swept, and closed (its choice unchanged: nothing in the list is clicked).
TooltipAudit auditTooltips(const std::function<void(const std::function<void()>&)>& frame, const std::string& shownTooltip, float step,
                           const std::vector<std::string>& windows = {}, const std::vector<unsigned>* dropdowns = nullptr);

} // namespace freeform::editor
