// The tools' panels: each tool's drawToolbar / drawPanel (declared in ui/tool_panels.h), and
// drawToolPanels, which lays them out in the Properties window: the creation buttons of every
// tool, then the section of the tool whose kind the selected item is, then the status line. A new
// tool's panel goes here, as drawPanel(<Tool>&, ToolContext&).

#include "ui/tool_panels.h"

#include <imgui.h>
#include <imgui_internal.h> // TableGetHeaderRowHeight: the header row as TableHeadersRow makes it

#include <algorithm>
#include <cstring>
#include <cstdio>

#include "freeform/core/error.h"
#include "tools/tools.h"
#include "ui/fit.h"
#include "ui/ui.h"

namespace freeform::editor {

namespace {

/// The curvature comb's checkbox and, while it is on, its scale slider (the curve and NURBS tools).
void combControls(bool& comb, double& combScale, const char* tip)
{
    ImGui::Checkbox("curvature comb (V)", &comb);
    tooltip(tip);
    if (!comb) return;
    float scale = static_cast<float>(combScale);
    if (ImGui::SliderFloat("comb scale", &scale, 0.05f, 10.0f, "%.2f", ImGuiSliderFlags_Logarithmic)) combScale = scale;
    tooltip("Length of the comb's teeth per unit of curvature");
}

/// SameLine when a button labelled `next` still fits on this line, so that no button is cut off
/// at the panel's edge (at 900 x 600 the toolbar wraps).
void sameLineIfFits(const char* next)
{
    const ImGuiStyle& style = ImGui::GetStyle();
    const float width = ImGui::CalcTextSize(next).x + 2 * style.FramePadding.x;
    const float right = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
    if (ImGui::GetItemRectMax().x + style.ItemSpacing.x + width <= right) ImGui::SameLine();
}

/// A table's header row as ImGui::TableHeadersRow makes it (same height, same IDs), with a
/// tooltip on each column's header (`tips`: one per column).
void headersRow(const char* const* tips)
{
    ImGui::TableNextRow(ImGuiTableRowFlags_Headers, ImGui::TableGetHeaderRowHeight());
    for (int n = 0; n < ImGui::TableGetColumnCount(); ++n) {
        if (!ImGui::TableSetColumnIndex(n)) continue;
        ImGui::PushID(n);
        ImGui::TableHeader(ImGui::TableGetColumnName(n));
        tooltip(tips[n]);
        ImGui::PopID();
    }
}

/// The selected object's row of the kind table; nullptr when nothing or a mesh is selected.
const KindInfo* selectedKind(const ToolContext& c)
{
    const int item = c.selection.item;
    return item >= 0 && item < c.scene.itemCount() ? c.scene.item(item).info() : nullptr;
}

bool selectedIs(const ToolContext& c, ObjectKind kind)
{
    const KindInfo* k = selectedKind(c);
    return k && k->kind == kind;
}

} // namespace

// ------------------------------------------------------------------ curves

void drawToolbar(CurveTool& tool, ToolContext& c)
{
    if (ImGui::Button(tool.creating() && !tool.creatingSpline() ? "finish curve (Enter)" : "create curve (C)")) {
        if (tool.creating()) tool.createFromClicks(c);
        else tool.startCreating(false);
    }
    tooltip(tool.creating() && !tool.creatingSpline() ? "Make a bezier_curve of the clicked points (at least 2); Backspace removes the last, Escape cancels"
                                          : "Click in the view to add control points of a Bezier curve (degree = clicks - 1); Enter finishes");
    const char* splineLabel = tool.creating() && tool.creatingSpline() ? "finish spline (Enter)" : "create C2 spline (Shift+C)";
    sameLineIfFits(splineLabel);
    if (ImGui::Button(splineLabel)) {
        if (tool.creating()) tool.createFromClicks(c);
        else tool.startCreating(true);
    }
    tooltip(tool.creating() && tool.creatingSpline() ? "Make a cubic bezier_spline through the clicked points, every inner joint C2"
                                         : "Click the points a cubic spline should pass through (the C2 interpolant); Enter finishes");
}

void drawPanel(CurveTool& tool, ToolContext& c)
{
    const KindInfo* kind = selectedKind(c);
    if (!kind || !kind->isCurve() || kind->rational) return;
    ImGui::TextUnformatted("Curve tools");
    float tf = static_cast<float>(tool.t);
    if (ImGui::SliderFloat("t", &tf, 0.0f, 1.0f, "%.4f")) tool.t = tf;
    tooltip("The parameter for split, insert and the de Casteljau construction (splines: a fraction of the whole range)");
    ImGui::Checkbox("de Casteljau at t (T)", &tool.construction);
    tooltip("Show every intermediate polygon of the de Casteljau triangle at t and the point f(t)");
    combControls(tool.comb, tool.combScale, "Teeth along the normal, of length proportional to the curvature, their tips joined");
    if (kind->kind != ObjectKind::DeBoorSpline) {
        if (ImGui::Button("elevate degree (E)")) tool.elevateSelected(c);
        tooltip("The same curve one degree higher (a spline: every segment; refused while a joint is C2)");
        sameLineIfFits("split at t (K)");
        if (ImGui::Button("split at t (K)")) tool.splitSelected(c);
        tooltip("Cut the curve or open spline at t into two objects");
    }
    if (ImGui::Button("insert point (I)")) tool.insertAtSelected(c);
    tooltip("Curve: a new point after the selected one (the degree rises). Spline: a joint in the segment (the shape stays)");
    sameLineIfFits("delete point (Del)");
    if (ImGui::Button("delete point (Del)")) tool.deleteSelected(c);
    tooltip("Curve: remove the selected point (the degree drops). Spline: remove the selected point's joint");
}

// ------------------------------------------------------------------ spline joints

void drawPanel(SplineTool& tool, ToolContext& c)
{
    if (!selectedIs(c, ObjectKind::BezierSpline)) return;
    const int item = c.selection.item;
    const auto& d = std::get<BezierSplineData>(c.scene.object(item).data);
    ImGui::Separator();
    ImGui::TextWrapped("Joints (1 free, 2 aligned G1, 3 mirrored C1, 4 C2)");
    static const char* names[] = {"free", "aligned", "mirrored", "C2"};
    static const Choice modeChoices[] = {
        {"free", "Free (C0): the two handles of the joint move independently"},
        {"aligned", "Aligned (G1): the handles stay on one line through the joint, each keeps its own length"},
        {"mirrored", "Mirrored (C1): the handles on one line, their lengths in the ratio of the two intervals"},
        {"C2", "C2: the second derivatives agree too; the handles follow the spline's de Boor points (cubic splines)"}};
    // The combo shows the inner joints' common mode, or "mixed".
    int common = -2;
    const std::vector<JointMode> current = jointModes(c.scene, item);
    for (int j = 0; j < static_cast<int>(current.size()); ++j) {
        if (!isInnerJoint(d, j)) continue;
        const int m = static_cast<int>(current[static_cast<std::size_t>(j)]);
        common = common == -2 ? m : common == m ? m : -1;
    }
    ImGui::SetNextItemWidth(120);
    static const char* allTips[] = {
        "Every inner joint free (C0): the handles keep where they are",
        "Every inner joint aligned (G1): the handles turn onto the bisector of their two directions",
        "Every inner joint mirrored (C1): the handles change least, no side preferred",
        "Every inner joint C2: the joints and end tangents stay, the inner handles become the C2 interpolant's"};
    noteDropdown("all joints");
    if (ImGui::BeginCombo("all joints", common >= 0 ? names[common] : common == -1 ? "mixed" : "-")) {
        for (int m = 0; m < 4; ++m)
        {
            if (ImGui::Selectable(names[m], m == common)) tool.setAllJointModes(c, static_cast<JointMode>(m));
            tooltip(allTips[m]);
        }
        ImGui::EndCombo();
    }
    tooltip("Set every inner joint to one mode (shows the current common mode, or mixed)");
    std::vector<JointContinuity<double>> report;
    try {
        report = splineContinuity(d);
    } catch (const Error& e) {
        ImGui::TextWrapped("%s", e.what());
    }
    const std::vector<JointMode> modes = jointModes(c.scene, item);
    // Four narrow columns, so that the table fits the panel's default width (at 900 x 600 too):
    // the joint's number, its mode, its C / G levels, and the jump of the lowest derivative that is
    // not continuous (order k = C + 1, at most 3); all three jumps in the cell's tooltip.
    if (ImGui::BeginTable("joints", 4, ImGuiTableFlags_Borders | ImGuiTableFlags_SizingFixedFit)) {
        static const char* heads[] = {"#", "mode", "C / G", "jump"};
        static const char* headTips[] = {"The joint's number along the spline (0: its start)",
                                         "The joint's handle mode (keys 1-4 with a point of it selected)",
                                         "The continuity the joint has: C (derivatives equal) and G (geometric) orders",
                                         ("k: |f_R^(k) - f_L^(k)|, the jump of the lowest derivative order k that is not continuous\n"
                                          "(k = C + 1, at most 3); hover a value for the jumps of orders 1, 2 and 3")};
        for (const char* h : heads) ImGui::TableSetupColumn(h);
        ImGui::TableNextRow(ImGuiTableRowFlags_Headers);
        for (int column = 0; column < 4; ++column) {
            ImGui::TableSetColumnIndex(column);
            fitText(heads[column]);
            ImGui::TableHeader(heads[column]);
            tooltip(headTips[column]);
        }
        for (const JointContinuity<double>& r : report) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            char number[16];
            std::snprintf(number, sizeof number, "%d", r.joint);
            ImGui::AlignTextToFramePadding();
            ImGui::TextUnformatted(number);
            fitItem(number);
            ImGui::TableNextColumn();
            int mode = static_cast<int>(modes[static_cast<std::size_t>(r.joint)]);
            ImGui::PushID(r.joint);
            ImGui::SetNextItemWidth(90);
            if (comboWithTips("##mode", mode, modeChoices)) tool.setJointMode(c, static_cast<JointMode>(mode), r.joint);
            fitWidth(names[mode], ImGui::CalcTextSize(names[mode]).x + 2 * ImGui::GetStyle().FramePadding.x + ImGui::GetFrameHeight(),
                     ImGui::GetItemRectSize().x);
            fitItem(names[mode]);
            tooltip("This joint's handle mode: free (C0), aligned (G1), mirrored (C1), C2 (cubic splines)");
            ImGui::PopID();
            ImGui::TableNextColumn();
            char levels[32];
            std::snprintf(levels, sizeof levels, "C%d G%d", r.C, r.G);
            ImGui::AlignTextToFramePadding();
            ImGui::TextUnformatted(levels);
            fitItem(levels);
            ImGui::TableNextColumn();
            const std::size_t order = std::min<std::size_t>(static_cast<std::size_t>(std::max(r.C, 0)) + 1, 3);
            std::string jumps;
            for (std::size_t k = 1; k < r.jumps.size() && k <= 3; ++k) {
                char buffer[48];
                std::snprintf(buffer, sizeof buffer, "%sorder %zu: %.3e", k > 1 ? "\n" : "", k, r.jumps[k]);
                jumps += buffer;
            }
            char jump[32] = "-";
            if (order < r.jumps.size()) std::snprintf(jump, sizeof jump, "%zu: %.1e", order, r.jumps[order]);
            ImGui::AlignTextToFramePadding();
            ImGui::TextUnformatted(jump);
            fitItem(jump);
            tooltip(jumps.c_str());
        }
        ImGui::EndTable();
    }
}

