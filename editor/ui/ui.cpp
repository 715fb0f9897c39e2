#include "ui/ui.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

#include "interaction/keymap.h"
#include "render/colour_map.h"
#include "scene/scene_drawer.h"
#include "tools/tools.h"
#include "ui/path_label.h"

namespace freeform::editor {

namespace {

constexpr float kPanelWidth = 290.0f;

/// The state of the drawUi call in progress (for tooltip(text) from the tools' panels).
UiState* currentState = nullptr;

/// Height of the main menu bar (the panels start below it).
float menuHeight()
{
    return ImGui::GetFrameHeight();
}

/// ImGui 1.86 maps its named keys to the backend's key codes.
bool keyPressed(ImGuiKey key)
{
    return ImGui::IsKeyPressed(ImGui::GetKeyIndex(key));
}

/// A key that went down in this frame (no repeat), when the dialog that asks has been up since an
/// earlier frame (`since`: the frame it appeared in, set here on its first frame).
bool dialogKey(ImGuiKey key, int& since)
{
    if (since < 0) since = ImGui::GetFrameCount();
    return ImGui::GetFrameCount() > since && ImGui::IsKeyPressed(ImGui::GetKeyIndex(key), false);
}

/// The status bar's lines at most: the text wraps at the window's width (the hint first, so the
/// active tool or mode and what the next click does are never the part cut); beyond this many
/// lines the rest is cut (its tooltip holds the whole text) and recorded (ui/fit.h).
constexpr int kStatusMaxLines = 3;

/// The status bar's height for this frame (set by drawUi from the text and the window's width).
float statusBarHeight = 0;

/// Height of the status bar at the bottom of the window.
float statusHeight()
{
    return statusBarHeight > 0 ? statusBarHeight : ImGui::GetFrameHeight() + 2;
}

/// The status bar's width for text (the window less its padding of 8 on each side).
float statusTextWidth()
{
    return std::max(ImGui::GetMainViewport()->Size.x - 16, 1.0f);
}

/// The notice after the hint, on the same line when both fit on one.
std::string statusNotice(const UiState& s)
{
    return s.notice.empty() ? std::string() : "   |   " + s.notice;
}

/// Lines the status bar needs for its text: one when hint and notice fit on one line, else the
/// hint wrapped and the notice wrapped below it.
int statusLines(const UiState& s)
{
    const float width = statusTextWidth(), line = ImGui::GetTextLineHeight();
    const std::string notice = statusNotice(s);
    if (ImGui::CalcTextSize(s.statusHint.c_str()).x + ImGui::CalcTextSize(notice.c_str()).x <= width) return 1;
    auto lines = [&](const std::string& text) {
        return text.empty() ? 0 : static_cast<int>(std::lround(ImGui::CalcTextSize(text.c_str(), nullptr, false, width).y / line));
    };
    return std::max(1, lines(s.statusHint) + lines(s.notice));
}

/// The status bar's height for `lines` lines of text (one line: the height it always had).
float statusHeightFor(int lines)
{
    const int shown = std::min(lines, kStatusMaxLines);
    return ImGui::GetFrameHeight() + 2 + float(shown - 1) * ImGui::GetTextLineHeightWithSpacing();
}

/// The panels' places for a window of the current size: Scene top left, Display below it to the
/// bottom, Properties top right; the same places as before at 1280 x 800, and none off-screen at
/// small sizes. Applied on the first frame and whenever the window's size changes.
struct Layout {
    ImVec2 scenePos, sceneSize, displayPos, displaySize, propertiesPos, propertiesSize;
};

Layout panelLayout()
{
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    const float top = vp->Pos.y + menuHeight() + 8, bottom = vp->Pos.y + vp->Size.y - statusHeight() - 8;
    const float avail = std::max(bottom - top, 120.0f);
    const float leftWidth = std::min(kPanelWidth - 20, std::max(150.0f, 0.3f * vp->Size.x));
    const float rightWidth = std::min(kPanelWidth, std::max(180.0f, 0.34f * vp->Size.x));
    Layout l;
    const float sceneHeight = std::min(260.0f, 0.4f * avail);
    l.scenePos = ImVec2(vp->Pos.x + 8, top);
    l.sceneSize = ImVec2(leftWidth, sceneHeight);
    l.displayPos = ImVec2(vp->Pos.x + 8, top + sceneHeight + 8);
    l.displaySize = ImVec2(leftWidth, std::max(avail - sceneHeight - 8, 60.0f));
    l.propertiesPos = ImVec2(vp->Pos.x + vp->Size.x - rightWidth - 8, top);
    l.propertiesSize = ImVec2(rightWidth, std::min(avail, 420.0f * std::max(1.0f, vp->Size.y / 800.0f)));
    return l;
}

/// Keeps the next panel's bottom above the status bar, which grows when its text wraps: a height
/// limit from the panel's top (where it was last frame, or where the layout puts it now).
void keepAboveStatusBar(const UiState& s, const char* name, const ImVec2& layoutPos)
{
    float top = layoutPos.y;
    if (!s.relayout)
        for (const auto& r : s.panels)
            if (r.name == name) top = r.y;
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    const float limit = vp->Pos.y + vp->Size.y - statusHeight() - 8 - top;
    ImGui::SetNextWindowSizeConstraints(ImVec2(0, 0), ImVec2(FLT_MAX, std::max(limit, 60.0f)));
}

/// Remembers where the current window is (for --state).
void notePanel(UiState& s, const char* name)
{
    const ImVec2 p = ImGui::GetWindowPos(), z = ImGui::GetWindowSize();
    for (auto& r : s.panels)
        if (r.name == name) {
            r = {name, p.x, p.y, z.x, z.y};
            return;
        }
    s.panels.push_back({name, p.x, p.y, z.x, z.y});
}

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
void widthBesideOwnLabel(const char* label)
{
    ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x - ImGui::CalcTextSize(label, nullptr, true).x - ImGui::GetStyle().ItemInnerSpacing.x);
}

bool colorEdit(const char* label, Vec3f& c)
{
    // Three drag fields of "%0.3f" beside the colour swatch (ImGui's ColorEdit3 with the Float
    // flag), as wide as the row allows.
    widthBesideOwnLabel(label);
    fitFields(FieldTexts(c.data(), 3, "%0.3f").pointers, 3, ImGui::GetFrameHeight() + ImGui::GetStyle().ItemInnerSpacing.x, true);
    return ImGui::ColorEdit3(label, c.data(), ImGuiColorEditFlags_Float);
}

bool materialEditor(Material& m)
{
    bool changed = false;
    changed |= colorEdit("ambient", m.ambient);
    tooltip("Ambient colour C_a (RGB in [0, 1]; click the swatch for a picker)");
    changed |= colorEdit("diffuse", m.diffuse);
    tooltip("Diffuse colour C_d, times max(0, l.n)");
    changed |= colorEdit("specular", m.specular);
    tooltip("Specular colour C_s, times max(0, v.r)^s (or n.h with Blinn)");
    changed |= ImGui::SliderFloat("shininess", &m.shininess, 1.0f, 500.0f, "%.0f", ImGuiSliderFlags_Logarithmic);
    tooltip("The specular exponent s: larger is a smaller, sharper highlight");
    return changed;
}

} // namespace

void askPath(UiState& s, UiActions& actions, UiState::PathDialog which, const std::string& initial)
{
    const char* titles[] = {"", "Open", "Save as", "Import mesh or .bpt", "Export OBJ"};
    const bool save = which == UiState::PathDialog::SaveAs || which == UiState::PathDialog::Export;
    if (const std::optional<std::string> chosen = actions.chooseFile(save, titles[static_cast<int>(which)], initial)) {
        if (chosen->empty()) return; // cancelled
        if (which == UiState::PathDialog::Open) actions.open(*chosen);
        else if (which == UiState::PathDialog::SaveAs) actions.saveAs(*chosen);
        else if (which == UiState::PathDialog::Import) actions.importFile(*chosen);
        else actions.exportMesh(*chosen);
        return;
    }
    s.pathDialog = which;
    std::snprintf(s.pathBuffer, sizeof s.pathBuffer, "%s", initial.c_str());
}

namespace {

/// The label of a recent file's entry: the path, shortened in the middle when long
/// (ui/path_label.h); its ImGui ID is the entry's index (pushed by the caller) and "###recent", so
/// that neither the path's length nor a "##" in it changes the ID or cuts what is shown.
std::string recentLabel(const std::string& path)
{
    std::string label;
    for (const char c : shortPathLabel(path)) {
        if (c == '#' && !label.empty() && label.back() == '#') label += ' '; // "##" would end what ImGui shows
        label += c;
    }
    return label + "###recent";
}

/// A recent file's tooltip: the full path, then what choosing it does (or that the file is gone).
std::string recentTooltip(const std::string& path, bool exists, const char* action)
{
    return path + "\n" + (exists ? action : "This file no longer exists");
}

} // namespace

