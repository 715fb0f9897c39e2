#include "interaction/keymap.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace freeform::editor {

namespace {

constexpr int kCtrl = GLFW_MOD_CONTROL, kShift = GLFW_MOD_SHIFT, kAlt = GLFW_MOD_ALT, kSuper = GLFW_MOD_SUPER;
constexpr int kNotCtrl = kCtrl;                    // any modifiers but Ctrl
constexpr int kPlain = kCtrl | kAlt | kSuper;      // Shift ignored, no Ctrl, Alt or Super
constexpr int kPlainShift = kPlain | kShift;       // exactly as given, Shift included

using C = KeyContext;
using A = KeyAction;

std::vector<KeyBinding> makeKeymap()
{
    return {
        // History: before everything, even while dragging.
        {GLFW_KEY_Z, kCtrl, kCtrl | kShift, C::History, A::Undo, "Ctrl+Z", "undo"},
        {GLFW_KEY_Z, kCtrl | kShift, kCtrl | kShift, C::History, A::Redo, "Ctrl+Shift+Z, Ctrl+Y", "redo"},
        {GLFW_KEY_Y, kCtrl, kCtrl, C::History, A::Redo, "Ctrl+Y", nullptr},
        // Files (and the opposite views).
        {GLFW_KEY_N, kCtrl, kCtrl, C::Files, A::NewDocument, "Ctrl+N", "new document"},
        {GLFW_KEY_O, kCtrl, kCtrl, C::Files, A::OpenDocument, "Ctrl+O", "open a document"},
        {GLFW_KEY_S, kCtrl, kCtrl | kShift, C::Files, A::Save, "Ctrl+S", "save (save as for an untitled document)"},
        {GLFW_KEY_S, kCtrl | kShift, kCtrl | kShift, C::Files, A::SaveAs, "Ctrl+Shift+S", "save as"},
        {GLFW_KEY_I, kCtrl, kCtrl, C::Files, A::ImportFile, "Ctrl+I", "import a mesh or a .bpt file"},
        {GLFW_KEY_E, kCtrl, kCtrl, C::Files, A::ExportMesh, "Ctrl+E", "export the visible surfaces and meshes (OBJ ...)"},
        {GLFW_KEY_Q, kCtrl, kCtrl, C::Files, A::Quit, "Ctrl+Q", "quit"},
        {GLFW_KEY_1, kCtrl, kCtrl, C::Files, A::ViewBack, "Ctrl+1", "back view"},
        {GLFW_KEY_KP_1, kCtrl, kCtrl, C::Files, A::ViewBack, "Ctrl+keypad 1", nullptr},
        {GLFW_KEY_3, kCtrl, kCtrl, C::Files, A::ViewLeft, "Ctrl+3", "left view"},
        {GLFW_KEY_KP_3, kCtrl, kCtrl, C::Files, A::ViewLeft, "Ctrl+keypad 3", nullptr},
        {GLFW_KEY_7, kCtrl, kCtrl, C::Files, A::ViewBottom, "Ctrl+7", "bottom view"},
        {GLFW_KEY_KP_7, kCtrl, kCtrl, C::Files, A::ViewBottom, "Ctrl+keypad 7", nullptr},
        // During a drag or a grab (G): every other key waits until it ends.
        {GLFW_KEY_ESCAPE, 0, 0, C::Gesture, A::GestureCancel, "Escape, right click", "cancel the drag or grab"},
        {GLFW_KEY_ENTER, 0, 0, C::Gesture, A::GestureConfirm, "Enter, Space, click", "confirm the drag or grab"},
        {GLFW_KEY_KP_ENTER, 0, 0, C::Gesture, A::GestureConfirm, "keypad Enter", nullptr},
        {GLFW_KEY_SPACE, 0, 0, C::Gesture, A::GestureConfirm, "Space", nullptr},
        {GLFW_KEY_X, 0, kShift, C::Gesture, A::AxisX, "X / Y / Z", "move along that axis (again: free)"},
        {GLFW_KEY_Y, 0, kShift, C::Gesture, A::AxisY, "Y", nullptr},
        {GLFW_KEY_Z, 0, kShift, C::Gesture, A::AxisZ, "Z", nullptr},
        {GLFW_KEY_X, kShift, kShift, C::Gesture, A::PlaneX, "Shift+X / Y / Z", "move in the plane orthogonal to that axis"},
        {GLFW_KEY_Y, kShift, kShift, C::Gesture, A::PlaneY, "Shift+Y", nullptr},
        {GLFW_KEY_Z, kShift, kShift, C::Gesture, A::PlaneZ, "Shift+Z", nullptr},
        // While creating a curve or spline by clicking.
        {GLFW_KEY_ENTER, 0, kPlain, C::Create, A::CreateFinish, "Enter, right click", "finish the curve or spline being created"},
        {GLFW_KEY_KP_ENTER, 0, kPlain, C::Create, A::CreateFinish, "keypad Enter", nullptr},
        {GLFW_KEY_ESCAPE, 0, kPlain, C::Create, A::CreateCancel, "Escape", "cancel the creation"},
        {GLFW_KEY_BACKSPACE, 0, kPlain, C::Create, A::CreateRemoveLast, "Backspace", "remove the last clicked point"},
        // Curves and splines.
        {GLFW_KEY_C, 0, kPlainShift, C::Curve, A::CreateCurve, "C", "create a curve by clicking its control points"},
        {GLFW_KEY_C, kShift, kPlainShift, C::Curve, A::CreateSpline, "Shift+C", "create a C2 cubic spline through the clicked points"},
        {GLFW_KEY_I, 0, kPlain, C::Curve, A::InsertPoint, "I", "insert a control point after the selected one (spline: a joint in its segment)"},
        {GLFW_KEY_DELETE, 0, kPlain, C::Curve, A::DeletePoint, "Delete", "delete the selected control point (spline: its joint)"},
        {GLFW_KEY_E, 0, kPlain, C::Curve, A::Elevate, "E", "elevate the degree (shape unchanged)"},
        {GLFW_KEY_K, 0, kPlain, C::Curve, A::Split, "K", "split the curve or open spline at the t slider"},
        {GLFW_KEY_T, 0, kPlain, C::Curve, A::Construction, "T", "de Casteljau construction at t on / off"},
        {GLFW_KEY_V, 0, kPlain, C::Curve, A::Comb, "V", "curvature comb on / off"},
        // Spline joints.
        {GLFW_KEY_1, 0, kPlain, C::Spline, A::JointFree, "1 (spline point selected)", "joint free"},
        {GLFW_KEY_2, 0, kPlain, C::Spline, A::JointAligned, "2 (spline point selected)", "joint aligned (G1)"},
        {GLFW_KEY_3, 0, kPlain, C::Spline, A::JointMirrored, "3 (spline point selected)", "joint mirrored (C1)"},
        {GLFW_KEY_4, 0, kPlain, C::Spline, A::JointC2, "4 (spline point selected)", "joint C2 (cubic splines)"},
        // Patches.
        {GLFW_KEY_P, 0, kPlain, C::Patch, A::CreatePatch, "P", "create a Bezier patch of the panel's degrees in the view plane"},
        // Rational and NURBS objects (NurbsTool). Alt + drag on a control point scales its weight
        // (the mouse section of the help).
        {GLFW_KEY_O, kShift, kPlainShift, C::Nurbs, A::CreateCircle, "Shift+O", "create an exact circle: click the centre, then a point on it"},
        {GLFW_KEY_U, kShift, kPlainShift, C::Nurbs, A::CreateArc, "Shift+U", "create an exact arc: click the centre, the start, the end (counter-clockwise)"},
        {GLFW_KEY_ESCAPE, 0, kPlain, C::Nurbs, A::CircleCancel, "Escape (circle or arc)", "cancel the circle or arc being created"},
        {GLFW_KEY_K, 0, kPlain, C::Nurbs, A::InsertKnot, "K (NURBS selected)", "insert a knot at the slider's parameter (shape unchanged)"},
        {GLFW_KEY_T, 0, kPlain, C::Nurbs, A::DeBoorConstruction, "T (NURBS curve selected)", "de Boor construction at the slider's parameter on / off"},
        {GLFW_KEY_V, 0, kPlain, C::Nurbs, A::Comb, "V (NURBS curve selected)", "curvature comb on / off"},
        // Lattices.
        {GLFW_KEY_L, 0, kPlain, C::Lattice, A::FitLattice, "L (imported mesh selected)", "fit a lattice to it (degrees and margin in the panel)"},
        {GLFW_KEY_D, 0, kPlain, C::Lattice, A::DirectManipulation, "D", "direct manipulation on / off (drag a point of a deformed mesh; the lattice follows)"},
        {GLFW_KEY_A, kShift, kPlainShift, C::Lattice, A::ApplyLattice, "Shift+A (lattice selected)", "apply it exactly to the document's curves, splines, patches and cages (as freeform ffd DOC)"},
        // Subdivision cages.
        {GLFW_KEY_E, 0, kPlainShift, C::Cage, A::CageEdgeMode, "E (cage selected)", "edge mode on / off: a click picks a cage edge"},
        {GLFW_KEY_S, 0, kPlainShift, C::Cage, A::SetCrease, "S (cage edge picked)", "crease: set the picked edge's sharpness to the panel's value"},
        {GLFW_KEY_S, kShift, kPlainShift, C::Cage, A::ClearCrease, "Shift+S (cage edge picked)", "crease: clear the picked edge's sharpness"},
        {GLFW_KEY_S, kAlt, kPlainShift, C::Cage, A::SetCorner, "Alt+S (cage points selected)", "corner: set the selected vertices' sharpness to the panel's value"},
        {GLFW_KEY_S, kAlt | kShift, kPlainShift, C::Cage, A::ClearCorner, "Alt+Shift+S (cage points selected)", "corner: clear the selected vertices' sharpness"},
        // Editing.
        {GLFW_KEY_A, 0, kCtrl | kShift | kAlt, C::Edit, A::SelectAll, "A", "select all points"},
        {GLFW_KEY_A, kAlt, kCtrl | kAlt, C::Edit, A::SelectNone, "Alt+A", "select no point"},
        {GLFW_KEY_ESCAPE, 0, kCtrl, C::Edit, A::Deselect, "Escape", "deselect the points, then the object"},
        {GLFW_KEY_G, 0, kCtrl | kShift | kAlt, C::Edit, A::Grab, "G", "grab: move the selected points with the pointer"},
        {GLFW_KEY_G, kShift, kCtrl | kShift | kAlt, C::Edit, A::ToggleGizmo, "Shift+G", "translate gizmo on / off"},
        {GLFW_KEY_TAB, kShift, kCtrl | kShift, C::Edit, A::ToggleSnap, "Shift+Tab", "snap to the grid on / off"},
        {GLFW_KEY_O, 0, kCtrl | kShift | kAlt, C::Edit, A::ToggleSoft, "O", "proportional (soft) editing on / off"},
        {GLFW_KEY_EQUAL, 0, kCtrl, C::Edit, A::SoftLarger, "+", "soft radius larger"},
        {GLFW_KEY_KP_ADD, 0, kCtrl, C::Edit, A::SoftLarger, "keypad +", nullptr},
        {GLFW_KEY_MINUS, 0, kCtrl, C::Edit, A::SoftSmaller, "-", "soft radius smaller"},
        {GLFW_KEY_KP_SUBTRACT, 0, kCtrl, C::Edit, A::SoftSmaller, "keypad -", nullptr},
        // View.
        {GLFW_KEY_1, 0, kNotCtrl, C::View, A::ViewFront, "1", "front view"},
        {GLFW_KEY_KP_1, 0, kNotCtrl, C::View, A::ViewFront, "keypad 1", nullptr},
        {GLFW_KEY_3, 0, kNotCtrl, C::View, A::ViewRight, "3", "right view"},
        {GLFW_KEY_KP_3, 0, kNotCtrl, C::View, A::ViewRight, "keypad 3", nullptr},
        {GLFW_KEY_7, 0, kNotCtrl, C::View, A::ViewTop, "7", "top view"},
        {GLFW_KEY_KP_7, 0, kNotCtrl, C::View, A::ViewTop, "keypad 7", nullptr},
        {GLFW_KEY_9, 0, kNotCtrl, C::View, A::ViewIso, "9", "isometric view"},
        {GLFW_KEY_KP_9, 0, kNotCtrl, C::View, A::ViewIso, "keypad 9", nullptr},
        {GLFW_KEY_5, 0, kNotCtrl, C::View, A::ToggleProjection, "5", "perspective <-> orthographic"},
        {GLFW_KEY_KP_5, 0, kNotCtrl, C::View, A::ToggleProjection, "keypad 5", nullptr},
        {GLFW_KEY_HOME, 0, kNotCtrl, C::View, A::FitAll, "Home", "fit all"},
        {GLFW_KEY_F, 0, kNotCtrl, C::View, A::FitSelection, "F", "fit the selection"},
        {GLFW_KEY_Z, 0, kNotCtrl, C::View, A::NextShading, "Z", "next shading mode (flat, Gouraud, Phong)"},
        {GLFW_KEY_W, 0, kNotCtrl, C::View, A::ToggleWireframe, "W", "wireframe overlay on / off"},
        {GLFW_KEY_R, 0, kNotCtrl, C::View, A::ToggleReflectionLines, "R", "reflection lines on / off"},
        {GLFW_KEY_F1, 0, kNotCtrl, C::View, A::ToggleHelp, "F1", "this help"},
        {GLFW_KEY_F2, 0, kNotCtrl, C::View, A::ToggleStatistics, "F2", "frame statistics on / off"},
    };
}

} // namespace

