#include "ui/tool_panels.h"

#include <imgui.h>

#include <cstdio>

#include "tools/tool_state.h"

namespace freeform::editor {

namespace {

using State = Tools::State;

void curvePanel(ToolContext& c, State& s, const std::string& type)
{
    ImGui::TextUnformatted("Curve tools");
    float t = static_cast<float>(s.t);
    if (ImGui::SliderFloat("t", &t, 0.0f, 1.0f, "%.4f")) s.t = t;
    ImGui::Checkbox("de Casteljau at t (T)", &s.construction);
    ImGui::Checkbox("curvature comb (V)", &s.comb);
    if (s.comb) {
        float scale = static_cast<float>(s.combScale);
        if (ImGui::SliderFloat("comb scale", &scale, 0.05f, 10.0f, "%.2f", ImGuiSliderFlags_Logarithmic)) s.combScale = scale;
    }
    if (type != "deboor_spline") {
        if (ImGui::Button("elevate degree (E)")) elevateSelected(c, s);
        ImGui::SameLine();
        if (ImGui::Button("split at t (K)")) splitSelected(c, s);
    }
    if (ImGui::Button("insert point (I)")) insertAtSelected(c, s);
    ImGui::SameLine();
    if (ImGui::Button("delete point (Del)")) deleteSelected(c, s);
}

void splinePanel(ToolContext& c, State& s, int item)
{
    const auto& d = std::get<BezierSplineData>(c.scene.object(item).data);
    ImGui::Separator();
    ImGui::TextUnformatted("Joints (1 free, 2 aligned G1, 3 mirrored C1, 4 C2)");
    static const char* names[] = {"free", "aligned", "mirrored", "C2"};
    int all = -1;
    ImGui::SetNextItemWidth(120);
    if (ImGui::Combo("all joints", &all, names, 4)) setAllJointModes(c, s, static_cast<JointMode>(all));
    std::vector<JointContinuity<double>> report;
    try {
        report = splineContinuity(d);
    } catch (const Error& e) {
        ImGui::TextWrapped("%s", e.what());
    }
    const std::vector<JointMode> modes = jointModes(c.scene, item);
    if (ImGui::BeginTable("joints", 4, ImGuiTableFlags_Borders | ImGuiTableFlags_SizingFixedFit)) {
        ImGui::TableSetupColumn("joint");
        ImGui::TableSetupColumn("mode");
        ImGui::TableSetupColumn("C / G");
        ImGui::TableSetupColumn("jumps |f_R^(k) - f_L^(k)|");
        ImGui::TableHeadersRow();
        for (const JointContinuity<double>& r : report) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::Text("%d", r.joint);
            ImGui::TableNextColumn();
            int mode = static_cast<int>(modes[static_cast<std::size_t>(r.joint)]);
            ImGui::PushID(r.joint);
            ImGui::SetNextItemWidth(90);
            if (ImGui::Combo("##mode", &mode, names, 4)) setJointMode(c, s, static_cast<JointMode>(mode), r.joint);
            ImGui::PopID();
            ImGui::TableNextColumn();
            ImGui::Text("C%d G%d", r.C, r.G);
            ImGui::TableNextColumn();
            std::string jumps;
            for (std::size_t k = 1; k < r.jumps.size() && k <= 3; ++k) {
                char buffer[32];
                std::snprintf(buffer, sizeof buffer, "%s%.2e", k > 1 ? "  " : "", r.jumps[k]);
                jumps += buffer;
            }
            ImGui::TextUnformatted(jumps.c_str());
        }
        ImGui::EndTable();
    }
}

void surfacePanel(ToolContext& c, State& s, int item)
{
    ImGui::TextUnformatted("Tessellation");
    ObjectSettings settings = c.scene.item(item).settings;
    Tessellation& t = settings.tessellation;
    int mode = t.mode == Tessellation::Mode::Adaptive ? 0 : 1;
    bool changed = ImGui::RadioButton("tolerance", &mode, 0);
    ImGui::SameLine();
    changed |= ImGui::RadioButton("segments", &mode, 1);
    t.mode = mode == 0 ? Tessellation::Mode::Adaptive : Tessellation::Mode::Uniform;
    if (mode == 0) {
        float tol = static_cast<float>(t.tolerance > 0 ? t.tolerance : c.scene.display.tolerance);
        if (ImGui::SliderFloat("tolerance", &tol, 1e-5f, 0.1f, "%.1e", ImGuiSliderFlags_Logarithmic)) {
            t.tolerance = tol;
            changed = true;
        }
    } else {
        changed |= ImGui::SliderInt("segments", &t.segments, 1, 64);
    }
    if (changed) c.scene.setSettings(item, settings, "tessellation");
    ImGui::Separator();
    if (ImGui::Button("edge continuity of all patches")) computeEdgeContinuity(c, s);
    if (!s.edges.empty()) {
        int g1 = 0, c1 = 0;
        for (const EdgeContinuity& e : s.edges) g1 += e.g1, c1 += e.c1;
        ImGui::Text("%zu edges: %d C1, %d G1, %zu G0 only", s.edges.size(), c1, g1, s.edges.size() - static_cast<std::size_t>(g1));
        static const char* sides[] = {"u0", "u1", "v0", "v1"};
        if (ImGui::BeginTable("edges", 4, ImGuiTableFlags_Borders | ImGuiTableFlags_ScrollY | ImGuiTableFlags_SizingFixedFit,
                              ImVec2(0, 180))) {
            ImGui::TableSetupColumn("edge");
            ImGui::TableSetupColumn("level");
            ImGui::TableSetupColumn("angle");
            ImGui::TableSetupColumn("gap");
            ImGui::TableHeadersRow();
            for (const EdgeContinuity& e : s.edges) {
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                ImGui::Text("%s.%s | %s.%s", s.edgePatchNames[static_cast<std::size_t>(e.a.patch)].c_str(),
                            sides[static_cast<int>(e.a.side)], s.edgePatchNames[static_cast<std::size_t>(e.b.patch)].c_str(),
                            sides[static_cast<int>(e.b.side)]);
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(e.c1 ? "C1" : e.g1 ? "G1" : "C0");
                ImGui::TableNextColumn();
                ImGui::Text("%.2e", e.angle);
                ImGui::TableNextColumn();
                ImGui::Text("%.1e", e.gap);
            }
            ImGui::EndTable();
        }
    }
}

void latticePanel(ToolContext& c, State& s, int item)
{
    ImGui::TextUnformatted("Free-form deformation");
    ObjectSettings settings = c.scene.item(item).settings;
    // The mesh it deforms.
    std::vector<std::string> meshes{"(none)"};
    int current = 0;
    for (int i = 0; i < c.scene.itemCount(); ++i)
        if (c.scene.item(i).kind == SceneItem::Kind::ImportedMesh) {
            if (c.scene.item(i).name == settings.ffd.mesh) current = static_cast<int>(meshes.size());
            meshes.push_back(c.scene.item(i).name);
        }
    if (ImGui::BeginCombo("mesh", meshes[static_cast<std::size_t>(current)].c_str())) {
        for (std::size_t k = 0; k < meshes.size(); ++k)
            if (ImGui::Selectable(meshes[k].c_str(), static_cast<int>(k) == current)) {
                settings.ffd.mesh = k == 0 ? std::string() : meshes[k];
                c.scene.setSettings(item, settings, "lattice mesh");
            }
        ImGui::EndCombo();
    }
    float w = static_cast<float>(settings.ffd.strength);
    if (ImGui::SliderFloat("strength", &w, 0.0f, 1.0f, "%.3f")) {
        settings.ffd.strength = w;
        c.scene.setSettings(item, settings, "strength");
    }
    DocumentObject o = c.scene.object(item);
    auto& data = std::get<LatticeData>(o.data);
    static const char* policies[] = {"keep", "clamp", "extrapolate"};
    int policy = data.outside == "keep" ? 0 : data.outside == "clamp" ? 1 : 2;
    if (ImGui::Combo("outside", &policy, policies, 3)) {
        data.outside = policies[policy];
        try {
            c.scene.replaceObject(item, o, "outside policy");
        } catch (const Error& e) {
            s.message = e.what();
        }
    }
    if (ImGui::Button("reset lattice")) resetLattice(c, s, item);
    ImGui::SameLine();
    ImGui::Checkbox("direct manipulation (D)", &s.direct);
    if (auto it = s.links.find(c.scene.item(item).name); it != s.links.end()) {
        const FfdLink& link = it->second;
        ImGui::Text("%zu vertices (%zu outside), update %.2f ms", link.report.vertices, link.report.outside, link.deformMs);
        ImGui::Text("det J in [%.4g, %.4g]", link.report.minDetJ, link.report.maxDetJ);
        if (link.report.foldCount > 0)
            ImGui::TextColored(ImVec4(1, 0.35f, 0.3f, 1), "fold-over: det J <= 0 at %zu vertices", link.report.foldCount);
        if (ImGui::Button("certify (det J > 0 on the box?)")) certifyLattice(c, s, item);
        if (link.certificate) {
            const Certificate& cert = *link.certificate;
            const bool ok = cert.verdict == Verdict::CertifiedInjective;
            ImGui::TextColored(ok ? ImVec4(0.5f, 1, 0.5f, 1) : ImVec4(1, 0.6f, 0.3f, 1), "%s (det J in [%.3g, %.3g], %d boxes)",
                               toString(cert.verdict).c_str(), cert.minCoefficient, cert.maxCoefficient, cert.boxes);
        }
        const bool scalar = c.scene.display.analysis == SurfaceAnalysis::ScalarMap;
        bool show = scalar;
        if (ImGui::Checkbox("det J colour map", &show) && show != scalar) {
            c.scene.display.analysis = show ? SurfaceAnalysis::ScalarMap : SurfaceAnalysis::None;
            c.scene.touch();
        }
        ImGui::InputText("##export", s.exportPath, sizeof s.exportPath);
        ImGui::SameLine();
        if (ImGui::Button("export deformed")) exportDeformed(c, s, item, s.exportPath);
    }
    if (ImGui::Button("apply exactly to curves and patches")) applyLatticeToObjects(c, s, item);
}

void meshPanel(ToolContext& c, State& s, int item)
{
    ImGui::TextUnformatted("Fit a lattice (L)");
    ImGui::InputInt3("degrees", s.latticeDegree);
    for (int& d : s.latticeDegree) d = std::clamp(d, 1, 12);
    float margin = static_cast<float>(s.margin);
    if (ImGui::SliderFloat("margin", &margin, 0.0f, 0.5f, "%.3f")) s.margin = margin;
    if (ImGui::Button("fit lattice")) fitLattice(c, s, item);
}

} // namespace

