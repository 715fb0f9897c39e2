#include "ui/ui.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "interaction/keymap.h"
#include "tools/tools.h"

namespace freeform::editor {

namespace {

constexpr float kPanelWidth = 290.0f;

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
    return ImGui::GetFrameHeight() + 2;
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
    const float leftWidth = std::min(kPanelWidth - 60, std::max(150.0f, 0.27f * vp->Size.x));
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

bool colorEdit(const char* label, Vec3f& c)
{
    return ImGui::ColorEdit3(label, c.data(), ImGuiColorEditFlags_Float);
}

bool materialEditor(Material& m)
{
    bool changed = false;
    changed |= colorEdit("ambient", m.ambient);
    changed |= colorEdit("diffuse", m.diffuse);
    changed |= colorEdit("specular", m.specular);
    changed |= ImGui::SliderFloat("shininess", &m.shininess, 1.0f, 500.0f, "%.0f", ImGuiSliderFlags_Logarithmic);
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

void mainMenu(Scene& scene, UiState& s, UiActions& actions)
{
    if (!ImGui::BeginMainMenuBar()) return;
    if (ImGui::BeginMenu("File")) {
        if (ImGui::MenuItem("New", "Ctrl+N")) actions.newDocument();
        if (ImGui::MenuItem("Open...", "Ctrl+O")) askPath(s, actions, UiState::PathDialog::Open, scene.path());
        if (ImGui::BeginMenu("Open recent", !actions.recentFiles().empty())) {
            for (const std::string& path : actions.recentFiles())
                if (ImGui::MenuItem(path.c_str())) actions.open(path);
            ImGui::EndMenu();
        }
        if (ImGui::MenuItem("Save", "Ctrl+S")) {
            if (scene.path().empty()) askPath(s, actions, UiState::PathDialog::SaveAs, "scene.json");
            else actions.save();
        }
        if (ImGui::MenuItem("Save as...", "Ctrl+Shift+S"))
            askPath(s, actions, UiState::PathDialog::SaveAs, scene.path().empty() ? "scene.json" : scene.path());
        ImGui::Separator();
        if (ImGui::MenuItem("Import mesh or .bpt...", "Ctrl+I")) askPath(s, actions, UiState::PathDialog::Import, "");
        if (ImGui::MenuItem("Export tessellation as OBJ...", "Ctrl+E")) askPath(s, actions, UiState::PathDialog::Export, "scene.obj");
        ImGui::Separator();
        if (ImGui::MenuItem("Quit", "Ctrl+Q")) actions.quit();
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Edit")) {
        const auto& h = scene.history();
        const std::string undoText = h.canUndo() ? "Undo " + h.undoLabel() : std::string("Undo");
        const std::string redoText = h.canRedo() ? "Redo " + h.redoLabel() : std::string("Redo");
        if (ImGui::MenuItem(undoText.c_str(), "Ctrl+Z", false, h.canUndo())) actions.undo();
        if (ImGui::MenuItem(redoText.c_str(), "Ctrl+Shift+Z", false, h.canRedo())) actions.redo();
        ImGui::Separator();
        Selection& sel = s.selection;
        const bool hasItem = sel.item >= 0 && sel.item < scene.itemCount();
        if (ImGui::MenuItem("Select all points", "A", false, hasItem)) {
            std::vector<int> all(static_cast<std::size_t>(scene.controlPointCount(sel.item)));
            for (std::size_t k = 0; k < all.size(); ++k) all[k] = static_cast<int>(k);
            sel.setPoints(std::move(all));
        }
        if (ImGui::MenuItem("Select none", "Alt+A", false, !sel.points.empty())) sel.points.clear();
        ImGui::Separator();
        ImGui::MenuItem("Snap to grid", "Shift+Tab", &s.edit.snap);
        ImGui::MenuItem("Proportional editing", "O", &s.edit.soft);
        ImGui::MenuItem("Translate gizmo", "Shift+G", &s.edit.gizmo);
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("View")) {
        DisplaySettings& d = scene.display;
        int shading = static_cast<int>(d.shading);
        if (ImGui::RadioButton("flat", &shading, 0) | ImGui::RadioButton("Gouraud", &shading, 1) |
            ImGui::RadioButton("Phong", &shading, 2)) {
            d.shading = static_cast<Shading>(shading);
            scene.touch();
        }
        ImGui::Separator();
        for (const char* v : {"front", "back", "left", "right", "top", "bottom", "iso"})
            if (ImGui::MenuItem(v)) actions.setView(v);
        ImGui::Separator();
        if (ImGui::MenuItem("Fit all", "Home")) actions.fit(false);
        if (ImGui::MenuItem("Fit selection", "F", false, s.selection.item >= 0)) actions.fit(true);
        bool ortho = scene.camera.projection == Projection::Orthographic;
        if (ImGui::MenuItem("Orthographic", "5", &ortho)) {
            scene.camera.projection = ortho ? Projection::Orthographic : Projection::Perspective;
            scene.touch();
        }
        bool arcball = scene.camera.orbit == OrbitMode::Arcball;
        if (ImGui::MenuItem("Arcball orbit", nullptr, &arcball)) {
            scene.camera.orbit = arcball ? OrbitMode::Arcball : OrbitMode::Turntable;
            scene.touch();
        }
        ImGui::MenuItem("Display panel", nullptr, &s.showDisplay);
        ImGui::MenuItem("Frame statistics", "F2", &s.showStats);
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Help")) {
        ImGui::MenuItem("Controls", "F1", &s.showHelp);
        ImGui::EndMenu();
    }
    ImGui::Separator();
    const std::string title = (scene.path().empty() ? std::string("untitled") : scene.path()) + (scene.modified() ? " *" : "");
    ImGui::TextUnformatted(title.c_str());
    char stats[96];
    std::snprintf(stats, sizeof stats, "   %ld triangles   %.1f ms", s.triangles, s.frameMs);
    ImGui::TextDisabled("%s", stats);
    ImGui::EndMainMenuBar();
}

void outliner(Scene& scene, UiState& s)
{
    const Layout l = panelLayout();
    const ImGuiCond cond = s.relayout ? ImGuiCond_Always : ImGuiCond_FirstUseEver;
    ImGui::SetNextWindowPos(l.scenePos, cond);
    ImGui::SetNextWindowSize(l.sceneSize, cond);
    if (ImGui::Begin("Scene")) {
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
            ImGui::SameLine();
            const std::string label = item.name + "  (" + item.type + ")" + (item.geometry.error.empty() ? "" : "  !");
            if (ImGui::Selectable(label.c_str(), s.selection.item == i)) {
                if (s.selection.item == i) s.selection.clear();
                else s.selection.selectItem(i);
            }
            if (!item.geometry.error.empty() && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", item.geometry.error.c_str());
            ImGui::PopID();
        }
        if (scene.itemCount() == 0) ImGui::TextDisabled("empty: open or import a file, or drop one here");
    }
    ImGui::End();
}

/// Editable control points of a document object (one row per point).
void controlPointTable(Scene& scene, int index, UiState& s)
{
    const DocumentObject& object = scene.object(index);
    const PointColumns* points = std::visit(
        [](const auto& d) -> const PointColumns* {
            using T = std::decay_t<decltype(d)>;
            if constexpr (std::is_same_v<T, SubdivisionSurfaceData>) return &d.vertices;
            else return &d.points;
        },
        object.data);
    const int dim = static_cast<int>(points->rows());
    const int count = static_cast<int>(points->cols());
    if (!ImGui::CollapsingHeader(("control points (" + std::to_string(count) + ")").c_str(), ImGuiTreeNodeFlags_DefaultOpen)) return;
    ImGui::BeginChild("points", ImVec2(0, 220), true);
    ImGuiListClipper clipper;
    clipper.Begin(count);
    while (clipper.Step()) {
        for (int k = clipper.DisplayStart; k < clipper.DisplayEnd; ++k) {
            double value[3] = {0, 0, 0};
            for (int r = 0; r < dim; ++r) value[r] = (*points)(r, k);
            ImGui::PushID(k);
            const std::string label = std::to_string(k);
            if (ImGui::InputScalarN(label.c_str(), ImGuiDataType_Double, value, dim, nullptr, nullptr, "%.6g",
                                    ImGuiInputTextFlags_EnterReturnsTrue)) {
                try {
                    scene.setControlPoint(index, k, Eigen::Vector3d(value[0], value[1], value[2]));
                } catch (const Error& e) {
                    s.error = e.what();
                }
            }
            ImGui::PopID();
        }
    }
    ImGui::EndChild();
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
        ImGui::TextDisabled("click a control point to select it (shift: add, ctrl+drag: box)");
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
    if (ImGui::InputScalarN("##selected", ImGuiDataType_Double, value, 3, nullptr, nullptr, "%.6g", ImGuiInputTextFlags_EnterReturnsTrue)) {
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
    if (!ImGui::CollapsingHeader("editing")) return;
    ImGui::Checkbox("snap to grid (Shift+Tab)", &s.edit.snap);
    ImGui::Checkbox("proportional (O)", &s.edit.soft);
    if (s.edit.soft) {
        if (!(s.edit.softRadius > 0)) s.edit.softRadius = 0.25 * scene.bounds().diagonal().norm();
        const double lo = 1e-4, hi = 1e4;
        ImGui::SliderScalar("radius (+/-)", ImGuiDataType_Double, &s.edit.softRadius, &lo, &hi, "%.4g", ImGuiSliderFlags_Logarithmic);
    }
    ImGui::Checkbox("translate gizmo (Shift+G)", &s.edit.gizmo);
}

void properties(Scene& scene, UiState& s, UiActions& actions)
{
    const Layout l = panelLayout();
    const ImGuiCond cond = s.relayout ? ImGuiCond_Always : ImGuiCond_FirstUseEver;
    ImGui::SetNextWindowPos(l.propertiesPos, cond);
    ImGui::SetNextWindowSize(l.propertiesSize, cond);
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
                if (item.kind == SceneItem::Kind::DocumentObject &&
                    ImGui::CollapsingHeader("tessellation", ImGuiTreeNodeFlags_DefaultOpen)) {
                    int mode = static_cast<int>(settings.tessellation.mode);
                    changed |= ImGui::Combo("mode", &mode, "adaptive\0uniform\0");
                    settings.tessellation.mode = static_cast<Tessellation::Mode>(mode);
                    if (settings.tessellation.mode == Tessellation::Mode::Adaptive) {
                        double t = settings.tessellation.tolerance > 0 ? settings.tessellation.tolerance : scene.display.tolerance;
                        const double lo = 1e-6, hi = 1.0;
                        if (ImGui::SliderScalar("tolerance", ImGuiDataType_Double, &t, &lo, &hi, "%.2e", ImGuiSliderFlags_Logarithmic)) {
                            settings.tessellation.tolerance = t;
                            changed = true;
                        }
                    } else {
                        changed |= ImGui::SliderInt("segments", &settings.tessellation.segments, 1, 200);
                    }
                    changed |= ImGui::Checkbox("reverse orientation", &settings.tessellation.flip);
                }
                if (ImGui::CollapsingHeader("material")) {
                    changed |= ImGui::Checkbox("own material", &settings.ownMaterial);
                    if (settings.ownMaterial) changed |= materialEditor(settings.material);
                }
            }
            if (changed) scene.setSettings(selected, settings);
            if (!item.geometry.error.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.3f, 1), "%s", item.geometry.error.c_str());
            if (item.kind == SceneItem::Kind::DocumentObject) {
                selectedPoints(scene, selected, s);
                editOptions(scene, s);
                controlPointTable(scene, selected, s);
            } else {
                ImGui::TextWrapped("file: %s", item.meshPath.c_str());
            }
            actions.toolPanels();
        }
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
    if (ImGui::Begin("Display", &s.showDisplay)) {
        notePanel(s, "Display");
        // Room for the longest label ("point size", "tolerance") beside the widgets.
        ImGui::PushItemWidth(-ImGui::GetFontSize() * 6.5f);
        DisplaySettings d = scene.display;
        int shading = static_cast<int>(d.shading);
        ImGui::Combo("shading", &shading, "flat\0Gouraud\0Phong\0");
        d.shading = static_cast<Shading>(shading);
        int specular = static_cast<int>(d.specular);
        ImGui::Combo("specular", &specular, "Phong (v.r)\0Blinn-Phong (n.h)\0");
        d.specular = static_cast<SpecularModel>(specular);
        int analysis = static_cast<int>(d.analysis);
        ImGui::Combo("analysis", &analysis, "none\0reflection lines\0scalar map\0");
        d.analysis = static_cast<SurfaceAnalysis>(analysis);
        if (d.analysis == SurfaceAnalysis::ReflectionLines) ImGui::SliderFloat("stripes", &d.stripes, 2.0f, 60.0f, "%.0f");
        ImGui::Checkbox("wireframe", &d.wireframe);
        ImGui::SameLine();
        ImGui::Checkbox("flip normals", &d.flipNormals);
        ImGui::Checkbox("nets", &d.controlNets);
        ImGui::SameLine();
        ImGui::Checkbox("points", &d.controlPoints);
        ImGui::SameLine();
        ImGui::Checkbox("normals", &d.normals);
        ImGui::Checkbox("grid", &d.grid);
        ImGui::SameLine();
        ImGui::Checkbox("axes", &d.axes);
        if (d.normals) ImGui::SliderFloat("normal length", &d.normalLength, 0.001f, 0.2f, "%.3f", ImGuiSliderFlags_Logarithmic);
        ImGui::SliderFloat("point size", &d.pointSize, 2.0f, 20.0f, "%.0f px");
        const double lo = 1e-6, hi = 1.0;
        const double plo = 0, phi = 8;
        ImGui::SliderScalar("pixel tolerance", ImGuiDataType_Double, &scene.pixelTolerance, &plo, &phi, "%.2f px (0: world)");
        if (!(scene.pixelTolerance > 0))
            ImGui::SliderScalar("tolerance", ImGuiDataType_Double, &d.tolerance, &lo, &hi, "%.2e", ImGuiSliderFlags_Logarithmic);
        if (ImGui::CollapsingHeader("material")) materialEditor(d.material);
        if (ImGui::CollapsingHeader("back faces, background")) {
            colorEdit("back faces", d.backColor);
            colorEdit("background", d.background);
        }
        if (ImGui::CollapsingHeader("lights", ImGuiTreeNodeFlags_DefaultOpen)) {
            ImGui::Checkbox("headlight", &d.headlight);
            if (d.headlight) colorEdit("headlight colour", d.headlightColor);
            for (std::size_t i = 0; i < d.lights.size(); ++i) {
                ImGui::PushID(static_cast<int>(i));
                ImGui::Separator();
                ImGui::Checkbox("on", &d.lights[i].enabled);
                ImGui::SameLine();
                ImGui::Text("light %zu", i + 1);
                ImGui::SameLine();
                const bool removeIt = ImGui::SmallButton("remove");
                ImGui::DragFloat3("position", d.lights[i].position.data(), 0.05f);
                colorEdit("colour", d.lights[i].color);
                ImGui::PopID();
                if (removeIt) {
                    d.lights.erase(d.lights.begin() + static_cast<std::ptrdiff_t>(i));
                    break;
                }
            }
            if (static_cast<int>(d.lights.size()) < kMaxLights - 1 && ImGui::Button("add light"))
                d.lights.push_back(PointLight{Vec3f(5, 5, 5), Vec3f(0.3f, 0.3f, 0.3f), true});
        }
        if (!(d == scene.display)) {
            const bool retessellate = d.tolerance != scene.display.tolerance;
            scene.display = d;
            scene.touch();
            if (retessellate) scene.invalidateGeometry();
        }
        ImGui::PopItemWidth();
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
        if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
        const bool enter = ImGui::InputText("##path", s.pathBuffer, sizeof s.pathBuffer, ImGuiInputTextFlags_EnterReturnsTrue);
        if (s.pathDialog == UiState::PathDialog::Open && !actions.recentFiles().empty()) {
            ImGui::TextDisabled("recent:");
            for (const std::string& path : actions.recentFiles())
                if (ImGui::Selectable(path.c_str())) std::snprintf(s.pathBuffer, sizeof s.pathBuffer, "%s", path.c_str());
        }
        const bool ok = ImGui::Button("OK") || enter;
        ImGui::SameLine();
        const bool cancel = ImGui::Button("Cancel") || keyPressed(ImGuiKey_Escape);
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
        ImGui::Text("%s has unsaved changes.", scene.path().empty() ? "The document" : scene.path().c_str());
        if (ImGui::Button("Save")) {
            const bool saved = scene.path().empty() ? false : actions.save();
            if (scene.path().empty()) s.error = "the document has no file yet: use File > Save as first";
            proceed = saved;
            ImGui::CloseCurrentPopup();
            if (!saved) s.pending = PendingAction::None;
        }
        ImGui::SameLine();
        if (ImGui::Button("Discard changes")) {
            proceed = true;
            ImGui::CloseCurrentPopup();
        }
        ImGui::SameLine();
        if (ImGui::Button("Cancel") || keyPressed(ImGuiKey_Escape)) {
            s.pending = PendingAction::None;
            ImGui::CloseCurrentPopup();
        }
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
        if (ImGui::Button("OK") || enter || escape) {
            s.error.clear();
            s.errorFrame = -1;
            ImGui::CloseCurrentPopup();
        }
        ImGui::EndPopup();
    }
}

void helpWindow(UiState& s)
{
    if (!s.showHelp) return;
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowSize(ImVec2(std::min(700.0f, vp->Size.x - 40), std::min(600.0f, vp->Size.y - 60)), ImGuiCond_FirstUseEver);
    if (ImGui::Begin("Controls", &s.showHelp)) {
        if (ImGui::CollapsingHeader("First steps", ImGuiTreeNodeFlags_DefaultOpen)) ImGui::TextUnformatted(firstStepsHelp());
        const std::string controls = controlsHelp();
        ImGui::TextUnformatted(controls.c_str());
    }
    ImGui::End();
}

void statsWindow(UiState& s)
{
    if (!s.showStats) return;
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x * 0.5f, vp->Pos.y + vp->Size.y - statusHeight() - 8), ImGuiCond_Always,
                            ImVec2(0.5f, 1.0f));
    ImGui::SetNextWindowBgAlpha(0.6f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings |
                                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoMove;
    if (ImGui::Begin("Frame statistics", nullptr, flags))
        ImGui::Text("frame %.2f ms   update %.2f ms   %ld triangles", s.frameMs, s.updateMs, s.triangles);
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
        const bool recover = ImGui::Button("Recover (Enter)") || enter;
        ImGui::SameLine();
        const bool escape = dialogKey(ImGuiKey_Escape, s.recoveryFrame);
        const bool discard = ImGui::Button("Discard (Escape)") || escape;
        if (recover || discard) {
            s.recovery.clear();
            s.recoveryFrame = -1;
            ImGui::CloseCurrentPopup();
            actions.recover(recover);
        }
        ImGui::EndPopup();
    }
}

} // namespace

