#pragma once
// The application: a GLFW window with an OpenGL 3.3 core context, the renderer, the scene and the
// panels. The frame loop follows Dear ImGui's order (poll events, new frames, build the UI, draw
// the scene, draw the UI, swap); io.WantCaptureMouse/WantCaptureKeyboard decide whether input
// goes to the panels or to the view, where the tools (tools/) see pointer and keys first, then the
// generic point editing (interaction/), then the camera. Headless runs (--screenshot, --frames,
// --replay) use a hidden window and the same drawing path, reading the pixels back instead of
// showing them; --replay feeds scripted events through the same handlers as GLFW's callbacks and
// into ImGui's io as its GLFW backend does. Unsaved changes are autosaved (autosaveDirectory()).

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "app/options.h"
#include "freeform/core/warning.h"
#include "app/recent_files.h"
#include "app/tooltip_audit.h"
#include "interaction/interaction.h"
#include "interaction/keymap.h"
#include "interaction/replay.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "scene/scene_drawer.h"
#include "scene/overlay.h"
#include "tools/tools.h"
#include "ui/ui.h"

struct GLFWwindow;

namespace freeform::editor {

class App final : public UiActions {
public:
    /// Creates the window (hidden when headless) and the renderer; Error when there is no display
    /// or no OpenGL 3.3 core context.
    App(Scene scene, const Options& options);
    ~App() override;
    App(const App&) = delete;
    App& operator=(const App&) = delete;

    /// The interactive loop, until the window closes. Returns the exit status.
    int run();
    /// Renders one frame at the options' size (with the panels unless --no-ui) and returns it.
    Image renderImage();
    /// Shows a message in the error dialog.
    void showError(const std::string& message) { ui_.error = message; }
    /// Renders `frames` frames and prints timing statistics on stdout.
    void printFrameStats(int frames);
    /// Feeds the events through the input handlers, rendering a frame after each.
    void replay(const std::vector<ReplayEvent>& events);
    /// Writes the state --state dumps (the error dialog, window and panels, camera) as JSON.
    void writeState(const std::string& path) const;
    /// Saves the document as it is now (File > Save as); Error when it cannot be written.
    void saveDocument(const std::string& path) { scene_.save(path); }
    const Scene& scene() const { return scene_; }

    // UiActions
    void newDocument() override;
    void open(const std::string& path) override;
    bool save() override;
    bool saveAs(const std::string& path) override;
    void importFile(const std::string& path) override;
    void exportMesh(const std::string& path) override;
    void exportPart(const std::string& path) override;
    void quit() override;
    void fit(bool selectionOnly) override;
    void setView(const std::string& name) override;
    const std::vector<std::string>& recentFiles() const override { return recent_.paths(); }
    void undo() override;
    void redo() override;
    void recover(bool accept) override;
    void toolPanels() override;
    std::optional<std::string> chooseFile(bool save, const std::string& title, const std::string& initial) override;

    // Input (GLFW callbacks forward here).
    void onMouseButton(int button, int action, int mods);
    void onCursor(double x, double y);
    void onScroll(double dy);
    void onKey(int key, int action, int mods);
    /// Carries out an action of the keymap's Files and View contexts (interaction/keymap.h).
    void perform(KeyAction action);
    void onDrop(int count, const char** paths);
    void onClose();

private:
    // Input of the interactive window, queued by the GLFW callbacks (glfwPollEvents) and taken
    // each frame: ImGui 1.86 reads key and button state once per frame, so a press and a release
    // of one key in the same frame would be lost; such a release waits for the next frame. The
    // view's handlers get the events after ImGui::NewFrame, when io.WantCapture* describe the
    // pointer's current place (a scroll over a panel is the panel's).
    //
    // ImGui decides whether the pointer is over one of its windows at NewFrame, from the pointer
    // position it is given and the windows of the previous frame. So, when the queue lags behind
    // the X server (slow frames, fast input), ImGui is given the queue's pointer position and
    // button state, not the live ones; a button press or a scroll is taken only as the first
    // event of a frame after a frame that took no key, character or button event (a dialog that
    // such an event closed is still in the previous frame's windows: a click just after its Enter
    // fell on the closed dialog and was lost, issue 12); and a pointer move after a press waits
    // for the next frame (the press is judged where it happened). --replay renders a frame before
    // each press, which is why replayed sessions never showed the lost click. After a frame that
    // opened or closed a dialog or popup, the next frame takes no input at all: the field a dialog
    // focuses takes keys only from the frame after it appeared (a path typed at once after Ctrl+I
    // lost its first character).
    struct InputEvent {
        enum class Type { Key, Char, Button, Scroll, Cursor } type = Type::Key;
        int code = 0, scancode = 0, action = 0, mods = 0;
        double x = 0, y = 0;
        unsigned int ch = 0;
    };
    void queueInput(const InputEvent& e) { input_.push_back(e); }
    void takeInput();        // before NewFrame: this frame's events to ImGui's backend
    void dispatchInput();    // after NewFrame: the same events to the view's handlers
    void dispatchEvents();   // (dispatchInput's loop, timed for --frame-log)
    // --frame-log (docs/performance.md, "Editor frame time"): the time the input handlers took
    // since the last logged frame (a drag's picking and point moves), and the log itself.
    template <class Handler>
    void timedInput(Handler&& handler)
    {
        const auto t0 = std::chrono::steady_clock::now();
        handler();
        inputMs_ += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    }
    double inputMs_ = 0;
    std::ofstream frameLog_;
    long loggedFrames_ = 0;
    struct LoggedFrame {
        bool dragging = false, changed = false;
        double input = 0, ui = 0, update = 0, overlay = 0, draw = 0, gui = 0, cpuStart = 0;
    } loggedFrame_;
    std::chrono::steady_clock::time_point lastLogged_;
    void logFrame(double endMs); // writes the frame's line once it has ended (endMs: its present or GPU wait)
    std::vector<InputEvent> input_, frameInput_;
    bool holdInput_ = false;                   // the previous frame opened or closed a dialog or popup
    int dialogs_ = 0;                          // which dialogs and popups were up (uiSignature)
    int uiSignature() const;
    bool lastFrameTookKeys_ = false;           // the previous frame took a key, character or button event
    bool haveQueuedCursor_ = false;            // a pointer position has come through the queue
    double queuedX_ = 0, queuedY_ = 0;         // the pointer as the queue has it (ImGui's MousePos)
    bool queuedDown_[5] = {};                  // the buttons as the queue has them (ImGui's MouseDown)
    std::string statusHint();
    std::string stateText() const;
    std::string lastState_;   // interactive --state: the text last written
    std::vector<TooltipAudit> audits_; // replay event tooltip_audit: the results, for --state

