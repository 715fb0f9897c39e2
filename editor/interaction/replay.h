#pragma once
// Scripted input for `freeform-editor FILE --replay EVENTS.json`: the events file format (docs/
// editor.md, "Replaying input") and its strict reader, and worldToPixel for tests that write
// event files. The application feeds each event through the same handlers as real input (its GLFW
// callbacks' handlers and ImGui's io) and renders a frame after each one.

#include <Eigen/Core>

#include <string>
#include <vector>

namespace freeform::editor {

class Scene;

struct ReplayEvent {
    enum class Type { Move, Press, Release, Key, KeyPress, KeyRelease, Text, Scroll, Frame, Open, Resize, Drop, TooltipAudit };
    Type type = Type::Frame;
    double x = 0, y = 0;        // pixels, origin top left (move, press, release, scroll)
    bool hasPosition = false;   // scroll: x and y given
    int button = 0;             // GLFW button: 0 left, 1 right, 2 middle
    int key = 0;                // GLFW key code
    int mods = 0;               // GLFW modifier bits
    double dy = 0;              // scroll
    int count = 1;              // frame
    int width = 0, height = 0;  // resize: the window's new size in pixels
    double step = 0;            // tooltip_audit: the sweep's step in pixels (0: half a line height)
    std::vector<std::string> windows; // tooltip_audit: only these top-level windows (empty: all)
    std::string text;           // text (UTF-8), open (path)
    std::vector<std::string> paths; // drop: the files dropped on the window
};

/// Parses the events file text; Error naming the event index and field on anything unexpected
/// (unknown type, key, button or modifier; a missing or mistyped field; an unknown field).
std::vector<ReplayEvent> parseReplay(const std::string& text, const std::string& source = "events");
/// Reads and parses an events file (Error when it cannot be read).
std::vector<ReplayEvent> readReplay(const std::string& path);

/// The GLFW key code of a key name of the format ("A".."Z", "0".."9", "Enter", "Escape",
/// "Delete", "Backspace", "Tab", "Space", "Left", "Right", "Up", "Down", "F1".."F12", "Plus",
/// "Minus"), or -1.
int keyCode(const std::string& name);

/// Where the world point p appears in a view of width x height pixels of the scene's camera
/// (origin top left, continuous coordinates: the cursor position that lies on it).
Eigen::Vector2d worldToPixel(const Scene& scene, int width, int height, const Eigen::Vector3d& p);

} // namespace freeform::editor
