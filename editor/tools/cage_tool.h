#pragma once
// The cage tool: what is specific to a selected `subdivision_surface` (docs/format.md): its scheme
// and boundary (the object's fields), its level (the item's uniform tessellation: segments per
// cage edge; 0 adaptive), its creases and corners, and the cage overlay (crease edges coloured by
// sharpness, sharp corners, the picked edge). Moving cage vertices stays generic control-point
// editing (interaction/), and applying a lattice to the cage stays the lattice tool's (one rule for
// every object type through deformDocument, docs/ffd.md).
//
// Crease editing: edge mode (key E) makes a left click on the selected cage pick the nearest cage
// edge within a few pixels; S sets the picked edge's sharpness to the panel's value, Shift+S clears
// it; Alt+S and Alt+Shift+S do the same for the selected cage vertices' corner sharpness. A cage
// read from a mesh file is written inline on its first crease or corner edit (its file tags become
// `creases` / `corners`; the file stays as it is), as when one of its vertices is moved. Each edit
// is one undo step; an edit whose result the library refuses (Loop on quads, say) changes nothing
// and says why in the status line.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "freeform/subdivision/subdivision_surface.h"
#include "tools/tool.h"

namespace freeform::editor {

class CageTool final : public Tool {
public:
    using Tool::Tool;

    KeyContext keyContext() const override { return KeyContext::Cage; }
    bool onKey(ToolContext& context, KeyAction action) override;
    /// In edge mode, a left press near an edge of the selected cage picks it.
    bool onPointer(ToolContext& context, const PointerEvent& event) override;
    /// The overlay of the selected cage (when showCage): creases, corners, the picked edge.
    void update(ToolContext& context, Overlay& overlay) override;
    void reset() override;

    // ---- operations on item indices (true on success; else the status line says why)
    bool setScheme(ToolContext& context, int item, const std::string& scheme);
    bool setBoundary(ToolContext& context, int item, const std::string& boundary);
    /// Uniform tessellation with `level` segments per cage edge (1..256), or adaptive for 0.
    bool setLevel(ToolContext& context, int item, int level);
    /// Picks the cage edge v0-v1 of the item (either order); false when the cage has no such edge.
    bool pickEdge(ToolContext& context, int item, int v0, int v1);
    /// Picks the edge of the selected cage nearest to pixel (x, y), within `radius` pixels.
    bool pickEdgeAt(ToolContext& context, double x, double y, double radius = 8);
    /// Sets the sharpness of cage edge v0-v1 (0 clears it: the entry is removed).
    bool setCrease(ToolContext& context, int item, int v0, int v1, double sharpness);
    bool clearCrease(ToolContext& context, int item, int v0, int v1) { return setCrease(context, item, v0, v1, 0); }
    /// Sets the corner sharpness of the cage vertices (0 clears them), one undo step.
    bool setCorners(ToolContext& context, int item, const std::vector<int>& vertices, double sharpness);

    /// The picked edge (low, high vertex index) of the item with id pickedItem(), if any.
    const std::optional<std::array<int, 2>>& pickedEdge() const { return picked_; }
    long pickedItem() const { return pickedItem_; }
    /// The cage of item i as the surface is built from it (file tags, then the object's own), or
    /// nothing when it is not a subdivision surface or cannot be read.
    static std::optional<SubdivisionCage> cageOf(const Scene& scene, int item);
    /// The sharpness of edge v0-v1 in a cage (the last entry for it wins, as OpenSubdiv's tags), 0 when none.
    static double edgeSharpness(const SubdivisionCage& cage, int v0, int v1);
    /// Whether item is a subdivision surface (the panel's section is shown for it).
    bool isCage(const Scene& scene, int item) const;

    // ---- settings the panel and the tests change
    double sharpness = kInfiniteSharpness; // what S and Alt+S set
    bool edgeMode = false;                 // key E: a click picks a cage edge
    bool showCage = true;                  // the crease overlay of the selected cage

private:
    /// Sets the cage's scheme or boundary (`field`, called `name` in the undo label and the status
    /// line) to value: one undo step, nothing when it is already value.
    bool setText(ToolContext& context, int item, std::string SubdivisionSurfaceData::*field, const std::string& value,
                 const std::string& name);
    /// Validates the new data through the document layer (the surface is built), then replaces.
    bool replaceCage(ToolContext& context, int item, const SubdivisionSurfaceData& data, const std::string& label);
    /// The item's data with a file cage made inline (file tags as creases / corners).
    SubdivisionSurfaceData inlineData(const Scene& scene, int item) const;
    std::optional<std::array<int, 2>> picked_;
    long pickedItem_ = 0;
    // The overlay's cage, cached per (item id, Scene::changeCount).
    long cacheItem_ = 0, cacheChange_ = -1;
    std::optional<SubdivisionCage> cache_;
};

} // namespace freeform::editor