    /// One frame; stillImage: for a screenshot (multisampled under Antialiasing::Auto, see
    /// scene/settings.h), not a frame of the interactive view.
    void frame(int width, int height, bool withUi, bool stillImage = false);
    void frameIfOutside(int item); // fits the view to the scene when a point of item is outside it
    /// One frame of the panels; `afterNewFrame` (the tooltip audit's hook) runs right after ImGui::NewFrame.
    void buildUi(const std::function<void()>& afterNewFrame = {});
    void carryOutPending();
    void replaceScene(Scene scene, bool keepAutosave = false);
    void viewSize(int& width, int& height) const;
    ViewTransform view() const;
    ToolContext toolContext();
    PointerEvent pointerEvent(PointerEvent::Type type, int button, int mods) const;
    void validateSelection();
    void maybeAutosave();
    void removeAutosave();
    void offerRecovery();
    void applyModifiers(int mods);
    void addRecent(const std::string& path);
    /// A new action starts (a button or key pressed, files dropped): the status bar's messages of
    /// the last one (the notice, the tools' message) go (docs/editor.md, "Status bar").
    void startAction();
    double aspect() const;

    /// The library's warnings since the last call, as the status line shows them ("warning: ...",
    /// joined by "; "; empty: none). They may arrive from the background tessellation's thread.
    std::string takeWarnings();

    Options options_;
    Scene scene_;
    UiState ui_;
    std::mutex warningsMutex_;
    std::vector<std::string> warnings_;
    // The library's warnings (freeform/core/warning.h) go to the status line, not to a terminal:
    // collected here, shown by the next frame (or at once by the action that caused them).
    ScopedWarningHandler warningHandler_{[this](const std::string& message) {
        std::lock_guard lock(warningsMutex_);
        warnings_.push_back(message);
    }};
    GLFWwindow* window_ = nullptr;
    std::unique_ptr<Renderer> renderer_;
    std::unique_ptr<SceneDrawer> drawer_;
    bool imgui_ = false;
    RecentFiles recent_;                  // File > Open recent (not kept by headless runs)
    Tools tools_;
    Interaction interaction_{ui_.edit};
    Overlay overlay_;
    std::optional<Scene> pendingScene_;   // opened, waiting for the unsaved-changes answer
    // Pointer state: the cursor (view pixels), the press that may become a camera drag or a click.
    enum class Drag { None, Pending, Orbit, Pan, Interact, Tool } drag_ = Drag::None;
    double cursorX_ = 0, cursorY_ = 0, lastX_ = 0, lastY_ = 0, pressX_ = 0, pressY_ = 0;
    int pressButton_ = -1;
    bool replaying_ = false;
    bool quitting_ = false;
    long lastChange_ = -1;
    // Autosave.
    bool autosave_ = false;
    double autosaveInterval_ = 60;
    std::filesystem::path autosaveDir_;
    std::chrono::steady_clock::time_point lastAutosave_;
    std::string lastAutosaveText_;

public:
    /// Where autosave files go: $FREEFORM_AUTOSAVE_DIR, else $XDG_STATE_HOME/freeform, else
    /// ~/.local/state/freeform, else the temporary folder's freeform-autosave.
    static std::filesystem::path autosaveDirectory();
};

} // namespace freeform::editor
