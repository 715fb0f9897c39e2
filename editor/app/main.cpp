// freeform-editor: the interactive editor, and its headless uses (--screenshot, --save, --frames,
// --replay).
// Contract as the command-line tool's: errors are one "error: ..." line on stderr, exit 1 for a file
// that cannot be read or written (and then no output file), exit 2 for a wrong command line.

#include <stb_image_write.h>

#include <cstdio>
#include <iostream>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <string>
#include <vector>

#include "app/app.h"
#include "app/options.h"
#include "freeform/core/error.h"
#include "freeform/io/file.h"
#include "interaction/replay.h"

using namespace freeform;
using namespace freeform::editor;

namespace {

/// Writes RGBA pixels (top row first) as PNG, atomically.
void writePng(const std::string& path, const Image& image)
{
    std::string bytes;
    auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
    };
    // Drop alpha: the frame is opaque.
    std::vector<unsigned char> rgb(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3);
    for (std::size_t i = 0, n = rgb.size() / 3; i < n; ++i)
        for (int c = 0; c < 3; ++c) rgb[3 * i + static_cast<std::size_t>(c)] = image.rgba[4 * i + static_cast<std::size_t>(c)];
    if (!stbi_write_png_to_func(append, &bytes, image.width, image.height, 3, rgb.data(), image.width * 3))
        throw Error(path + ": PNG encoding failed");
    writeFileAtomically(path, bytes);
}

/// Applies the view options of the command line to the loaded scene.
void applyOptions(Scene& scene, const Options& o)
{
    DisplaySettings& d = scene.display;
    if (o.shading) d.shading = *o.shading == "flat" ? Shading::Flat : *o.shading == "gouraud" ? Shading::Gouraud : Shading::Phong;
    if (o.lighting) d.specular = *o.lighting == "blinn" ? SpecularModel::Blinn : SpecularModel::Phong;
    if (o.analysis) d.analysis = *o.analysis == "reflection_lines" ? SurfaceAnalysis::ReflectionLines : SurfaceAnalysis::None;
    if (o.samples) {
        d.samples = *o.samples; // asked for on the command line: on every renderer
        d.antialiasing = Antialiasing::Always;
    }
    if (o.wireframe) d.wireframe = true;
    if (o.flipNormals) d.flipNormals = true;
    if (o.tolerance) {
        d.tolerance = *o.tolerance;
        scene.pixelTolerance = 0; // a world tolerance asked for: not the view's
        for (int i = 0; i < scene.itemCount(); ++i) {
            ObjectSettings s = scene.item(i).settings;
            s.tessellation.tolerance = 0; // the command line's tolerance for everything
            scene.setSettings(i, s);
        }
        scene.invalidateGeometry();
    }
    if (o.segments) {
        for (int i = 0; i < scene.itemCount(); ++i) {
            ObjectSettings s = scene.item(i).settings;
            s.tessellation.mode = Tessellation::Mode::Uniform;
            s.tessellation.segments = *o.segments;
            scene.setSettings(i, s);
        }
    }
    if (o.projection) scene.camera.projection = *o.projection == "orthographic" ? Projection::Orthographic : Projection::Perspective;
    if (o.view) {
        scene.camera.setView(*o.view);
        scene.updateGeometry();
        const Eigen::AlignedBox3d box = scene.bounds();
        scene.camera.fit(box, double(o.width) / double(o.height));
    }
}

} // namespace

int main(int argc, char** argv)
{
#if defined(__GLIBC__)
    // Keep freed heap memory instead of giving the top of the heap back to the system after every
    // frame. With glibc's default (a trim threshold that follows the largest freed block), a
    // lattice drag over a 64k-vertex mesh put the heap in a state where each frame's large
    // temporary buffers (llvmpipe's vertex data among them) were returned and faulted in again:
    // from then on every frame, at rest too, took about 45 ms more (page faults in the profile),
    // 126-133 ms a drag frame against 75-86 ms with this setting (docs/performance.md, "Lattice
    // drag in the window"). A quarter of a GiB is what the editor may keep unused at most.
    mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
    Options options;
    try {
        options = parseOptions(std::vector<std::string>(argv + 1, argv + argc));
    } catch (const UsageError& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 2;
    }
    if (options.help) {
        std::cout << helpText();
        return 0;
    }
    try {
        // A bad events file stops everything before any output is written.
        std::vector<ReplayEvent> events;
        if (!options.replay.empty()) events = readReplay(options.replay);
        Scene scene;
        std::string loadError;
        if (!options.file.empty()) {
            try {
                scene = Scene::load(options.file, double(options.width) / double(options.height));
            } catch (const Error& e) {
                if (options.headless()) throw;
                loadError = e.what(); // the window opens with an empty document and shows the error
            }
        }
        applyOptions(scene, options);
        if (!options.replay.empty()) {
            App app(std::move(scene), options);
            app.replay(events);
            if (!options.state.empty()) app.writeState(options.state);
            if (!options.save.empty()) app.saveDocument(options.save);
            if (!options.screenshot.empty()) writePng(options.screenshot, app.renderImage());
            return 0;
        }
        if (!options.save.empty()) scene.save(options.save);
        if (!options.screenshot.empty() || options.frames > 0) {
            App app(std::move(scene), options);
            if (options.frames > 0) app.printFrameStats(options.frames);
            if (!options.screenshot.empty()) writePng(options.screenshot, app.renderImage());
            return 0;
        }
        if (!options.save.empty()) return 0;
        std::unique_ptr<App> app;
        try {
            app = std::make_unique<App>(std::move(scene), options);
        } catch (const Error& e) {
            std::cerr << "error: " << e.what() << "\n"
                      << "freeform-editor needs a display for its window. Without one, render a picture instead:\n"
                      << "  xvfb-run -a -s \"-screen 0 1280x800x24\" freeform-editor FILE --screenshot shot.png\n"
                      << "(scripts/run-editor.sh does this by itself when DISPLAY is not set)\n";
            return 1;
        }
        if (!loadError.empty()) app->showError(loadError);
        const int status = app->run();
        if (!options.state.empty()) app->writeState(options.state);
        return status;
    } catch (const Error& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 1;
    }
}
