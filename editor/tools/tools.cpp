#include "tools/tools.h"

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
}

void Tools::reset()
{
    message_.clear();
    for (Tool* tool : all_) tool->reset();
}

} // namespace freeform::editor
