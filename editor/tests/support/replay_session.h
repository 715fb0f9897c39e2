#pragma once
// What the editor's replayed-session tests share (test_render_replay.cpp,
// test_render_spline_modes.cpp, test_render_tools.cpp): running build/bin/freeform-editor, the
// events of a replay file (docs/editor.md, "Replaying input") and a replay that saves the document.
// Header only; the test targets define FREEFORM_EDITOR and FREEFORM_TEST_TMP (editor/CMakeLists.txt).

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "editor_process.h" // editor/tests/support
#include "support/process.h"

namespace freeform::editor::replay_test {

inline const std::string kTmp = FREEFORM_TEST_TMP;
/// The window size every replay here runs at.
constexpr int kW = 1280, kH = 800;

template <typename... Parts>
std::string cat(const Parts&... parts)
{
    std::ostringstream s;
    (s << ... << parts);
    return s.str();
}

/// Runs the editor binary with `arguments` (support/editor_process.h); `environment` is prepended
/// (VAR=value ...).
inline test::ProcessResult runEditor(const std::string& arguments, const std::string& environment = "")
{
    return test::runEditorBinary(arguments, environment);
}

inline nlohmann::ordered_json move(const Eigen::Vector2d& p) { return {{"type", "move"}, {"x", p.x()}, {"y", p.y()}}; }
/// A left button event ("press" or "release") at p, with Shift held when `shift`.
inline nlohmann::ordered_json button(const char* type, const Eigen::Vector2d& p, bool shift = false)
{
    nlohmann::ordered_json e = {{"type", type}, {"button", "left"}, {"x", p.x()}, {"y", p.y()}};
    if (shift) e["mods"] = {"shift"};
    return e;
}
inline nlohmann::ordered_json press(const Eigen::Vector2d& p, bool shift = false) { return button("press", p, shift); }
inline nlohmann::ordered_json release(const Eigen::Vector2d& p, bool shift = false) { return button("release", p, shift); }
inline nlohmann::ordered_json key(const std::string& k, const std::vector<std::string>& mods = {})
{
    nlohmann::ordered_json e = {{"type", "key"}, {"key", k}};
    if (!mods.empty()) e["mods"] = mods;
    return e;
}
inline nlohmann::ordered_json frames(int count) { return {{"type", "frame"}, {"count", count}}; }

/// Appends a move to p, a press and a release there.
inline void click(nlohmann::ordered_json& events, const Eigen::Vector2d& p, bool shift = false)
{
    events.push_back(move(p));
    events.push_back(press(p, shift));
    events.push_back(release(p, shift));
}

/// Appends a move to `from`, a press, two moves (half way, `to`) and a release.
inline void drag(nlohmann::ordered_json& events, const Eigen::Vector2d& from, const Eigen::Vector2d& to)
{
    events.push_back(move(from));
    events.push_back(press(from));
    events.push_back(move(0.5 * (from + to)));
    events.push_back(move(to));
    events.push_back(release(to));
}

/// A perspective camera looking at `target` from the front right above (back (1, -2, 1), right
/// (2, 1, 0), 35 degrees), as the editor saves it in a document's "editor" member.
inline nlohmann::ordered_json frontRightCamera(const Eigen::Vector3d& target, double distance)
{
    const Eigen::Vector3d back = Eigen::Vector3d(1, -2, 1).normalized(), right = Eigen::Vector3d(2, 1, 0).normalized();
    Eigen::Matrix3d frame;
    frame << right, back.cross(right), back;
    const Eigen::Quaterniond q(frame);
    return {{"target", {target.x(), target.y(), target.z()}}, {"distance", distance}, {"orientation", {q.w(), q.x(), q.y(), q.z()}},
            {"fovy", 35.0}, {"projection", "perspective"}, {"orbit", "turntable"}};
}

/// Replays `events` on `doc` at kW x kH (the events written to `<prefix>.events.json` under the
/// test folder), saves the document to `<prefix>.out.json` and returns that path; the run must
/// succeed and write it.
inline std::string replayAndSave(const std::string& doc, const std::string& prefix, const nlohmann::ordered_json& events,
                                 const std::string& environment = "")
{
    const std::string file = cat(kTmp, "/", prefix, ".events.json"), out = cat(kTmp, "/", prefix, ".out.json");
    test::writeText(file, nlohmann::ordered_json{{"events", events}}.dump(1));
    std::filesystem::remove(out);
    const auto r = runEditor(cat("'", doc, "' --replay '", file, "' --save '", out, "' --size ", kW, "x", kH), environment);
    INFO(r.err);
    REQUIRE(r.status == 0);
    REQUIRE(std::filesystem::exists(out));
    return out;
}

} // namespace freeform::editor::replay_test
