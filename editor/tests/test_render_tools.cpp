// Replayed sessions of the editing tools (label "render": they need an X display). Each runs
// build/bin/freeform-editor FILE --replay EVENTS.json --save OUT.json with event files written from
// worldToPixel (interaction/replay.h) and checks the saved document against an independent route:
//   - a joint made C1 with the handle-mode key 3 (mirrored): before, the library's continuity
//     analysis (jointContinuity on the two segments read from the file) and `freeform continuity`
//     say C0; after, C1 and G1; the opposite handle sits where the hand formula puts it
//     (p3 + (h1 / h0) (p3 - p2)), every other point is where it was;
//   - a lattice fitted to an imported OBJ mesh (L), one lattice point dragged, the det J colour map
//     switched on and the deformed mesh exported through the lattice panel: the exported vertex
//     lines equal, character for character, those `freeform ffd` writes for the same mesh and the
//     lattice taken out of the saved document, and the file's other lines are the input's;
//   - all joints of a free cubic spline set to C2 through the panel's "all joints" combo: C2 at every
//     joint by the library's analysis and the CLI, the hand-computed first moved handle, the left
//     points of each joint unmoved; Ctrl+Z gives the original bytes back;
//   - a curve drawn by clicking (C, clicks, Enter): its control points project exactly onto the
//     clicked pixels and lie in the view plane through the scene's centre; Ctrl+Z removes it.
//
// The panel widgets are clicked at fixed pixels: the Properties window opens at a fixed place and
// size (no ini file), and after scrolling it to the end the last rows of a tool panel sit at fixed
// heights above its bottom edge. If the panels change, these tests fail (no export, no mode
// change) rather than pass by accident; docs/images/replay/*.events.json use the same positions.

#include <catch2/catch.hpp>

#include <freeform/core/types.h>
#include <freeform/curve/continuity.h>

#include <nlohmann/json.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "interaction/replay.h"
#include "scene/scene.h"
#include "support/process.h"
#include "support/replay_session.h"
#include "support/text_lines.h"

