// The application's window and frame loop (app/app.h): the window, the renderer and ImGui set up
// and torn down, each frame's UI and drawing, the status bar's hint, the --state dump, headless
// frames and screenshots, the frame log and --frames' statistics. The input handlers and --replay
// are in app_input.cpp; the file actions, undo and redo, and the autosave in app_files.cpp.

#include "app/app.h"

#include <epoxy/gl.h>
// GLFW after the loader, and without its own GL header.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cfloat>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <numeric>

#include "freeform/core/error.h"
#include "freeform/io/file.h"

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

double millisecondsSince(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/// CPU time of the whole process (every thread: llvmpipe's rasteriser threads included), in ms.
double processCpuMilliseconds()
{
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

double median(std::vector<double> values)
{
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n == 0 ? 0 : n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
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
    // Then the input callbacks are ours (replacing the backend's, which takeInput calls each frame
    // with the queued events): everything goes through the queue.
    using Type = InputEvent::Type;
    glfwSetKeyCallback(window_, [](GLFWwindow* w, int k, int sc, int a, int m) { appOf(w)->queueInput({Type::Key, k, sc, a, m, 0, 0, 0}); });
    glfwSetCharCallback(window_, [](GLFWwindow* w, unsigned int c) { appOf(w)->queueInput({Type::Char, 0, 0, 0, 0, 0, 0, c}); });
    glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int b, int a, int m) { appOf(w)->queueInput({Type::Button, b, 0, a, m, 0, 0, 0}); });
    glfwSetScrollCallback(window_, [](GLFWwindow* w, double dx, double dy) { appOf(w)->queueInput({Type::Scroll, 0, 0, 0, 0, dx, dy, 0}); });
    glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) { appOf(w)->queueInput({Type::Cursor, 0, 0, 0, 0, x, y, 0}); });
    ImGui_ImplOpenGL3_Init("#version 330 core");
    imgui_ = true;
    replaying_ = !options_.replay.empty();
    if (!options_.frameLog.empty()) {
        frameLog_.open(options_.frameLog, std::ios::trunc);
        if (!frameLog_) throw Error(options_.frameLog + ": cannot open the frame log for writing");
        // input: the handlers of the events since the last frame (picking, the drag's point moves);
        // ui: ImGui's frame; update: tools, geometry and derived items (the deformed meshes);
        // overlay; draw: the scene drawer (uploads included); gui: ImGui's draw calls; end: the
        // present and buffer swap in a window, the wait for the GPU (glFinish) headless; total:
        // all of them; period: from the previous frame's end to this one's; cpu: the process's CPU
        // time (every thread) from the frame's start to its end.
        frameLog_ << "frame\tdragging\tchanged\tinput_ms\tui_ms\tupdate_ms\toverlay_ms\tdraw_ms\tgui_ms\tend_ms\ttotal_ms\tperiod_ms\tcpu_ms\n";
    }
    // Autosave: interactive sessions always, headless ones only when the folder is given.
    autosave_ = !options_.headless() || std::getenv("FREEFORM_AUTOSAVE_DIR") != nullptr;
    if (const char* interval = std::getenv("FREEFORM_AUTOSAVE_INTERVAL")) {
        char* end = nullptr;
        const double v = std::strtod(interval, &end);
        if (end != interval && *end == 0 && v >= 0) autosaveInterval_ = v;
    }
    autosaveDir_ = autosaveDirectory();
    lastAutosave_ = std::chrono::steady_clock::now();
    if (autosave_) offerRecovery();
    // The recent-files list: FREEFORM_CONFIG_DIR/recent.json when that folder is given, else the
    // user's (app/recent_files.h). Headless runs read it only from a folder given so (a test's), and
    // never write it.
    const char* config = std::getenv("FREEFORM_CONFIG_DIR");
    if (config && *config) recent_ = RecentFiles(fs::path(config) / "recent.json");
    if (!options_.headless() || (config && *config)) {
        const std::string message = recent_.load();
        if (!message.empty()) ui_.notice = "recent files ignored: " + message;
    }
    if (!scene_.path().empty()) addRecent(scene_.path());
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