// ------------------------------------------------------------------ patches

void drawToolbar(PatchTool& tool, ToolContext& c)
{
    if (ImGui::Button("create patch (P)")) tool.createPatch(c);
    tooltip("Add a flat bezier_surface of degrees m x n in the view plane, centred in the scene");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(80);
    ImGui::InputInt2("m, n", tool.degree);
    tooltip("The degrees (1 to 20) of the patch that \"create patch\" adds");
    for (int& d : tool.degree) d = std::clamp(d, 1, 20);
}

namespace {

/// The selected surface's tessellation settings (patches, rational and NURBS surfaces).
void drawTessellationSettings(ToolContext& c)
{
    const int item = c.selection.item;
    ImGui::TextUnformatted("Tessellation");
    ObjectSettings settings = c.scene.item(item).settings;
    Tessellation& t = settings.tessellation;
    int mode = t.mode == Tessellation::Mode::Adaptive ? 0 : 1;
    bool changed = ImGui::RadioButton("tolerance", &mode, 0);
    tooltip("Adaptive tessellation to a distance (world units)");
    ImGui::SameLine();
    changed |= ImGui::RadioButton("segments", &mode, 1);
    tooltip("Uniform tessellation: this many segments per patch side");
    t.mode = mode == 0 ? Tessellation::Mode::Adaptive : Tessellation::Mode::Uniform;
    if (mode == 0) {
        float tol = static_cast<float>(t.tolerance > 0 ? t.tolerance : c.scene.display.tolerance);
        if (ImGui::SliderFloat("tolerance", &tol, 1e-5f, 0.1f, "%.1e", ImGuiSliderFlags_Logarithmic)) {
            t.tolerance = tol;
            changed = true;
        }
        tooltip("The largest distance between the surface and its triangles, world units (Ctrl+click types a value)");
    } else {
        changed |= ImGui::SliderInt("segments", &t.segments, 1, 64);
        tooltip("Segments per patch side (uniform tessellation)");
    }
    if (changed) c.scene.setSettings(item, settings, "tessellation");
}

} // namespace

