#pragma once
// The application: a GLFW window with an OpenGL 3.3 core context, the renderer, the scene and the
// panels. The frame loop follows Dear ImGui's order (poll events, new frames, build the UI, draw
// the scene, draw the UI, swap); io.WantCaptureMouse/WantCaptureKeyboard decide whether input
// goes to the panels or to the camera. Headless runs (--screenshot, --frames) use a hidden window
// and the same drawing path, reading the pixels back instead of showing them.

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "app/options.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "scene/scene_drawer.h"
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

    // UiActions
    void newDocument() override;
    void open(const std::string& path) override;
    bool save() override;
    bool saveAs(const std::string& path) override;
    void importFile(const std::string& path) override;
    void exportMesh(const std::string& path) override;
    void quit() override;
    void fit(bool selectionOnly) override;
    void setView(const std::string& name) override;
    const std::vector<std::string>& recentFiles() const override { return recent_; }

    // Input (GLFW callbacks forward here).
    void onMouseButton(int button, int action, int mods);
    void onCursor(double x, double y);
    void onScroll(double dy);
    void onKey(int key, int action, int mods);
    void onDrop(int count, const char** paths);
    void onClose();

private:
    void frame(int width, int height, bool withUi);
    void buildUi();
    void carryOutPending();
    void replaceScene(Scene scene);
    void addRecent(const std::string& path);
    void loadRecent();
    void saveRecent() const;
    double aspect() const;

    Options options_;
    Scene scene_;
    UiState ui_;
    GLFWwindow* window_ = nullptr;
    std::unique_ptr<Renderer> renderer_;
    std::unique_ptr<SceneDrawer> drawer_;
    bool imgui_ = false;
    std::vector<std::string> recent_;
    // Mouse drag state.
    enum class Drag { None, Orbit, Pan } drag_ = Drag::None;
    double lastX_ = 0, lastY_ = 0;
    bool quitting_ = false;
};

} // namespace freeform::editor