void App::buildUi(const std::function<void()>& afterNewFrame)
{
    ImGui_ImplOpenGL3_NewFrame();
    if (options_.headless()) {
        // A hidden window has no real pointer: the GLFW backend's frame would overwrite the mouse
        // state that --replay feeds in (as the backend's callbacks do), so only the sizes are set.
        ImGuiIO& io = ImGui::GetIO();
        io.DisplaySize = ImVec2(float(options_.width), float(options_.height));
        io.DisplayFramebufferScale = ImVec2(1, 1);
        io.DeltaTime = 1.0f / 60.0f;
    } else {
        takeInput();
        ImGui_ImplGlfw_NewFrame();
        // The backend polls the live pointer and buttons; ImGui must see them as the queue has
        // them, in step with the events it gets this frame (see InputEvent in app.h).
        ImGuiIO& io = ImGui::GetIO();
        if (haveQueuedCursor_ && io.MousePos.x != -FLT_MAX) io.MousePos = ImVec2(float(queuedX_), float(queuedY_));
        for (int b = 0; b < 5; ++b) io.MouseDown[b] = queuedDown_[b];
    }
    ImGui::NewFrame();
    if (afterNewFrame) afterNewFrame();
    if (!options_.headless()) dispatchInput();
    ui_.statusHint = statusHint();
    if (drawUi(scene_, ui_, *this)) carryOutPending();
    const int dialogs = uiSignature();
    if (dialogs != dialogs_) holdInput_ = true;
    dialogs_ = dialogs;
    ImGui::Render();
}

int App::uiSignature() const
{
    // The dialogs up, and whether any ImGui popup (menus included) is open.
    return static_cast<int>(ui_.pathDialog) | (ui_.error.empty() ? 0 : 1 << 4) | (static_cast<int>(ui_.pending) << 5) |
           (ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopup) ? 1 << 10 : 0);
}

std::string App::statusHint()
{
    std::string hint;
    if (tools_.curve().creating()) {
        hint = tools_.curve().creatingSpline()
                   ? "Create C2 spline (Shift+C): click a point the spline passes through; Enter finishes, Backspace removes the last, Escape cancels"
                   : "Create curve (C): click to add a control point; Enter finishes, Backspace removes the last, Escape cancels";
    } else if (tools_.nurbs().creating()) {
        hint = "Create circle (Shift+O) or arc (Shift+U): click the centre, then the radius (arc: then the end); Escape cancels";
    } else if (interaction_.busy()) {
        hint = "Move: the selected points follow the pointer; X/Y/Z constrain, click or Enter confirms, Escape or right click cancels";
    } else if (tools_.spline().dragging()) {
        hint = "Move de Boor point: the spline is rebuilt from its de Boor points and stays C2";
    } else if (ui_.selection.item >= 0 && ui_.selection.item < scene_.itemCount()) {
        const SceneItem& selected = scene_.item(ui_.selection.item);
        hint = "Select (" + selected.name + ", " + selected.type + "): click a point to select it, drag to move it";
        if (selected.is(ObjectKind::BezierSpline)) hint += "; 1-4 set the joint's mode (free, aligned, mirrored, C2)";
        else if (selected.is(ObjectKind::Lattice)) hint += "; D drags the deformed mesh directly";
        else if (selected.is(ObjectKind::Part)) {
            const std::string face = faceSummary(std::get<PartData>(scene_.object(ui_.selection.item).data), ui_.selection.face);
            hint = "Select (" + selected.name + ", part): " + (face.empty() ? "click a face to see it" : face) +
                   "; L fits a lattice to it; File > Export part writes STEP or IGES";
        }
        else if (NurbsTool::handles(selected.info())) {
            hint += "; Alt+drag a point: its weight; K: insert a knot at t";
            if (selected.info()->isCurve()) hint += "; T: de Boor construction; V: curvature comb";
        }
        hint += "; Escape deselects";
    } else {
        hint = "Select: click an object or point; C: curve, Shift+C: C2 spline; drag: orbit, wheel: zoom; F1: help";
    }
    const std::string& message = tools_.message();
    if (!message.empty()) hint += "   |   " + message;
    // The old meshes are drawn while the background job for the view's tolerance runs (never in
    // headless runs, which wait for it).
    if (scene_.tessellationPending()) hint += "   |   tessellating for the view...";
    return hint;
}

