#pragma once
// Command-line options of freeform-editor (the help text in options.cpp lists them all).

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace freeform::editor {

/// A wrong command line: exit status 2.
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct Options {
    std::string file;                      // document, .bpt or mesh; empty: a new document
    std::string screenshot;                // write a PNG and exit
    std::string save;                      // write the document and exit (after --replay)
    std::string replay;                    // feed the events of this file, then save/screenshot and exit
    std::string state;                     // --state OUT.json: the editor's state written on exit
    int width = 1280, height = 800;        // --size (screenshot), window size otherwise
    bool sizeGiven = false;
    std::optional<std::string> shading;    // flat | gouraud | phong
    std::optional<std::string> lighting;   // phong | blinn
    std::optional<std::string> view;       // front | back | left | right | top | bottom | iso
    std::optional<std::string> projection; // perspective | orthographic
    std::optional<std::string> analysis;   // none | reflection_lines
    std::optional<double> tolerance;       // adaptive tessellation tolerance
    std::optional<int> segments;           // uniform tessellation of every surface
    std::optional<int> samples;            // multisampling
    bool wireframe = false;
    bool flipNormals = false;
    bool noUi = false;
    int frames = 0;                        // --frames N: render N frames and print timings
    std::string frameLog;                  // --frame-log OUT.tsv: each frame's phases in ms, one line per frame
    bool help = false;

    bool headless() const { return !screenshot.empty() || !save.empty() || frames > 0 || !replay.empty(); }
};

/// Parses argv (without the program name). UsageError on unknown or malformed options.
Options parseOptions(const std::vector<std::string>& args);

/// The --help text.
const char* helpText();

} // namespace freeform::editor