void tooltip(UiState& state, const char* text)
{
    if (!ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) return;
    ImGui::SetTooltip("%s", text);
    state.tooltip = text;
}

void tooltip(const char* text)
{
    if (currentState) tooltip(*currentState, text);
    else if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) ImGui::SetTooltip("%s", text);
}

bool comboWithTips(const char* label, int& current, const Choice* choices, int count)
{
    noteDropdown(label);
    const int shown = std::clamp(current, 0, count - 1);
    bool changed = false;
    if (ImGui::BeginCombo(label, choices[shown].label)) {
        for (int k = 0; k < count; ++k) {
            ImGui::PushID(k);
            if (ImGui::Selectable(choices[k].label, k == shown) && k != current) {
                current = k;
                changed = true;
            }
            if (k == shown) ImGui::SetItemDefaultFocus();
            tooltip(choices[k].tip);
            ImGui::PopID();
        }
        ImGui::EndCombo();
    }
    return changed;
}

void noteDropdown(const char* label)
{
    if (currentState) currentState->dropdowns.push_back(ImGui::GetID(label));
}

void recordWidget(const char* name)
{
    if (!currentState || !ImGui::IsItemVisible()) return;
    const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
    currentState->widgets.push_back({name, lo.x, lo.y, hi.x - lo.x, hi.y - lo.y});
}

void recordLatticeReadout(const UiState::LatticeReadout& readout)
{
    if (currentState) currentState->latticeReadout = readout;
}

bool scalarRangeControls(DisplaySettings& d)
{
    bool changed = ImGui::Checkbox("auto range", &d.scalarAuto);
    tooltip("On: the colours span the det J values drawn now (they rescale while you drag).\n"
            "Off: the fixed range below (default 0 to 2; det J = 1, the volume kept, in the middle).");
    if (!d.scalarAuto) {
        float range[2] = {d.scalarMin, d.scalarMax};
        fitFields(FieldTexts(range, 2, "%.3g").pointers, 2);
        if (ImGui::InputFloat2("min, max", range, "%.3g", ImGuiInputTextFlags_EnterReturnsTrue) && std::isfinite(range[0]) &&
            std::isfinite(range[1]) && range[0] < range[1]) {
            d.scalarMin = range[0];
            d.scalarMax = range[1];
            changed = true;
        }
        tooltip("The det J values at the two ends of the colour bar (Enter applies; min < max).\n"
                "Values outside get the end colours. Saved with the document's display settings.");
    }
    return changed;
}