namespace {
constexpr Eigen::Index kStatePixelLimit = 4096; // --state: control points listed in "pixels" at most
} // namespace

std::string App::stateText() const
{
    nlohmann::ordered_json j;
    int w = 1, h = 1;
    viewSize(w, h);
    j["window"] = {w, h};
    j["error"] = ui_.error;
    j["path_dialog"] = ui_.pathDialog != UiState::PathDialog::None;
    j["unsaved_dialog"] = ui_.pending != PendingAction::None;
    j["modified"] = scene_.modified();
    j["undo"] = {{"steps", scene_.history().size()}, {"label", scene_.history().undoLabel()}};
    j["popup_open"] = ImGui::GetCurrentContext() != nullptr && ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId | ImGuiPopupFlags_AnyPopupLevel);
    nlohmann::ordered_json panels = nlohmann::ordered_json::object();
    for (const auto& p : ui_.panels) panels[p.name] = {p.x, p.y, p.width, p.height};
    j["panels"] = panels;
    j["camera"] = {{"distance", scene_.camera.distance},
                   {"target", {scene_.camera.target.x(), scene_.camera.target.y(), scene_.camera.target.z()}}};
    j["status"] = ui_.statusHint;
    j["objects"] = scene_.itemCount();
    // The selection, with its control points' places on screen (tests driving the real window
    // click and drag there): null when nothing is selected.
    const Selection& sel = ui_.selection;
    if (sel.item >= 0 && sel.item < scene_.itemCount()) {
        const ViewTransform v = ViewTransform::of(scene_, w, h);
        const Eigen::Matrix3Xd points = scene_.controlPoints(sel.item);
        nlohmann::ordered_json pixels = nullptr; // (not for large meshes: the text is made every frame)
        if (points.cols() <= kStatePixelLimit) pixels = nlohmann::ordered_json::array();
        for (Eigen::Index k = 0; k < points.cols() && points.cols() <= kStatePixelLimit; ++k) {
            if (const auto q = v.toPixel(points.col(k))) pixels.push_back({q->x(), q->y()});
            else pixels.push_back(nullptr);
        }
        j["selection"] = {{"item", scene_.item(sel.item).name}, {"type", scene_.item(sel.item).type}, {"points", sel.points}, {"pixels", pixels}};
    } else {
        j["selection"] = nullptr;
    }
    j["notice"] = ui_.notice;
    j["tooltip"] = ui_.tooltip;
    if (ui_.statsText.empty()) j["stats"] = nullptr;
    else j["stats"] = ui_.statsText;
    nlohmann::ordered_json widgets = nlohmann::ordered_json::object();
    for (const auto& p : ui_.widgets) widgets[p.name] = {p.x, p.y, p.width, p.height};
    j["widgets"] = widgets;
    nlohmann::ordered_json overflows = nlohmann::ordered_json::array();
    for (const Overflow& o : ui_.overflows)
        overflows.push_back({{"panel", o.panel}, {"label", o.label}, {"needed", o.needed}, {"available", o.available}});
    j["overflows"] = overflows;
    if (!audits_.empty()) {
        nlohmann::ordered_json audits = nlohmann::ordered_json::array();
        for (const TooltipAudit& a : audits_) {
            nlohmann::ordered_json items = nlohmann::ordered_json::array(), missing = nlohmann::ordered_json::array();
            for (const TooltipAuditItem& item : a.items) {
                items.push_back({{"window", item.window}, {"path", item.path}, {"x", item.x}, {"y", item.y}, {"scrolled", item.scrolled}, {"hovered", item.hovered},
                                 {"tooltip", item.tooltip}, {"text", item.text}, {"dropdown", item.dropdown}});
                if (!item.tooltip) missing.push_back(item.window + ": " + item.path);
            }
            nlohmann::ordered_json dropdowns = nlohmann::ordered_json::array();
            for (const TooltipAuditDropdown& d : a.dropdowns)
                dropdowns.push_back({{"window", d.window}, {"path", d.path}, {"opened", d.opened}, {"choices", d.choices}});
            audits.push_back(
                {{"points", a.points}, {"step", a.step}, {"windows", a.windows}, {"items", items}, {"missing", missing}, {"dropdowns", dropdowns}});
        }
        j["tooltip_audits"] = audits;
    }
    // The lattice panel's read-out row as drawn in the last frame (null when not drawn).
    if (ui_.latticeReadout.shown) {
        const UiState::LatticeReadout& r = ui_.latticeReadout;
        j["lattice_readout"] = {{"vertices", r.vertices}, {"outside", r.outside}, {"update_ms", r.updateMs}, {"det_j_min", r.minDetJ},
                                {"det_j_max", r.maxDetJ},  {"fold_overs", r.folds},  {"lines", r.lines}};
    } else {
        j["lattice_readout"] = nullptr;
    }
    // Proportional editing (O) and the radius it uses now (+ / - scale it).
    j["proportional"] = {{"on", ui_.edit.soft}, {"radius", interaction_.softRadius(scene_)}};
    // A quit was confirmed (Ctrl+Q or File > Quit without unsaved changes, or the dialog's Save or
    // Discard): the editor stops (a replay handles no later event).
    j["quit"] = quitting_;
    if (ui_.legendRect[2] > 0)
        j["legend"] = {{"rect", {ui_.legendRect[0], ui_.legendRect[1], ui_.legendRect[2], ui_.legendRect[3]}},
                       {"min", ui_.legendMin},
                       {"max", ui_.legendMax}};
    else
        j["legend"] = nullptr;
    return j.dump(1) + "\n";
}

