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
#include <fstream>
#include <iostream>
#include <numeric>

#include <sys/wait.h>
#include <unistd.h>

#include "freeform/core/error.h"
#include "freeform/io/file.h"
#include "ui/tool_panels.h"

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

const char* kAutosaveFile = "autosave.json";
const char* kAutosavePathFile = "autosave-path.txt";

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

void App::takeInput()
{
    // In order, until a key or button would change a second time in this frame: the rest waits.
    // A button press or a scroll waits until it is the first event of a frame that follows a frame
    // without key, character or button events, and a pointer move after it waits for the next
    // frame, so that ImGui judges it at its place, against windows that are up to date (app.h).
    if (holdInput_) { // ImGui's windows changed in the previous frame: one frame for them to settle
        holdInput_ = false;
        lastFrameTookKeys_ = false;
        return;
    }
    std::vector<std::pair<InputEvent::Type, int>> changed;
    std::size_t taken = 0;
    bool tookKeys = false, tookPress = false;
    for (; taken < input_.size(); ++taken) {
        const InputEvent& e = input_[taken];
        const bool press = (e.type == InputEvent::Type::Button && e.action == GLFW_PRESS) || e.type == InputEvent::Type::Scroll;
        if (press && (taken > 0 || lastFrameTookKeys_)) break;
        if (e.type == InputEvent::Type::Cursor && tookPress) break;
        if (e.type == InputEvent::Type::Key || e.type == InputEvent::Type::Button) {
            const std::pair<InputEvent::Type, int> id{e.type, e.code};
            if (std::find(changed.begin(), changed.end(), id) != changed.end()) break;
            changed.push_back(id);
        }
        tookPress = tookPress || press;
        tookKeys = tookKeys || e.type == InputEvent::Type::Key || e.type == InputEvent::Type::Char || e.type == InputEvent::Type::Button;
        if (e.type == InputEvent::Type::Cursor) {
            haveQueuedCursor_ = true;
            queuedX_ = e.x;
            queuedY_ = e.y;
        }
        if (e.type == InputEvent::Type::Button && e.code >= 0 && e.code < 5) queuedDown_[e.code] = e.action == GLFW_PRESS;
        switch (e.type) {
        case InputEvent::Type::Key: ImGui_ImplGlfw_KeyCallback(window_, e.code, e.scancode, e.action, e.mods); break;
        case InputEvent::Type::Char: ImGui_ImplGlfw_CharCallback(window_, e.ch); break;
        case InputEvent::Type::Button: ImGui_ImplGlfw_MouseButtonCallback(window_, e.code, e.action, e.mods); break;
        case InputEvent::Type::Scroll: ImGui_ImplGlfw_ScrollCallback(window_, e.x, e.y); break;
        case InputEvent::Type::Cursor: break; // the backend reads the pointer itself
        }
        frameInput_.push_back(e);
    }
    input_.erase(input_.begin(), input_.begin() + static_cast<std::ptrdiff_t>(taken));
    lastFrameTookKeys_ = tookKeys;
}

void App::dispatchInput()
{
    timedInput([this] { dispatchEvents(); });
}