void drawPanel(PatchTool& tool, ToolContext& c)
{
    const KindInfo* kind = selectedKind(c);
    if (!kind || !kind->isSurface() || kind->rational || kind->parameters != KindParameters::UV) return;
    drawTessellationSettings(c);
    ImGui::Separator();
    if (ImGui::Button("edge continuity of all patches")) tool.computeEdgeContinuity(c);
    tooltip("List every edge two bezier_surface objects share, with its level (C1, G1, C0), angle and gap");
    if (!tool.edges().empty()) {
        int g1 = 0, c1 = 0;
        for (const EdgeContinuity& e : tool.edges()) g1 += e.g1, c1 += e.c1;
        ImGui::Text("%zu %s: %d C1, %d G1, %zu C0", tool.edges().size(), tool.edges().size() == 1 ? "edge" : "edges", c1, g1,
                    tool.edges().size() - static_cast<std::size_t>(g1));
        tooltip("C1: the cross-boundary derivatives agree; G1: the tangent planes agree; C0: only the positions\n"
                "(the table follows every change of the patches)");
        static const char* sides[] = {"u0", "u1", "v0", "v1"};
        // Patch names make the edge column wide: the table scrolls sideways, that column frozen.
        if (ImGui::BeginTable("edges", 4, ImGuiTableFlags_Borders | ImGuiTableFlags_ScrollX | ImGuiTableFlags_ScrollY | ImGuiTableFlags_SizingFixedFit,
                              ImVec2(0, 180))) {
            ImGui::TableSetupScrollFreeze(1, 1);
            ImGui::TableSetupColumn("edge");
            ImGui::TableSetupColumn("level");
            ImGui::TableSetupColumn("angle (deg)");
            ImGui::TableSetupColumn("gap (units)");
            static const char* const tips[] = {"The two patches and their sides (u0, u1, v0, v1) that meet at the edge",
                                               "C1: derivatives across agree; G1: tangent planes agree; C0: only positions",
                                               "The largest angle between the two tangent planes along the edge, degrees",
                                               "The largest distance between the two sides' points along the edge, world units"};
            headersRow(tips);
            for (const EdgeContinuity& e : tool.edges()) {
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                ImGui::Text("%s.%s | %s.%s", tool.edgePatchNames()[static_cast<std::size_t>(e.a.patch)].c_str(),
                            sides[static_cast<int>(e.a.side)], tool.edgePatchNames()[static_cast<std::size_t>(e.b.patch)].c_str(),
                            sides[static_cast<int>(e.b.side)]);
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(e.c1 ? "C1" : e.g1 ? "G1" : "C0");
                ImGui::TableNextColumn();
                ImGui::Text("%.3g", e.angle * 180.0 / 3.14159265358979323846);
                ImGui::TableNextColumn();
                ImGui::Text("%.1e", e.gap);
            }
            ImGui::EndTable();
        }
    }
}