void App::writeState(const std::string& path) const
{
    // The library's atomic writer (io/file.h): a reader never sees half a file, and a run killed
    // while writing leaves nothing behind.
    writeFileAtomically(path, stateText());
}

void App::viewSize(int& width, int& height) const
{
    if (options_.headless()) {
        width = options_.width;
        height = options_.height;
    } else {
        glfwGetWindowSize(window_, &width, &height);
    }
    width = std::max(width, 1);
    height = std::max(height, 1);
}

ViewTransform App::view() const
{
    int w = 1, h = 1;
    viewSize(w, h);
    return ViewTransform::of(scene_, w, h);
}

ToolContext App::toolContext()
{
    int w = 1, h = 1;
    viewSize(w, h);
    ToolContext context{scene_, ui_.selection, w, h, ViewTransform::of(scene_, w, h).viewProjection};
    return context;
}

PointerEvent App::pointerEvent(PointerEvent::Type type, int button, int mods) const
{
    PointerEvent e;
    e.type = type;
    e.button = button;
    e.mods = mods;
    e.x = cursorX_;
    e.y = cursorY_;
    view().ray(cursorX_, cursorY_, e.rayOrigin, e.rayDirection);
    return e;
}

void App::validateSelection()
{
    Selection& s = ui_.selection;
    if (s.item >= scene_.itemCount()) s.clear();
    if (s.hoverItem >= scene_.itemCount()) s.hoverItem = s.hoverPoint = -1;
    if (s.item >= 0 && !s.points.empty()) {
        const int n = scene_.controlPointCount(s.item);
        if (s.points.back() >= n) s.points.erase(std::lower_bound(s.points.begin(), s.points.end(), n), s.points.end());
    }
}