void App::dispatchEvents()
{
    for (const InputEvent& e : frameInput_) {
        switch (e.type) {
        case InputEvent::Type::Key: onKey(e.code, e.action, e.mods); break;
        case InputEvent::Type::Char: break;
        case InputEvent::Type::Button: onMouseButton(e.code, e.action, e.mods); break;
        case InputEvent::Type::Scroll: onScroll(e.y); break;
        case InputEvent::Type::Cursor: onCursor(e.x, e.y); break;
        }
    }
    frameInput_.clear();
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
        else if (NurbsTool::handles(selected.info())) hint += "; Alt+drag a point: its weight; K: insert a knot at t; T: de Boor construction";
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

std::optional<std::string> App::chooseFile(bool save, const std::string& title, const std::string& initial)
{
    // zenity (a Debian package) where there is a desktop display; never in headless runs, nor
    // when FREEFORM_NO_ZENITY=1 (tests driving the window); the typed path otherwise.
    if (options_.headless()) return std::nullopt;
    if (const char* no = std::getenv("FREEFORM_NO_ZENITY"); no && std::string(no) == "1") return std::nullopt;
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    if ((!display || !*display) && (!wayland || !*wayland)) return std::nullopt;
    static const bool haveZenity = std::system("command -v zenity >/dev/null 2>&1") == 0;
    if (!haveZenity) return std::nullopt;
    auto quoted = [](const std::string& text) {
        std::string q = "'";
        for (char c : text) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
        return q + "'";
    };
    std::string command = "zenity --file-selection --title=" + quoted("freeform editor: " + title);
    if (save) command += " --save --confirm-overwrite";
    if (!initial.empty()) command += " --filename=" + quoted(initial);
    command += " 2>/dev/null";
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return std::nullopt;
    std::string out;
    char buffer[512];
    while (std::fgets(buffer, sizeof buffer, pipe)) out += buffer;
    const int status = pclose(pipe);
    while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
    if (status == -1 || !WIFEXITED(status)) return std::nullopt;
    if (WEXITSTATUS(status) == 1) return std::string(); // cancelled
    if (WEXITSTATUS(status) != 0 || out.empty()) return std::nullopt; // zenity failed: type the path
    return out;
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

// ------------------------------------------------------------------------------------ actions

void App::replaceScene(Scene scene, bool keepAutosave)
{
    interaction_.finish(scene_);
    drawer_->clear();
    scene_ = std::move(scene);
    ui_.selection = Selection{};
    tools_.reset();
    pendingScene_.reset();
    lastChange_ = -1;
    if (!keepAutosave) removeAutosave();
}

void App::newDocument()
{
    if (scene_.modified()) {
        ui_.pending = PendingAction::New;
        return;
    }
    replaceScene(Scene());
    ui_.notice = "new document";
}

void App::open(const std::string& path)
{
    // Read it first: a file that cannot be read shows its error and never asks about (or touches)
    // the open document.
    try {
        Scene next = Scene::load(path, aspect());
        if (scene_.modified()) {
            pendingScene_ = std::move(next);
            ui_.pending = PendingAction::Open;
            ui_.pendingPath = path;
            return;
        }
        replaceScene(std::move(next));
        ui_.notice = "opened " + path;
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
        ui_.notice = "new document";
    } else if (action == PendingAction::Open && pendingScene_) {
        Scene next = std::move(*pendingScene_);
        replaceScene(std::move(next));
        ui_.notice = "opened " + ui_.pendingPath;
        addRecent(ui_.pendingPath);
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
        ui_.notice = "saved " + path;
        addRecent(path);
        removeAutosave();
        return true;
    } catch (const Error& e) {
        ui_.error = e.what();
        return false;
    }
}

void App::importFile(const std::string& path)
{
    try {
        const std::optional<UpAxis> format = formatUpAxis(path);
        const UpAxis up = format.value_or(ui_.importUp);
        scene_.importFile(path, up);
        fit(false); // the camera takes in the scene with the imported object
        if (scene_.itemCount() > 0 && scene_.item(scene_.itemCount() - 1).kind == SceneItem::Kind::ImportedMesh)
            ui_.notice = std::string("imported ") + fs::path(path).filename().string() + " as " + (up == UpAxis::Y ? "Y" : "Z") +
                         " up (" + (format ? "the glTF convention" : "the Import dialog's choice") +
                         "); Properties > up axis changes it";
        if (const std::string warnings = takeWarnings(); !warnings.empty())
            ui_.notice += (ui_.notice.empty() ? "" : "; ") + warnings;
    } catch (const Error& e) {
        ui_.error = e.what();
    }
}

void App::exportMesh(const std::string& path)
{
    try {
        scene_.exportMesh(path);
        ui_.notice = "exported the tessellation to " + path;
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
    const Selection& sel = ui_.selection;
    if (selectionOnly && sel.item >= 0 && sel.item < scene_.itemCount()) {
        const Eigen::Matrix3Xd points = scene_.controlPoints(sel.item);
        Eigen::AlignedBox3d selected;
        selected.setEmpty();
        for (int k : sel.points)
            if (k < points.cols()) selected.extend(Eigen::Vector3d(points.col(k)));
        if (!selected.isEmpty() && selected.diagonal().norm() > 0) box = selected;
        else if (!selected.isEmpty()) box = Eigen::AlignedBox3d(selected.min() - Eigen::Vector3d::Constant(0.5), selected.max() + Eigen::Vector3d::Constant(0.5));
        else if (!scene_.item(sel.item).geometry.bounds.isEmpty()) box = scene_.item(sel.item).geometry.bounds;
    }
    scene_.camera.fit(box, aspect());
    scene_.touch();
}

void App::frameIfOutside(int item)
{
    // A lattice fitted around a mesh is larger than the mesh (its margin); when a control point
    // lies outside the view, the view frames the scene and the item's points (same direction).
    if (item < 0 || item >= scene_.itemCount()) return;
    scene_.updateGeometry();
    int w = 1, h = 1;
    viewSize(w, h);
    const Eigen::Matrix4d viewProjection = ViewTransform::of(scene_, w, h).viewProjection;
    const Eigen::Matrix3Xd points = scene_.controlPoints(item);
    bool outside = false;
    Eigen::AlignedBox3d box = scene_.bounds();
    for (Eigen::Index k = 0; k < points.cols(); ++k) {
        const Eigen::Vector4d clip = viewProjection * points.col(k).homogeneous();
        outside = outside || !(clip.w() > 0) || std::abs(clip.x()) > clip.w() || std::abs(clip.y()) > clip.w();
        box.extend(Eigen::Vector3d(points.col(k)));
    }
    if (!outside) return;
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
    if (options_.headless()) return; // tests and scripts leave the user's list alone
    const std::string message = recent_.add(path);
    if (!message.empty()) ui_.notice = "recent files not saved: " + message; // a convenience: never an error dialog
}

// ------------------------------------------------------------------------------------ undo, tools

void App::undo()
{
    interaction_.finish(scene_); // Ctrl+Z during a drag: keep it as a step, then take it back
    const std::string label = scene_.history().undoLabel();
    ui_.notice = scene_.undo() ? "undone: " + label : "nothing to undo";
    validateSelection();
}

void App::redo()
{
    interaction_.finish(scene_);
    const std::string label = scene_.history().redoLabel();
    ui_.notice = scene_.redo() ? "redone: " + label : "nothing to redo";
    validateSelection();
}

void App::toolPanels()
{
    ToolContext context = toolContext();
    drawToolPanels(context, tools_);
}

// ------------------------------------------------------------------------------------ autosave

std::filesystem::path App::autosaveDirectory()
{
    if (const char* dir = std::getenv("FREEFORM_AUTOSAVE_DIR"); dir && *dir) return fs::path(dir);
    if (const char* state = std::getenv("XDG_STATE_HOME"); state && *state) return fs::path(state) / "freeform";
    if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".local" / "state" / "freeform";
    std::error_code ec;
    std::string name = "freeform-autosave-";
    name += std::to_string(::getuid());
    return fs::temp_directory_path(ec) / name;
}

void App::maybeAutosave()
{
    if (!autosave_ || !scene_.modified()) return;
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - lastAutosave_).count() < autosaveInterval_) return;
    lastAutosave_ = now;
    std::string text = formatDocument(scene_.toDocument(Scene::MeshPaths::Absolute)); // it lives elsewhere
    if (text == lastAutosaveText_) return;
    try {
        std::error_code ec;
        fs::create_directories(autosaveDir_, ec);
        writeFileAtomically((autosaveDir_ / kAutosaveFile).string(), text);
        writeFileAtomically((autosaveDir_ / kAutosavePathFile).string(), scene_.path() + "\n");
        lastAutosaveText_ = std::move(text);
    } catch (const Error&) {
        // An unwritable state folder must not interrupt the work; the next interval tries again.
    }
}

void App::removeAutosave()
{
    if (!autosave_) return;
    std::error_code ec;
    fs::remove(autosaveDir_ / kAutosaveFile, ec);
    fs::remove(autosaveDir_ / kAutosavePathFile, ec);
    lastAutosaveText_.clear();
}

void App::offerRecovery()
{
    std::error_code ec;
    if (!fs::exists(autosaveDir_ / kAutosaveFile, ec)) return;
    std::string original;
    std::ifstream in(autosaveDir_ / kAutosavePathFile);
    std::getline(in, original);
    std::string text = "The editor closed with unsaved changes to ";
    text += original.empty() ? std::string("an untitled document") : original;
    text += ". They were autosaved to ";
    text += (autosaveDir_ / kAutosaveFile).string();
    text += ".\nRecover them (they open as unsaved changes) or discard them?";
    ui_.recovery = text;
}

void App::recover(bool accept)
{
    const fs::path file = autosaveDir_ / kAutosaveFile;
    if (!accept) {
        removeAutosave();
        return;
    }
    std::string original;
    std::ifstream in(autosaveDir_ / kAutosavePathFile);
    std::getline(in, original);
    try {
        replaceScene(Scene::recover(file.string(), original, aspect()), true);
    } catch (const Error& e) {
        ui_.error = e.what();
    }
}

// ------------------------------------------------------------------------------------ input

void App::startAction()
{
    ui_.notice.clear();
    tools_.message().clear();
}

void App::onMouseButton(int button, int action, int mods)
{
    if (action == GLFW_PRESS) startAction(); // on a panel too: a click there starts an action as well
    if (action == GLFW_RELEASE) {
        if (button != pressButton_) return;
        if (drag_ == Drag::Pending) {
            interaction_.click(scene_, ui_.selection, view(), mods, cursorX_, cursorY_);
        } else if (drag_ == Drag::Interact) {
            interaction_.release(scene_, ui_.selection, view(), button, mods, cursorX_, cursorY_);
        } else if (drag_ == Drag::Tool) {
            ToolContext context = toolContext();
            tools_.onPointer(context, pointerEvent(PointerEvent::Type::Release, button, mods));
        }
        drag_ = Drag::None;
        pressButton_ = -1;
        return;
    }
    if (ImGui::GetIO().WantCaptureMouse || drag_ != Drag::None) return;
    lastX_ = pressX_ = cursorX_;
    lastY_ = pressY_ = cursorY_;
    pressButton_ = button;
    // A grab (G) in progress takes the click (confirm or cancel).
    if (interaction_.busy()) {
        interaction_.press(scene_, ui_.selection, view(), button, mods, cursorX_, cursorY_);
        drag_ = Drag::Interact;
        return;
    }
    ToolContext context = toolContext();
    if (tools_.onPointer(context, pointerEvent(PointerEvent::Type::Press, button, mods))) {
        drag_ = Drag::Tool;
        return;
    }
    if (interaction_.press(scene_, ui_.selection, view(), button, mods, cursorX_, cursorY_)) {
        drag_ = Drag::Interact;
        return;
    }
    if (button == GLFW_MOUSE_BUTTON_LEFT) drag_ = (mods & GLFW_MOD_SHIFT) ? Drag::Pan : Drag::Pending;
    else if (button == GLFW_MOUSE_BUTTON_MIDDLE || button == GLFW_MOUSE_BUTTON_RIGHT) drag_ = Drag::Pan;
}

void App::onCursor(double x, double y)
{
    cursorX_ = x;
    cursorY_ = y;
    if (drag_ == Drag::Interact) {
        interaction_.move(scene_, ui_.selection, view(), x, y);
        return;
    }
    if (drag_ == Drag::Tool) {
        ToolContext context = toolContext();
        tools_.onPointer(context, pointerEvent(PointerEvent::Type::Move, pressButton_, 0));
        return;
    }
    if (drag_ == Drag::None) {
        // Hover (and a running grab, which follows the pointer without a button).
        ToolContext context = toolContext();
        if (interaction_.busy() || !tools_.onPointer(context, pointerEvent(PointerEvent::Type::Move, -1, 0)))
            interaction_.move(scene_, ui_.selection, view(), x, y);
        lastX_ = x;
        lastY_ = y;
        return;
    }
    if (drag_ == Drag::Pending) {
        if (std::hypot(x - pressX_, y - pressY_) < 3) return; // still a click
        drag_ = Drag::Orbit;
    }
    const double dx = x - lastX_, dy = y - lastY_;
    if (dx == 0 && dy == 0) return;
    int w = 1, h = 1;
    viewSize(w, h);
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
    viewSize(w, h);
    scene_.camera.zoom(std::pow(0.85, dy), {2 * cursorX_ / w - 1, 1 - 2 * cursorY_ / h}, double(w) / h);
    scene_.touch();
}

void App::onKey(int key, int action, int mods)
{
    const bool modifier = key == GLFW_KEY_LEFT_SHIFT || key == GLFW_KEY_RIGHT_SHIFT || key == GLFW_KEY_LEFT_CONTROL ||
                          key == GLFW_KEY_RIGHT_CONTROL || key == GLFW_KEY_LEFT_ALT || key == GLFW_KEY_RIGHT_ALT ||
                          key == GLFW_KEY_LEFT_SUPER || key == GLFW_KEY_RIGHT_SUPER;
    if (action == GLFW_PRESS && !modifier) startAction(); // typing in a field too: Enter there is the action
    if (action == GLFW_RELEASE || ImGui::GetIO().WantCaptureKeyboard) return;
    // Escape while a menu is open closes the menu (ui/ui_menu_dialogs.cpp, endMenu) and does nothing else.
    if (key == GLFW_KEY_ESCAPE && ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId | ImGuiPopupFlags_AnyPopupLevel)) return;
    // The keymap's contexts in dispatch order (interaction/keymap.h, docs/editor.md): undo and redo
    // always; during a drag or grab its keys and nothing else; files; the tools; editing; views.
    if (const KeyBinding* b = findBinding(KeyContext::History, key, mods)) {
        if (b->action == KeyAction::Undo) undo();
        else redo();
        return;
    }
    if (mods & GLFW_MOD_CONTROL) {
        if (interaction_.busy()) return; // files and views wait until the drag ends
        if (const KeyBinding* b = findBinding(KeyContext::Files, key, mods)) perform(b->action);
        return;
    }
    if (interaction_.busy()) {
        interaction_.key(scene_, ui_.selection, view(), key, mods, cursorX_, cursorY_);
        return;
    }
    ToolContext context = toolContext();
    if (tools_.onKey(context, key, mods)) return;
    if (interaction_.key(scene_, ui_.selection, view(), key, mods, cursorX_, cursorY_)) return;
    if (const KeyBinding* b = findBinding(KeyContext::View, key, mods)) perform(b->action);
}

