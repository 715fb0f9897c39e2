#include "app/app.h"

#include <epoxy/gl.h>
// GLFW after the loader, and without its own GL header.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numeric>

#include "freeform/core/error.h"

namespace freeform::editor {

namespace fs = std::filesystem;

namespace {

std::string& glfwErrorText()
{
    static std::string text;
    return text;
}

void onGlfwError(int code, const char* description)
{
    glfwErrorText() = std::string(description ? description : "unknown") + " (GLFW error " + std::to_string(code) + ")";
}

App* appOf(GLFWwindow* window)
{
    return static_cast<App*>(glfwGetWindowUserPointer(window));
}

fs::path recentFilePath()
{
    const char* config = std::getenv("XDG_CONFIG_HOME");
    const char* home = std::getenv("HOME");
    if (config && *config) return fs::path(config) / "freeform" / "recent-files.txt";
    if (home && *home) return fs::path(home) / ".config" / "freeform" / "recent-files.txt";
    return {};
}

double millisecondsSince(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

} // namespace

App::App(Scene scene, const Options& options) : options_(options), scene_(std::move(scene))
{
    glfwSetErrorCallback(onGlfwError);
    if (!glfwInit())
        throw Error("cannot open a window: " + (glfwErrorText().empty() ? std::string("no display") : glfwErrorText()));
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, options_.headless() ? GLFW_FALSE : GLFW_TRUE);
    const std::string title = "freeform editor";
    window_ = glfwCreateWindow(options_.width, options_.height, title.c_str(), nullptr, nullptr);
    if (!window_) {
        glfwTerminate();
        throw Error("cannot create an OpenGL 3.3 core window: " + glfwErrorText());
    }
    glfwMakeContextCurrent(window_);
    if (epoxy_gl_version() < 33) {
        glfwDestroyWindow(window_);
        glfwTerminate();
        throw Error("OpenGL 3.3 is needed, the driver offers " + std::to_string(epoxy_gl_version() / 10) + "." +
                    std::to_string(epoxy_gl_version() % 10));
    }
    glfwSwapInterval(1);
    glfwSetWindowUserPointer(window_, this);
    // Our callbacks first: the ImGui backend chains to them.
    glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int b, int a, int m) { appOf(w)->onMouseButton(b, a, m); });
    glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) { appOf(w)->onCursor(x, y); });
    glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double dy) { appOf(w)->onScroll(dy); });
    glfwSetKeyCallback(window_, [](GLFWwindow* w, int k, int, int a, int m) { appOf(w)->onKey(k, a, m); });
    glfwSetDropCallback(window_, [](GLFWwindow* w, int n, const char** p) { appOf(w)->onDrop(n, p); });
    glfwSetWindowCloseCallback(window_, [](GLFWwindow* w) { appOf(w)->onClose(); });

    renderer_ = createGlRenderer();
    drawer_ = std::make_unique<SceneDrawer>(*renderer_);

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr; // panel layout is not saved between runs
    ImGui::StyleColorsDark();
    ImGui::GetStyle().WindowRounding = 4.0f;
    ImGui_ImplGlfw_InitForOpenGL(window_, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");
    imgui_ = true;
    if (!options_.headless()) loadRecent();
    if (!scene_.path().empty() && !options_.headless()) addRecent(scene_.path());
}

