#include "tools/tools.h"

#include "tools/tool_util.h"

namespace freeform::editor {

Tools::Tools() : all_{&curve_, &spline_, &patch_, &nurbs_, &lattice_, &cage_} {}

bool Tools::onKey(ToolContext& c, int key, int mods)
{
    // Creation owns Enter, Escape and Backspace while it runs.
    if (curve_.creating())
        if (const KeyBinding* b = findBinding(KeyContext::Create, key, mods); b && curve_.onKey(c, b->action)) return true;
    for (Tool* tool : all_)
        if (const KeyBinding* b = findBinding(tool->keyContext(), key, mods); b && tool->onKey(c, b->action)) return true;
    return false;
}

bool Tools::onPointer(ToolContext& c, const PointerEvent& e)
{
    for (Tool* tool : all_)
        if (tool->onPointer(c, e)) return true;
    return false;
}

void Tools::update(ToolContext& c, Overlay& o)
{
    // The spline tool first: its joint modes complete the frame's edits before anything is drawn.
    spline_.update(c, o);
    curve_.update(c, o);
    patch_.update(c, o);
    nurbs_.update(c, o);
    lattice_.update(c, o);
    cage_.update(c, o);
    // A part's picked face (Selection::face): its boundary over the scene, in orange.
    const int i = c.selection.item;
    if (i >= 0 && i < c.scene.itemCount() && c.selection.face >= 0) {
        const ItemGeometry& g = c.scene.item(i).geometry;
        if (g.surface && g.vertexFace.size() == static_cast<std::size_t>(g.surface->vertexCount()))
            for (const auto& [a, b] : g.outline)
                if (g.vertexFace[static_cast<std::size_t>(a)] == c.selection.face)
                    o.addLine(f3(g.surface->positions.col(a)), f3(g.surface->positions.col(b)), Vec3f(1.0f, 0.55f, 0.1f), true);
    }
}

void Tools::reset()
{
    message_.clear();
    for (Tool* tool : all_) tool->reset();
}

} // namespace freeform::editor