void App::perform(KeyAction action)
{
    DisplaySettings& d = scene_.display;
    auto dialog = [&](UiState::PathDialog which, const std::string& text) { askPath(ui_, *this, which, text); };
    switch (action) {
    // Files
    case KeyAction::NewDocument: newDocument(); break;
    case KeyAction::OpenDocument: dialog(UiState::PathDialog::Open, scene_.path()); break;
    case KeyAction::Save:
        if (!scene_.path().empty()) {
            save();
            break;
        }
        [[fallthrough]];
    case KeyAction::SaveAs: dialog(UiState::PathDialog::SaveAs, scene_.path().empty() ? "scene.json" : scene_.path()); break;
    case KeyAction::ImportFile: dialog(UiState::PathDialog::Import, ""); break;
    case KeyAction::ExportMesh: dialog(UiState::PathDialog::Export, "scene.obj"); break;
    case KeyAction::Quit: quit(); break;
    case KeyAction::ViewBack: setView("back"); break;
    case KeyAction::ViewLeft: setView("left"); break;
    case KeyAction::ViewBottom: setView("bottom"); break;
    // View
    case KeyAction::ViewFront: setView("front"); break;
    case KeyAction::ViewRight: setView("right"); break;
    case KeyAction::ViewTop: setView("top"); break;
    case KeyAction::ViewIso: setView("iso"); break;
    case KeyAction::ToggleProjection:
        scene_.camera.projection = scene_.camera.projection == Projection::Perspective ? Projection::Orthographic : Projection::Perspective;
        scene_.touch();
        break;
    case KeyAction::FitAll: fit(false); break;
    case KeyAction::FitSelection: fit(true); break;
    case KeyAction::NextShading:
        d.shading = static_cast<Shading>((static_cast<int>(d.shading) + 1) % 3);
        scene_.touch();
        break;
    case KeyAction::ToggleWireframe:
        d.wireframe = !d.wireframe;
        scene_.touch();
        break;
    case KeyAction::ToggleReflectionLines:
        d.analysis = d.analysis == SurfaceAnalysis::ReflectionLines ? SurfaceAnalysis::None : SurfaceAnalysis::ReflectionLines;
        scene_.touch();
        break;
    case KeyAction::ToggleHelp: ui_.showHelp = !ui_.showHelp; break;
    case KeyAction::ToggleStatistics: ui_.showStats = !ui_.showStats; break;
    default: break; // the other contexts' actions are handled by Interaction and the tools
    }
}

