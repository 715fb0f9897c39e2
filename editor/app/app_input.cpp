// The application's input (app/app.h): the queue of GLFW's events taken into each frame and
// dispatched, the handlers of pointer, wheel, keys (the keymap's actions), dropped files and the
// window's close button, and --replay, which feeds scripted events through the same handlers and
// into ImGui's io as its GLFW backend does.

#include "app/app.h"

// GLFW without its own GL header (no GL calls here; app.cpp includes the loader, libepoxy).
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <imgui.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "freeform/core/error.h"

namespace freeform::editor {

namespace fs = std::filesystem;

// ------------------------------------------------------------------------------------ input

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
