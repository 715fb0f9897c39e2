// The main menu bar (File, Edit, View, Help, the document's name and the frame's figures) and the
// dialogs and windows over the panels: the typed path (open, save as, import, export), unsaved
// changes, errors, the help (F1), the frame statistics (F2) and the autosave recovery (ui/ui.h).

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

#include "ui/path_label.h"
#include "ui/ui_internal.h"

namespace freeform::editor::ui_detail {

namespace {

/// Ends an open menu; Escape closes it (and the menus it was opened from): ImGui 1.86 does so
/// only with keyboard navigation on, which the editor leaves off (its keys are its own).
void endMenu()
{
    if (keyPressed(ImGuiKey_Escape)) ImGui::CloseCurrentPopup();
    ImGui::EndMenu();
}

} // namespace

void mainMenu(Scene& scene, UiState& s, UiActions& actions)
{
    if (!ImGui::BeginMainMenuBar()) return;
    // A menu's title has its tooltip while the menu is closed (open, the menu itself shows).
    const bool fileMenu = ImGui::BeginMenu("File");
    recordWidget("menu File");
    if (!fileMenu) tooltip(s, "New, Open, Save, Import a mesh, .bpt or part, Export the tessellation or a part, Quit");
    if (fileMenu) {
        if (ImGui::MenuItem("New", "Ctrl+N")) actions.newDocument();
        tooltip(s, "An empty document (asks first when there are unsaved changes)");
        if (ImGui::MenuItem("Open...", "Ctrl+O")) askPath(s, actions, UiState::PathDialog::Open, scene.path());
        tooltip(s, "Open a freeform document (.json), a .bpt patch file, a mesh, or a STEP or IGES part");
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
        if (ImGui::MenuItem("Import mesh, .bpt or part...", "Ctrl+I")) askPath(s, actions, UiState::PathDialog::Import, "");
        tooltip(s, "Add a mesh (.obj .ply .stl .off .gltf .glb), the patches of a .bpt file, or the part of a STEP or IGES\n"
                   "file (.step .stp .iges .igs .brep: one part object, its faces trimmed NURBS) to the document");
        if (ImGui::MenuItem("Export tessellation as OBJ...", "Ctrl+E")) askPath(s, actions, UiState::PathDialog::Export, "scene.obj");
        tooltip(s, "Write every visible surface and mesh, merged, as one OBJ");
        std::string why;
        const int part = scene.findPartItem(s.selection.item, &why);
        if (ImGui::MenuItem("Export part as STEP or IGES...", nullptr, false, part >= 0))
            askPath(s, actions, UiState::PathDialog::ExportPart, scene.item(part).name + ".step");
        const std::string partTip = part >= 0 ? std::string("Write the selected part (or the document's only one) as STEP or IGES, by the path's "
                                                             "extension\n(docs/cad.md: faces as B-spline surfaces; every degree must be at most 25)")
                                              : "Write a part as STEP or IGES: " + why;
        tooltip(s, partTip.c_str());
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

void pathDialog(Scene& scene, UiState& s, UiActions& actions)
{
    if (s.pathDialog == UiState::PathDialog::None) return;
    const char* titles[] = {"", "Open", "Save as", "Import", "Export OBJ", "Export part"};
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
            usePath(actions, which, path);
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

} // namespace freeform::editor::ui_detail
