// The ImGui panels' frame (ui/ui.h): drawUi, which draws every panel in its order; the helpers
// the panels share (ui/ui_internal.h: the panels' places, the status bar's height, dialog keys,
// colour and material fields, recent files' labels); tooltips, dropdowns and the recorded widgets;
// askPath; the help texts; the det J legend and the status bar. The Scene, Properties and Display
// panels are in ui_panels.cpp, the main menu and the dialogs in ui_menu_dialogs.cpp.

#include "ui/ui.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "interaction/keymap.h"
#include "render/colour_map.h"
#include "scene/scene_drawer.h"
#include "ui/path_label.h"
#include "ui/ui_internal.h"

namespace freeform::editor {

namespace {

constexpr float kPanelWidth = 290.0f;

/// The state of the drawUi call in progress (for tooltip(text) from the tools' panels).
UiState* currentState = nullptr;

/// The status bar's lines at most: the text wraps at the window's width (the hint first, so the
/// active tool or mode and what the next click does are never the part cut); beyond this many
/// lines the rest is cut (its tooltip holds the whole text) and recorded (ui/fit.h).
constexpr int kStatusMaxLines = 3;

/// The status bar's height for this frame (set by drawUi from the text and the window's width).
float statusBarHeight = 0;

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

} // namespace

namespace ui_detail {

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

/// Height of the status bar at the bottom of the window.
float statusHeight()
{
    return statusBarHeight > 0 ? statusBarHeight : ImGui::GetFrameHeight() + 2;
}

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

} // namespace ui_detail

void askPath(UiState& s, UiActions& actions, UiState::PathDialog which, const std::string& initial)
{
    const char* titles[] = {"", "Open", "Save as", "Import mesh, .bpt or part", "Export OBJ", "Export part as STEP or IGES"};
    const bool save = which == UiState::PathDialog::SaveAs || which == UiState::PathDialog::Export || which == UiState::PathDialog::ExportPart;
    if (const std::optional<std::string> chosen = actions.chooseFile(save, titles[static_cast<int>(which)], initial)) {
        if (!chosen->empty()) usePath(actions, which, *chosen); // empty: cancelled
        return;
    }
    s.pathDialog = which;
    std::snprintf(s.pathBuffer, sizeof s.pathBuffer, "%s", initial.c_str());
}

void usePath(UiActions& actions, UiState::PathDialog which, const std::string& path)
{
    switch (which) {
    case UiState::PathDialog::Open: actions.open(path); break;
    case UiState::PathDialog::SaveAs: actions.saveAs(path); break;
    case UiState::PathDialog::Import: actions.importFile(path); break;
    case UiState::PathDialog::Export: actions.exportMesh(path); break;
    case UiState::PathDialog::ExportPart: actions.exportPart(path); break;
    case UiState::PathDialog::None: break;
    }
}

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
        fitFields(ui_detail::FieldTexts(range, 2, "%.3g").pointers, 2);
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
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x - 8, vp->Pos.y + vp->Size.y - ui_detail::statusHeight() - 8), ImGuiCond_Always,
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
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x, vp->Pos.y + vp->Size.y - ui_detail::statusHeight()), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(vp->Size.x, ui_detail::statusHeight()), ImGuiCond_Always);
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
    ui_detail::mainMenu(scene, state, actions);
    statusBar(state);
    colourLegend(scene, state);
    ui_detail::outliner(scene, state);
    ui_detail::properties(scene, state, actions);
    ui_detail::displayPanel(scene, state);
    ui_detail::helpWindow(state);
    ui_detail::statsWindow(state);
    ui_detail::recoveryDialog(state, actions);
    ui_detail::pathDialog(scene, state, actions);
    const bool proceed = ui_detail::unsavedDialog(scene, state, actions);
    ui_detail::errorDialog(state);
    state.relayout = false;
    recordOverflowsInto(nullptr);
    currentState = nullptr;
    return proceed;
}

} // namespace freeform::editor