namespace {

/// Ends an open menu; Escape closes it (and the menus it was opened from): ImGui 1.86 does so
/// only with keyboard navigation on, which the editor leaves off (its keys are its own).
void endMenu()
{
    if (keyPressed(ImGuiKey_Escape)) ImGui::CloseCurrentPopup();
    ImGui::EndMenu();
}

void mainMenu(Scene& scene, UiState& s, UiActions& actions)
{
    if (!ImGui::BeginMainMenuBar()) return;
    // A menu's title has its tooltip while the menu is closed (open, the menu itself shows).
    const bool fileMenu = ImGui::BeginMenu("File");
    recordWidget("menu File");
    if (!fileMenu) tooltip(s, "New, Open, Save, Import a mesh or .bpt, Export the tessellation, Quit");
    if (fileMenu) {
        if (ImGui::MenuItem("New", "Ctrl+N")) actions.newDocument();
        tooltip(s, "An empty document (asks first when there are unsaved changes)");
        if (ImGui::MenuItem("Open...", "Ctrl+O")) askPath(s, actions, UiState::PathDialog::Open, scene.path());
        tooltip(s, "Open a freeform document (.json), a .bpt patch file or a mesh");
        const bool recentMenu = ImGui::BeginMenu("Open recent", !actions.recentFiles().empty());
        if (recentMenu) {
            // Most recent first; a file that is gone is shown greyed and cannot be chosen.
            for (std::size_t k = 0; k < actions.recentFiles().size(); ++k) {
                const std::string& path = actions.recentFiles()[k];
                std::error_code ec;
                const bool exists = std::filesystem::exists(path, ec);
                ImGui::PushID(static_cast<int>(k));
                if (ImGui::MenuItem(recentLabel(path).c_str(), nullptr, false, exists)) actions.open(path);
                tooltip(s, recentTooltip(path, exists, "Open this document (asks first when there are unsaved changes)").c_str());
                ImGui::PopID();
            }
            fitWindow();
            endMenu();
        }
        // After EndMenu the last item is "Open recent" again: its tooltip shows while its list is open too.
        tooltip(s, actions.recentFiles().empty() ? "The last 8 documents opened or saved (none yet)"
                                                 : "The last 8 documents opened or saved, most recent first");
        if (ImGui::MenuItem("Save", "Ctrl+S")) {
            if (scene.path().empty()) askPath(s, actions, UiState::PathDialog::SaveAs, "scene.json");
            else actions.save();
        }
        tooltip(s, "Write the document (atomically: a crash never destroys the previous file)");
        if (ImGui::MenuItem("Save as...", "Ctrl+Shift+S"))
            askPath(s, actions, UiState::PathDialog::SaveAs, scene.path().empty() ? "scene.json" : scene.path());
        tooltip(s, "Write the document under a new path");
        ImGui::Separator();
        if (ImGui::MenuItem("Import mesh or .bpt...", "Ctrl+I")) askPath(s, actions, UiState::PathDialog::Import, "");
        tooltip(s, "Add a mesh (.obj .ply .stl .off .gltf .glb) or the patches of a .bpt file to the document");
        if (ImGui::MenuItem("Export tessellation as OBJ...", "Ctrl+E")) askPath(s, actions, UiState::PathDialog::Export, "scene.obj");
        tooltip(s, "Write every visible surface and mesh, merged, as one OBJ");
        ImGui::Separator();
        if (ImGui::MenuItem("Quit", "Ctrl+Q")) actions.quit();
        tooltip(s, "Close the editor (asks first when there are unsaved changes)");
        fitWindow();
        endMenu();
    }
    const bool editMenu = ImGui::BeginMenu("Edit");
    if (!editMenu) tooltip(s, "Undo, redo, select points, snapping, proportional editing, the gizmo");
    if (editMenu) {
        const auto& h = scene.history();
        const std::string undoText = h.canUndo() ? "Undo " + h.undoLabel() : std::string("Undo");
        const std::string redoText = h.canRedo() ? "Redo " + h.redoLabel() : std::string("Redo");
        if (ImGui::MenuItem(undoText.c_str(), "Ctrl+Z", false, h.canUndo())) actions.undo();
        tooltip(s, "Take the last change back (the last 1000 are kept)");
        if (ImGui::MenuItem(redoText.c_str(), "Ctrl+Shift+Z", false, h.canRedo())) actions.redo();
        tooltip(s, "Make the last undone change again (also Ctrl+Y)");
        ImGui::Separator();
        Selection& sel = s.selection;
        const bool hasItem = sel.item >= 0 && sel.item < scene.itemCount();
        if (ImGui::MenuItem("Select all points", "A", false, hasItem)) {
            std::vector<int> all(static_cast<std::size_t>(scene.controlPointCount(sel.item)));
            for (std::size_t k = 0; k < all.size(); ++k) all[k] = static_cast<int>(k);
            sel.setPoints(std::move(all));
        }
        tooltip(s, "Select every control point of the selected object");
        if (ImGui::MenuItem("Select none", "Alt+A", false, !sel.points.empty())) sel.points.clear();
        tooltip(s, "Deselect the points (the object stays selected)");
        ImGui::Separator();
        ImGui::MenuItem("Snap to grid", "Shift+Tab", &s.edit.snap);
        tooltip(s, "Dragged points land on multiples of the ground grid's step");
        ImGui::MenuItem("Proportional editing", "O", &s.edit.soft);
        tooltip(s, "Unselected points within the radius follow a drag, with a smooth falloff");
        ImGui::MenuItem("Translate gizmo", "Shift+G", &s.edit.gizmo);
        tooltip(s, "Arrows and squares at the selected points' centre: drag along an axis or in a plane");
        fitWindow();
        endMenu();
    }
    const bool viewMenu = ImGui::BeginMenu("View");
    if (!viewMenu) tooltip(s, "Shading, the camera's side and projection, fitting, the Display panel, statistics");
    if (viewMenu) {
        DisplaySettings& d = scene.display;
        int shading = static_cast<int>(d.shading);
        bool shadingChanged = ImGui::RadioButton("flat", &shading, 0);
        tooltip(s, "One colour per triangle");
        shadingChanged |= ImGui::RadioButton("Gouraud", &shading, 1);
        tooltip(s, "Lit at the vertices, colours interpolated");
        shadingChanged |= ImGui::RadioButton("Phong", &shading, 2);
        tooltip(s, "Normals interpolated and lit per pixel");
        if (shadingChanged) {
            d.shading = static_cast<Shading>(shading);
            scene.touch();
        }
        ImGui::Separator();
        for (const char* v : {"front", "back", "left", "right", "top", "bottom", "iso"}) {
            if (ImGui::MenuItem(v)) actions.setView(v);
            tooltip(s, "Look at the scene from this side (keys 1, 3, 7 with Ctrl for the opposite, 9: iso)");
        }
        ImGui::Separator();
        if (ImGui::MenuItem("Fit all", "Home")) actions.fit(false);
        tooltip(s, "Move the camera so that everything just fits");
        if (ImGui::MenuItem("Fit selection", "F", false, s.selection.item >= 0)) actions.fit(true);
        tooltip(s, "Move the camera so that the selected points (else the object) just fit");
        bool ortho = scene.camera.projection == Projection::Orthographic;
        if (ImGui::MenuItem("Orthographic", "5", &ortho)) {
            scene.camera.projection = ortho ? Projection::Orthographic : Projection::Perspective;
            scene.touch();
        }
        tooltip(s, "Orthographic or perspective projection");
        bool arcball = scene.camera.orbit == OrbitMode::Arcball;
        if (ImGui::MenuItem("Arcball orbit", nullptr, &arcball)) {
            scene.camera.orbit = arcball ? OrbitMode::Arcball : OrbitMode::Turntable;
            scene.touch();
        }
        tooltip(s, "Orbit freely (arcball) rather than about world z with a level horizon (turntable)");
        ImGui::MenuItem("Display panel", nullptr, &s.showDisplay);
        tooltip(s, "Show or hide the Display panel");
        ImGui::MenuItem("Frame statistics", "F2", &s.showStats);
        tooltip(s, "Frame time, update time and triangle count at the bottom of the view");
        fitWindow();
        endMenu();
    }
    const bool helpMenu = ImGui::BeginMenu("Help");
    if (!helpMenu) tooltip(s, "The controls and the first steps (F1)");
    if (helpMenu) {
        ImGui::MenuItem("Controls", "F1", &s.showHelp);
        tooltip(s, "First steps, the mouse and every key");
        fitWindow();
        endMenu();
    }
    ImGui::Separator();
    const std::string full = (scene.path().empty() ? std::string("untitled") : scene.path()) + (scene.modified() ? " *" : "");
    char stats[96];
    std::snprintf(stats, sizeof stats, "   %ld triangles   %.1f ms", s.triangles, s.frameMs);
    // The document's path, or only its file name where the whole path and the figures do not fit.
    const float room = ImGui::GetWindowDrawList()->GetClipRectMax().x - ImGui::GetCursorScreenPos().x - ImGui::CalcTextSize(stats).x -
                       2 * ImGui::GetStyle().ItemSpacing.x;
    std::string title = full;
    if (ImGui::CalcTextSize(full.c_str()).x > room && !scene.path().empty())
        title = std::filesystem::path(scene.path()).filename().string() + (scene.modified() ? " *" : "");
    ImGui::TextUnformatted(title.c_str());
    fitItem(title.c_str());
    if (title != full) tooltip(s, full.c_str());
    ImGui::TextDisabled("%s", stats);
    fitItem(stats);
    ImGui::EndMainMenuBar();
}

void outliner(Scene& scene, UiState& s)
{
    const Layout l = panelLayout();
    const ImGuiCond cond = s.relayout ? ImGuiCond_Always : ImGuiCond_FirstUseEver;
    ImGui::SetNextWindowPos(l.scenePos, cond);
    ImGui::SetNextWindowSize(l.sceneSize, cond);
    if (ImGui::Begin("Scene", nullptr, ImGuiWindowFlags_HorizontalScrollbar)) {
        notePanel(s, "Scene");
        for (int i = 0; i < scene.itemCount(); ++i) {
            SceneItem& item = scene.item(i);
            ImGui::PushID(i);
            bool visible = item.settings.visible;
            if (ImGui::Checkbox("##visible", &visible)) {
                ObjectSettings settings = item.settings;
                settings.visible = visible;
                scene.setSettings(i, settings);
            }
            tooltip(s, "Show or hide this object");
            ImGui::SameLine();
            const std::string label = item.name + "  (" + item.type + ")" + (item.geometry.error.empty() ? "" : "  !");
            if (ImGui::Selectable(label.c_str(), s.selection.item == i)) {
                if (s.selection.item == i) s.selection.clear();
                else s.selection.selectItem(i);
            }
            const std::string tip = item.name + " (" + item.type + "): click to select, again to deselect" +
                                    (item.geometry.error.empty() ? std::string() : "\n" + item.geometry.error);
            tooltip(s, tip.c_str());
            ImGui::PopID();
        }
        if (scene.itemCount() == 0) {
            ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
            ImGui::TextWrapped("empty: open or import a file, or drop one here");
            ImGui::PopStyleColor();
        }
        fitPanel();
    }
    ImGui::End();
}

/// The widest of the coordinates' texts at the fields' precision (kPointFormat), for the control
/// point table's columns: computed again only when the item's content changes (its key).
constexpr const char* kPointFormat = "%.6g";

/// A coordinate field showing `value` at kPointFormat. True, with `value` set, only when Enter
/// confirms text that was edited and reads as a finite number in full (surrounding spaces
/// allowed). Enter on the text as shown changes nothing, so a value keeps the bits its six digits
/// do not show; text that is not a number, or is not finite, is refused with a notice in the
/// status bar naming `what`, and `value` is left as it was. (ImGui's InputDouble parses the text
/// it shows back on every Enter, and takes text it cannot read without a word.)
bool coordinateField(const char* label, double& value, UiState& s, const std::string& what)
{
    char shown[64], buffer[64];
    std::snprintf(shown, sizeof shown, kPointFormat, value);
    std::memcpy(buffer, shown, sizeof buffer);
    if (!ImGui::InputText(label, buffer, sizeof buffer, ImGuiInputTextFlags_EnterReturnsTrue | ImGuiInputTextFlags_AutoSelectAll))
        return false;
    if (std::strcmp(buffer, shown) == 0) return false;
    std::string text = buffer;
    const auto space = [](char c) { return c == ' ' || c == '\t'; };
    while (!text.empty() && space(text.back())) text.pop_back();
    std::size_t first = 0;
    while (first < text.size() && space(text[first])) ++first;
    text.erase(0, first);
    char* end = nullptr;
    const double parsed = text.empty() ? 0.0 : std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size()) {
        s.notice = what + ": \"" + text + "\" is not a number; nothing changed";
        return false;
    }
    if (!std::isfinite(parsed)) {
        s.notice = what + ": " + text + " is refused, a coordinate must be finite; nothing changed";
        return false;
    }
    value = parsed;
    return true;
}

float widestCoordinate(const SceneItem& item, const Eigen::Ref<const Eigen::MatrixXd>& points)
{
    static long cachedId = -1, cachedKey = -1;
    static Eigen::Index cachedCount = -1;
    static float cachedWidth = 0;
    if (item.id == cachedId && item.key == cachedKey && points.size() == cachedCount) return cachedWidth;
    float widest = 0;
    char text[32];
    for (Eigen::Index k = 0; k < points.size(); ++k) {
        std::snprintf(text, sizeof text, kPointFormat, points.data()[k]);
        widest = std::max(widest, ImGui::CalcTextSize(text).x);
    }
    cachedId = item.id, cachedKey = item.key, cachedCount = points.size(), cachedWidth = widest;
    return widest;
}

