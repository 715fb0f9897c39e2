#pragma once
// The editor's one keymap: every key binding (key, modifiers, context, action, help line) is an
// entry of keymap(). Key handling looks actions up here (the application for files, history and
// views, Interaction for editing and gestures, each tool for its own context) and the F1 help text
// is generated from the same entries (keymapHelp), so the two cannot disagree.
//
// Matching: an entry matches a key press when the key is the same and (mods & modMask) == mods
// of the entry; modifiers outside modMask are ignored (e.g. the view keys take Shift+1 like 1).
// Within one context no two entries match the same key press (tests/test_keymap.cpp checks it).
// An entry without help text is listed under the help line before it (the keypad twin of a key,
// or Y and Z under "X / Y / Z").
// The dispatch order of the contexts is the application's (App::onKey, docs/editor.md).

#include <string>
#include <vector>

namespace freeform::editor {

/// Who handles an entry, and when it is active.
enum class KeyContext {
    History,    // Ctrl: undo and redo, even during a drag (App)
    Files,      // Ctrl: files and the opposite views (App)
    Gesture,    // while a drag or grab runs: constraints, confirm, cancel (Interaction)
    Create,     // while a curve is being created by clicking (CurveTool)
    Curve,      // curves and splines (CurveTool)
    Spline,     // spline joint handle modes (SplineTool)
    Patch,      // Bezier patches (PatchTool)
    Nurbs,      // rational and NURBS objects: circles, arcs, knots, weights (NurbsTool)
    Lattice,    // lattices and FFD (LatticeTool)
    Cage,       // subdivision cages: creases and corners (CageTool)
    Edit,       // selection and editing options (Interaction)
    View,       // camera, display and windows (App)
};

enum class KeyAction {
    // History
    Undo, Redo,
    // Files
    NewDocument, OpenDocument, Save, SaveAs, ImportFile, ExportMesh, Quit, ViewBack, ViewLeft, ViewBottom,
    // Gesture
    GestureCancel, GestureConfirm, AxisX, AxisY, AxisZ, PlaneX, PlaneY, PlaneZ,
    // Create
    CreateFinish, CreateCancel, CreateRemoveLast,
    // Curve
    CreateCurve, CreateSpline, Elevate, Split, InsertPoint, DeletePoint, Construction, Comb,
    // Spline
    JointFree, JointAligned, JointMirrored, JointC2,
    // Patch
    CreatePatch,
    // Nurbs
    CreateCircle, CreateArc, CircleCancel, InsertKnot, DeBoorConstruction,
    // Lattice
    FitLattice, DirectManipulation, ApplyLattice,
    // Cage
    CageEdgeMode, SetCrease, ClearCrease, SetCorner, ClearCorner,
    // Edit
    SelectAll, SelectNone, Deselect, Grab, ToggleGizmo, ToggleSoft, ToggleSnap, SoftLarger, SoftSmaller,
    // View
    ViewFront, ViewRight, ViewTop, ViewIso, ToggleProjection, FitAll, FitSelection, NextShading, ToggleWireframe,
    ToggleReflectionLines, ToggleHelp, ToggleStatistics,
};

struct KeyBinding {
    int key = 0;                // GLFW key code
    int mods = 0;               // GLFW modifier bits that must be held ...
    int modMask = 0;            // ... among these (the others are ignored)
    KeyContext context = KeyContext::View;
    KeyAction action = KeyAction::ToggleHelp;
    const char* keys = "";      // as the help shows it ("Shift+C")
    const char* help = nullptr; // the help line; nullptr: listed under the entry before it
};

/// Every binding, in help order.
const std::vector<KeyBinding>& keymap();
/// Whether entry b matches a press of `key` with modifier bits `mods`.
bool matches(const KeyBinding& b, int key, int mods);
/// The action of `context` bound to this key press, if any (at most one: see above).
const KeyBinding* findBinding(KeyContext context, int key, int mods);
/// The section title of a context in the help ("Editing", "Tools: curves and splines" ...).
const char* contextTitle(KeyContext context);
/// The help text of every entry with help: a title line per context, then one line per entry,
/// "  <keys padded to 26 columns><help>".
std::string keymapHelp();
/// One help line as keymapHelp writes it (without the newline).
std::string helpLine(const KeyBinding& b);

} // namespace freeform::editor
