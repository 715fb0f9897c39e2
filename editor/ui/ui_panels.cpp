// The Scene, Properties and Display panels (ui/ui.h): the outliner; the selected item's
// properties with its tessellation, material, the selected points' fields and the control point
// table (coordinateField: typed coordinates, refused with a notice when not a finite number); the
// display settings (shading, analysis, overlays, anti-aliasing, tolerance, material, lights).

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "freeform/document/object_data.h"
#include "tools/tools.h"
#include "ui/ui_internal.h"

namespace freeform::editor::ui_detail {

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

namespace {

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
    static const Eigen::MatrixXd none(3, 0); // no points held
    const PointColumns* held = dataPoints(object.data);
    return held ? Eigen::Ref<const Eigen::MatrixXd>(*held) : Eigen::Ref<const Eigen::MatrixXd>(none);
}

/// A part: its counts and one row per face, its surface kind, degrees and trim loops (docs/cad.md, "In the editor"). Its faces are not edited point by point: a lattice
/// deforms them (L fits one).
void partTable(const Scene& scene, int index, UiState& s)
{
    const ObjectData& data = scene.object(index).data;
    std::vector<const TrimmedSurfaceData*> faces;
    std::vector<std::string> kinds;
    if (const auto* part = std::get_if<PartData>(&data)) {
        ImGui::TextWrapped("%s", partSummary(*part).c_str());
        for (const PartFaceData& f : part->faces) {
            faces.push_back(&f.surface);
            kinds.push_back(f.kind.empty() ? "nurbs" : f.kind);
        }
    }
    ImGui::TextWrapped("L fits a lattice; File > Export part writes STEP or IGES");
    const std::string header = "faces (" + std::to_string(faces.size()) + ")";
    const bool open = ImGui::CollapsingHeader(header.c_str(), ImGuiTreeNodeFlags_DefaultOpen);
    recordWidget(header.c_str());
    tooltip(s, "Each face: the surface kind the file gave it, the degrees (u x v) of its exact NURBS form, its trim loops (click to fold)");
    if (!open) return;
    const ImGuiTableFlags flags = ImGuiTableFlags_BordersOuter | ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY;
    if (!ImGui::BeginTable("faces", 4, flags, ImVec2(0, std::min(220.0f, ImGui::GetTextLineHeightWithSpacing() * float(faces.size() + 2)))))
        return;
    ImGui::TableSetupScrollFreeze(0, 1);
    ImGui::TableSetupColumn("#", ImGuiTableColumnFlags_WidthFixed);
    ImGui::TableSetupColumn("surface");
    ImGui::TableSetupColumn("degree");
    ImGui::TableSetupColumn("loops");
    ImGui::TableHeadersRow();
    ImGuiListClipper clipper;
    clipper.Begin(static_cast<int>(faces.size()));
    while (clipper.Step())
        for (int f = clipper.DisplayStart; f < clipper.DisplayEnd; ++f) {
            const TrimmedSurfaceData& face = *faces[static_cast<std::size_t>(f)];
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            // A row click picks the face (outlined in the view), as a click on it in the view does.
            // Faces count from 1, as Open CASCADE and every error count them.
            const std::string number = std::to_string(f + 1);
            if (ImGui::Selectable(number.c_str(), s.selection.face == f, ImGuiSelectableFlags_SpanAllColumns))
                s.selection.face = s.selection.face == f ? -1 : f;
            tooltip(s, "Pick this face: its boundary is outlined in the view, the status line describes it (click again: none)");
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(kinds[static_cast<std::size_t>(f)].c_str());
            ImGui::TableNextColumn();
            ImGui::Text("%d x %d", face.surface.degree[0], face.surface.degree[1]);
            ImGui::TableNextColumn();
            ImGui::Text("%zu", face.loops.size());
        }
    ImGui::EndTable();
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

} // namespace

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
                // The kind table's words for the data (document/kinds.h).
                const std::string details = item.is(ObjectKind::Part) ? std::string() : objectDetails(scene.object(selected).data); // a part: its table below
                if (!details.empty())
                    ImGui::TextUnformatted(details.c_str());
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
                if (item.is(ObjectKind::Part)) {
                    partTable(scene, selected, s);
                } else {
                    selectedPoints(scene, selected, s);
                    editOptions(scene, s);
                    controlPointTable(scene, selected, s);
                }
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

} // namespace freeform::editor::ui_detail