/// The points the control point table lists: the object's own; for a subdivision cage whose mesh
/// is a file, the file's vertices as read (the ones drawn and picked), and typing one makes the
/// cage inline as dragging it does (Scene::setControlPoints).
Eigen::Ref<const Eigen::MatrixXd> tablePoints(const Scene& scene, int index)
{
    const DocumentObject& object = scene.object(index);
    if (const auto* cage = std::get_if<SubdivisionSurfaceData>(&object.data)) {
        if (!cage->mesh.empty()) return scene.item(index).geometry.netPoints;
        return cage->vertices;
    }
    return std::visit(
        [](const auto& d) -> Eigen::Ref<const Eigen::MatrixXd> {
            if constexpr (std::is_same_v<std::decay_t<decltype(d)>, SubdivisionSurfaceData>) return d.vertices;
            else return d.points;
        },
        object.data);
}

/// Editable control points of a document object: a table of one row per point, its number and
/// one field per coordinate; every field gets the width of the widest coordinate's text (when
/// the columns are wider than the panel the table scrolls sideways, the number column frozen).
void controlPointTable(Scene& scene, int index, UiState& s)
{
    const Eigen::Ref<const Eigen::MatrixXd> listed = tablePoints(scene, index);
    const Eigen::Ref<const Eigen::MatrixXd>* points = &listed;
    const int dim = static_cast<int>(points->rows());
    const int count = static_cast<int>(points->cols());
    const std::string header = "control points (" + std::to_string(count) + ")";
    const bool open = ImGui::CollapsingHeader(header.c_str(), ImGuiTreeNodeFlags_DefaultOpen);
    recordWidget(header.c_str());
    tooltip(s, "Show or hide the table of every control point's coordinates (click to fold)");
    if (!open) return;
    const ImGuiStyle& style = ImGui::GetStyle();
    // Narrow cell and frame paddings, so that three fields of typical values fit the panel.
    const ImVec2 cellPadding(2, 1), framePadding(2, style.FramePadding.y);
    const float field = std::max(widestCoordinate(scene.item(index), *points), ImGui::CalcTextSize("x").x) + 2 * framePadding.x;
    const float number = ImGui::CalcTextSize(std::to_string(std::max(count - 1, 0)).c_str()).x;
    const float natural = number + float(dim) * field + float(dim + 1) * 2 * cellPadding.x + float(dim + 2) + style.ScrollbarSize;
    ImGuiTableFlags flags = ImGuiTableFlags_BordersOuter | ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY |
                            ImGuiTableFlags_SizingFixedFit;
    if (natural > ImGui::GetContentRegionAvail().x) flags |= ImGuiTableFlags_ScrollX;
    ImGui::PushStyleVar(ImGuiStyleVar_CellPadding, cellPadding);
    if (ImGui::BeginTable("points", dim + 1, flags, ImVec2(0, 220))) {
        ImGui::TableSetupScrollFreeze(1, 1);
        ImGui::TableSetupColumn("#", ImGuiTableColumnFlags_WidthFixed, number);
        // Sharing the panel's width when they fit (each then at least `field` wide), else each
        // `field` wide and the table scrolls.
        const bool scroll = (flags & ImGuiTableFlags_ScrollX) != 0;
        static const char* axes[] = {"x", "y", "z"};
        for (int r = 0; r < dim; ++r)
            ImGui::TableSetupColumn(axes[r], scroll ? ImGuiTableColumnFlags_WidthFixed : ImGuiTableColumnFlags_WidthStretch, scroll ? field : 1.0f);
        // The header row as TableHeadersRow makes it, with a tooltip on each column's head.
        ImGui::TableNextRow(ImGuiTableRowFlags_Headers);
        for (int column = 0; column <= dim; ++column) {
            if (!ImGui::TableSetColumnIndex(column)) continue;
            ImGui::PushID(column);
            ImGui::TableHeader(ImGui::TableGetColumnName(column));
            tooltip(s, column == 0 ? "The control point's index (its place in the control net)"
                                   : "The control point's coordinate along this axis, world units; type a value and press Enter");
            ImGui::PopID();
        }
        ImGui::PushStyleVar(ImGuiStyleVar_FramePadding, framePadding);
        ImGuiListClipper clipper;
        clipper.Begin(count);
        while (clipper.Step()) {
            for (int k = clipper.DisplayStart; k < clipper.DisplayEnd; ++k) {
                double value[3] = {0, 0, 0};
                for (int r = 0; r < dim; ++r) value[r] = (*points)(r, k);
                ImGui::PushID(k);
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                const std::string label = std::to_string(k);
                ImGui::AlignTextToFramePadding();
                ImGui::TextUnformatted(label.c_str());
                fitItem(label.c_str());
                bool entered = false;
                for (int r = 0; r < dim; ++r) {
                    ImGui::TableNextColumn();
                    ImGui::PushID(r);
                    ImGui::SetNextItemWidth(-FLT_MIN);
                    const std::string what = "point " + std::to_string(k) + " " + axes[r];
                    entered |= coordinateField("##c", value[r], s, what);
                    recordWidget(("table " + what).c_str());
                    char text[32];
                    std::snprintf(text, sizeof text, kPointFormat, value[r]);
                    fitValue(text);
                    tooltip(s, "Control point coordinates; type new ones and press Enter (one undo step)");
                    ImGui::PopID();
                }
                if (entered) {
                    try {
                        scene.setControlPoint(index, k, Eigen::Vector3d(value[0], value[1], value[2]), "set point");
                    } catch (const Error& e) {
                        s.error = e.what();
                    }
                }
                ImGui::PopID();
            }
        }
        ImGui::PopStyleVar();
        ImGui::EndTable();
    }
    ImGui::PopStyleVar();
}

/// Numeric entry for the selected points: one point's coordinates, or the centroid of several
/// (editing it moves them all by the same amount). One undo step per edit.
void selectedPoints(Scene& scene, int index, UiState& s)
{
    const Eigen::Matrix3Xd points = scene.controlPoints(index);
    std::vector<int> ks;
    for (int k : s.selection.points)
        if (k < points.cols()) ks.push_back(k);
    if (ks.empty()) {
        ImGui::PushTextWrapPos(0);
        ImGui::TextDisabled("click a control point to select it (shift: add, ctrl+drag: box)");
        ImGui::PopTextWrapPos();
        return;
    }
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (int k : ks) centre += points.col(k);
    centre /= double(ks.size());
    double value[3] = {centre.x(), centre.y(), centre.z()};
    std::string label = ks.size() == 1 ? std::string("point ") : std::string();
    label += std::to_string(ks.size() == 1 ? ks.front() : static_cast<int>(ks.size()));
    if (ks.size() > 1) label += " points (centre)";
    ImGui::TextUnformatted(label.c_str());
    // One field per coordinate, each as wide as the widest of the three texts: in one row when
    // three fit the panel's width, else one per row with its axis's name.
    char texts[3][32];
    float widest = 0;
    for (int r = 0; r < 3; ++r) {
        std::snprintf(texts[r], sizeof texts[r], kPointFormat, value[r]);
        widest = std::max(widest, fieldWidthFor(texts[r]));
    }
    const float spacing = ImGui::GetStyle().ItemInnerSpacing.x, avail = ImGui::GetContentRegionAvail().x;
    const bool oneRow = 3 * widest + 2 * spacing <= avail;
    static const char* axes[] = {"x", "y", "z"};
    bool entered = false;
    for (int r = 0; r < 3; ++r) {
        ImGui::PushID(r);
        if (oneRow) {
            if (r > 0) ImGui::SameLine(0, spacing);
            ImGui::SetNextItemWidth((avail - 2 * spacing) / 3);
        } else {
            ImGui::SetNextItemWidth(avail - spacing - ImGui::CalcTextSize("x").x);
        }
        entered |= coordinateField(oneRow ? "##selected" : axes[r], value[r], s,
                                   ks.size() == 1 ? "point " + std::to_string(ks.front()) + " " + axes[r]
                                                  : std::string(axes[r]) + " of the selected points' centre");
        fitValue(texts[r]);
        recordWidget(r == 0 ? "selected x" : r == 1 ? "selected y" : "selected z");
        tooltip(s, ks.size() == 1 ? "The selected point's coordinates: type new ones and press Enter"
                                  : "The selected points' centre: a new one moves them all by the same offset (Enter)");
        ImGui::PopID();
    }
    if (entered) {
        const Eigen::Vector3d target(value[0], value[1], value[2]);
        Eigen::Matrix3Xd moved(3, static_cast<Eigen::Index>(ks.size()));
        for (std::size_t j = 0; j < ks.size(); ++j)
            moved.col(static_cast<Eigen::Index>(j)) = ks.size() == 1 ? target : Eigen::Vector3d(points.col(ks[j]) + (target - centre));
        try {
            scene.setControlPoints(index, ks, moved, ks.size() == 1 ? "set point" : "set points");
        } catch (const Error& e) {
            s.error = e.what();
        }
    }
}

