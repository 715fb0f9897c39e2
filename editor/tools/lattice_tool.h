#pragma once
// The lattice tool: fits a lattice to an imported mesh (key L; degrees and margin in the panel),
// links it to that mesh by the mesh's stable id (the scene then keeps the deformed mesh up to date:
// scene/derived.h), resets it, exports the deformed mesh as `freeform ffd` would, applies the
// lattice exactly to the document's curves, patches and subdivision cages, certifies det J > 0,
// and direct manipulation (key D: drag a point of a deformed mesh, the lattice follows).

#include <optional>
#include <string>
#include <utility>

#include "tools/tool.h"

namespace freeform::editor {

class LatticeTool final : public Tool {
public:
    using Tool::Tool;

    KeyContext keyContext() const override { return KeyContext::Lattice; }
    bool onKey(ToolContext& context, KeyAction action) override;
    bool onPointer(ToolContext& context, const PointerEvent& event) override;
    void update(ToolContext& context, Overlay& overlay) override;
    void reset() override;

    // ---- operations on item indices (true on success; else the status line says why)
    bool fitLattice(ToolContext& context, int meshItem);
    bool resetLattice(ToolContext& context, int latticeItem);
    bool exportDeformed(ToolContext& context, int latticeItem, const std::string& path);
    bool applyLatticeToObjects(ToolContext& context, int latticeItem);
    bool certifyLattice(ToolContext& context, int latticeItem);

    bool dragging() const { return dragLattice_ != 0; }
    /// The item the last fitLattice added, once (-1: none since the last call): the app frames
    /// the view on the scene when that lattice does not fit in it.
    int takeFitted() { return std::exchange(fitted_, -1); }

    // ---- settings the panel and the tests change
    int degree[3] = {3, 3, 3};  // of fitted lattices
    double margin = 0.05;       // of fitted lattices, relative to the mesh's box
    bool direct = false;        // direct-manipulation mode (key D)
    char exportPath[512] = "deformed.obj";

private:
    long dragLattice_ = 0;      // the lattice item's id during a direct drag, else 0
    Eigen::Vector3d dragPlanePoint_ = Eigen::Vector3d::Zero(), dragPlaneNormal_ = Eigen::Vector3d::UnitZ();
    std::optional<Lattice> dragStart_; // the lattice at the start of the drag
    Eigen::Vector3d directRest_ = Eigen::Vector3d::Zero(), directTarget_ = Eigen::Vector3d::Zero();
    int fitted_ = -1;           // the item fitLattice added, until takeFitted
};

} // namespace freeform::editor
