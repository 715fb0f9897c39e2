// Replayed sessions (label "render": they need an X display). They run
// build/bin/freeform-editor FILE --replay EVENTS.json --save OUT.json with event files written from
// worldToPixel (interaction/replay.h), and check the saved documents:
//   - dragging one control point of a curve moves exactly that point by the view-plane drag through
//     it, computed here from the camera of the document with core/transform.h (look-at and
//     perspective built by hand, rays unprojected with an Eigen inverse): tolerance 1e-9 world
//     units (both sides in double; the editor's near and far planes differ from ours, which moves
//     nothing but the rounding); with grid snapping on, the point lands exactly on the grid;
//   - a session of several changes undone with Ctrl+Z step by step gives the original file byte for
//     byte, and Ctrl+Shift+Z redoes it to the edited one;
//   - opening a corrupt file mid-session keeps the document, and the session goes on;
//   - autosave writes the unsaved document when asked to (FREEFORM_AUTOSAVE_DIR) and the next start
//     recovers it (Enter in the recovery dialog) or discards it (Escape);
//   - a bad events file: exit 1, one "error:" line, nothing written.

#include <catch2/catch.hpp>

#include <freeform/core/transform.h>

#include <nlohmann/json.hpp>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "interaction/replay.h"
#include "scene/scene.h"
#include "support/process.h"
#include "support/replay_session.h"