const std::vector<KeyBinding>& keymap()
{
    static const std::vector<KeyBinding> table = makeKeymap();
    return table;
}

bool matches(const KeyBinding& b, int key, int mods)
{
    return b.key == key && (mods & b.modMask) == b.mods;
}

const KeyBinding* findBinding(KeyContext context, int key, int mods)
{
    for (const KeyBinding& b : keymap())
        if (b.context == context && matches(b, key, mods)) return &b;
    return nullptr;
}

const char* contextTitle(KeyContext context)
{
    switch (context) {
    case KeyContext::History: return "Undo";
    case KeyContext::Files: return "Files";
    case KeyContext::Gesture: return "During a drag or grab";
    case KeyContext::Create: return "While creating a curve or spline";
    case KeyContext::Curve: return "Tools: curves and splines";
    case KeyContext::Spline: return "Tools: spline joints";
    case KeyContext::Patch: return "Tools: patches";
    case KeyContext::Nurbs: return "Tools: rational and NURBS objects";
    case KeyContext::Lattice: return "Tools: lattices";
    case KeyContext::Cage: return "Tools: subdivision cages";
    case KeyContext::Edit: return "Editing";
    case KeyContext::View: return "View";
    }
    return "";
}

std::string helpLine(const KeyBinding& b)
{
    std::string line = "  ";
    line += b.keys;
    line += ' ';
    while (line.size() < 28) line += ' ';
    line += b.help ? b.help : "";
    return line;
}

std::string keymapHelp()
{
    std::string text;
    bool first = true;
    KeyContext current = KeyContext::History;
    for (const KeyBinding& b : keymap()) {
        if (!b.help) continue;
        if (first || b.context != current) {
            text += contextTitle(b.context);
            text += '\n';
            current = b.context;
            first = false;
        }
        text += helpLine(b);
        text += '\n';
    }
    return text;
}

} // namespace freeform::editor
