#include "app/options.h"

#include <charconv>
#include <set>

namespace freeform::editor {

namespace {

int parseInt(const std::string& text, const std::string& option, int lo, int hi)
{
    int value = 0;
    const auto r = std::from_chars(text.data(), text.data() + text.size(), value);
    if (r.ec != std::errc() || r.ptr != text.data() + text.size() || value < lo || value > hi)
        throw UsageError("option " + option + " needs an integer in " + std::to_string(lo) + ".." + std::to_string(hi) +
                         ", found \"" + text + "\"");
    return value;
}

std::string oneOf(const std::string& text, const std::string& option, const std::set<std::string>& allowed)
{
    if (allowed.count(text)) return text;
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
    throw UsageError("option " + option + " must be one of " + list + ", found \"" + text + "\"");
}

} // namespace

Options parseOptions(const std::vector<std::string>& args)
{
    Options o;
    std::set<std::string> seen;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a.rfind("--", 0) != 0) {
            if (!o.file.empty()) throw UsageError("more than one file given: \"" + o.file + "\" and \"" + a + "\"");
            o.file = a;
            continue;
        }
        if (seen.count(a)) throw UsageError("option " + a + " is given twice");
        seen.insert(a);
        auto value = [&]() -> std::string {
            if (i + 1 >= args.size()) throw UsageError("option " + a + " needs a value");
            return args[++i];
        };
        if (a == "--help" || a == "-h") o.help = true;
        else if (a == "--screenshot") o.screenshot = value();
        else if (a == "--save") o.save = value();
        else if (a == "--replay") o.replay = value();
        else if (a == "--state") o.state = value();
        else if (a == "--size") {
            const std::string v = value();
            const auto x = v.find('x');
            if (x == std::string::npos) throw UsageError("option --size needs WIDTHxHEIGHT, found \"" + v + "\"");
            o.width = parseInt(v.substr(0, x), "--size", 16, 8192);
            o.height = parseInt(v.substr(x + 1), "--size", 16, 8192);
            o.sizeGiven = true;
        } else if (a == "--shading") o.shading = oneOf(value(), a, {"flat", "gouraud", "phong"});
        else if (a == "--lighting") o.lighting = oneOf(value(), a, {"phong", "blinn"});
        else if (a == "--view") o.view = oneOf(value(), a, {"front", "back", "left", "right", "top", "bottom", "iso"});
        else if (a == "--projection") o.projection = oneOf(value(), a, {"perspective", "orthographic"});
        else if (a == "--analysis") o.analysis = oneOf(value(), a, {"none", "reflection_lines"});
        else if (a == "--tolerance") {
            const std::string v = value();
            double t = 0;
            const auto r = std::from_chars(v.data(), v.data() + v.size(), t);
            if (r.ec != std::errc() || r.ptr != v.data() + v.size() || !(t > 0))
                throw UsageError("option --tolerance needs a positive number, found \"" + v + "\"");
            o.tolerance = t;
        } else if (a == "--segments") o.segments = parseInt(value(), a, 1, 1000);
        else if (a == "--samples") o.samples = parseInt(value(), a, 0, 16);
        else if (a == "--frames") o.frames = parseInt(value(), a, 1, 100000);
        else if (a == "--frame-log") o.frameLog = value();
        else if (a == "--wireframe") o.wireframe = true;
        else if (a == "--flip-normals") o.flipNormals = true;
        else if (a == "--no-ui") o.noUi = true;
        else throw UsageError("unknown option " + a + " (see --help)");
    }
    return o;
}

const char* helpText()
{
    return R"(freeform-editor: view and edit freeform documents, Bezier patch files and meshes.

usage: freeform-editor [FILE] [options]

FILE is a freeform document (.json), a Bezier patch file (.bpt), a mesh (.obj .ply .stl .off .gltf
.glb) or a STEP, IGES or BRep part (.step .stp .iges .igs .brep). Without --screenshot, --save or --frames the
editor opens a window (it needs a display).

headless use:
  --screenshot OUT.png   render one frame off-screen and write it as PNG, then exit
  --save OUT.json        write the document (with the editor's camera and display settings), then exit
  --frames N             render N frames off-screen and print the frame times, then exit
  --replay EVENTS.json   feed the input events of the file (mouse, keys, text, frames; docs/editor.md)
                         to a hidden window of --size, rendering a frame after each; then --save
                         and/or --screenshot write the result, and the editor exits
  --frame-log OUT.tsv    write each frame's time by phase (input, ui, update, overlay, draw, gui,
                         and its end: the present in a window, the wait for the GPU headless),
                         milliseconds, one line per frame (docs/performance.md)
  --size WxH             image size in pixels (default 1280x800; also the window size)
  --state OUT.json       when the editor exits (after --replay, or when its window closes) write its
                         state: the error dialog's message, the window and panel rectangles, the
                         camera (docs/editor.md, "Replaying input"); for tests
  --no-ui                leave the panels out of the screenshot

view (override what the document says):
  --shading flat|gouraud|phong      --lighting phong|blinn (specular term)
  --view front|back|left|right|top|bottom|iso   (also fits the view to the scene)
  --projection perspective|orthographic
  --analysis none|reflection_lines  --wireframe  --flip-normals (draw with negated normals)
  --tolerance T          adaptive tessellation tolerance (world units)
  --segments N           uniform tessellation with N x N quads per patch, for every surface
  --samples N            multisampling with N samples on every renderer (0 = off); without it,
                         the document's (default: auto, 4 on a GPU and in screenshots, none
                         for the frames of a software renderer such as llvmpipe)

environment: FREEFORM_AUTOSAVE_DIR (the autosave folder; headless runs autosave only when it is
set), FREEFORM_AUTOSAVE_INTERVAL (seconds between autosaves, default 60), FREEFORM_CONFIG_DIR
(the folder of File > Open recent's recent.json instead of $XDG_CONFIG_HOME/freeform; headless
runs read the list only from it, and never write it).

exit status: 0 success, 1 a file could not be read or written (or no display), 2 bad command line.
)";
}

} // namespace freeform::editor