std::string App::takeWarnings()
{
    std::vector<std::string> taken;
    {
        std::lock_guard lock(warningsMutex_);
        taken.swap(warnings_);
    }
    std::string text;
    for (const std::string& w : taken) text += (text.empty() ? "warning: " : "; warning: ") + w;
    return text;
}

void App::frame(int width, int height, bool withUi, bool stillImage)
{
    const auto t0 = std::chrono::steady_clock::now();
    const double cpu0 = frameLog_.is_open() ? processCpuMilliseconds() : 0;
    const double inputBefore = inputMs_;
    if (std::string warnings = takeWarnings(); !warnings.empty()) ui_.notice = std::move(warnings);
    if (withUi) buildUi();
    const double inputInUi = inputMs_ - inputBefore; // a window's events are handled inside buildUi
    validateSelection();
    // The tools' follow-up (joint modes), then the geometry of what changed and the derived items
    // (the meshes lattices deform): the "update" time.
    const auto t1 = std::chrono::steady_clock::now();
    bool dirty = scene_.changeCount() != lastChange_;
    for (int i = 0; i < scene_.itemCount() && !dirty; ++i) dirty = scene_.item(i).geometryDirty;
    overlay_.clear();
    ToolContext context = toolContext();
    tools_.update(context, overlay_);
    if (const int fitted = tools_.lattice().takeFitted(); fitted >= 0) frameIfOutside(fitted);
    // A zoom that changes the pixel size by 2x re-tessellates in the background (the scene keeps
    // drawing the old meshes and swaps the new ones in when they are ready; edits are rebuilt at
    // once). Headless runs (--screenshot, --frames, --replay, --save) wait for it every frame, so
    // what they draw and pick is deterministic: the synchronous result.
    scene_.setBackgroundTessellation(true); // (idempotent; also for a scene opened since)
    scene_.updateViewTolerance(height);
    scene_.updateGeometry();
    if (options_.headless()) scene_.finishTessellation();
    if (dirty) ui_.updateMs = millisecondsSince(t1);
    const auto t2 = std::chrono::steady_clock::now();
    lastChange_ = scene_.changeCount();
    validateSelection();
    interaction_.fillOverlay(scene_, ui_.selection, view(), overlay_);
    const auto t3 = std::chrono::steady_clock::now();
    ui_.triangles = drawer_->draw(scene_, width, height, ui_.selection.item, &overlay_, stillImage);
    const auto t4 = std::chrono::steady_clock::now();
    if (withUi) {
        renderer_->bindOverlayTarget();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    }
    ui_.frameMs = millisecondsSince(t0);
    if (frameLog_.is_open()) {
        const auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
        const auto t5 = std::chrono::steady_clock::now();
        loggedFrame_ = {interaction_.busy(), dirty, inputMs_, ms(t0, t1) - inputInUi, ms(t1, t2), ms(t2, t3), ms(t3, t4), ms(t4, t5), cpu0};
        inputMs_ = 0;
        // Headless, the frame ends here: the wait for the GPU stands for a window's present.
        if (options_.headless()) {
            renderer_->finish();
            logFrame(millisecondsSince(t5));
        }
    }
}

