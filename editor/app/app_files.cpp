// The application's file actions and the rest of UiActions (app/app.h, ui/ui.h): new, open, save,
// save as, import, export, quit, fitting the view, the recent files, the desktop's file chooser
// (zenity), undo and redo, the tools' panels; the autosave of unsaved changes and its recovery.

#include "app/app.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <sys/wait.h>
#include <unistd.h>

#include "freeform/core/error.h"
#include "freeform/io/file.h"
#include "ui/tool_panels.h"

namespace freeform::editor {

namespace fs = std::filesystem;

namespace {

const char* kAutosaveFile = "autosave.json";
const char* kAutosavePathFile = "autosave-path.txt";

} // namespace

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
        const int added = scene_.importFile(path, up);
        fit(false); // the camera takes in the scene with the imported object
        if (added < scene_.itemCount() && scene_.item(added).is(ObjectKind::Part))
            ui_.notice = std::string("imported ") + fs::path(path).filename().string() + " as the part \"" + scene_.item(added).name +
                         "\": " + partSummary(std::get<PartData>(scene_.object(added).data)) +
                         "; select it and press L to fit a lattice";
        else if (scene_.itemCount() > 0 && scene_.item(scene_.itemCount() - 1).kind == SceneItem::Kind::ImportedMesh)
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

void App::exportPart(const std::string& path)
{
    try {
        const Scene::PartExport e = scene_.exportPart(scene_.partItem(ui_.selection.item), path);
        ui_.notice = "wrote the part \"" + e.name + "\" to " + path + " (" + std::to_string(e.faces) + " faces";
        ui_.notice += Scene::approximationText(e.deform);
        ui_.notice += e.valid ? ", a valid shape)" : ", Open CASCADE's check finds the shape invalid)";
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

} // namespace freeform::editor
