// The editor's own JSON readers, compiled alone into the target (not the editor library: no
// GLFW, OpenGL or ImGui; replay.cpp uses only GLFW's key constants from its header).
//   FUZZ_KIND 1: a replay file (editor/interaction/replay.cpp, parseReplay).
//   FUZZ_KIND 2: display settings and object settings (editor/scene/settings.cpp, fromText). An
//                accepted text must write (toJson) and read back without an error.
// A freeform::Error is the expected answer to bad input; anything else is a finding.

#include <freeform/core/error.h>

#include <string>

#include "fuzz_common.h"
#include "interaction/replay.h"
#include "scene/settings.h"

#if FUZZ_KIND == 1
#include <cstdlib>

#include "interaction/picking.h"

// replay.cpp's worldToPixel (not reached from parseReplay) needs the view of a scene, which brings
// the whole scene layer: the target links these two in its place, and they abort if ever called.
namespace freeform::editor {
ViewTransform ViewTransform::of(const Scene&, int, int) { std::abort(); }
std::optional<Eigen::Vector3d> ViewTransform::toPixel(const Eigen::Vector3d&) const { std::abort(); }
} // namespace freeform::editor
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string text(reinterpret_cast<const char*>(data), size);
#if FUZZ_KIND == 1
    try {
        (void)freeform::editor::parseReplay(text, "fuzz.json");
    } catch (const freeform::Error&) {
    }
#else
    using freeform::editor::DisplaySettings;
    using freeform::editor::ObjectSettings;
    try {
        const DisplaySettings d = DisplaySettings::fromText(text, "display.json");
        try {
            (void)DisplaySettings::fromText(d.toJson().dump(), "written.json");
        } catch (const freeform::Error& e) {
            fuzz::fail(std::string("written display settings do not read back: ") + e.what());
        }
    } catch (const freeform::Error&) {
    }
    try {
        const ObjectSettings o = ObjectSettings::fromText(text, "object \"fuzz\".editor");
        try {
            (void)ObjectSettings::fromText(o.toJson().dump(), "written");
        } catch (const freeform::Error& e) {
            fuzz::fail(std::string("written object settings do not read back: ") + e.what());
        }
    } catch (const freeform::Error&) {
    }
#endif
    return 0;
}