namespace test_render_tools {

using namespace freeform;
using namespace freeform::editor;
using namespace freeform::editor::replay_test;
using Json = nlohmann::ordered_json;
using freeform::test::lines;

namespace {

namespace fs = std::filesystem;

// The Properties window (ui/ui.cpp): 290 pixels wide, 8 from the right edge, 420 high, 8 below the
// 19-pixel menu bar; so its bottom edge is at y = 447.
constexpr double kPanelBottom = 19 + 8 + 420;
const Eigen::Vector2d kPanelScroll(1100, 60); // over the panel, off its scrolling child windows

/// A camera looking from the front right above (as the editor saves it).
Json camera(const Eigen::Vector3d& target, double distance) { return frontRightCamera(target, distance); }

/// Writes `j` and lets the editor save it once, so that a load and a save reproduce it byte for byte.
std::string writeDocument(const std::string& name, const Json& j)
{
    const std::string source = cat(kTmp, "/tools_", name, ".source.json"), doc = cat(kTmp, "/tools_", name, ".json");
    test::writeText(source, j.dump(2));
    const auto r = runEditor(cat("'", source, "' --save '", doc, "'"));
    INFO(r.err);
    REQUIRE(r.status == 0);
    return doc;
}

/// Runs a replay of `events` on `doc` and returns the saved file.
std::string replay(const std::string& doc, const std::string& name, const Json& events)
{
    return replayAndSave(doc, cat("tools_", name), events);
}

/// A click and one frame after it.
void clickFrame(Json& events, const Eigen::Vector2d& p)
{
    click(events, p);
    events.push_back(frames(1));
}

/// Scrolls the Properties window to its end.
void scrollPanelToEnd(Json& events)
{
    events.push_back({{"type", "scroll"}, {"dy", -30}, {"x", kPanelScroll.x()}, {"y", kPanelScroll.y()}});
    events.push_back(frames(2));
}

Eigen::Vector3d vec(const Json& p) { return {p[0].get<double>(), p[1].get<double>(), p[2].get<double>()}; }

/// The points of the object named `name` in a saved document.
std::vector<Eigen::Vector3d> savedPoints(const std::string& path, const std::string& name)
{
    const Json j = Json::parse(test::slurp(path));
    for (const Json& o : j["objects"])
        if (o["name"] == name) {
            std::vector<Eigen::Vector3d> out;
            for (const Json& p : o["points"]) out.push_back(vec(p));
            return out;
        }
    FAIL("no object " << name << " in " << path);
    return {};
}

/// The continuity of every inner joint of an open cubic spline, by the library's analysis of the
/// segments themselves (not through the editor's tools).
std::vector<JointContinuity<double>> jointsOf(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& intervals)
{
    std::vector<JointContinuity<double>> out;
    auto segment = [&](std::size_t i) {
        PointMatrix<double, 3> s(3, 4);
        for (int k = 0; k < 4; ++k) s.col(k) = points[3 * i + static_cast<std::size_t>(k)];
        return s;
    };
    for (std::size_t i = 0; i + 1 < intervals.size(); ++i)
        out.push_back(jointContinuity<double, 3>(segment(i), segment(i + 1), intervals[i], intervals[i + 1]));
    return out;
}

/// `freeform continuity` of the spline: the (C, G) of each joint.
std::vector<std::pair<int, int>> cliContinuity(const std::string& doc, const std::string& name)
{
    const auto r = test::cli(cat("continuity '", doc, "' --object ", name));
    INFO(r.err);
    REQUIRE(r.status == 0);
    std::vector<std::pair<int, int>> out;
    const Json report = Json::parse(r.out);
    for (const Json& j : report["joints"]) out.emplace_back(j["C"].get<int>(), j["G"].get<int>());
    return out;
}

bool startsWith(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

} // namespace

TEST_CASE("the mirrored handle mode (key 3) makes a C0 joint C1 by the continuity analysis", "[render][replay][tools]")
{
    // Two cubic segments on intervals 1 and 2 meeting at p3 with a kink.
    const std::vector<Eigen::Vector3d> points = {{-3, 0, 0}, {-2.5, 0, 1.5}, {-1, 0.5, 2}, {0, 0, 1}, {1, 0, 2}, {2.5, 0, 1}, {3, 0, 0}};
    const std::vector<double> intervals = {1, 2};
    Json pts = Json::array();
    for (const auto& p : points) pts.push_back({p.x(), p.y(), p.z()});
    const std::string doc = writeDocument(
        "mirror", {{"format", "freeform"},
                   {"version", 1},
                   {"objects", {{{"name", "s"}, {"type", "bezier_spline"}, {"degree", 3}, {"points", pts}, {"intervals", intervals}}}},
                   {"editor", {{"camera", camera({0, 0, 0.75}, 11)}}}});

    const auto before = jointsOf(savedPoints(doc, "s"), intervals);
    REQUIRE(before.size() == 1);
    CHECK(before[0].C == 0);
    CHECK(before[0].G == 0);
    CHECK(cliContinuity(doc, "s") == std::vector<std::pair<int, int>>{{0, 0}});

    const Scene scene = Scene::load(doc);
    Json events = Json::array();
    clickFrame(events, worldToPixel(scene, kW, kH, points[0])); // selects the spline
    clickFrame(events, worldToPixel(scene, kW, kH, points[3])); // selects the joint point
    events.push_back(key("3"));
    const std::string out = replay(doc, "mirror", events);

    const std::vector<Eigen::Vector3d> after = savedPoints(out, "s");
    REQUIRE(after.size() == points.size());
    // The joint keeps its left handle; the right one goes to p3 + (h1 / h0) (p3 - p2) = (2, -1, -1).
    CHECK(after[4] == Eigen::Vector3d(2, -1, -1));
    for (std::size_t k : {0, 1, 2, 3, 5, 6}) CHECK(after[k] == points[k]);
    const auto joints = jointsOf(after, intervals);
    CHECK(joints[0].C == 1);
    CHECK(joints[0].G == 1);
    CHECK(joints[0].jumps[1] < 1e-12);
    CHECK(cliContinuity(out, "s") == std::vector<std::pair<int, int>>{{1, 1}});
    // The mode is saved with the spline (joints 0 and 2 are its ends).
    const Json saved = Json::parse(test::slurp(out))["objects"][0];
    CHECK(saved["editor"]["joints"] == Json::array({"free", "mirrored", "free"}));
}

TEST_CASE("a lattice fitted to an imported mesh, dragged and exported, gives freeform ffd's mesh", "[render][replay][tools]")
{
    const std::string mesh = cat(FREEFORM_SOURCE_DIR, "/data/meshes/sphere.obj");
    Json meshes = Json::array({{{"name", "sphere"}, {"path", mesh}}});
    const std::string doc = writeDocument("ffd", {{"format", "freeform"},
                                                  {"version", 1},
                                                  {"objects", Json::array()},
                                                  {"editor", {{"camera", camera({0, 0, 0}, 7)}, {"meshes", meshes}}}});
    const Scene scene = Scene::load(doc);

    // Phase 1: select the mesh (a click on its middle) and fit a lattice (L, degrees 3 x 3 x 3).
    Json fit = Json::array();
    clickFrame(fit, worldToPixel(scene, kW, kH, Eigen::Vector3d::Zero()));
    fit.push_back(key("L"));
    const std::string fitted = replay(doc, "ffd_fit", fit);
    const std::vector<Eigen::Vector3d> rest = savedPoints(fitted, "sphere_lattice");
    REQUIRE(rest.size() == 64);

    // Phase 2: the same, then drag lattice point 63 (the corner at (s, t, u) = (1, 1, 1)), switch
    // the det J colour map on and export the deformed mesh through the lattice panel.
    const std::string exported = kTmp + "/tools_ffd_exported.obj", reference = kTmp + "/tools_ffd_reference.obj";
    fs::remove(exported);
    Json events = fit;
    const Eigen::Vector2d corner = worldToPixel(scene, kW, kH, rest[63]);
    drag(events, corner, corner + Eigen::Vector2d(43, -34));
    events.push_back(key("Escape")); // deselects the point (the lattice stays selected)
    scrollPanelToEnd(events);
    clickFrame(events, {1000, kPanelBottom - 64});           // "det J colour map"
    clickFrame(events, {1080, kPanelBottom - 41});           // the export path field
    events.push_back(key("A", {"ctrl"}));               // select its text ...
    events.push_back({{"type", "text"}, {"text", exported}}); // ... and type over it
    events.push_back(key("Enter"));
    clickFrame(events, {1220, kPanelBottom - 41});           // "export deformed"
    const std::string out = replay(doc, "ffd", events);
    REQUIRE(fs::exists(exported));

    // Exactly point 63 moved.
    const std::vector<Eigen::Vector3d> moved = savedPoints(out, "sphere_lattice");
    REQUIRE(moved.size() == 64);
    for (std::size_t k = 0; k < 63; ++k) CHECK(moved[k] == rest[k]);
    CHECK((moved[63] - rest[63]).norm() > 0.1);
    const Json saved = Json::parse(test::slurp(out));
    CHECK(saved["objects"][0]["editor"]["ffd"]["mesh"] == "sphere");
    CHECK(saved["editor"]["display"]["analysis"] == "scalar_map");

    // The lattice from the saved document, by itself, through the command-line tool.
    Json lattice = saved["objects"][0];
    lattice.erase("editor");
    const std::string latticeFile = kTmp + "/tools_ffd_lattice.json";
    test::writeText(latticeFile, Json{{"format", "freeform"}, {"version", 1}, {"objects", Json::array({lattice})}}.dump(1));
    fs::remove(reference);
    const auto r = test::cli(cat("ffd '", mesh, "' --lattice '", latticeFile, "' -o '", reference, "'"));
    INFO(r.err);
    REQUIRE(r.status == 0);

    const std::vector<std::string> ours = lines(test::slurp(exported)), theirs = lines(test::slurp(reference)),
                                   input = lines(test::slurp(mesh));
    REQUIRE(ours.size() == input.size());
    REQUIRE(theirs.size() == input.size());
    int vertices = 0, changed = 0;
    for (std::size_t i = 0; i < ours.size(); ++i) {
        if (startsWith(input[i], "v ")) {
            ++vertices;
            CHECK(ours[i] == theirs[i]);
            changed += ours[i] != input[i];
        } else if (!startsWith(input[i], "vn ")) {
            CHECK(ours[i] == input[i]); // faces, texture coordinates, groups, comments
        }
    }
    CHECK(vertices == 266);
    CHECK(changed > 10); // the corner's move reaches a good part of the sphere
}

TEST_CASE("all joints of a cubic spline set to C2 through the panel are C2; undo gives the file back", "[render][replay][tools]")
{
    const std::vector<Eigen::Vector3d> points = {{-4.5, 0, 0}, {-4, 0, 1.5},  {-2.5, 0.5, 2}, {-1.5, 0, 1},   {-0.5, 0, 2},
                                                 {0.5, -0.5, 1}, {1.5, 0, 0}, {2.5, 0, 1},    {3.5, 0.5, 1.5}, {4.5, 0, 0}};
    const std::vector<double> intervals = {1, 2, 1.5};
    Json pts = Json::array();
    for (const auto& p : points) pts.push_back({p.x(), p.y(), p.z()});
    const std::string doc = writeDocument(
        "c2", {{"format", "freeform"},
               {"version", 1},
               {"objects", {{{"name", "s"}, {"type", "bezier_spline"}, {"degree", 3}, {"points", pts}, {"intervals", intervals}}}},
               {"editor", {{"camera", camera({0.5, 0.25, 0.5}, 15)}}}});
    for (const auto& j : jointsOf(points, intervals)) CHECK(j.C == 0);

    const Scene scene = Scene::load(doc);
    Json events = Json::array();
    clickFrame(events, worldToPixel(scene, kW, kH, points[0]));
    scrollPanelToEnd(events);
    // The spline panel ends with the joints table (two rows); the "all joints" combo is above it,
    // and its list opens below it: free, aligned, mirrored, C2.
    clickFrame(events, {1040, kPanelBottom - 85});
    clickFrame(events, {1020, kPanelBottom - 10});
    const std::string out = replay(doc, "c2", events);

    const std::vector<Eigen::Vector3d> after = savedPoints(out, "s");
    REQUIRE(after.size() == points.size());
    // The joints stay exactly where they were, the end handles (the end tangents) up to rounding;
    // the inner handles are those of the C2 interpolant of the joints.
    for (std::size_t k : {0, 3, 6, 9}) CHECK(after[k] == points[k]);
    for (std::size_t k : {1, 8}) CHECK((after[k] - points[k]).norm() < 1e-12);
    for (std::size_t k : {2, 4, 5, 7}) CHECK((after[k] - points[k]).norm() > 1e-3); // they had to move
    const auto joints = jointsOf(after, intervals);
    REQUIRE(joints.size() == 2);
    for (const auto& j : joints) {
        INFO("joint " << &j - joints.data() + 1 << " jumps " << j.jumps[1] << " " << j.jumps[2]);
        CHECK(j.C == 2);
        CHECK(j.G == 2);
    }
    CHECK(cliContinuity(out, "s") == std::vector<std::pair<int, int>>{{2, 2}, {2, 2}});
    CHECK(Json::parse(test::slurp(out))["objects"][0]["editor"]["joints"] == Json::array({"free", "c2", "c2", "free"}));

    // One undo step takes the modes and the points back.
    Json undone = events;
    undone.push_back(key("Z", {"ctrl"}));
    CHECK(test::slurp(replay(doc, "c2_undo", undone)) == test::slurp(doc));
}

TEST_CASE("a curve drawn by clicking has its points under the clicks, in the view plane", "[render][replay][tools]")
{
    const std::string doc = writeDocument(
        "draw", {{"format", "freeform"},
                 {"version", 1},
                 {"objects", {{{"name", "c"}, {"type", "bezier_curve"}, {"points", {{-2, 0, 0}, {-1, 0, 1.5}, {1, 0, 1.5}, {2, 0, 0}}}}}},
                 {"editor", {{"camera", camera({0, 0, 0.75}, 9)}}}});
    Scene scene = Scene::load(doc);
    scene.updateGeometry();
    const Eigen::Vector3d centre = scene.bounds().center();
    const std::vector<Eigen::Vector2d> clicks = {{420.25, 520}, {500, 300.5}, {700, 280}, {820.75, 560.125}};
    Json events = Json::array();
    events.push_back(key("C"));
    for (const auto& p : clicks) clickFrame(events, p);
    events.push_back(key("Enter"));
    const std::string out = replay(doc, "draw", events);

    const Json saved = Json::parse(test::slurp(out));
    REQUIRE(saved["objects"].size() == 2);
    CHECK(saved["objects"][1]["type"] == "bezier_curve");
    const std::vector<Eigen::Vector3d> drawn = savedPoints(out, saved["objects"][1]["name"].get<std::string>());
    REQUIRE(drawn.size() == clicks.size());
    // The plane through the centre of the scene's bounds, orthogonal to the viewing direction.
    const Eigen::Vector3d back = Eigen::Vector3d(1, -2, 1).normalized();
    for (std::size_t k = 0; k < drawn.size(); ++k) {
        const Eigen::Vector2d at = worldToPixel(scene, kW, kH, drawn[k]);
        INFO("point " << k << " at " << at.transpose() << ", clicked " << clicks[k].transpose());
        CHECK((at - clicks[k]).norm() < 1e-6);
        CHECK(std::abs((drawn[k] - centre).dot(back)) < 1e-9);
    }
    Json undone = events;
    undone.push_back(key("Z", {"ctrl"}));
    CHECK(test::slurp(replay(doc, "draw_undo", undone)) == test::slurp(doc));
}

TEST_CASE("a spline drawn with Shift+C passes through the clicks and is C2 by freeform continuity", "[render][replay][tools]")
{
    const std::string doc = writeDocument(
        "draw_spline", {{"format", "freeform"},
                        {"version", 1},
                        {"objects", {{{"name", "c"}, {"type", "bezier_curve"}, {"points", {{-2, 0, 0}, {-1, 0, 1.5}, {1, 0, 1.5}, {2, 0, 0}}}}}},
                        {"editor", {{"camera", camera({0, 0, 0.75}, 9)}}}});
    Scene scene = Scene::load(doc);
    scene.updateGeometry();
    const std::vector<Eigen::Vector2d> clicks = {{380, 520}, {480, 260}, {640, 470}, {760, 250.5}, {900, 540}};
    Json events = Json::array();
    events.push_back(key("C", {"shift"}));
    for (const auto& p : clicks) clickFrame(events, p);
    events.push_back(key("Enter"));
    const std::string out = replay(doc, "draw_spline", events);

    const Json saved = Json::parse(test::slurp(out));
    REQUIRE(saved["objects"].size() == 2);
    const Json& spline = saved["objects"][1];
    CHECK(spline["type"] == "bezier_spline");
    CHECK(spline["degree"] == 3);
    const std::vector<Eigen::Vector3d> points = savedPoints(out, spline["name"].get<std::string>());
    REQUIRE(points.size() == 3 * (clicks.size() - 1) + 1);
    for (std::size_t k = 0; k < clicks.size(); ++k) // the joints are under the clicks
        CHECK((worldToPixel(scene, kW, kH, points[3 * k]) - clicks[k]).norm() < 1e-6);
    // C2 at every inner joint, by the command-line tool on the saved file.
    CHECK(cliContinuity(out, spline["name"].get<std::string>()) == std::vector<std::pair<int, int>>{{2, 2}, {2, 2}, {2, 2}});
    CHECK(spline["editor"]["joints"] == Json::array({"free", "c2", "c2", "c2", "free"}));
    Json undone = events;
    undone.push_back(key("Z", {"ctrl"}));
    CHECK(test::slurp(replay(doc, "draw_spline_undo", undone)) == test::slurp(doc));
}

TEST_CASE("fit/apply lattice by --replay then --save writes freeform ffd's objects, number for number", "[render][replay][tools][ffd]")
{
    // data/ffd_every_type.json (every object type and the skewed cubic lattice "L", docs/ffd.md) with
    // absolute paths for its cage and mesh files and a camera, so the pixels of the lattice's points
    // are known, and control nets and points shown (a lattice is drawn as its net). The editor: a click on a lattice point selects "L", Shift+A applies it (the lattice
    // panel's "apply exactly to curves and patches"), --save writes the document. The command line:
    // `freeform ffd DOC --lattice DOC --object L -o OUT`. Both go through deformDocument; this test
    // ties the real window's input path to the command's output.
    Json source = Json::parse(test::slurp(cat(FREEFORM_SOURCE_DIR, "/data/ffd_every_type.json")));
    for (Json& o : source["objects"])
        if (o["type"] == "subdivision_surface" && o.contains("mesh")) o["mesh"] = cat(FREEFORM_SOURCE_DIR, "/data/", o["mesh"].get<std::string>());
    for (Json& m : source["editor"]["meshes"]) m["path"] = cat(FREEFORM_SOURCE_DIR, "/data/", m["path"].get<std::string>());
    source["editor"]["camera"] = camera({0.5, 0, 0.25}, 16);
    source["editor"]["display"] = {{"control_nets", true}, {"control_points", true}}; // the lattice's points show, and pick
    const std::string doc = writeDocument("every_type", source);

    const std::string cliOut = cat(kTmp, "/tools_every_type.cli.json");
    fs::remove(cliOut);
    const auto r = test::cli(cat("ffd '", doc, "' --lattice '", doc, "' --object L -o '", cliOut, "'"));
    INFO(r.err);
    REQUIRE(r.status == 0);

    // The lattice point whose pixel lies farthest from the pixel of the objects' centre: outside
    // every other object on screen (they lie in [-1, 1]^3, the lattice box is larger).
    const Scene scene = Scene::load(doc);
    const Eigen::Vector2d centre = worldToPixel(scene, kW, kH, Eigen::Vector3d::Zero());
    Eigen::Vector2d target = centre;
    for (const Json& o : source["objects"])
        if (o["name"] == "L")
            for (const Json& p : o["points"]) {
                const Eigen::Vector2d px = worldToPixel(scene, kW, kH, vec(p));
                const bool onScreen = px.x() > 260 && px.x() < kW - 310 && px.y() > 40 && px.y() < kH - 40; // off the panels
                if (onScreen && (px - centre).norm() > (target - centre).norm()) target = px;
            }
    REQUIRE(target != centre);
    Json events = Json::array();
    clickFrame(events, target);
    events.push_back(key("A", {"shift"}));
    events.push_back(frames(2));
    const std::string out = replay(doc, "every_type", events);

    const Json editor = Json::parse(test::slurp(out)), cli = Json::parse(test::slurp(cliOut));
    REQUIRE(editor["objects"].size() == cli["objects"].size());
    const Json before = Json::parse(test::slurp(doc));
    std::set<std::string> changed;
    for (std::size_t k = 0; k < cli["objects"].size(); ++k) {
        Json a = editor["objects"][k], b = cli["objects"][k], o = before["objects"][k];
        a.erase("editor");
        b.erase("editor");
        o.erase("editor");
        INFO("object " << b["name"]);
        CHECK(a == b); // JSON numbers compare as doubles: number for number
        if (b != o) changed.insert(b["name"].get<std::string>());
    }
    // The table of docs/ffd.md, "Documents", by hand: the 3D curve, splines (the de Boor one under
    // this non-affine lattice as a bezier_spline), the patches and the cage change; the 2D objects,
    // the de Boor surface (non-affine lattice: skipped) and the lattice itself stay.
    CHECK(changed == std::set<std::string>{"curve3", "spline3", "deboor3", "patch", "complex_a", "complex_b", "cage"});
}

} // namespace test_render_tools