const char* firstStepsHelp()
{
    return "Draw a C2 spline: Shift+C, click the points it should pass through, Enter.\n"
           "  Its joints are in mode C2 (Properties > Joints); drag the cyan de Boor points,\n"
           "  and it stays C2. T: de Casteljau construction at t, V: curvature comb.\n"
           "Smooth a teapot patch: File > Open data/teapot.bpt, R (reflection lines), click a\n"
           "  patch, drag its net points (G, X/Y/Z to constrain); Properties > 'edge continuity\n"
           "  of all patches' lists C0/G1/C1 per shared edge; a smaller tolerance removes facets.\n"
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

void statusBar(UiState& s)
{
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(vp->Pos.x, vp->Pos.y + vp->Size.y - statusHeight()), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(vp->Size.x, statusHeight()), ImGuiCond_Always);
    ImGui::SetNextWindowBgAlpha(0.75f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                   ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoBringToFrontOnFocus;
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(8, 2));
    if (ImGui::Begin("##status", nullptr, flags)) ImGui::TextUnformatted(s.statusHint.c_str());
    ImGui::End();
    ImGui::PopStyleVar();
}

bool drawUi(Scene& scene, UiState& state, UiActions& actions)
{
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    state.relayout = state.relayout || vp->Size.x != state.layoutWidth || vp->Size.y != state.layoutHeight;
    state.layoutWidth = vp->Size.x;
    state.layoutHeight = vp->Size.y;
    mainMenu(scene, state, actions);
    statusBar(state);
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
    return proceed;
}

} // namespace freeform::editor