// ------------------------------------------------------------------ lattices

void drawPanel(LatticeTool& tool, ToolContext& c)
{
    const int item = c.selection.item;
    if (item >= 0 && item < c.scene.itemCount() && isFfdTarget(c.scene.item(item))) return drawMeshPanel(tool, c, item);
    if (!selectedIs(c, ObjectKind::Lattice)) return;
    ImGui::TextUnformatted("Free-form deformation");
    ObjectSettings settings = c.scene.item(item).settings;
    // The mesh it deforms (the link is the mesh's id; the document names it).
    std::vector<std::string> meshes{"(none)"};
    std::vector<std::string> tips{"Deform no mesh: the lattice alone (the link is dropped; undo restores it)"};
    int current = 0;
    bool part = false; // the lattice deforms a part's tessellation (a preview of the exact composition)
    for (int i = 0; i < c.scene.itemCount(); ++i)
        if (isFfdTarget(c.scene.item(i))) {
            const SceneItem& target = c.scene.item(i);
            if (target.id == c.scene.item(item).deforms) {
                current = static_cast<int>(meshes.size());
                part = target.kind == SceneItem::Kind::DocumentObject;
            }
            meshes.push_back(target.name);
            tips.push_back(target.kind == SceneItem::Kind::ImportedMesh
                               ? "Deform the imported mesh " + target.name + ", read from " + target.meshPath
                               : "Preview the deformation of the " + target.type + " " + target.name +
                                     " on its tessellation ('apply exactly' composes it, 'export deformed' writes STEP or IGES)");
        }
    // A part's export is STEP or IGES: the mesh default becomes a part's.
    if (part && std::strcmp(tool.exportPath, "deformed.obj") == 0) std::strcpy(tool.exportPath, "deformed.step");
    noteDropdown("mesh");
    const bool meshOpen = ImGui::BeginCombo("mesh", meshes[static_cast<std::size_t>(current)].c_str());
    recordWidget("mesh");
    tooltip("The imported mesh or part this lattice deforms as you drag its points");
    if (meshOpen) {
        for (std::size_t k = 0; k < meshes.size(); ++k) {
            const bool chosen = ImGui::Selectable(meshes[k].c_str(), static_cast<int>(k) == current);
            recordWidget(("mesh: " + meshes[k]).c_str()); // the open list's entries, for tests that click one
            tooltip(tips[k].c_str());
            if (chosen) {
                settings.ffd.mesh = k == 0 ? std::string() : meshes[k];
                c.scene.setSettings(item, settings, "lattice mesh");
            }
        }
        ImGui::EndCombo();
    }
    float w = static_cast<float>(settings.ffd.strength);
    const bool strengthChanged = ImGui::SliderFloat("strength", &w, 0.0f, 1.0f, "%.3f");
    recordWidget("strength");
    if (strengthChanged) {
        settings.ffd.strength = w;
        c.scene.setSettings(item, settings, "strength");
    }
    tooltip("W in p' = p + W sum B (P - R): 0 leaves the mesh, 1 is the full deformation");
    DocumentObject o = c.scene.object(item);
    auto& data = std::get<LatticeData>(o.data);
    static const char* policies[] = {"keep", "clamp", "extrapolate"};
    static const char* policyTips[] = {
        "Vertices outside the lattice box do not move (the mesh tears at the box where its boundary points moved)",
        "Vertices outside move as the nearest point of the box does: continuous everywhere (what Blender does)",
        "The lattice's polynomial continued outside the box: smooth, but it grows quickly away from it"};
    static_assert(int(OutsidePolicy::Keep) == 0 && int(OutsidePolicy::Clamp) == 1 && int(OutsidePolicy::Extrapolate) == 2);
    int policy = static_cast<int>(data.outside);
    // BeginCombo rather than Combo (the same control) so that the open list's entries are recorded.
    bool policyChanged = false;
    noteDropdown("outside");
    const bool policyOpen = ImGui::BeginCombo("outside", policies[policy]);
    recordWidget("outside");
    tooltip("Vertices outside the lattice box: keep them, clamp them to the box, or extrapolate the polynomial");
    if (policyOpen) {
        for (int k = 0; k < 3; ++k) {
            if (ImGui::Selectable(policies[k], k == policy) && k != policy) {
                policy = k;
                policyChanged = true;
            }
            recordWidget((std::string("outside: ") + policies[k]).c_str());
            tooltip(policyTips[k]);
        }
        ImGui::EndCombo();
    }
    if (policyChanged) {
        data.outside = static_cast<OutsidePolicy>(policy);
        try {
            c.scene.replaceObject(item, o, "outside policy");
        } catch (const Error& e) {
            tool.status() = e.what();
        }
    }
    if (ImGui::Button("reset lattice")) tool.resetLattice(c, item);
    tooltip("Put every lattice point back at its rest place (one undo step)");
    sameLineIfFits("XX direct manipulation (D)");
    ImGui::Checkbox("direct manipulation (D)", &tool.direct);
    tooltip("Press on the deformed mesh and drag: the lattice changes least so that the grabbed point follows the pointer");
    if (const FfdLink* link = c.scene.ffdLink(item)) {
        // The text is formatted once: drawn, and recorded as drawn with its numbers (--state,
        // "lattice_readout").
        UiState::LatticeReadout readout;
        readout.shown = true;
        readout.vertices = link->report.vertices;
        readout.outside = link->report.outside;
        readout.folds = link->report.foldCount;
        readout.updateMs = link->deformMs;
        readout.minDetJ = link->report.minDetJ;
        readout.maxDetJ = link->report.maxDetJ;
        char line[160];
        std::snprintf(line, sizeof line, "%zu vertices (%zu outside), update %.2f ms", readout.vertices, readout.outside, readout.updateMs);
        readout.lines.emplace_back(line);
        // Drawn in two pieces, so that a narrow panel breaks the line between them, never inside a
        // number (TextWrapped may break after the decimal point).
        const std::string& first = readout.lines.back();
        const std::size_t cut = first.find(" update ");
        const std::string counts = first.substr(0, cut), update = first.substr(cut + 1);
        fitText(counts.c_str());
        ImGui::TextUnformatted(counts.c_str());
        recordWidget("read-out");
        sameLineIfFits(update.c_str());
        fitText(update.c_str());
        ImGui::TextUnformatted(update.c_str());
        std::snprintf(line, sizeof line, "det J in [%.4g, %.4g]", readout.minDetJ, readout.maxDetJ);
        readout.lines.emplace_back(line);
        ImGui::TextUnformatted(line);
        if (readout.folds > 0) {
            std::snprintf(line, sizeof line, "fold-over: det J <= 0 at %zu %s", readout.folds, readout.folds == 1 ? "vertex" : "vertices");
            readout.lines.emplace_back(line);
            ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.35f, 0.3f, 1));
            ImGui::TextWrapped("%s", line);
            ImGui::PopStyleColor();
            recordWidget("fold-over");
        }
        recordLatticeReadout(readout);
        if (ImGui::Button("certify (det J > 0 on the box?)")) tool.certifyLattice(c, item);
        tooltip("Bernstein bound on det J over the whole box: certified injective, folds, or undecided");
        if (link->certificate) {
            const Certificate& cert = *link->certificate;
            const bool ok = cert.verdict == Verdict::CertifiedInjective;
            ImGui::PushStyleColor(ImGuiCol_Text, ok ? ImVec4(0.5f, 1, 0.5f, 1) : ImVec4(1, 0.6f, 0.3f, 1));
            ImGui::TextWrapped("%s (det J in [%.3g, %.3g], %d boxes)", toString(cert.verdict).c_str(), cert.minCoefficient,
                               cert.maxCoefficient, cert.boxes);
            ImGui::PopStyleColor();
        }
        const bool scalar = c.scene.display.analysis == SurfaceAnalysis::ScalarMap;
        bool show = scalar;
        const bool toggled = ImGui::Checkbox("det J colour map", &show);
        tooltip("Colour the mesh by det J, the local volume change (Display > analysis \"scalar map\"), with a legend");
        if (toggled && show != scalar) {
            c.scene.display.analysis = show ? SurfaceAnalysis::ScalarMap : SurfaceAnalysis::None;
            c.scene.touch();
        }

        // The field takes what the button leaves, so that the button is never cut off.
        const float button = ImGui::CalcTextSize("export deformed").x + 2 * ImGui::GetStyle().FramePadding.x;
        ImGui::SetNextItemWidth(std::max(60.0f, ImGui::GetContentRegionAvail().x - button - ImGui::GetStyle().ItemSpacing.x));
        ImGui::InputText("##export", tool.exportPath, sizeof tool.exportPath);
        recordWidget("export path");
        tooltip(part ? "Path of the deformed part to write (.step .stp .iges .igs .brep), relative to the working directory"
                     : "Path of the deformed mesh to write, relative to the working directory; its extension sets the format");
        ImGui::SameLine();
        const bool exportClicked = ImGui::Button("export deformed");
        recordWidget("export deformed");
        if (exportClicked) tool.exportDeformed(c, item, tool.exportPath);
        tooltip(part ? "Write the part composed exactly with the lattice (faces over degree 25 approximated, the error reported),\n"
                       "as freeform ffd PART.step does, to the path on the left"
                     : "Write the deformed mesh (computed in double, as freeform ffd does) to the path on the left");
    }
    if (ImGui::Button("apply exactly to curves and patches")) tool.applyLatticeToObjects(c, item);
    tooltip("Deform every other object of the document exactly, by composition: curves, patches, parts (Shift+A;\n"
            "freeform ffd DOC's rule). A part this lattice previews takes the exact image and the lattice goes back to rest");
    // The colour map's range last, so that switching the map on moves no row above it.
    if (c.scene.ffdLink(item) && c.scene.display.analysis == SurfaceAnalysis::ScalarMap) {
        ImGui::TextUnformatted("det J colour range");
        DisplaySettings d = c.scene.display;
        if (scalarRangeControls(d)) {
            c.scene.display = d;
            c.scene.touch();
        }
    }
}

