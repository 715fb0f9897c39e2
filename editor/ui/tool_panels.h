#pragma once
// The tools' ImGui panels (curve, spline, surface and lattice sections of the Properties window).

#include "tools/tools.h"

namespace freeform::editor {

/// Draws the tool sections for the selected item inside the current ImGui window.
void drawToolPanels(ToolContext& context, Tools& tools);

} // namespace freeform::editor
