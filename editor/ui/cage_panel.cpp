// The cage tool's panel (tools/cage_tool.h; declared in ui/tool_panels.h): the section of the Properties window for a selected
// subdivision_surface. It only reads the scene and calls the tool's operations, so every change is
// one undo step made by the tool.

#include <imgui.h>

#include <cstdio>
#include <string>

#include "ui/tool_panels.h"
#include "ui/ui.h"

namespace freeform::editor {

void drawPanel(CageTool& tool, ToolContext& c)
{
    const int item = c.selection.item;
    if (!tool.isCage(c.scene, item)) return;
    const auto& d = std::get<SubdivisionSurfaceData>(c.scene.object(item).data);
    ImGui::TextUnformatted("Subdivision cage");
    if (!d.mesh.empty()) {
        // Wrapped: a path can be longer than the panel is wide.
        ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
        ImGui::TextWrapped("cage file: %s", d.mesh.c_str());
        ImGui::PopStyleColor();
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("written inline on the first crease, corner or vertex edit; the file stays as it is");
    }

    static const char* schemes[] = {"catmark", "loop"};
    int scheme = d.scheme == "loop" ? 1 : 0;
    static const Choice schemeChoices[] = {
        {"Catmull-Clark (catmark)", "Catmull-Clark: for cages of any polygons; every face becomes quads at the first step"},
        {"Loop (triangles only)", "Loop: for cages made of triangles only; each triangle becomes four at every step"}};
    if (comboWithTips("scheme", scheme, schemeChoices)) tool.setScheme(c, item, schemes[scheme]);
    tooltip("Subdivision scheme (the object's scheme field): Catmull-Clark for any polygons, Loop for triangle cages only");
    static const char* boundaries[] = {"edge_only", "edge_and_corner", "none"};
    int boundary = d.boundary == "edge_and_corner" ? 1 : d.boundary == "none" ? 2 : 0;
    static const Choice boundaryChoices[] = {
        {"edge only", "Boundary edges act as infinitely sharp creases (the default)"},
        {"edge and corner", "As edge only, and boundary vertices with a single face are sharp corners too"},
        {"none", "Faces touching the boundary have no limit surface: the outer ring only shapes the inner faces"}};
    if (comboWithTips("boundary", boundary, boundaryChoices)) tool.setBoundary(c, item, boundaries[boundary]);
    tooltip("Boundary interpolation (the object's boundary field): edge only, edge and corner (corners stay put), or none");
    const Tessellation& t = c.scene.item(item).settings.tessellation;
    int level = t.mode == Tessellation::Mode::Uniform ? t.segments : 0;
    if (ImGui::SliderInt("level", &level, 0, 32, level == 0 ? "adaptive" : "%d segments")) tool.setLevel(c, item, level);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("segments per cage edge of the limit surface's tessellation (0: adaptive to the tolerance)");

    const std::optional<SubdivisionCage> cage = tool.cageOf(c.scene, item);
    const ItemGeometry& g = c.scene.item(item).geometry;
    if (cage) {
        int creases = 0, corners = 0;
        for (const EdgeCrease& e : cage->creases) creases += e.sharpness > 0;
        for (const VertexCorner& v : cage->corners) corners += v.sharpness > 0;
        ImGui::Text("cage: %d vertices, %d faces", cage->mesh.vertexCount(), cage->mesh.faceCount());
        ImGui::Text("      %d creases, %d corners", creases, corners);
    }
    if (g.surface) ImGui::Text("limit surface: %d triangles", g.surface->faceCount());
    ImGui::Checkbox("show creases and corners", &tool.showCage);
    tooltip("Overlay: crease edges orange (red when infinitely sharp), sharp corners as points, the picked edge yellow");

    ImGui::Separator();
    ImGui::Checkbox("edge mode (E)", &tool.edgeMode);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("a click in the view picks the nearest edge of this cage");
    float s = static_cast<float>(tool.sharpness);
    if (ImGui::SliderFloat("sharpness", &s, 0.0f, 10.0f, s >= 10.0f ? "%.1f (infinite)" : "%.2f")) tool.sharpness = s;
    tooltip("The sharpness that crease (S) and corner (Alt+S) set; 10 or more is infinitely sharp");
    const bool pickedHere = tool.pickedEdge() && tool.pickedItem() == c.scene.item(item).id;
    if (pickedHere) {
        const auto& e = *tool.pickedEdge();
        ImGui::Text("edge %d-%d: sharpness %.3g", e[0], e[1], cage ? tool.edgeSharpness(*cage, e[0], e[1]) : 0.0);
        if (ImGui::Button("crease (S)")) tool.setCrease(c, item, e[0], e[1], tool.sharpness);
        tooltip("Give the picked edge the sharpness above (one undo step)");
        ImGui::SameLine();
        if (ImGui::Button("clear (Shift+S)")) tool.clearCrease(c, item, e[0], e[1]);
        tooltip("Remove the picked edge's crease (one undo step)");
    } else {
        ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
        ImGui::TextWrapped("no edge picked (E, then click an edge)");
        ImGui::PopStyleColor();
    }
    char label[64];
    std::snprintf(label, sizeof label, "corners: %zu point(s)", c.selection.points.size());
    ImGui::TextUnformatted(label);
    if (ImGui::Button("corner (Alt+S)")) tool.setCorners(c, item, c.selection.points, tool.sharpness);
    tooltip("Give the selected cage vertices the corner sharpness above (one undo step)");
    ImGui::SameLine();
    if (ImGui::Button("clear (Alt+Shift+S)")) tool.setCorners(c, item, c.selection.points, 0);
    tooltip("Remove the corner sharpness of the selected cage vertices (one undo step)");
}

} // namespace freeform::editor