void drawToolPanels(ToolContext& c, Tools& tools)
{
    State& s = tools.state();
    const int item = c.selection.item;
    ImGui::Separator();
    if (ImGui::Button(s.creating && !s.creatingSpline ? "finish curve (Enter)" : "create curve (C)")) {
        if (s.creating) createCurveFromClicks(c, s);
        else s.creating = true, s.creatingSpline = false;
    }
    ImGui::SameLine();
    if (ImGui::Button(s.creating && s.creatingSpline ? "finish spline (Enter)" : "create C2 spline (Shift+C)")) {
        if (s.creating) createCurveFromClicks(c, s);
        else s.creating = true, s.creatingSpline = true;
    }
    if (ImGui::Button("create patch (P)")) createPatch(c, s);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(80);
    ImGui::InputInt2("m, n", s.patchDegree);
    for (int& d : s.patchDegree) d = std::clamp(d, 1, 20);
    if (item >= 0 && item < c.scene.itemCount()) {
        const std::string type = c.scene.item(item).type;
        ImGui::Separator();
        if (type == "bezier_curve" || type == "bezier_spline" || type == "deboor_spline") curvePanel(c, s, type);
        if (type == "bezier_spline") splinePanel(c, s, item);
        if (type == "bezier_surface" || type == "deboor_surface") surfacePanel(c, s, item);
        if (type == "lattice") latticePanel(c, s, item);
        if (type == "mesh") meshPanel(c, s, item);
    }
    if (!s.message.empty()) ImGui::TextWrapped("%s", s.message.c_str());
}

} // namespace freeform::editor