void drawMeshPanel(LatticeTool& tool, ToolContext& c, int meshItem)
{
    ImGui::TextUnformatted("Fit a lattice (L)");
    ImGui::InputInt3("degrees", tool.degree);
    tooltip("The lattice's degrees per axis (1 to 12)");
    for (int& d : tool.degree) d = std::clamp(d, 1, 12);
    float m = static_cast<float>(tool.margin);
    if (ImGui::SliderFloat("margin", &m, 0.0f, 0.5f, "%.3f")) tool.margin = m;
    tooltip("Each side of the mesh's bounding box is pushed out by this fraction of its largest extent");
    if (ImGui::Button("fit lattice")) tool.fitLattice(c, meshItem);
    tooltip("Add a lattice around this mesh or part, bound to it, and select it (L)");
}

// ------------------------------------------------------------------ rational and NURBS objects

void drawToolbar(NurbsTool& tool, ToolContext&)
{
    if (ImGui::Button(tool.creating() && !tool.arc() ? "cancel circle (Esc)" : "circle (Shift+O)")) {
        if (tool.creating()) tool.cancelCreating();
        else tool.startCreating(false);
    }
    tooltip("Exact circle (a closed rational nurbs_curve): click the centre, then a point of the circle");
    ImGui::SameLine();
    if (ImGui::Button(tool.creating() && tool.arc() ? "cancel arc (Esc)" : "arc (Shift+U)")) {
        if (tool.creating()) tool.cancelCreating();
        else tool.startCreating(true);
    }
    tooltip("Exact arc: click the centre, the start, then the end (counter-clockwise); up to 90 degrees a rational_bezier_curve, beyond a nurbs_curve");
}

