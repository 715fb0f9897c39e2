#pragma once
// The ImGui panels: main menu, scene outliner, properties of the selected item, display settings
// (shading, material, lights, overlays, analysis), dialogs (open/save/import/export by path, unsaved
// changes, errors, help). The panels edit the Scene directly through its methods and ask the app
// for everything that touches files or the window through UiActions.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "interaction/interaction.h"
#include "interaction/selection.h"
#include "scene/scene.h"
#include "ui/fit.h"

namespace freeform::editor {

/// What the panels ask of the application.
class UiActions {
public:
    virtual ~UiActions() = default;
    virtual void newDocument() = 0;                       // asks first when there are unsaved changes
    virtual void open(const std::string& path) = 0;       // idem
    virtual bool save() = 0;                              // false (with an error shown) on failure
    virtual bool saveAs(const std::string& path) = 0;
    virtual void importFile(const std::string& path) = 0;
    virtual void exportMesh(const std::string& path) = 0;
    virtual void exportPart(const std::string& path) = 0; // the selected (or only) part, as STEP or IGES
    virtual void quit() = 0;                              // asks first
    virtual void fit(bool selectionOnly) = 0;
    virtual void setView(const std::string& name) = 0;
    virtual const std::vector<std::string>& recentFiles() const = 0;
    virtual void undo() = 0;                              // Ctrl+Z (ends a running drag first)
    virtual void redo() = 0;                              // Ctrl+Shift+Z, Ctrl+Y
    virtual void recover(bool accept) = 0;                // the autosave recovery dialog's answer
    virtual void toolPanels() = 0;                        // the tools' sections of the Properties window
    /// The desktop's file chooser (zenity, where one is installed and a desktop display is there):
    /// nullopt when there is none (the typed-path dialog is used instead), an empty string when the
    /// user cancelled it, else the chosen path.
    virtual std::optional<std::string> chooseFile(bool save, const std::string& title, const std::string& initial)
    {
        (void)save, (void)title, (void)initial;
        return std::nullopt;
    }
};

enum class PendingAction { None, New, Open, Quit };

/// State of the panels that is not part of the document.
struct UiState {
    Selection selection;              // the selected item and its selected control points
    EditSettings edit;                // snapping, soft editing, gizmo
    std::string error;                // shown in a modal until dismissed
    PendingAction pending = PendingAction::None; // waits for the unsaved-changes answer
    std::string pendingPath;
    bool showDisplay = true;
    bool showHelp = false;
    bool showStats = false;           // the frame statistics overlay (F2)
    double frameMs = 0;               // last frame time, for the status line
    double updateMs = 0;              // CPU time of the last frame that rebuilt something
    long triangles = 0;
    // Autosave recovery: offered in a modal when `recovery` is not empty (its description).
    std::string recovery;
    // Path dialog: which action it serves and the text being edited.
    enum class PathDialog { None, Open, SaveAs, Import, Export, ExportPart } pathDialog = PathDialog::None;
    char pathBuffer[1024] = {};
    // True from the dialog's first frame until its path field is active: that activation selects
    // the whole prefilled path (ImGui keeps a field's edit state between activations, and after a
    // typed path was confirmed, the next one would start with the cursor after the old text).
    bool pathSelectAll = false;
    // Dialogs answer only keys pressed after they appeared (the Enter that confirms one dialog must
    // not close the next one in the same frame, nor while it is held): the frame each appeared in.
    int errorFrame = -1;
    int recoveryFrame = -1;
    // Panel layout: laid out again against the window's size whenever that changes (the user's
    // moves and resizes hold until then). The size last laid out for, and where each panel is
    // (name, x, y, width, height in pixels), for the state dump (--state).
    float layoutWidth = 0, layoutHeight = 0;
    bool relayout = true;
    struct PanelRect {
        std::string name;
        float x = 0, y = 0, width = 0, height = 0;
    };
    std::vector<PanelRect> panels;
    /// The status bar's text: the active tool or mode and what the next click does (set by the app
    /// each frame).
    std::string statusHint;
    /// A notice for the status bar (e.g. a recent-files list that could not be read, the up axis an
    /// import chose), shown after the hint until the next one.
    std::string notice;
    /// The scalar colour map's legend as drawn in the last frame (for --state): the colour bar's
    /// rectangle in pixels (x, y, width, height; width 0: no legend) and the range it shows.
    float legendRect[4] = {0, 0, 0, 0};
    float legendMin = 0, legendMax = 0;
    /// The tooltip shown in the last frame (empty: none), for --state.
    std::string tooltip;
    /// The frame statistics overlay's text as drawn in the last frame (empty: not shown), for
    /// --state.
    std::string statsText;
    /// Where some controls were drawn in the last frame (name, x, y, width, height in pixels; see
    /// recordWidget), for --state: tests that drive a control find it there.
    std::vector<PanelRect> widgets;
    /// The ImGui IDs of the dropdowns (combos) drawn in the last frame: the tooltip audit
    /// (app/tooltip_audit.h) opens each of them to check its choices.
    std::vector<unsigned> dropdowns;
    /// The up axis File > Import gives OBJ, PLY, STL and OFF files (their formats have no
    /// convention): the last choice in the Import dialog, Z at first. glTF and GLB are always Y.
    UpAxis importUp = UpAxis::Z;
    /// Every text the panels drew without the room it needs, over the whole session (ui/fit.h;
    /// for --state, "overflows").
    std::vector<Overflow> overflows;
    /// The lattice panel's read-out row as drawn in the last frame (for --state,
    /// "lattice_readout"): the numbers it formats, from the same variables, and its lines of text
    /// as drawn (the last one, drawn in red, the fold-over count when `folds` > 0).
    struct LatticeReadout {
        bool shown = false; // false: no read-out drawn (no lattice with a linked mesh selected)
        std::size_t vertices = 0, outside = 0, folds = 0;
        double updateMs = 0, minDetJ = 0, maxDetJ = 0;
        std::vector<std::string> lines;
    } latticeReadout;
};

/// The tooltip of the last widget (ImGui 1.86 has no SetItemTooltip): shown while it is hovered.
void tooltip(UiState& state, const char* text);
/// The same for the panels that have no UiState at hand (the tools' panels); it records into the
/// state drawUi was last called with.
void tooltip(const char* text);
/// One choice of a dropdown: its label and its own tooltip (what choosing it does).
struct Choice {
    const char* label;
    const char* tip;
};
/// A dropdown (ImGui's combo: the same ID, look and list) whose every choice has its own tooltip.
/// `current` is the choice shown. True when the user picked a choice other than the current one;
/// `current` is then that choice. The closed dropdown's own tooltip is given after it as usual.
bool comboWithTips(const char* label, int& current, const Choice* choices, int count);
template <int N>
bool comboWithTips(const char* label, int& current, const Choice (&choices)[N])
{
    return comboWithTips(label, current, choices, N);
}
/// Notes that the next widget is a dropdown labelled `label` (UiState::dropdowns); comboWithTips
/// does it itself.
void noteDropdown(const char* label);
/// Records the last widget's rectangle under `name` in the state drawUi was last called with
/// (UiState::widgets, --state's `widgets`) when it is visible (not clipped or scrolled away).
void recordWidget(const char* name);
/// Records the lattice panel's read-out row as drawn this frame (UiState::latticeReadout) in the
/// state drawUi was last called with.
void recordLatticeReadout(const UiState::LatticeReadout& readout);

/// The scalar colour map's range controls: "auto" or fixed min/max (DisplaySettings). True when
/// something changed.
bool scalarRangeControls(DisplaySettings& display);

/// Asks for a path for `which` (Open, Save as, Import, Export): the desktop's file chooser when
/// there is one (the action is then carried out at once), else the typed-path dialog.
void askPath(UiState& state, UiActions& actions, UiState::PathDialog which, const std::string& initial);
/// What a path dialog does with the path it was given (open, save as, import, export).
void usePath(UiActions& actions, UiState::PathDialog which, const std::string& path);

/// Builds every panel for this frame (between ImGui::NewFrame and ImGui::Render). Returns true
/// when the user resolved a pending action with "Discard" or after a successful "Save": the
/// caller then carries it out.
bool drawUi(Scene& scene, UiState& state, UiActions& actions);

/// The three tasks of docs/editor.md "First steps", short, for the help window.
const char* firstStepsHelp();
/// The F1 help (the Help window; docs/editor.md lists the same keys): the mouse, then every key
/// binding of the keymap (interaction/keymap.h).
std::string controlsHelp();

} // namespace freeform::editor