App::~App()
{
    if (imgui_) {
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
    drawer_.reset();
    renderer_.reset();
    if (window_) glfwDestroyWindow(window_);
    glfwTerminate();
}

double App::aspect() const
{
    int w = 1, h = 1;
    glfwGetFramebufferSize(window_, &w, &h);
    return double(std::max(w, 1)) / double(std::max(h, 1));
}

void App::buildUi()
{
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    if (options_.headless()) {
        ImGuiIO& io = ImGui::GetIO();
        io.DisplaySize = ImVec2(float(options_.width), float(options_.height));
        io.DisplayFramebufferScale = ImVec2(1, 1);
    }
    ImGui::NewFrame();
    if (drawUi(scene_, ui_, *this)) carryOutPending();
    ImGui::Render();
}

void App::frame(int width, int height, bool withUi)
{
    const auto t0 = std::chrono::steady_clock::now();
    if (withUi) buildUi();
    ui_.triangles = drawer_->draw(scene_, width, height, ui_.selected);
    if (withUi) {
        renderer_->bindOverlayTarget();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    }
    ui_.frameMs = millisecondsSince(t0);
}

int App::run()
{
    while (!quitting_) {
        glfwPollEvents();
        if (glfwWindowShouldClose(window_)) break;
        int w = 1, h = 1;
        glfwGetFramebufferSize(window_, &w, &h);
        if (w == 0 || h == 0) { // minimised
            glfwWaitEvents();
            continue;
        }
        frame(w, h, true);
        renderer_->presentToWindow(w, h);
        glfwSwapBuffers(window_);
    }
    return 0;
}

Image App::renderImage()
{
    // The panels settle their layout over the first frames (auto-sized windows appear on the second).
    const int frames = options_.noUi ? 1 : 3;
    for (int i = 0; i < frames; ++i) frame(options_.width, options_.height, !options_.noUi);
    return renderer_->readPixels();
}

void App::printFrameStats(int frames)
{
    auto t0 = std::chrono::steady_clock::now();
    scene_.updateGeometry();
    const double tessellation = millisecondsSince(t0);
    long vertices = 0;
    for (int i = 0; i < scene_.itemCount(); ++i)
        if (scene_.item(i).geometry.surface) vertices += scene_.item(i).geometry.surface->vertexCount();
    t0 = std::chrono::steady_clock::now();
    frame(options_.width, options_.height, false);
    renderer_->finish();
    const double first = millisecondsSince(t0);
    std::vector<double> times;
    for (int i = 0; i < frames; ++i) {
        t0 = std::chrono::steady_clock::now();
        frame(options_.width, options_.height, false);
        renderer_->finish();
        times.push_back(millisecondsSince(t0));
    }
    std::vector<double> sorted = times;
    std::sort(sorted.begin(), sorted.end());
    const double median = sorted.size() % 2 ? sorted[sorted.size() / 2]
                                            : 0.5 * (sorted[sorted.size() / 2 - 1] + sorted[sorted.size() / 2]);
    const double mean = std::accumulate(times.begin(), times.end(), 0.0) / double(times.size());
    std::printf("renderer: %s\n", reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
    std::printf("size: %dx%d, samples: %d, shading: %s\n", options_.width, options_.height, scene_.display.samples,
                scene_.display.shading == Shading::Flat ? "flat" : scene_.display.shading == Shading::Gouraud ? "gouraud" : "phong");
    std::printf("triangles: %ld\nvertices: %ld\n", ui_.triangles, vertices);
    std::printf("tessellation_ms: %.3f\nfirst_frame_ms: %.3f\n", tessellation, first);
    std::printf("frames: %d\nframe_ms_median: %.3f\nframe_ms_mean: %.3f\nframe_ms_min: %.3f\nframe_ms_max: %.3f\n", frames,
                median, mean, sorted.front(), sorted.back());
}

// ------------------------------------------------------------------------------------ actions

void App::replaceScene(Scene scene)
{
    drawer_->clear();
    scene_ = std::move(scene);
    ui_.selected = -1;
}

void App::newDocument()
{
    if (scene_.modified()) {
        ui_.pending = PendingAction::New;
        return;
    }
    replaceScene(Scene());
}

void App::open(const std::string& path)
{
    if (scene_.modified()) {
        ui_.pending = PendingAction::Open;
        ui_.pendingPath = path;
        return;
    }
    try {
        replaceScene(Scene::load(path, aspect()));
        addRecent(path);
    } catch (const Error& e) {
        ui_.error = e.what();
    }
}

void App::carryOutPending()
{
    const PendingAction action = ui_.pending;
    ui_.pending = PendingAction::None;
    if (action == PendingAction::New) {
        replaceScene(Scene());
    } else if (action == PendingAction::Open) {
        try {
            replaceScene(Scene::load(ui_.pendingPath, aspect()));
            addRecent(ui_.pendingPath);
        } catch (const Error& e) {
            ui_.error = e.what();
        }
    } else if (action == PendingAction::Quit) {
        quitting_ = true;
    }
}

bool App::save()
{
    if (scene_.path().empty()) {
        ui_.pathDialog = UiState::PathDialog::SaveAs;
        std::snprintf(ui_.pathBuffer, sizeof ui_.pathBuffer, "%s", "scene.json");
        return false;
    }
    return saveAs(scene_.path());
}

bool App::saveAs(const std::string& path)
{
    try {
        scene_.save(path);
        addRecent(path);
        return true;
    } catch (const Error& e) {
        ui_.error = e.what();
        return false;
    }
}

void App::importFile(const std::string& path)
{
    try {
        scene_.importFile(path);
    } catch (const Error& e) {
        ui_.error = e.what();
    }
}

void App::exportMesh(const std::string& path)
{
    try {
        scene_.exportMesh(path);
    } catch (const Error& e) {
        ui_.error = e.what();
    }
}

void App::quit()
{
    if (scene_.modified()) ui_.pending = PendingAction::Quit;
    else quitting_ = true;
}

void App::fit(bool selectionOnly)
{
    scene_.updateGeometry();
    Eigen::AlignedBox3d box = scene_.bounds();
    if (selectionOnly && ui_.selected >= 0 && ui_.selected < scene_.itemCount() &&
        !scene_.item(ui_.selected).geometry.bounds.isEmpty())
        box = scene_.item(ui_.selected).geometry.bounds;
    scene_.camera.fit(box, aspect());
    scene_.touch();
}

void App::setView(const std::string& name)
{
    scene_.camera.setView(name);
    scene_.touch();
}

void App::addRecent(const std::string& path)
{
    std::error_code ec;
    const std::string absolute = fs::absolute(path, ec).lexically_normal().string();
    recent_.erase(std::remove(recent_.begin(), recent_.end(), absolute), recent_.end());
    recent_.insert(recent_.begin(), absolute);
    if (recent_.size() > 10) recent_.resize(10);
    saveRecent();
}

void App::loadRecent()
{
    const fs::path file = recentFilePath();
    if (file.empty()) return;
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);)
        if (!line.empty() && recent_.size() < 10) recent_.push_back(line);
}

