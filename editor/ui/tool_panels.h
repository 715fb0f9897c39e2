#pragma once
// The tools' ImGui panels (curve, spline, surface, lattice, NURBS and cage sections of the Properties
// window). They live here, not in tools/, so that the tools compile and link without ImGui or ui/
// (editor/CMakeLists.txt: freeform_editor_tools): a panel reads a tool's public state and calls its
// operations, as a test does.

#include "tools/tools.h"

namespace freeform::editor {

/// Draws the tools' creation buttons, the section for the selected item, then the status line,
/// inside the current ImGui window.
void drawToolPanels(ToolContext& context, Tools& tools);

// Each tool's creation buttons (the toolbar at the top of the panel) and its section for a selected
// item of its kind (nothing when the item is of another kind).
void drawToolbar(CurveTool& tool, ToolContext& context);
void drawToolbar(PatchTool& tool, ToolContext& context);
void drawToolbar(NurbsTool& tool, ToolContext& context);
void drawPanel(CurveTool& tool, ToolContext& context);
void drawPanel(SplineTool& tool, ToolContext& context);
void drawPanel(PatchTool& tool, ToolContext& context);
void drawPanel(LatticeTool& tool, ToolContext& context);
/// The lattice tool's section for a selected imported mesh or part (fit a lattice).
void drawMeshPanel(LatticeTool& tool, ToolContext& context, int meshItem);
void drawPanel(NurbsTool& tool, ToolContext& context);
void drawPanel(CageTool& tool, ToolContext& context); // ui/cage_panel.cpp

} // namespace freeform::editor
