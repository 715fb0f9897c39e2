#pragma once
// Clipped-text checks (docs/editor.md, "Nothing clipped"): the panels ask, for the texts they draw
// in table cells, numeric fields and the status bar, and for each panel as a whole, whether the
// text got the room it needs, and record every overflow (panel, label, needed and available
// pixels). Nothing is shown: the list goes to the state dump (--state, "overflows"), where
// editor/tests/test_render_layout_fit.cpp asserts it is empty at 900 x 600, 1280 x 800 and
// 1600 x 1000 with each object type selected.

#include <string>
#include <vector>

namespace freeform::editor {

/// Text that did not get the width it needs.
struct Overflow {
    std::string panel; // the top-level window (Properties, Display, Scene, ##status ...)
    std::string label; // what was cut: the label or value text, or "(widest row)" for a panel
    float needed = 0, available = 0; // pixels
};

/// Where the checks record until the next call (nullptr: nowhere); drawUi sets it for its frame.
/// Each (panel, label) is kept once, with the largest shortfall seen.
void recordOverflowsInto(std::vector<Overflow>* list);

/// The last item (text, button, field ...) against the visible area it was drawn in: the panel's
/// clip rectangle, or its table cell's. `label` names it in the record. Inside a window or table
/// that scrolls sideways everything can be reached, and nothing is recorded.
void fitItem(const char* label);

/// A text about to be drawn at the cursor (e.g. a table header): its width against the room to the
/// right of the cursor (the cell's or the panel's, whichever ends first).
void fitText(const char* text);

/// A value drawn inside the last item (a numeric field): its text and the frame padding against the
/// item's width; also fitItem(text).
void fitValue(const char* text);

/// The current panel as a whole, before its End(): the widest thing laid out in it (including a
/// table's natural width) against its visible width. A panel with a horizontal scroll bar shows
/// everything and passes. Recorded as "(widest row)", or "(widest row, <what>)" with `what` (e.g.
/// the selected object's type).
void fitPanel(const std::string& what = "");

/// A dialog, menu or other window that sizes itself to its contents, before its End(): as
/// fitPanel(what) (the widest row against the visible width; a dialog wider than the screen is made
/// narrower than its rows by ImGui), and its rectangle against the screen (the main viewport): a
/// window reaching past an edge of the screen is cut there, recorded as "(cut by the screen, width)"
/// or "(cut by the screen, height)". Not in the frames where the window appears (its size is not
/// known yet).
void fitWindow(const std::string& what = "");

/// A text that needs `needed` pixels and gets `available`.
void fitWidth(const char* label, float needed, float available);

/// Before a widget of n fields in a row (DragFloat3, InputFloat2, ColorEdit3 ...) of the next
/// item width: each of the n texts against its field's width, as ImGui divides the width (less
/// `reserve`, e.g. a colour swatch and its spacing). A typed field (InputFloat2: the text from the
/// frame's left padding) needs the text and both paddings; a drag field (`centred`: ImGui centres
/// the text and clips it at the frame) the text and 1 px on each side.
void fitFields(const char* const texts[], int n, float reserve = 0, bool centred = false);

/// The width a numeric field needs to show `text` whole (the text and the frame's padding).
float fieldWidthFor(const char* text);

} // namespace freeform::editor