namespace test_render_replay {

using namespace freeform;
using namespace freeform::editor;
using namespace freeform::editor::replay_test;
using Json = nlohmann::ordered_json;

namespace {

namespace fs = std::filesystem;

const Eigen::Vector3d kPoints[4] = {{-2, 0, 0}, {-1, 0, 1.5}, {1, 0, 1.5}, {2, 0, 0}};

/// The curve document with a fixed perspective camera from the front right above, as the editor
/// saves it (so that a load and a save reproduce it byte for byte).
std::string curveDocument()
{
    const std::string source = kTmp + "/replay_source.json", doc = kTmp + "/replay_curve.json";
    static bool written = false;
    if (written) return doc;
    written = true;
    Json j = {{"format", "freeform"}, {"version", 1}};
    Json points = Json::array();
    for (const auto& p : kPoints) points.push_back({p.x(), p.y(), p.z()});
    j["objects"] = Json::array({{{"name", "c"}, {"type", "bezier_curve"}, {"points", points}}});
    j["editor"] = {{"camera", frontRightCamera(Eigen::Vector3d(0, 0, 0.75), 9.0)}};
    test::writeText(source, j.dump(2));
    const auto r = runEditor(cat("'", source, "' --save '", doc, "'"));
    INFO(r.err);
    REQUIRE(r.status == 0);
    return doc;
}

/// The control points of object 0 of a saved document.
std::vector<Eigen::Vector3d> savedPoints(const std::string& path)
{
    const Json j = Json::parse(test::slurp(path));
    std::vector<Eigen::Vector3d> out;
    for (const Json& p : j["objects"][0]["points"]) out.emplace_back(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
    return out;
}

/// The camera of a saved document as matrices built by hand from core/transform.h.
struct HandCamera {
    Eigen::Matrix4d inverse;
    Eigen::Vector3d back;
};

HandCamera handCamera(const std::string& path)
{
    const Json c = Json::parse(test::slurp(path))["editor"]["camera"];
    const Eigen::Vector3d target(c["target"][0].get<double>(), c["target"][1].get<double>(), c["target"][2].get<double>());
    const Eigen::Quaterniond q(c["orientation"][0].get<double>(), c["orientation"][1].get<double>(), c["orientation"][2].get<double>(),
                               c["orientation"][3].get<double>());
    const Eigen::Vector3d back = q * Eigen::Vector3d::UnitZ(), up = q * Eigen::Vector3d::UnitY();
    const Eigen::Vector3d eye = target + c["distance"].get<double>() * back;
    const Eigen::Matrix4d m = perspective<double>(c["fovy"].get<double>() * M_PI / 180, double(kW) / kH, 0.1, 100) * lookAt<double>(eye, target, up);
    return {m.inverse(), back};
}

/// Where the ray through pixel (x, y) meets the plane through p orthogonal to the view direction.
Eigen::Vector3d hitViewPlane(const HandCamera& c, double x, double y, const Eigen::Vector3d& p)
{
    auto unproject = [&](double z) {
        const Eigen::Vector4d w = c.inverse * Eigen::Vector4d(2 * x / kW - 1, 1 - 2 * y / kH, z, 1);
        return Eigen::Vector3d(w.head<3>() / w.w());
    };
    const Eigen::Vector3d o = unproject(-1), d = (unproject(1) - o).normalized();
    return o + ((p - o).dot(c.back) / d.dot(c.back)) * d;
}

/// Appends a click on the curve (its end, point 0) to select it.
void selectCurve(Json& events, const Scene& scene)
{
    const Eigen::Vector2d p = worldToPixel(scene, kW, kH, kPoints[0]);
    events.push_back(move(p));
    events.push_back(press(p));
    events.push_back(release(p));
}

/// Runs a replay of `events` on the curve document and returns the saved file.
std::string replay(const std::string& name, const Json& events, const std::string& environment = "")
{
    return replayAndSave(curveDocument(), cat("replay_", name), events, environment);
}

} // namespace

TEST_CASE("a replayed drag moves exactly the grabbed control point by the view-plane drag", "[render][replay]")
{
    const Scene scene = Scene::load(curveDocument());
    const Eigen::Vector2d p1 = worldToPixel(scene, kW, kH, kPoints[1]);
    const Eigen::Vector2d from = p1 + Eigen::Vector2d(2, -1), to = from + Eigen::Vector2d(63, -41);
    Json events = Json::array();
    selectCurve(events, scene);
    drag(events, from, to);
    const std::vector<Eigen::Vector3d> after = savedPoints(replay("drag", events));

    const HandCamera camera = handCamera(curveDocument());
    const Eigen::Vector3d expected = kPoints[1] + hitViewPlane(camera, to.x(), to.y(), kPoints[1]) - hitViewPlane(camera, from.x(), from.y(), kPoints[1]);
    INFO("moved to " << after[1].transpose() << ", expected " << expected.transpose());
    CHECK((after[1] - expected).norm() < 1e-9);
    CHECK((after[1] - kPoints[1]).norm() > 0.1); // it did move, by about 75 pixels' worth
    for (int k : {0, 2, 3}) CHECK(after[static_cast<std::size_t>(k)] == kPoints[k]);
}

TEST_CASE("a replayed drag with grid snapping puts the point exactly on the grid", "[render][replay]")
{
    const Scene scene = Scene::load(curveDocument());
    const Eigen::Vector2d p1 = worldToPixel(scene, kW, kH, kPoints[1]);
    const Eigen::Vector2d to = p1 + Eigen::Vector2d(47, 36);
    Json events = Json::array();
    selectCurve(events, scene);
    events.push_back(key("Tab", {"shift"})); // snapping on
    drag(events, p1, to);
    const std::vector<Eigen::Vector3d> after = savedPoints(replay("snap", events));
    // The grid step: bounds x in [-2, 2], y = 0, z in [0, 1.5]; extent max(2, 0.5 |(4, 0, 1.5)|) = 2.136;
    // an eighth is 0.267, the next 1-2-5 step 0.5.
    const double step = 0.5;
    const HandCamera camera = handCamera(curveDocument());
    const Eigen::Vector3d free = kPoints[1] + hitViewPlane(camera, to.x(), to.y(), kPoints[1]) - hitViewPlane(camera, p1.x(), p1.y(), kPoints[1]);
    INFO("snapped " << after[1].transpose() << ", free " << free.transpose());
    for (int r = 0; r < 3; ++r) {
        CHECK(after[1][r] / step == std::round(after[1][r] / step));
        CHECK(std::abs(after[1][r] - free[r]) <= step / 2 + 1e-9);
    }
    CHECK(after[1] != kPoints[1]);
    for (int k : {0, 2, 3}) CHECK(after[static_cast<std::size_t>(k)] == kPoints[k]);
}

TEST_CASE("undoing every step of a replayed session gives the original bytes, redo the edited ones", "[render][replay]")
{
    const Scene scene = Scene::load(curveDocument());
    const std::string original = test::slurp(curveDocument());
    Json session = Json::array();
    selectCurve(session, scene);
    const Eigen::Vector2d p1 = worldToPixel(scene, kW, kH, kPoints[1]), p2 = worldToPixel(scene, kW, kH, kPoints[2]),
                          p3 = worldToPixel(scene, kW, kH, kPoints[3]);
    drag(session, p1, p1 + Eigen::Vector2d(30, -50));           // step 1
    drag(session, p2, p2 + Eigen::Vector2d(-40, 25));           // step 2
    session.push_back(move(p3));                                // step 3: select point 3, G, X, click
    session.push_back(press(p3));
    session.push_back(release(p3));
    session.push_back(key("G"));
    session.push_back(move(p3 + Eigen::Vector2d(60, 10)));
    session.push_back(key("X"));
    session.push_back(move(p3 + Eigen::Vector2d(70, 20)));
    session.push_back(press(p3 + Eigen::Vector2d(70, 20)));
    session.push_back(release(p3 + Eigen::Vector2d(70, 20)));
    session.push_back(key("A"));                                 // step 4: all points, gizmo-free grab
    session.push_back(key("G"));
    session.push_back(move(p3 + Eigen::Vector2d(90, 20)));
    session.push_back(key("Enter"));
    const std::string edited = test::slurp(replay("session", session));
    CHECK(edited != original);

    Json undone = session;
    for (int k = 0; k < 3; ++k) undone.push_back(key("Z", {"ctrl"}));
    CHECK(test::slurp(replay("undo3", undone)) != original); // one step left
    undone.push_back(key("Z", {"ctrl"}));
    CHECK(test::slurp(replay("undo4", undone)) == original);
    undone.push_back(key("Z", {"ctrl"})); // nothing left to undo: no change
    CHECK(test::slurp(replay("undo5", undone)) == original);

    Json redone = undone;
    for (int k = 0; k < 3; ++k) redone.push_back(key("Z", {"ctrl", "shift"}));
    redone.push_back(key("Y", {"ctrl"}));
    CHECK(test::slurp(replay("redo", redone)) == edited);
}

TEST_CASE("opening a corrupt file mid-session keeps the document and the session goes on", "[render][replay]")
{
    const Scene scene = Scene::load(curveDocument());
    const std::string corrupt = kTmp + "/replay_corrupt.json";
    test::writeText(corrupt, "{\"format\": \"freeform\", \"version\": 1, \"objects\": [{\"name\": \"c\", \"type\": \"bezier_curve\", \"points\": [[0, 0], [1");
    const Eigen::Vector2d p1 = worldToPixel(scene, kW, kH, kPoints[1]), p2 = worldToPixel(scene, kW, kH, kPoints[2]);
    Json before = Json::array();
    selectCurve(before, scene);
    drag(before, p1, p1 + Eigen::Vector2d(30, -50));
    Json after = Json::array();
    drag(after, p2, p2 + Eigen::Vector2d(-40, 25));

    Json withOpen = before;
    withOpen.push_back({{"type", "open"}, {"path", corrupt}});
    withOpen.push_back({{"type", "frame"}, {"count", 2}});
    withOpen.push_back(key("Escape")); // closes the error dialog
    for (const Json& e : after) withOpen.push_back(e);
    Json without = before;
    for (const Json& e : after) without.push_back(e);

    const std::string kept = test::slurp(replay("corrupt", withOpen));
    const std::string reference = test::slurp(replay("no_corrupt", without));
    CHECK(kept == reference);
    const std::vector<Eigen::Vector3d> points = savedPoints(kTmp + "/replay_corrupt.out.json");
    CHECK(points[1] != kPoints[1]); // before the open
    CHECK(points[2] != kPoints[2]); // after it
}

TEST_CASE("autosave writes the unsaved document; the next start recovers or discards it", "[render][replay]")
{
    const Scene scene = Scene::load(curveDocument());
    const std::string dir = kTmp + "/replay_autosave";
    fs::remove_all(dir);
    const std::string environment = cat("FREEFORM_AUTOSAVE_DIR='", dir, "' FREEFORM_AUTOSAVE_INTERVAL=0");
    const Eigen::Vector2d p1 = worldToPixel(scene, kW, kH, kPoints[1]);
    Json events = Json::array();
    selectCurve(events, scene);
    drag(events, p1, p1 + Eigen::Vector2d(30, -50));
    const std::string edited = test::slurp(replay("autosave", events, environment));
    REQUIRE(fs::exists(dir + "/autosave.json"));
    CHECK(test::slurp(dir + "/autosave.json") == edited);
    CHECK(test::slurp(dir + "/autosave-path.txt") == curveDocument() + "\n");

    // No autosave without the variable in headless runs.
    fs::remove_all(kTmp + "/replay_no_autosave");
    replay("no_autosave", events, cat("XDG_STATE_HOME='", kTmp, "/replay_no_autosave'"));
    CHECK_FALSE(fs::exists(kTmp + "/replay_no_autosave"));

    // The next start offers it: Enter recovers (the file stays until a save), Escape discards it.
    const std::string recovered = test::slurp(replay("recover", Json::array({key("Enter")}), environment));
    CHECK(recovered == edited);
    CHECK(fs::exists(dir + "/autosave.json"));
    const std::string discarded = test::slurp(replay("discard", Json::array({key("Escape")}), environment));
    CHECK(discarded == test::slurp(curveDocument()));
    CHECK_FALSE(fs::exists(dir + "/autosave.json"));
}

TEST_CASE("a bad events file: exit 1, one error line, nothing written", "[render][replay]")
{
    const std::string events = kTmp + "/replay_bad.events.json", out = kTmp + "/replay_bad.out.json", png = kTmp + "/replay_bad.png";
    fs::remove(out);
    fs::remove(png);
    test::writeText(events, R"({"events": [{"type": "move", "x": 1, "y": 2}, {"type": "key", "key": "Hyper"}]})");
    const auto r = runEditor(cat("'", curveDocument(), "' --replay '", events, "' --save '", out, "' --screenshot '", png, "'"));
    CHECK(r.status == 1);
    CHECK(r.err.rfind("error: ", 0) == 0);
    CHECK(r.err.find("events[1].key") != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.out.empty());
    CHECK_FALSE(fs::exists(out));
    CHECK_FALSE(fs::exists(png));
    const auto missing = runEditor(cat("'", curveDocument(), "' --replay '", kTmp, "/no-such-events.json' --save '", out, "'"));
    CHECK(missing.status == 1);
    CHECK_FALSE(fs::exists(out));
}

} // namespace test_render_replay
