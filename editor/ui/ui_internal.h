#pragma once
// What the three files of the ImGui panels share (private to editor/ui): ui.cpp defines these
// helpers (the panels' places, the status bar's height, dialog keys, colour and material fields,
// recent files' labels) and draws the status bar and the legend; ui_panels.cpp draws the Scene,
// Properties and Display panels; ui_menu_dialogs.cpp the main menu and the dialogs. drawUi
// (ui.cpp) calls the panels of the other two in its order.

#include <imgui.h>

#include <cstdio>
#include <string>

#include "ui/ui.h"

namespace freeform::editor::ui_detail {

/// Height of the main menu bar (the panels start below it).
float menuHeight();

/// ImGui 1.86 maps its named keys to the backend's key codes.
bool keyPressed(ImGuiKey key);

/// A key that went down in this frame (no repeat), when the dialog that asks has been up since an
/// earlier frame (`since`: the frame it appeared in, set here on its first frame).
bool dialogKey(ImGuiKey key, int& since);

/// Height of the status bar at the bottom of the window.
float statusHeight();

/// The panels' places for a window of the current size: Scene top left, Display below it to the
/// bottom, Properties top right; the same places as before at 1280 x 800, and none off-screen at
/// small sizes. Applied on the first frame and whenever the window's size changes.
struct Layout {
    ImVec2 scenePos, sceneSize, displayPos, displaySize, propertiesPos, propertiesSize;
};

Layout panelLayout();

/// Keeps the next panel's bottom above the status bar, which grows when its text wraps: a height
/// limit from the panel's top (where it was last frame, or where the layout puts it now).
void keepAboveStatusBar(const UiState& s, const char* name, const ImVec2& layoutPos);

/// Remembers where the current window is (for --state).
void notePanel(UiState& s, const char* name);

/// The texts of n float fields at a printf format (for fitFields).
struct FieldTexts {
    char text[4][32];
    const char* pointers[4];
    FieldTexts(const float* v, int n, const char* format)
    {
        for (int k = 0; k < n && k < 4; ++k) {
            std::snprintf(text[k], sizeof text[k], format, double(v[k]));
            pointers[k] = text[k];
        }
    }
};

/// The next item as wide as the row less its own label (three-field rows: colours, positions).
void widthBesideOwnLabel(const char* label);

/// A colour's three fields and swatch, as wide as the row allows.
bool colorEdit(const char* label, Vec3f& c);

/// A material's colours and shininess; true when one changed.
bool materialEditor(Material& m);

/// The label of a recent file's entry: the path, shortened in the middle when long
/// (ui/path_label.h); its ImGui ID is the entry's index (pushed by the caller) and "###recent", so
/// that neither the path's length nor a "##" in it changes the ID or cuts what is shown.
std::string recentLabel(const std::string& path);

/// A recent file's tooltip: the full path, then what choosing it does (or that the file is gone).
std::string recentTooltip(const std::string& path, bool exists, const char* action);

// ---- ui_panels.cpp
void outliner(Scene& scene, UiState& s);
void properties(Scene& scene, UiState& s, UiActions& actions);
void displayPanel(Scene& scene, UiState& s);

// ---- ui_menu_dialogs.cpp
void mainMenu(Scene& scene, UiState& s, UiActions& actions);
void pathDialog(Scene& scene, UiState& s, UiActions& actions);
bool unsavedDialog(Scene& scene, UiState& s, UiActions& actions);
void errorDialog(UiState& s);
void helpWindow(UiState& s);
void statsWindow(UiState& s);
void recoveryDialog(UiState& s, UiActions& actions);

} // namespace freeform::editor::ui_detail