void App::saveRecent() const
{
    if (options_.headless()) return;
    const fs::path file = recentFilePath();
    if (file.empty()) return;
    std::error_code ec;
    fs::create_directories(file.parent_path(), ec);
    std::string text;
    for (const std::string& r : recent_) text += r + "\n";
    try {
        writeFileAtomically(file.string(), text);
    } catch (const Error&) {
        // The recent-files list is a convenience: a read-only home directory must not stop the editor.
    }
}

// ------------------------------------------------------------------------------------ input

void App::onMouseButton(int button, int action, int mods)
{
    if (action == GLFW_RELEASE) {
        drag_ = Drag::None;
        return;
    }
    if (ImGui::GetIO().WantCaptureMouse) return;
    glfwGetCursorPos(window_, &lastX_, &lastY_);
    if (button == GLFW_MOUSE_BUTTON_LEFT) drag_ = (mods & GLFW_MOD_SHIFT) ? Drag::Pan : Drag::Orbit;
    else if (button == GLFW_MOUSE_BUTTON_MIDDLE || button == GLFW_MOUSE_BUTTON_RIGHT) drag_ = Drag::Pan;
}

void App::onCursor(double x, double y)
{
    const double dx = x - lastX_, dy = y - lastY_;
    if (drag_ == Drag::None || (dx == 0 && dy == 0)) {
        lastX_ = x;
        lastY_ = y;
        return;
    }
    int w = 1, h = 1;
    glfwGetWindowSize(window_, &w, &h);
    Camera& c = scene_.camera;
    if (drag_ == Drag::Orbit) {
        if (c.orbit == OrbitMode::Turntable) {
            c.orbitTurntable(dx * 0.008, dy * 0.008);
        } else {
            const double s = std::max(std::min(w, h), 1);
            c.orbitArcball({(2 * lastX_ - w) / s, (h - 2 * lastY_) / s}, {(2 * x - w) / s, (h - 2 * y) / s});
        }
    } else {
        c.pan(dx, dy, h);
    }
    scene_.touch();
    lastX_ = x;
    lastY_ = y;
}