/// Snapping, proportional editing and the gizmo.
void editOptions(Scene& scene, UiState& s)
{
    const bool open = ImGui::CollapsingHeader("editing");
    tooltip(s, "Snapping to the grid, proportional editing and the translate gizmo (click to unfold)");
    if (!open) return;
    ImGui::Checkbox("snap to grid (Shift+Tab)", &s.edit.snap);
    tooltip(s, "Dragged points land on multiples of the ground grid's step");
    ImGui::Checkbox("proportional (O)", &s.edit.soft);
    tooltip(s, "Unselected points within the radius follow a drag, weighted 1 - 3t^2 + 2t^3");
    if (s.edit.soft) {
        if (!(s.edit.softRadius > 0)) s.edit.softRadius = 0.25 * scene.bounds().diagonal().norm();
        const double lo = 1e-4, hi = 1e4;
        ImGui::SliderScalar("radius (+/-)", ImGuiDataType_Double, &s.edit.softRadius, &lo, &hi, "%.4g", ImGuiSliderFlags_Logarithmic);
        tooltip(s, "The proportional editing radius, world units (+ and - scale it by 1.25)");
    }
    ImGui::Checkbox("translate gizmo (Shift+G)", &s.edit.gizmo);
    tooltip(s, "Arrows and squares at the selected points' centre: drag along an axis or in a plane");
}

void properties(Scene& scene, UiState& s, UiActions& actions)
{
    const Layout l = panelLayout();
    const ImGuiCond cond = s.relayout ? ImGuiCond_Always : ImGuiCond_FirstUseEver;
    ImGui::SetNextWindowPos(l.propertiesPos, cond);
    ImGui::SetNextWindowSize(l.propertiesSize, cond);
    keepAboveStatusBar(s, "Properties", l.propertiesPos);
    if (ImGui::Begin("Properties")) {
        notePanel(s, "Properties");
        const int selected = s.selection.item;
        if (selected < 0 || selected >= scene.itemCount()) {
            ImGui::PushTextWrapPos(0);
            ImGui::TextDisabled("select an object in the Scene panel or the view");
            ImGui::PopTextWrapPos();
        } else {
            SceneItem& item = scene.item(selected);
            ImGui::Text("%s", item.name.c_str());
            ImGui::TextDisabled("%s", item.type.c_str());
            ObjectSettings settings = item.settings;
            bool changed = ImGui::Checkbox("visible", &settings.visible);
            tooltip(s, "Show or hide this object");
            if (item.kind == SceneItem::Kind::DocumentObject) {
                std::visit(
                    [](const auto& d) {
                        using T = std::decay_t<decltype(d)>;
                        if constexpr (std::is_same_v<T, BezierCurveData>) ImGui::Text("degree %d, %dD", int(d.points.cols()) - 1, int(d.points.rows()));
                        else if constexpr (std::is_same_v<T, BezierSplineData>) ImGui::Text("degree %d, %s", d.degree, d.closed ? "closed" : "open");
                        else if constexpr (std::is_same_v<T, DeBoorSplineData>) ImGui::Text("degree %d, end %s", d.degree, d.end.c_str());
                        else if constexpr (std::is_same_v<T, BezierSurfaceData> || std::is_same_v<T, DeBoorSurfaceData>) ImGui::Text("degree %d x %d", d.degree[0], d.degree[1]);
                        else if constexpr (std::is_same_v<T, LatticeData>) ImGui::Text("degree %d x %d x %d", d.degree[0], d.degree[1], d.degree[2]);
                        else if constexpr (std::is_same_v<T, SubdivisionSurfaceData>) {} // scheme, boundary, creases: the cage tool's panel
                        else ImGui::Text("%s", objectType(ObjectData(d)).c_str()); // rational and NURBS types
                    },
                    scene.object(selected).data);
            }
            if (item.geometry.surface) {
                ImGui::Text("%d vertices, %d triangles", item.geometry.surface->vertexCount(), item.geometry.surface->faceCount());
                bool tessellationOpen = false;
                if (item.kind == SceneItem::Kind::DocumentObject) {
                    tessellationOpen = ImGui::CollapsingHeader("tessellation", ImGuiTreeNodeFlags_DefaultOpen);
                    tooltip(s, "How finely this object is cut into triangles for the view and exports (click to fold)");
                }
                if (tessellationOpen) {
                    int mode = static_cast<int>(settings.tessellation.mode);
                    static const Choice modes[] = {
                        {"adaptive", "Cut each patch until its triangles lie within the tolerance of the surface (world units)"},
                        {"uniform", "Cut each patch side into a fixed number of segments, however flat or curved it is"}};
                    changed |= comboWithTips("mode", mode, modes);
                    tooltip(s, "Adaptive: to a distance; uniform: a fixed number of segments per patch side");
                    settings.tessellation.mode = static_cast<Tessellation::Mode>(mode);
                    if (settings.tessellation.mode == Tessellation::Mode::Adaptive) {
                        double t = settings.tessellation.tolerance > 0 ? settings.tessellation.tolerance : scene.display.tolerance;
                        const double lo = 1e-6, hi = 1.0;
                        if (ImGui::SliderScalar("tolerance", ImGuiDataType_Double, &t, &lo, &hi, "%.2e", ImGuiSliderFlags_Logarithmic)) {
                            settings.tessellation.tolerance = t;
                            changed = true;
                        }
                        tooltip(s, "This object's tessellation tolerance, world units (Ctrl+click types a value)");
                    } else {
                        changed |= ImGui::SliderInt("segments", &settings.tessellation.segments, 1, 200);
                        tooltip(s, "Segments per patch side");
                    }
                    changed |= ImGui::Checkbox("reverse orientation", &settings.tessellation.flip);
                    tooltip(s, "Reverse the triangles and normals (inside out)");
                }
                const bool materialOpen = ImGui::CollapsingHeader("material");
                tooltip(s, "This object's own colours and shininess (click to unfold)");
                if (materialOpen) {
                    changed |= ImGui::Checkbox("own material", &settings.ownMaterial);
                    tooltip(s, "Use a material of this object's own rather than the Display panel's");
                    if (settings.ownMaterial) changed |= materialEditor(settings.material);
                }
            }
            if (changed) scene.setSettings(selected, settings);
            if (!item.geometry.error.empty()) {
                // Wrapped: an error names files and fields and is longer than the panel is wide.
                ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.4f, 0.3f, 1));
                ImGui::TextWrapped("%s", item.geometry.error.c_str());
                ImGui::PopStyleColor();
            }
            if (item.kind == SceneItem::Kind::DocumentObject) {
                selectedPoints(scene, selected, s);
                editOptions(scene, s);
                controlPointTable(scene, selected, s);
            } else {
                ImGui::TextWrapped("file: %s", item.meshPath.c_str());
                int up = item.up == UpAxis::Y ? 1 : 0;
                static const Choice ups[] = {
                    {"Z up (as the world)", "The file's coordinates are used as they are: its z points up"},
                    {"Y up (turned to Z up)", "The file's y points up: turned a quarter about x, (x, y, z) -> (x, -z, y)"}};
                if (comboWithTips("up axis", up, ups)) {
                    scene.setUpAxis(selected, up == 1 ? UpAxis::Y : UpAxis::Z);
                }
                tooltip(s, "The file's up direction. Y up (every glTF, most OBJ files) is turned a quarter about x,\n"
                           "(x, y, z) -> (x, -z, y), so that it stands in the Z-up world; exports write the file's own\n"
                           "coordinates back. Saved in the document (meshes[].up).");
            }
            actions.toolPanels();
        }
        fitPanel(selected >= 0 && selected < scene.itemCount() ? scene.item(selected).type + " selected" : std::string());
    }
    ImGui::End();
}

