#pragma once
// The patch tool: creates Bezier patches (key P, degrees in the panel) and reads out the edge
// continuity (C0 / G1 / C1, angle, gap) of every edge the document's patches share. Its panel also
// holds the selected surface's tessellation.

#include <string>
#include <vector>

#include "freeform/surface/patch_complex.h"
#include "tools/tool.h"

namespace freeform::editor {

class PatchTool final : public Tool {
public:
    using Tool::Tool;

    KeyContext keyContext() const override { return KeyContext::Patch; }
    bool onKey(ToolContext& context, KeyAction action) override;
    void reset() override;
    /// Keeps the edge continuity table (once computed) up to date with every change of the scene.
    void update(ToolContext& context, Overlay& overlay) override;

    /// A patch of degrees `degree` in the view plane through the scene's centre, selected.
    bool createPatch(ToolContext& context);
    /// The edge continuity of all bezier_surface objects (edges(), edgePatchNames()).
    bool computeEdgeContinuity(ToolContext& context);

    const std::vector<EdgeContinuity>& edges() const { return edges_; }
    /// The object name of each patch index of edges().
    const std::vector<std::string>& edgePatchNames() const { return edgePatchNames_; }

    int degree[2] = {3, 3};     // of new patches (panel "m, n")

private:
    bool computeEdges(ToolContext& context, bool report);
    long edgesChange_ = -1;     // Scene::changeCount when edges_ was computed
    std::vector<EdgeContinuity> edges_;
    std::vector<std::string> edgePatchNames_;
};

} // namespace freeform::editor