void App::onScroll(double dy)
{
    if (ImGui::GetIO().WantCaptureMouse) return;
    int w = 1, h = 1;
    glfwGetWindowSize(window_, &w, &h);
    double x = 0, y = 0;
    glfwGetCursorPos(window_, &x, &y);
    scene_.camera.zoom(std::pow(0.85, dy), {2 * x / std::max(w, 1) - 1, 1 - 2 * y / std::max(h, 1)}, double(w) / std::max(h, 1));
    scene_.touch();
}

void App::onKey(int key, int action, int mods)
{
    if (action == GLFW_RELEASE || ImGui::GetIO().WantCaptureKeyboard) return;
    const bool ctrl = mods & GLFW_MOD_CONTROL, shift = mods & GLFW_MOD_SHIFT;
    DisplaySettings& d = scene_.display;
    auto dialog = [&](UiState::PathDialog which, const std::string& text) {
        ui_.pathDialog = which;
        std::snprintf(ui_.pathBuffer, sizeof ui_.pathBuffer, "%s", text.c_str());
    };
    if (ctrl) {
        if (key == GLFW_KEY_N) newDocument();
        else if (key == GLFW_KEY_O) dialog(UiState::PathDialog::Open, scene_.path());
        else if (key == GLFW_KEY_S && (shift || scene_.path().empty()))
            dialog(UiState::PathDialog::SaveAs, scene_.path().empty() ? "scene.json" : scene_.path());
        else if (key == GLFW_KEY_S) save();
        else if (key == GLFW_KEY_I) dialog(UiState::PathDialog::Import, "");
        else if (key == GLFW_KEY_E) dialog(UiState::PathDialog::Export, "scene.obj");
        else if (key == GLFW_KEY_Q) quit();
        else if (key == GLFW_KEY_1 || key == GLFW_KEY_KP_1) setView("back");
        else if (key == GLFW_KEY_3 || key == GLFW_KEY_KP_3) setView("left");
        else if (key == GLFW_KEY_7 || key == GLFW_KEY_KP_7) setView("bottom");
        return;
    }
    switch (key) {
    case GLFW_KEY_1: case GLFW_KEY_KP_1: setView("front"); break;
    case GLFW_KEY_3: case GLFW_KEY_KP_3: setView("right"); break;
    case GLFW_KEY_7: case GLFW_KEY_KP_7: setView("top"); break;
    case GLFW_KEY_9: case GLFW_KEY_KP_9: setView("iso"); break;
    case GLFW_KEY_5: case GLFW_KEY_KP_5:
        scene_.camera.projection = scene_.camera.projection == Projection::Perspective ? Projection::Orthographic : Projection::Perspective;
        scene_.touch();
        break;
    case GLFW_KEY_HOME: fit(false); break;
    case GLFW_KEY_F: fit(true); break;
    case GLFW_KEY_Z: d.shading = static_cast<Shading>((static_cast<int>(d.shading) + 1) % 3); scene_.touch(); break;
    case GLFW_KEY_W: d.wireframe = !d.wireframe; scene_.touch(); break;
    case GLFW_KEY_R:
        d.analysis = d.analysis == SurfaceAnalysis::ReflectionLines ? SurfaceAnalysis::None : SurfaceAnalysis::ReflectionLines;
        scene_.touch();
        break;
    case GLFW_KEY_F1: ui_.showHelp = !ui_.showHelp; break;
    default: break;
    }
}

void App::onDrop(int count, const char** paths)
{
    for (int i = 0; i < count; ++i) {
        std::string ext = fs::path(paths[i]).extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        if (ext == ".json") open(paths[i]);
        else importFile(paths[i]);
    }
}

void App::onClose()
{
    glfwSetWindowShouldClose(window_, GLFW_FALSE);
    quit();
}

} // namespace freeform::editor