void App::onDrop(int count, const char** paths)
{
    startAction();
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

// ------------------------------------------------------------------------------------ replay

void App::applyModifiers(int mods)
{
    // As ImGui's GLFW backend: the modifier flags and the modifier keys' down state.
    ImGuiIO& io = ImGui::GetIO();
    io.KeyCtrl = io.KeysDown[GLFW_KEY_LEFT_CONTROL] = (mods & GLFW_MOD_CONTROL) != 0;
    io.KeyShift = io.KeysDown[GLFW_KEY_LEFT_SHIFT] = (mods & GLFW_MOD_SHIFT) != 0;
    io.KeyAlt = io.KeysDown[GLFW_KEY_LEFT_ALT] = (mods & GLFW_MOD_ALT) != 0;
    io.KeySuper = io.KeysDown[GLFW_KEY_LEFT_SUPER] = (mods & GLFW_MOD_SUPER) != 0;
}

void App::replay(const std::vector<ReplayEvent>& events)
{
    ImGuiIO& io = ImGui::GetIO();
    const bool withUi = !options_.noUi;
    auto render = [&] {
        frame(options_.width, options_.height, withUi);
        maybeAutosave();
    };
    auto moveTo = [&](double x, double y, int mods) {
        if (x == cursorX_ && y == cursorY_ && io.MousePos.x == float(x) && io.MousePos.y == float(y)) return;
        applyModifiers(mods);
        io.MousePos = ImVec2(float(x), float(y));
        timedInput([&] { onCursor(x, y); });
        render(); // ImGui sees the hover before a press there, as after a real move
    };
    render();
    for (const ReplayEvent& e : events) {
        switch (e.type) {
        case ReplayEvent::Type::Move:
            applyModifiers(e.mods);
            io.MousePos = ImVec2(float(e.x), float(e.y));
            timedInput([&] { onCursor(e.x, e.y); });
            break;
        case ReplayEvent::Type::Press:
        case ReplayEvent::Type::Release: {
            moveTo(e.x, e.y, e.mods);
            applyModifiers(e.mods);
            const bool down = e.type == ReplayEvent::Type::Press;
            if (e.button < 5) io.MouseDown[e.button] = down;
            timedInput([&] { onMouseButton(e.button, down ? GLFW_PRESS : GLFW_RELEASE, e.mods); });
            break;
        }
        case ReplayEvent::Type::Key:
            applyModifiers(e.mods);
            io.KeysDown[e.key] = true;
            onKey(e.key, GLFW_PRESS, e.mods);
            render();
            io.KeysDown[e.key] = false;
            onKey(e.key, GLFW_RELEASE, e.mods);
            break;
        case ReplayEvent::Type::KeyPress:
        case ReplayEvent::Type::KeyRelease: {
            applyModifiers(e.mods);
            const bool down = e.type == ReplayEvent::Type::KeyPress;
            io.KeysDown[e.key] = down;
            onKey(e.key, down ? GLFW_PRESS : GLFW_RELEASE, e.mods);
            break;
        }
        case ReplayEvent::Type::Text:
            // No modifiers held (like every event without "mods"): ImGui drops characters typed
            // with Ctrl held, which a preceding Ctrl+A would otherwise leave set.
            applyModifiers(0);
            io.AddInputCharactersUTF8(e.text.c_str());
            break;
        case ReplayEvent::Type::Scroll:
            if (e.hasPosition) moveTo(e.x, e.y, e.mods);
            applyModifiers(e.mods);
            io.MouseWheel += float(e.dy);
            onScroll(e.dy);
            break;
        case ReplayEvent::Type::Frame:
            for (int i = 1; i < e.count; ++i) render();
            break;
        case ReplayEvent::Type::Open:
            open(e.text);
            break;
        case ReplayEvent::Type::Drop: {
            // What the window's GLFW drop callback calls, with the same arguments.
            std::vector<const char*> paths;
            for (const std::string& path : e.paths) paths.push_back(path.c_str());
            onDrop(static_cast<int>(paths.size()), paths.data());
            break;
        }
        case ReplayEvent::Type::TooltipAudit:
            // A test hook (docs/editor.md): the pointer swept over every panel, frames of the
            // panels only; the result goes to --state.
            if (withUi)
                audits_.push_back(auditTooltips([this](const std::function<void()>& hook) { buildUi(hook); }, ui_.tooltip, float(e.step), e.windows, &ui_.dropdowns));
            break;
        case ReplayEvent::Type::Resize:
            // As a window resized by the user: the view and the panels get the new size.
            options_.width = e.width;
            options_.height = e.height;
            glfwSetWindowSize(window_, e.width, e.height);
            break;
        }
        render();
        if (quitting_) break;
    }
}

} // namespace freeform::editor