void displayPanel(Scene& scene, UiState& s)
{
    if (!s.showDisplay) return;
    const Layout l = panelLayout();
    const ImGuiCond cond = s.relayout ? ImGuiCond_Always : ImGuiCond_FirstUseEver;
    ImGui::SetNextWindowPos(l.displayPos, cond);
    ImGui::SetNextWindowSize(l.displaySize, cond);
    keepAboveStatusBar(s, "Display", l.displayPos);
    if (ImGui::Begin("Display", &s.showDisplay)) {
        notePanel(s, "Display");
        // Room for the longest label ("normal length", "px tolerance") beside the widgets.
        ImGui::PushItemWidth(-(ImGui::CalcTextSize("normal length").x + 2 * ImGui::GetStyle().ItemInnerSpacing.x));
        DisplaySettings d = scene.display;
        int shading = static_cast<int>(d.shading);
        static const Choice shadings[] = {{"flat", "One colour per triangle: the facets show"},
                                          {"Gouraud", "Lit at the vertices, the colours interpolated across each triangle"},
                                          {"Phong", "The normals interpolated and lit at every pixel: the smoothest highlights"}};
        comboWithTips("shading", shading, shadings);
        tooltip(s, "Flat: one colour per triangle; Gouraud: lit per vertex; Phong: lit per pixel (key Z cycles)");
        d.shading = static_cast<Shading>(shading);
        int specular = static_cast<int>(d.specular);
        static const Choice speculars[] = {
            {"Phong (v.r)", "The highlight max(0, v.r)^s: v towards the eye, r the light's direction mirrored about the normal"},
            {"Blinn (n.h)", "Blinn-Phong's highlight max(0, n.h)^s: h halfway between the light's and the eye's directions"}};
        comboWithTips("specular", specular, speculars);
        tooltip(s, "The highlight: Phong's max(0, v.r)^s or Blinn-Phong's max(0, n.h)^s");
        d.specular = static_cast<SpecularModel>(specular);
        int analysis = static_cast<int>(d.analysis);
        static const Choice analyses[] = {
            {"none", "No analysis: every surface in its material"},
            {"reflection lines", "Stripes of a sphere map reflected in the surfaces: they break at a C0 edge and kink at a G1 one (key R)"},
            {"scalar map", "A lattice's deformed mesh coloured by det J, the local volume change (1: kept), with a legend"}};
        comboWithTips("analysis", analysis, analyses);
        tooltip(s, "Reflection lines (R) show the smoothness across edges one order down;\nthe scalar map colours a lattice's mesh by det J");
        d.analysis = static_cast<SurfaceAnalysis>(analysis);
        if (d.analysis == SurfaceAnalysis::ReflectionLines) {
            ImGui::SliderFloat("stripes", &d.stripes, 2.0f, 60.0f, "%.0f");
            tooltip(s, "Number of reflection-line stripes across the sphere map");
        }
        if (d.analysis == SurfaceAnalysis::ScalarMap) scalarRangeControls(d);
        ImGui::Checkbox("wireframe", &d.wireframe);
        tooltip(s, "Triangle edges over the shaded surface (W)");
        ImGui::SameLine();
        ImGui::Checkbox("flip normals", &d.flipNormals);
        tooltip(s, "Draw with negated normals (for meshes whose normals point inwards)");
        ImGui::Checkbox("nets", &d.controlNets);
        tooltip(s, "Control polygons and nets of every object (the selected one always shows its own)");
        ImGui::SameLine();
        ImGui::Checkbox("points", &d.controlPoints);
        tooltip(s, "Control points of every object, pickable");
        ImGui::SameLine();
        ImGui::Checkbox("normals", &d.normals);
        tooltip(s, "Surface normals as short lines");
        ImGui::Checkbox("grid", &d.grid);
        tooltip(s, "The ground grid in the plane z = 0");
        ImGui::SameLine();
        ImGui::Checkbox("axes", &d.axes);
        tooltip(s, "The x (red), y (green) and z (blue) axes");
        if (d.normals) {
            ImGui::SliderFloat("normal length", &d.normalLength, 0.001f, 0.2f, "%.3f", ImGuiSliderFlags_Logarithmic);
            tooltip(s, "Length of the normal lines, as a fraction of the scene's diameter");
        }
        ImGui::SliderFloat("point size", &d.pointSize, 2.0f, 20.0f, "%.0f px");
        tooltip(s, "Diameter of the control point discs, pixels");
        {
            // Anti-aliasing (docs/editor.md): auto (display.samples on a GPU and in screenshots,
            // none for a software renderer's frames), or a fixed multisample count everywhere.
            const int counts[] = {0, 2, 4, 8};
            int choice = 0;
            if (d.antialiasing == Antialiasing::Always)
                for (int k = 0; k < 4; ++k)
                    if (d.samples == counts[k]) choice = k + 1;
            if (d.antialiasing == Antialiasing::Always && choice == 0) choice = 3; // a count not offered: shown as 4x
            static const Choice samples[] = {
                {"auto", "The document's samples on a GPU and in screenshots, none for the frames of a software renderer (llvmpipe)"},
                {"off", "No multisampling anywhere: the edges show their steps"},
                {"2x", "2 samples per pixel everywhere"},
                {"4x", "4 samples per pixel everywhere"},
                {"8x", "8 samples per pixel everywhere (the smoothest edges, the slowest)"}};
            if (comboWithTips("anti-alias", choice, samples) && !(choice == 0 && d.antialiasing == Antialiasing::Auto)) {
                d.antialiasing = choice == 0 ? Antialiasing::Auto : Antialiasing::Always;
                if (choice > 0) d.samples = counts[choice - 1];
                else if (d.samples == 0) d.samples = 4;
            }
            tooltip(s, "Multisampling: auto = the document's samples on a GPU and in screenshots, none for the frames of a software renderer (llvmpipe); or a fixed count everywhere");
        }
        const double lo = 1e-6, hi = 1.0;
        const double plo = 0, phi = 8;
        ImGui::SliderScalar("px tolerance", ImGuiDataType_Double, &scene.pixelTolerance, &plo, &phi, "%.2f px");
        tooltip(s, "Tessellate to this many pixels of the current view (0: to the world tolerance instead).\nNot saved in the document.");
        if (!(scene.pixelTolerance > 0)) {
            ImGui::SliderScalar("tolerance", ImGuiDataType_Double, &d.tolerance, &lo, &hi, "%.2e", ImGuiSliderFlags_Logarithmic);
            tooltip(s, "Tessellation tolerance of surfaces and curves, world units (exports use it too)");
        }
        const bool materialOpen = ImGui::CollapsingHeader("material");
        tooltip(s, "The default material of surfaces (click to unfold)");
        if (materialOpen) materialEditor(d.material);
        const bool backOpen = ImGui::CollapsingHeader("back faces, background");
        tooltip(s, "The colour of back faces and of the view's background (click to unfold)");
        if (backOpen) {
            colorEdit("back faces", d.backColor);
            tooltip(s, "Diffuse colour of back faces (seen through openings or inside out)");
            colorEdit("background", d.background);
            tooltip(s, "The view's background colour");
        }
        const bool lightsOpen = ImGui::CollapsingHeader("lights", ImGuiTreeNodeFlags_DefaultOpen);
        tooltip(s, "The headlight and up to 7 point lights (click to fold)");
        if (lightsOpen) {
            ImGui::Checkbox("headlight", &d.headlight);
            tooltip(s, "A light at the eye, moving with the camera");
            if (d.headlight) {
                colorEdit("colour##headlight", d.headlightColor);
                tooltip(s, "The headlight's colour");
            }
            for (std::size_t i = 0; i < d.lights.size(); ++i) {
                ImGui::PushID(static_cast<int>(i));
                ImGui::Separator();
                ImGui::Checkbox("on", &d.lights[i].enabled);
                tooltip(s, "Switch this light on or off");
                ImGui::SameLine();
                ImGui::Text("light %zu", i + 1);
                ImGui::SameLine();
                const bool removeIt = ImGui::SmallButton("remove");
                tooltip(s, "Remove this light");
                widthBesideOwnLabel("position");
                fitFields(FieldTexts(d.lights[i].position.data(), 3, "%.3f").pointers, 3, 0, true);
                ImGui::DragFloat3("position", d.lights[i].position.data(), 0.05f);
                tooltip(s, "The light's position in world coordinates (drag, or double-click to type)");
                colorEdit("colour", d.lights[i].color);
                tooltip(s, "The light's colour");
                ImGui::PopID();
                if (removeIt) {
                    d.lights.erase(d.lights.begin() + static_cast<std::ptrdiff_t>(i));
                    break;
                }
            }
            if (static_cast<int>(d.lights.size()) < kMaxLights - 1) {
                if (ImGui::Button("add light")) d.lights.push_back(PointLight{Vec3f(5, 5, 5), Vec3f(0.3f, 0.3f, 0.3f), true});
                tooltip(s, "Add a point light (up to 7 besides the headlight)");
            }
        }
        if (!(d == scene.display)) {
            const bool retessellate = d.tolerance != scene.display.tolerance;
            scene.display = d;
            scene.touch();
            if (retessellate) scene.invalidateGeometry();
        }
        ImGui::PopItemWidth();
        fitPanel();
    }
    ImGui::End();
}