void App::logFrame(double endMs)
{
    const auto now = std::chrono::steady_clock::now();
    const double period = loggedFrames_ == 0 ? 0 : std::chrono::duration<double, std::milli>(now - lastLogged_).count();
    lastLogged_ = now;
    const LoggedFrame& f = loggedFrame_;
    char line[256];
    std::snprintf(line, sizeof line, "%ld\t%d\t%d\t%.3f\t%.3f\t%.3f\t%.3f\t%.3f\t%.3f\t%.3f\t%.3f\t%.3f\t%.3f\n", loggedFrames_++,
                  f.dragging ? 1 : 0, f.changed ? 1 : 0, f.input, f.ui, f.update, f.overlay, f.draw, f.gui, endMs,
                  f.input + f.ui + f.update + f.overlay + f.draw + f.gui + endMs, period, processCpuMilliseconds() - f.cpuStart);
    frameLog_ << line << std::flush;
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
        const auto presented = std::chrono::steady_clock::now();
        renderer_->presentToWindow(w, h);
        glfwSwapBuffers(window_);
        if (frameLog_.is_open()) logFrame(millisecondsSince(presented));
        maybeAutosave();
        // --state in a window: the state file follows every change (tests driving the window read it).
        if (!options_.state.empty()) {
            std::string text = stateText();
            if (text != lastState_) {
                lastState_ = std::move(text);
                try {
                    writeState(options_.state);
                } catch (const Error& e) {
                    std::cerr << "error: " << e.what() << "\n";
                }
            }
        }
    }
    if (quitting_) removeAutosave(); // a confirmed quit: nothing unsaved is wanted any more
    return 0;
}

Image App::renderImage()
{
    // The panels settle their layout over the first frames (auto-sized windows appear on the second).
    const int frames = options_.noUi ? 1 : 3;
    for (int i = 0; i < frames; ++i) frame(options_.width, options_.height, !options_.noUi, true);
    return renderer_->readPixels();
}

void App::printFrameStats(int frames)
{
    auto t0 = std::chrono::steady_clock::now();
    scene_.setBackgroundTessellation(true);
    scene_.updateViewTolerance(options_.height);
    scene_.finishTessellation();
    const double tessellation = millisecondsSince(t0);
    long vertices = 0;
    for (int i = 0; i < scene_.itemCount(); ++i)
        if (scene_.item(i).geometry.surface) vertices += scene_.item(i).geometry.surface->vertexCount();
    t0 = std::chrono::steady_clock::now();
    frame(options_.width, options_.height, false);
    renderer_->finish();
    const double first = millisecondsSince(t0);
    std::vector<double> times, cpu;
    for (int i = 0; i < frames; ++i) {
        t0 = std::chrono::steady_clock::now();
        const double c0 = processCpuMilliseconds();
        frame(options_.width, options_.height, false);
        renderer_->finish();
        times.push_back(millisecondsSince(t0));
        cpu.push_back(processCpuMilliseconds() - c0);
    }
    std::vector<double> sorted = times;
    std::sort(sorted.begin(), sorted.end());
    const double mean = std::accumulate(times.begin(), times.end(), 0.0) / double(times.size());
    std::printf("renderer: %s\n", reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
    // samples: the multisample count the frames used (docs/editor.md, "Anti-aliasing").
    std::printf("antialiasing: %s\n", scene_.display.antialiasing == Antialiasing::Auto ? "auto" : "always");
    std::printf("size: %dx%d, samples: %d, shading: %s\n", options_.width, options_.height, drawer_->samples(),
                scene_.display.shading == Shading::Flat ? "flat" : scene_.display.shading == Shading::Gouraud ? "gouraud" : "phong");
    std::printf("triangles: %ld\nvertices: %ld\n", ui_.triangles, vertices);
    std::printf("tessellation_ms: %.3f\nfirst_frame_ms: %.3f\n", tessellation, first);
    std::printf("frames: %d\nframe_ms_median: %.3f\nframe_ms_mean: %.3f\nframe_ms_min: %.3f\nframe_ms_max: %.3f\n", frames,
                median(times), mean, sorted.front(), sorted.back());
    // CPU time of all the process's threads per frame: less sensitive to other processes on a
    // shared machine than the wall-clock time (docs/performance.md, "Editor frame time").
    std::printf("frame_cpu_ms_median: %.3f\n", median(cpu));
}


} // namespace freeform::editor