void drawPanel(NurbsTool& tool, ToolContext& c)
{
    const KindInfo* kind = selectedKind(c);
    if (!tool.handles(kind)) return;
    const int item = c.selection.item;
    if (kind->isSurface()) {
        drawTessellationSettings(c);
        ImGui::Separator();
    }
    if (kind->kind == ObjectKind::Part) return; // its faces are deformed by a lattice, not edited point by point
    ImGui::TextUnformatted("Weights (Alt + drag a point: scale)");
    const std::vector<double> weights = tool.weightsOf(c.scene, item);
    if (c.selection.points.empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
        ImGui::TextWrapped("select control points to type their weight");
        ImGui::PopStyleColor();
    } else {
        const int k = c.selection.points.back();
        if (k >= 0 && k < static_cast<int>(weights.size())) tool.followTypedWeight(item, k, weights[static_cast<std::size_t>(k)]);
        if (k >= 0 && k < static_cast<int>(weights.size())) {
            ImGui::TextWrapped("point %d: weight %.6g%s", k, weights[static_cast<std::size_t>(k)],
                               c.selection.points.size() > 1 ? " (last selected)" : "");
        }
        ImGui::SetNextItemWidth(120);
        ImGui::InputDouble("##weight", &tool.typedWeight, 0, 0, "%.6g");
        tooltip("The weight to give the selected control points (> 0); Alt + drag a point scales it instead");
        const char* setLabel = c.selection.points.size() > 1 ? "set the selected points' weight" : "set weight";
        sameLineIfFits(setLabel);
        if (ImGui::Button(setLabel))
            tool.setWeights(c, item, c.selection.points, tool.typedWeight);
        tooltip("Set the selected points' weight to the typed value (one undo step)");
    }
    const bool curve = kind->isCurve();
    if (curve) ImGui::Checkbox("de Boor construction at t (T)", &tool.construction);
    if (curve) tooltip("Show the de Boor construction (homogeneous, projected) at the slider's parameter t");
    if (curve)
        combControls(tool.comb, tool.combScale,
                     "Teeth along the curve's normal, as long as its curvature: a circle's are all equal; a step at a knot is a "
                     "jump of the curvature there");
    if (!kind->knots) return;
    ImGui::Separator();
    ImGui::TextUnformatted("Knots");
    ImGui::Checkbox("show knots", &tool.showKnots);
    tooltip("Curves: a dot at each distinct knot, one tick per unit of multiplicity (red: C0 or less). Surfaces: isoparametric lines at the knots");
    if (kind->isSurface()) {
        ImGui::RadioButton("in u", &tool.direction, 0);
        tooltip("Insert knots in the u direction (every column of the net)");
        ImGui::SameLine();
        ImGui::RadioButton("in v", &tool.direction, 1);
        tooltip("Insert knots in the v direction (every row of the net)");
    }
    float tf = static_cast<float>(tool.t);
    if (ImGui::SliderFloat("t", &tf, 0.0f, 1.0f, "%.4f")) tool.t = tf;
    tooltip("A parameter along the domain, 0 = its start, 1 = its end (the de Boor construction and knot insertion use it)");
    double u = tool.sliderParameter(c);
    ImGui::SetNextItemWidth(120);
    if (ImGui::InputDouble("u (knot value)", &u, 0, 0, "%.6g", ImGuiInputTextFlags_EnterReturnsTrue)) {
        // The typed parameter sets the slider: t = (u - a) / (b - a) on the domain [a, b].
        const double saved = tool.t;
        tool.t = 0;
        const double a = tool.sliderParameter(c);
        tool.t = 1;
        const double b = tool.sliderParameter(c);
        tool.t = b > a ? std::clamp((u - a) / (b - a), 0.0, 1.0) : saved;
    }
    tooltip("The parameter u in the knot range itself; Enter moves the slider there");
    if (ImGui::Button("insert knot at u (K)")) tool.insertKnot(c, tool.sliderParameter(c), tool.direction);
    tooltip("Boehm knot insertion at u: one more control point (row, column), the shape unchanged (one undo step)");
    // The knot vector(s), each distinct value with its multiplicity.
    const ObjectData& data = c.scene.object(item).data;
    auto list = [](const std::vector<double>& knots) {
        std::string text;
        for (std::size_t i = 0; i < knots.size();) {
            std::size_t j = i;
            while (j < knots.size() && knots[j] == knots[i]) ++j;
            char buffer[48];
            std::snprintf(buffer, sizeof buffer, "%s%.6g", text.empty() ? "" : ", ", knots[i]);
            text += buffer;
            if (j - i > 1) text += " (x" + std::to_string(j - i) + ")";
            i = j;
        }
        return text;
    };
    if (const auto* d = std::get_if<NurbsCurveData>(&data)) {
        ImGui::TextWrapped("degree %d, knots: %s", d->degree, list(d->knots).c_str());
    } else if (const auto* d = std::get_if<NurbsSurfaceData>(&data)) {
        ImGui::TextWrapped("degrees %d, %d; u: %s", d->degree[0], d->degree[1], list(d->knots[0]).c_str());
        ImGui::TextWrapped("v: %s", list(d->knots[1]).c_str());
    }
}

// ------------------------------------------------------------------ the set

void drawToolPanels(ToolContext& c, Tools& tools)
{
    ImGui::Separator();
    drawToolbar(tools.curve(), c);
    drawToolbar(tools.patch(), c);
    drawToolbar(tools.nurbs(), c);
    const int item = c.selection.item;
    if (item >= 0 && item < c.scene.itemCount()) {
        ImGui::Separator();
        // In the tools' dispatch order (Tools::all). A trimmed surface gets two sections: the
        // NURBS tool's tessellation settings, then the lattice tool's "fit a lattice".
        drawPanel(tools.curve(), c);
        drawPanel(tools.spline(), c);
        drawPanel(tools.patch(), c);
        drawPanel(tools.nurbs(), c);
        drawPanel(tools.lattice(), c);
        drawPanel(tools.cage(), c);
    }
    if (!tools.message().empty()) ImGui::TextWrapped("%s", tools.message().c_str());
}

} // namespace freeform::editor