void pathDialog(Scene& scene, UiState& s, UiActions& actions)
{
    if (s.pathDialog == UiState::PathDialog::None) return;
    const char* titles[] = {"", "Open", "Save as", "Import", "Export OBJ"};
    const char* title = titles[static_cast<int>(s.pathDialog)];
    if (!ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
    if (ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::TextUnformatted("path (or drop a file on the window):");
        ImGui::SetNextItemWidth(480);
        if (ImGui::IsWindowAppearing()) {
            ImGui::SetKeyboardFocusHere();
            s.pathSelectAll = true;
        }
        const bool enter = ImGui::InputText("##path", s.pathBuffer, sizeof s.pathBuffer,
                                            ImGuiInputTextFlags_EnterReturnsTrue | (s.pathSelectAll ? ImGuiInputTextFlags_AutoSelectAll : 0));
        if (ImGui::IsItemActive()) s.pathSelectAll = false;
        tooltip(s, "The file's path, relative to the working directory; Enter confirms");
        if (s.pathDialog == UiState::PathDialog::Import) {
            int up = s.importUp == UpAxis::Y ? 1 : 0;
            ImGui::SetNextItemWidth(200);
            static const Choice ups[] = {{"Z up", "The file's coordinates are used as they are: its z points up"},
                                         {"Y up", "The file's y points up: turned a quarter about x, (x, y, z) -> (x, -z, y)"}};
            if (comboWithTips("up axis of OBJ, PLY, STL, OFF", up, ups)) s.importUp = up == 1 ? UpAxis::Y : UpAxis::Z;
            tooltip(s, "These formats do not say which way is up: Y up files are turned to the Z-up world.\n"
                       "glTF and GLB are always read Y up (the glTF specification). Remembered until the editor quits;\n"
                       "Properties > up axis changes it for one mesh.");
        }
        if (s.pathDialog == UiState::PathDialog::Open && !actions.recentFiles().empty()) {
            ImGui::TextDisabled("recent:");
            for (std::size_t k = 0; k < actions.recentFiles().size(); ++k) {
                const std::string& path = actions.recentFiles()[k];
                std::error_code ec;
                const bool exists = std::filesystem::exists(path, ec);
                ImGui::PushID(static_cast<int>(k));
                if (ImGui::Selectable(recentLabel(path).c_str(), false, exists ? 0 : ImGuiSelectableFlags_Disabled))
                    std::snprintf(s.pathBuffer, sizeof s.pathBuffer, "%s", path.c_str());
                tooltip(s, recentTooltip(path, exists, "Put this path in the field").c_str());
                ImGui::PopID();
            }
        }
        const bool okButton = ImGui::Button("OK");
        tooltip(s, "Use this path (Enter)");
        const bool ok = okButton || enter;
        ImGui::SameLine();
        const bool cancelButton = ImGui::Button("Cancel");
        tooltip(s, "Close without doing anything (Escape)");
        const bool cancel = cancelButton || keyPressed(ImGuiKey_Escape);
        if (ok && std::strlen(s.pathBuffer) > 0) {
            const std::string path = s.pathBuffer;
            const UiState::PathDialog which = s.pathDialog;
            s.pathDialog = UiState::PathDialog::None;
            ImGui::CloseCurrentPopup();
            if (which == UiState::PathDialog::Open) actions.open(path);
            else if (which == UiState::PathDialog::SaveAs) actions.saveAs(path);
            else if (which == UiState::PathDialog::Import) actions.importFile(path);
            else actions.exportMesh(path);
        } else if (cancel) {
            s.pathDialog = UiState::PathDialog::None;
            ImGui::CloseCurrentPopup();
        }
        fitWindow();
        ImGui::EndPopup();
    }
    (void)scene;
}

bool unsavedDialog(Scene& scene, UiState& s, UiActions& actions)
{
    if (s.pending == PendingAction::None) return false;
    const char* title = "Unsaved changes";
    if (!ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
    bool proceed = false;
    if (ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        // A long path is shortened in the middle (the dialog must fit the window); hovering shows it whole.
        ImGui::Text("%s has unsaved changes.", scene.path().empty() ? "The document" : shortPathLabel(scene.path()).c_str());
        if (!scene.path().empty() && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", scene.path().c_str());
        const bool saveButton = ImGui::Button("Save");
        tooltip(s, "Save the document, then go on");
        if (saveButton) {
            const bool saved = scene.path().empty() ? false : actions.save();
            if (scene.path().empty()) s.error = "the document has no file yet: use File > Save as first";
            proceed = saved;
            ImGui::CloseCurrentPopup();
            if (!saved) s.pending = PendingAction::None;
        }
        ImGui::SameLine();
        const bool discardButton = ImGui::Button("Discard changes");
        tooltip(s, "Go on without saving: the changes are lost");
        if (discardButton) {
            proceed = true;
            ImGui::CloseCurrentPopup();
        }
        ImGui::SameLine();
        const bool cancelButton = ImGui::Button("Cancel");
        tooltip(s, "Stay in this document (Escape)");
        if (cancelButton || keyPressed(ImGuiKey_Escape)) {
            s.pending = PendingAction::None;
            ImGui::CloseCurrentPopup();
        }
        fitWindow();
        ImGui::EndPopup();
    }
    return proceed;
}

void errorDialog(UiState& s)
{
    if (s.error.empty()) return;
    const char* title = "Error";
    if (!ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
    if (ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::PushTextWrapPos(560);
        ImGui::TextUnformatted(s.error.c_str());
        ImGui::PopTextWrapPos();
        ImGui::TextDisabled("The open document was not changed.");
        const bool enter = dialogKey(ImGuiKey_Enter, s.errorFrame), escape = dialogKey(ImGuiKey_Escape, s.errorFrame);
        const bool okButton = ImGui::Button("OK");
        tooltip(s, "Close this message (Enter or Escape)");
        if (okButton || enter || escape) {
            s.error.clear();
            s.errorFrame = -1;
            ImGui::CloseCurrentPopup();
        }
        fitWindow();
        ImGui::EndPopup();
    }
}

void helpWindow(UiState& s)
{
    if (!s.showHelp) return;
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    // As wide as its widest line where the window allows (else it scrolls sideways), centred.
    const std::string controls = controlsHelp();
    const ImGuiStyle& style = ImGui::GetStyle();
    const float widest = std::max(ImGui::CalcTextSize(firstStepsHelp()).x, ImGui::CalcTextSize(controls.c_str()).x) +
                         2 * style.WindowPadding.x + style.ScrollbarSize + 2;
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + 0.5f * vp->Size.x, vp->Pos.y + 0.5f * vp->Size.y), ImGuiCond_FirstUseEver, ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowSize(ImVec2(std::min(widest, vp->Size.x - 16), std::min(600.0f, vp->Size.y - 60)), ImGuiCond_FirstUseEver);
    if (ImGui::Begin("Controls", &s.showHelp, ImGuiWindowFlags_HorizontalScrollbar)) {
        const bool open = ImGui::CollapsingHeader("First steps", ImGuiTreeNodeFlags_DefaultOpen);
        tooltip(s, "Three short tasks: draw a C2 spline, smooth a patch pair, deform a mesh (click to fold)");
        if (open) ImGui::TextUnformatted(firstStepsHelp());
        ImGui::TextUnformatted(controls.c_str());
        fitWindow();
    }
    ImGui::End();
}

void statsWindow(UiState& s)
{
    s.statsText.clear();
    if (!s.showStats) return;
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x * 0.5f, vp->Pos.y + vp->Size.y - statusHeight() - 8), ImGuiCond_Always,
                            ImVec2(0.5f, 1.0f));
    ImGui::SetNextWindowBgAlpha(0.6f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings |
                                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoMove |
                                   ImGuiWindowFlags_NoInputs; // see-through for the pointer: a point under it can be picked
    if (ImGui::Begin("Frame statistics", nullptr, flags)) {
        char text[160];
        std::snprintf(text, sizeof text, "frame %.2f ms   update %.2f ms   %ld triangles", s.frameMs, s.updateMs, s.triangles);
        ImGui::TextUnformatted(text);
        s.statsText = text;
    }
    ImGui::End();
}

void recoveryDialog(UiState& s, UiActions& actions)
{
    if (s.recovery.empty()) return;
    const char* title = "Recover unsaved changes";
    if (!ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
    if (ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::PushTextWrapPos(560);
        ImGui::TextUnformatted(s.recovery.c_str());
        ImGui::PopTextWrapPos();
        const bool enter = dialogKey(ImGuiKey_Enter, s.recoveryFrame);
        const bool recoverButton = ImGui::Button("Recover (Enter)");
        tooltip(s, "Open the autosaved document as unsaved changes to its file");
        const bool recover = recoverButton || enter;
        ImGui::SameLine();
        const bool escape = dialogKey(ImGuiKey_Escape, s.recoveryFrame);
        const bool discardButton = ImGui::Button("Discard (Escape)");
        tooltip(s, "Delete the autosave and start as usual");
        const bool discard = discardButton || escape;
        if (recover || discard) {
            s.recovery.clear();
            s.recoveryFrame = -1;
            ImGui::CloseCurrentPopup();
            actions.recover(recover);
        }
        fitWindow();
        ImGui::EndPopup();
    }
}

} // namespace

const char* firstStepsHelp()
{
    return "Draw a C2 spline: Shift+C, click the points it should pass through, Enter.\n"
           "  Its joints are in mode C2 (Properties > Joints); drag the cyan de Boor points,\n"
           "  and it stays C2. T: de Casteljau construction at t, V: curvature comb.\n"
           "Smooth a patch pair: File > Open examples/data/c0-patches.json, R (reflection lines:\n"
           "  they break at the C0 edge), click a patch, 'edge continuity of all patches' lists the\n"
           "  edge as C0; move the rows beside it collinear (G, Z) and press it again: C1 and G1.\n"
           "Deform a mesh: Ctrl+I imports it, click it, L fits a lattice; drag the lattice points\n"
           "  and the mesh follows; 'export deformed' in the lattice panel writes it (any format\n"
           "  by extension, nothing else in the file changes). Ctrl+Z undoes every step.\n";
}

std::string controlsHelp()
{
    // The mouse, then every key of the keymap (interaction/keymap.h), the one table that key
    // handling uses too.
    std::string text = "Mouse (in the view)\n"
                       "  left click on a point     select it (the selected object's points first)\n"
                       "  shift + left click        add or remove a point from the selection\n"
                       "  left drag on a point      move the selected points in the view plane\n"
                       "  left drag on the gizmo    move along an axis (arrow) or in a plane (square)\n"
                       "  ctrl + left drag          box select (ctrl + shift: add to the selection)\n"
                       "  alt + left drag on a\n"
                       "    point                   scale its weight (rational and NURBS objects; up: heavier)\n"
                       "  left click on a curve\n"
                       "    or surface              select that object\n"
                       "  left click on nothing     deselect the points, then the object\n"
                       "  left drag on nothing      orbit (turntable or arcball: View menu)\n"
                       "  middle drag, right drag,\n"
                       "  shift + left drag         pan\n"
                       "  wheel                     zoom towards the cursor\n";
    text += keymapHelp();
    text += "Files can also be dropped on the window: documents open, meshes and .bpt files are imported.\n"
            "Unsaved changes are autosaved every minute and offered for recovery at the next start.\n";
    return text;
}

/// The scalar colour map's legend, at the bottom right of the view while the map is drawn: the
/// colour bar (its pixel columns coloured by render/colour_map.h, the shader's map) with its values
/// at both ends and in the middle.
void colourLegend(const Scene& scene, UiState& s)
{
    s.legendRect[2] = 0;
    if (scene.display.analysis != SurfaceAnalysis::ScalarMap) return;
    const std::optional<std::pair<float, float>> range = scalarRange(scene);
    if (!range) return;
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x - 8, vp->Pos.y + vp->Size.y - statusHeight() - 8), ImGuiCond_Always,
                            ImVec2(1.0f, 1.0f));
    ImGui::SetNextWindowBgAlpha(0.75f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings |
                                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoMove;
    if (ImGui::Begin("det J legend", nullptr, flags)) {
        const float lo = range->first, hi = range->second;
        ImGui::Text("det J (%s)", scene.display.scalarAuto ? "auto range" : "fixed range");
        const float width = 200.0f, height = 14.0f;
        const ImVec2 p = ImGui::GetCursorScreenPos();
        ImDrawList* draw = ImGui::GetWindowDrawList();
        for (int k = 0; k < static_cast<int>(width); ++k) {
            const Vec3f c = colourMap(static_cast<float>(k) / (width - 1));
            draw->AddRectFilled(ImVec2(p.x + float(k), p.y), ImVec2(p.x + float(k) + 1, p.y + height),
                                ImGui::ColorConvertFloat4ToU32(ImVec4(c.x(), c.y(), c.z(), 1)));
        }
        ImGui::Dummy(ImVec2(width, height));
        char text[3][32];
        std::snprintf(text[0], sizeof text[0], "%.3g", lo);
        std::snprintf(text[1], sizeof text[1], "%.3g", 0.5f * (lo + hi));
        std::snprintf(text[2], sizeof text[2], "%.3g", hi);
        const float y = ImGui::GetCursorPosY();
        ImGui::TextUnformatted(text[0]);
        ImGui::SameLine(ImGui::GetCursorStartPos().x + 0.5f * (width - ImGui::CalcTextSize(text[1]).x));
        ImGui::SetCursorPosY(y);
        ImGui::TextUnformatted(text[1]);
        ImGui::SameLine(ImGui::GetCursorStartPos().x + width - ImGui::CalcTextSize(text[2]).x);
        ImGui::SetCursorPosY(y);
        ImGui::TextUnformatted(text[2]);
        s.legendRect[0] = p.x;
        s.legendRect[1] = p.y;
        s.legendRect[2] = width;
        s.legendRect[3] = height;
        s.legendMin = lo;
        s.legendMax = hi;
    }
    ImGui::End();
}

void statusBar(UiState& s)
{
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x, vp->Pos.y + vp->Size.y - statusHeight()), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(vp->Size.x, statusHeight()), ImGuiCond_Always);
    ImGui::SetNextWindowBgAlpha(0.75f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                   ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoBringToFrontOnFocus;
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(8, 2));
    if (ImGui::Begin("##status", nullptr, flags)) {
        const int lines = statusLines(s);
        const ImVec4 noticeColour(1.0f, 0.8f, 0.4f, 1.0f);
        if (lines == 1) {
            ImGui::TextUnformatted(s.statusHint.c_str());
            fitItem(s.statusHint.c_str());
            tooltip(s, s.statusHint.c_str()); // the whole text, where a narrow window cuts the line
            if (!s.notice.empty()) {
                ImGui::SameLine(0, 0);
                ImGui::TextColored(noticeColour, "%s", statusNotice(s).c_str());
                fitItem(s.notice.c_str());
            }
        } else {
            // Wrapped: the hint (the tool or mode, then what the next click does) on the first
            // lines, the notice below; beyond kStatusMaxLines the end is cut, and recorded.
            ImGui::PushTextWrapPos(0);
            ImGui::TextUnformatted(s.statusHint.c_str());
            tooltip(s, s.statusHint.c_str()); // the whole text, where a narrow window cuts the line
            if (!s.notice.empty()) {
                ImGui::PushStyleVar(ImGuiStyleVar_ItemSpacing, ImVec2(ImGui::GetStyle().ItemSpacing.x, 0));
                ImGui::TextColored(noticeColour, "%s", s.notice.c_str());
                ImGui::PopStyleVar();
            }
            ImGui::PopTextWrapPos();
            if (lines > kStatusMaxLines) {
                const std::string all = s.statusHint + statusNotice(s);
                fitWidth(all.c_str(), ImGui::CalcTextSize(all.c_str()).x, float(kStatusMaxLines) * statusTextWidth());
            }
        }
    }
    ImGui::End();
    ImGui::PopStyleVar();
}

bool drawUi(Scene& scene, UiState& state, UiActions& actions)
{
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    state.relayout = state.relayout || vp->Size.x != state.layoutWidth || vp->Size.y != state.layoutHeight;
    state.layoutWidth = vp->Size.x;
    state.layoutHeight = vp->Size.y;
    currentState = &state;
    recordOverflowsInto(&state.overflows);
    statusBarHeight = statusHeightFor(statusLines(state));
    state.tooltip.clear();
    state.widgets.clear();
    state.latticeReadout = {};
    state.dropdowns.clear();
    mainMenu(scene, state, actions);
    statusBar(state);
    colourLegend(scene, state);
    outliner(scene, state);
    properties(scene, state, actions);
    displayPanel(scene, state);
    helpWindow(state);
    statsWindow(state);
    recoveryDialog(state, actions);
    pathDialog(scene, state, actions);
    const bool proceed = unsavedDialog(scene, state, actions);
    errorDialog(state);
    state.relayout = false;
    recordOverflowsInto(nullptr);
    currentState = nullptr;
    return proceed;
}

} // namespace freeform::editor
