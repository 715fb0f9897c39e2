// More promises of docs/editor.md that had no test (issue 12; label "render": they need an X
// display). Each runs build/bin/freeform-editor through a replayed session and checks what it
// wrote against facts known here, independently of the editor:
//   - the lattice panel's `mesh` and `outside` combos, set as a user does it (a click on the combo,
//     a click on the entry of its open list, found through --state `widgets`): the saved lattice's
//     `outside` is the entry clicked; "(none)" unlinks the mesh (the saved link is gone and the
//     panel's read-out row, drawn only for a linked mesh, disappears), choosing the mesh again
//     links it back;
//   - the file chooser: a fake `zenity` first in PATH (it records its arguments and prints a path)
//     is never called by a headless run, which falls back to the dialog where the path is typed;
//     the typed path opens the document;
//   - reflection lines kink at an edge that is G1 but not G2: a patch pair built here as the height
//     fields z = y^2/3 (left) and z = y^2/3 + k x^2 (right), joined C1 at x = 0 with a jump of 2k in
//     z_xx; seen from above the stripes are straight along x on the left (the normal depends on y
//     only) and slanted on the right (slope -3k N^2 at the edge, derived by hand), and they meet at
//     the edge: every pixel dark or light as the stripe formula says, and the stripe edges measured
//     in the image have slope about 0 on the left, clearly negative on the right, and the same y at
//     x = 0 from both sides;
//   - the camera table, through the saved camera: 1 3 7 and Ctrl+1 3 7 give the eye axes written
//     by hand, 9 the isometric axes, 5 switches the projection, middle / right / Shift+left drags
//     pan by the hand-computed pixel size, a left drag orbits only past 3 pixels (turntable: the
//     eye's x stays horizontal), Home and F fit everything and the selected line;
//   - the keyboard table's Z, W, R, Ctrl+N and Ctrl+S, through the saved document.

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <Eigen/Core>

#include <cstdlib>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "image_compare.h"
#include "interaction/replay.h"
#include "scene/scene.h"
#include "support/process.h"
#include "support/replay_session.h"

namespace test_render_promises_more {

using namespace freeform;
using namespace freeform::editor;
using namespace freeform::editor::replay_test;
using Json = nlohmann::ordered_json;

namespace {

namespace fs = std::filesystem;

struct Run {
    test::ProcessResult process;
    Json state;
    Json saved; // the --save output (null when none)
};

Run replayRun(const std::string& doc, const std::string& name, const Json& events, bool save = true,
              const std::string& environment = "FREEFORM_NO_ZENITY=1")
{
    const std::string file = cat(kTmp, "/promises_more_", name, ".events.json"), state = cat(kTmp, "/promises_more_", name, ".state.json"),
                      out = cat(kTmp, "/promises_more_", name, ".out.json");
    test::writeText(file, Json{{"events", events}}.dump(1));
    fs::remove(state);
    fs::remove(out);
    std::string args = cat("'", doc, "' --replay '", file, "' --state '", state, "' --size ", kW, "x", kH);
    if (save) args += cat(" --save '", out, "'");
    Run r;
    r.process = runEditor(args, environment);
    INFO(r.process.err);
    REQUIRE(r.process.status == 0);
    REQUIRE(fs::exists(state));
    r.state = Json::parse(test::slurp(state));
    if (save) {
        REQUIRE(fs::exists(out));
        r.saved = Json::parse(test::slurp(out));
    }
    return r;
}

Eigen::Vector2d centre(const Json& rect)
{
    return {rect[0].get<double>() + 0.5 * rect[2].get<double>(), rect[1].get<double>() + 0.5 * rect[3].get<double>()};
}

void clickAt(Json& events, const Eigen::Vector2d& p)
{
    click(events, p);
    events.push_back(frames(2));
}

Json latticeOf(const Json& saved)
{
    for (const Json& o : saved["objects"])
        if (o["type"] == "lattice") return o;
    return nullptr;
}

std::string sphereObj() { return cat(FREEFORM_SOURCE_DIR, "/data/meshes/sphere.obj"); }

} // namespace

// ---------------------------------------------------------------- lattice panel: mesh, outside

TEST_CASE("the lattice panel's outside and mesh combos set by clicks; the read-out row only for a linked mesh", "[render][replay][ffd]")
{
    const Json camera = frontRightCamera(Eigen::Vector3d::Zero(), 7);
    const std::string doc = cat(kTmp, "/promises_more_lattice.json");
    test::writeText(doc, Json{{"format", "freeform"},
                              {"version", 1},
                              {"objects", Json::array()},
                              {"editor", {{"camera", camera}, {"meshes", Json::array({{{"name", "sphere"}, {"path", sphereObj()}}})}}}}
                             .dump(1));
    const Scene scene = Scene::load(doc);

    // Select the sphere (a click at its centre), fit a lattice (L): the lattice is selected and its
    // panel shows the combos and, the mesh being linked, the read-out.
    Json events = Json::array();
    clickAt(events, worldToPixel(scene, kW, kH, Eigen::Vector3d::Zero()));
    events.push_back(key("L"));
    events.push_back(frames(2));
    // Properties scrolled to its end (the wheel over it, just under its title bar: off its
    // scrolling child windows), where the lattice panel's rows are.
    const Json properties = replayRun(doc, "lattice_panels", events, false).state["panels"]["Properties"];
    events.push_back({{"type", "scroll"}, {"dy", -30}, {"x", centre(properties).x()}, {"y", properties[1].get<double>() + 35}});
    events.push_back(frames(2));
    const Run fitted = replayRun(doc, "lattice_fit", events);
    const Json lattice = latticeOf(fitted.saved);
    REQUIRE(lattice.is_object());
    CHECK(lattice["editor"]["ffd"]["mesh"] == "sphere");
    const Json widgets = fitted.state["widgets"];
    for (const char* name : {"mesh", "outside", "read-out"}) {
        INFO(name);
        REQUIRE(widgets.contains(name));
    }
    // The rows in the documented order: mesh, (strength), outside, (buttons), read-out.
    CHECK(widgets["mesh"][1].get<double>() < widgets["outside"][1].get<double>());
    CHECK(widgets["outside"][1].get<double>() < widgets["read-out"][1].get<double>());
    // The lists are closed: none of their entries is drawn.
    for (const auto& [name, rect] : widgets.items()) CHECK(name.find(": ") == std::string::npos);

    SECTION("outside: a click on the combo opens its three entries; a click on one saves it")
    {
        // The policy the fit wrote (docs/format.md: keep, clamp or extrapolate); the test picks
        // another one, so that the saved value can only come from the click.
        const std::string before = lattice.value("outside", std::string("clamp"));
        const std::string wanted = before == "extrapolate" ? "keep" : "extrapolate";
        Json open = events;
        clickAt(open, centre(widgets["outside"]));
        const Run opened = replayRun(doc, "lattice_outside_open", open, false);
        const Json& w = opened.state["widgets"];
        for (const char* entry : {"outside: keep", "outside: clamp", "outside: extrapolate"}) {
            INFO(entry);
            REQUIRE(w.contains(entry));
            // The list opens below the combo.
            CHECK(w[entry][1].get<double>() >= widgets["outside"][1].get<double>() + widgets["outside"][3].get<double>() - 1);
        }
        Json chosen = open;
        clickAt(chosen, centre(w[cat("outside: ", wanted)]));
        const Run done = replayRun(doc, "lattice_outside_set", chosen);
        CHECK(done.state["error"] == "");
        const Json saved = latticeOf(done.saved);
        REQUIRE(saved.is_object());
        CHECK(saved["outside"] == wanted);
        // Only the policy changed: the points are the fitted ones.
        CHECK(saved["points"] == lattice["points"]);
        // One undo step gives the policy back.
        Json undone = chosen;
        undone.push_back(key("Z", {"ctrl"}));
        undone.push_back(frames(2));
        const Json back = latticeOf(replayRun(doc, "lattice_outside_undo", undone).saved);
        CHECK(back.value("outside", std::string("clamp")) == before);
    }
    SECTION("mesh: \"(none)\" unlinks the mesh and the read-out goes; the mesh chosen again links it back")
    {
        Json open = events;
        clickAt(open, centre(widgets["mesh"]));
        const Run opened = replayRun(doc, "lattice_mesh_open", open, false);
        const Json& w = opened.state["widgets"];
        REQUIRE(w.contains("mesh: (none)"));
        REQUIRE(w.contains("mesh: sphere"));
        Json none = open;
        clickAt(none, centre(w["mesh: (none)"]));
        const Run unlinked = replayRun(doc, "lattice_mesh_none", none);
        const Json saved = latticeOf(unlinked.saved);
        REQUIRE(saved.is_object());
        const bool linked = saved.contains("editor") && saved["editor"].contains("ffd") && saved["editor"]["ffd"].contains("mesh") &&
                            saved["editor"]["ffd"]["mesh"] != "";
        CHECK_FALSE(linked);
        CHECK_FALSE(unlinked.state["widgets"].contains("read-out"));
        CHECK(unlinked.state["widgets"].contains("mesh"));

        // Open the list again and choose the sphere.
        Json again = none;
        clickAt(again, centre(unlinked.state["widgets"]["mesh"]));
        const Run reopened = replayRun(doc, "lattice_mesh_reopen", again, false);
        REQUIRE(reopened.state["widgets"].contains("mesh: sphere"));
        clickAt(again, centre(reopened.state["widgets"]["mesh: sphere"]));
        const Run relinked = replayRun(doc, "lattice_mesh_relink", again);
        CHECK(latticeOf(relinked.saved)["editor"]["ffd"]["mesh"] == "sphere");
        CHECK(relinked.state["widgets"].contains("read-out"));
    }
}

// ------------------------------------------------------------------------------- file chooser

TEST_CASE("headless runs never open the file chooser: a zenity first in PATH is not called; the typed path opens", "[render][replay][files]")
{
    // A fake zenity: records its arguments, prints a path, exits 0 (what the real one does when a
    // file is chosen).
    const std::string bin = cat(kTmp, "/promises_more_fakebin"), log = cat(kTmp, "/promises_more_zenity.log");
    fs::create_directories(bin);
    fs::remove(log);
    const std::string target = cat(kTmp, "/promises_more_target.json");
    test::writeText(target, Json{{"format", "freeform"},
                                 {"version", 1},
                                 {"objects", Json::array({{{"name", "t1"}, {"type", "bezier_curve"}, {"points", {{0, 0, 0}, {1, 0, 0}}}},
                                                          {{"name", "t2"}, {"type", "bezier_curve"}, {"points", {{0, 1, 0}, {1, 1, 0}}}},
                                                          {{"name", "t3"}, {"type", "bezier_curve"}, {"points", {{0, 2, 0}, {1, 2, 0}}}}})}}
                                .dump(1));
    test::writeText(cat(bin, "/zenity"), cat("#!/bin/sh\necho \"$@\" >> '", log, "'\necho '", target, "'\n"));
    fs::permissions(cat(bin, "/zenity"), fs::perms::owner_all);
    const std::string environment = cat("PATH='", bin, "':\"$PATH\" FREEFORM_NO_ZENITY=0");
    // The fake is what `command -v zenity` finds with that PATH (the editor's own test), and it
    // works: it prints the target and logs its arguments.
    const auto found = test::run(cat(environment, " sh -c 'command -v zenity'"));
    REQUIRE(found.status == 0);
    CHECK(found.out.find(cat(bin, "/zenity")) != std::string::npos);
    const auto tried = test::run(cat(environment, " zenity --probe"));
    CHECK(tried.out.find(target) != std::string::npos);
    REQUIRE(fs::exists(log));
    fs::remove(log);
    REQUIRE(std::getenv("DISPLAY") != nullptr); // a display is there: only headlessness keeps zenity away

    const std::string doc = cat(kTmp, "/promises_more_start.json");
    test::writeText(doc, Json{{"format", "freeform"},
                              {"version", 1},
                              {"objects", Json::array({{{"name", "a"}, {"type", "bezier_curve"}, {"points", {{0, 0, 0}, {1, 1, 0}}}}})}}
                             .dump(1));
    SECTION("Ctrl+O opens the typed-path dialog, not the chooser")
    {
        const Run r = replayRun(doc, "chooser_open", Json::array({key("O", {"ctrl"}), frames(2)}), false, environment);
        CHECK(r.state["path_dialog"] == true);
        CHECK(r.state["objects"] == 1);
        CHECK_FALSE(fs::exists(log));
    }
    SECTION("the typed path, confirmed with Enter, opens that document")
    {
        const Json events = Json::array({key("O", {"ctrl"}), frames(2), key("A", {"ctrl"}), {{"type", "text"}, {"text", target}},
                                         key("Enter"), frames(2)});
        const Run r = replayRun(doc, "chooser_typed", events, true, environment);
        CHECK(r.state["error"] == "");
        CHECK(r.state["path_dialog"] == false);
        CHECK(r.state["objects"] == 3);
        REQUIRE(r.saved["objects"].size() == 3);
        CHECK(r.saved["objects"][2]["name"] == "t3");
        CHECK_FALSE(fs::exists(log));
    }
    SECTION("Save as (Ctrl+Shift+S), Import (Ctrl+I) and Export (Ctrl+E) do not call it either")
    {
        for (const char* k : {"S", "I", "E"}) {
            INFO(k);
            const std::vector<std::string> mods = std::string(k) == "S" ? std::vector<std::string>{"ctrl", "shift"} : std::vector<std::string>{"ctrl"};
            const Run r = replayRun(doc, cat("chooser_", k), Json::array({key(k, mods), frames(2)}), false, environment);
            CHECK(r.state["path_dialog"] == true);
        }
        CHECK_FALSE(fs::exists(log));
    }
}

// ---------------------------------------------------------------- reflection lines: G1 kink

TEST_CASE("reflection lines kink at a G1 edge that is not G2: straight on one side, slanted on the other, joined at the edge", "[render][reflection]")
{
    // Two biquadratic patches over x in [-1.5, 0] and [0, 1.5], y in [-0.75, 0.75], control points
    // evenly spaced in x and y, heights X_i + Y_j: Y = (0.1875, -0.1875, 0.1875) are the Bezier
    // coefficients of y^2 / 3 on [-0.75, 0.75] (y0^2/3, (y0^2 + y0 L)/3, (y0 + L)^2/3 with
    // y0 = -0.75, L = 1.5), X = (0, 0, 0) on the left and (0, 0, 2.25 k) on the right, those of
    // k x^2 on [0, 1.5]. At x = 0 both have z_x = 0 (C1, so G1); z_xx is 0 and 2k (not G2).
    constexpr double k = 0.2, kStripes = 12, gamma = M_PI / 4;
    auto patch = [&](const std::string& name, double x0, bool right) {
        Json rows = Json::array();
        const double X[3] = {0, 0, right ? 2.25 * k : 0}, Y[3] = {0.1875, -0.1875, 0.1875};
        for (int i = 0; i < 3; ++i) {
            Json row = Json::array();
            for (int j = 0; j < 3; ++j) row.push_back({x0 + 0.75 * i, -0.75 + 0.75 * j, X[i] + Y[j]});
            rows.push_back(row);
        }
        return Json{{"name", name}, {"type", "bezier_surface"}, {"degree", {2, 2}}, {"points", rows}};
    };
    auto height = [&](double x, double y) { return y * y / 3 + (x > 0 ? k * x * x : 0); };
    // Seen from above, orthographic, turned 45 degrees about the view axis (the eye's x is
    // (cos 45, sin 45, 0)): phase = 12 n.x_eye with n = (-z_x, -z_y, 1) / N.
    const Eigen::Vector3d ex(std::cos(gamma), std::sin(gamma), 0);
    auto phaseDistance = [&](double x, double y) {
        const double zx = x > 0 ? 2 * k * x : 0, zy = 2 * y / 3;
        const double phase = kStripes * Eigen::Vector3d(-zx, -zy, 1).normalized().dot(ex);
        return std::abs(phase - std::round(phase));
    };
    const Eigen::Quaterniond q(Eigen::AngleAxisd(gamma, Eigen::Vector3d::UnitZ()));
    const Json camera = {{"target", {0.0, 0.0, 0.2}}, {"distance", 6.0}, {"orientation", {q.w(), q.x(), q.y(), q.z()}},
                         {"fovy", 35.0}, {"projection", "orthographic"}, {"orbit", "turntable"}};
    const Json editor = {{"camera", camera},
                         {"display", {{"analysis", "reflection_lines"}, {"grid", false}, {"axes", false}, {"background", {0.5, 0.5, 0.5}}}}};
    const std::string doc = cat(kTmp, "/promises_more_g1.json"), png = cat(kTmp, "/promises_more_g1.png");
    test::writeText(doc, Json{{"format", "freeform"}, {"version", 1}, {"objects", Json::array({patch("left", -1.5, false), patch("right", 0, true)})}, {"editor", editor}}.dump(1));
    fs::remove(png);
    const auto r = runEditor(cat("'", doc, "' --screenshot '", png, "' --no-ui --size ", kW, "x", kH));
    INFO(r.err);
    REQUIRE(r.status == 0);
    const test::RgbImage image = test::loadPng(png);
    REQUIRE(image.width == kW);
    const Scene scene = Scene::load(doc);
    auto pixel = [&](double x, double y) { return worldToPixel(scene, kW, kH, {x, y, height(x, y)}); };
    for (double x : {-1.5, 1.5})
        for (double y : {-0.75, 0.75}) {
            const Eigen::Vector2d p = pixel(x, y); // the whole pair in the picture
            REQUIRE(p.x() >= 0);
            REQUIRE(p.x() < kW);
            REQUIRE(p.y() >= 0);
            REQUIRE(p.y() < kH);
        }
    const double scale = (pixel(1, 0) - pixel(0, 0)).norm(); // pixels per world unit (orthographic)
    REQUIRE(scale > 150);
    auto dark = [](const unsigned char* c) { return c[0] < 40 && c[1] < 40 && c[2] < 40; };
    auto light = [](const unsigned char* c) { return c[0] > 215 && c[1] > 215 && c[2] > 215; };

    // 1. Every pixel clearly on or off a stripe is dark or light as the formula says.
    long agree = 0, disagree = 0;
    const double margin = 4 / scale;
    for (double x = -1.5 + margin; x < 1.5 - margin; x += 0.5 / scale)
        for (double y = -0.75 + margin; y < 0.75 - margin; y += 0.5 / scale) {
            const Eigen::Vector2d p = pixel(x, y);
            const unsigned char* c = image.at(static_cast<int>(p.x()), static_cast<int>(p.y()));
            const double d = phaseDistance(x, y);
            if (d < 0.25 - 0.06) (dark(c) ? agree : disagree) += 1;
            else if (d > 0.25 + 0.06) (light(c) ? agree : disagree) += 1;
        }
    INFO(agree << " samples as the formula says, " << disagree << " not");
    CHECK(agree > 100000);
    CHECK(disagree <= agree / 1000);

    // 2. The stripe edges (dark <-> light) measured in the image along four world columns, two on
    // each side of the edge: y of each edge, from the samples' classification.
    // Each edge is kept with its kind (+1: dark below, light above; -1: the other way), and only
    // edges of one kind are matched across columns (edges of one kind are a stripe period apart).
    auto edges = [&](double x) {
        std::vector<std::pair<double, int>> ys;
        int last = 0; // 1 dark, -1 light, 0 none yet
        double lastY = 0;
        for (double y = -0.7; y <= 0.7; y += 0.25 / scale) {
            const Eigen::Vector2d p = pixel(x, y);
            const unsigned char* c = image.at(static_cast<int>(p.x()), static_cast<int>(p.y()));
            const int now = dark(c) ? 1 : light(c) ? -1 : 0;
            if (now == 0) continue;
            if (last != 0 && now != last) ys.emplace_back(0.5 * (lastY + y), last);
            last = now;
            lastY = y;
        }
        return ys;
    };
    const double a = 0.02, b = 0.06;
    const auto l2 = edges(-b), l1 = edges(-a), r1 = edges(a), r2 = edges(b);
    INFO("edges: " << l2.size() << ", " << l1.size() << " | " << r1.size() << ", " << r2.size());
    // The same stripe edge on the four columns: from each edge at x = -0.02 with |y| < 0.5, the
    // nearest edge of its kind on the next column (those are 0.08 or more apart; a stripe moves by
    // less than 0.03 between neighbouring columns).
    auto nearest = [](const std::vector<std::pair<double, int>>& ys, double y, int kind) {
        double best = 1e9;
        for (const auto& [v, k] : ys)
            if (k == kind && std::abs(v - y) < std::abs(best - y)) best = v;
        return best;
    };
    double worstLeftSlope = 0, worstJoin = 0, leastRightSlope = 1e9, worstRightVsHand = 0;
    int matched = 0;
    for (const auto& [yl1, kind] : l1) {
        if (std::abs(yl1) > 0.5) continue;
        const double yl2 = nearest(l2, yl1, kind), yr1 = nearest(r1, yl1, kind), yr2 = nearest(r2, yr1, kind);
        INFO("edge at y = " << yl1 << ": " << yl2 << ", " << yl1 << " | " << yr1 << ", " << yr2);
        REQUIRE(std::abs(yl2 - yl1) < 0.05);
        REQUIRE(std::abs(yr1 - yl1) < 0.05);
        REQUIRE(std::abs(yr2 - yr1) < 0.05);
        ++matched;
        const double left = (yl1 - yl2) / (b - a), right = (yr2 - yr1) / (b - a);
        worstLeftSlope = std::max(worstLeftSlope, std::abs(left));
        leastRightSlope = std::min(leastRightSlope, -right);
        // Joined: both sides' lines continued to x = 0 meet.
        worstJoin = std::max(worstJoin, std::abs((yl1 + a * left) - (yr1 - a * right)));
        // The hand slope on the right at the edge: -f_x / f_y of f = n.x_eye, which at x = 0 is
        // -3 k N^2 with N^2 = 1 + (2y/3)^2 (f_x = -2k cos45 / N, f_y = -(2/3) sin45 / N^3).
        const double y = 0.5 * (yl1 + yr1), hand = -3 * k * (1 + 4 * y * y / 9);
        worstRightVsHand = std::max(worstRightVsHand, std::abs(right - hand));
    }
    CHECK(matched >= 8);
    INFO("left slopes within " << worstLeftSlope << ", right slopes at least " << leastRightSlope << " downwards (off the hand slope by "
                               << worstRightVsHand << "), the two sides meet at x = 0 within " << worstJoin * scale << " px");
    CHECK(worstLeftSlope < 0.05);           // straight along x on the G1-only side's flat neighbour
    CHECK(leastRightSlope > 0.45);          // a kink: the direction turns by more than 24 degrees
    CHECK(worstRightVsHand < 0.15);         // as the hand slope says (it drifts a little over 0.02 .. 0.06)
    CHECK(worstJoin * scale < 2.5);         // joined, not broken (a C0 edge would break them)
}

// ------------------------------------------------------------------------------ camera table

namespace {

/// The saved camera's eye axes in world coordinates: right (eye x), up (eye y), back (eye z).
struct Axes {
    Eigen::Vector3d right, up, back, target;
    double distance = 0;
    std::string projection;
};

Axes savedCamera(const Json& saved)
{
    const Json& c = saved["editor"]["camera"];
    const Eigen::Quaterniond q(c["orientation"][0].get<double>(), c["orientation"][1].get<double>(), c["orientation"][2].get<double>(),
                               c["orientation"][3].get<double>());
    const Eigen::Matrix3d m = q.normalized().toRotationMatrix();
    Axes a;
    a.right = m.col(0);
    a.up = m.col(1);
    a.back = m.col(2);
    a.target = Eigen::Vector3d(c["target"][0].get<double>(), c["target"][1].get<double>(), c["target"][2].get<double>());
    a.distance = c["distance"].get<double>();
    a.projection = c["projection"].get<std::string>();
    return a;
}

Json buttonEvent(const char* type, const char* button, const Eigen::Vector2d& p, const std::vector<std::string>& mods = {})
{
    Json e = {{"type", type}, {"button", button}, {"x", p.x()}, {"y", p.y()}};
    if (!mods.empty()) e["mods"] = mods;
    return e;
}

/// A drag with `button` from `from` by `by` pixels in 4 steps.
Json dragWith(const char* button, const Eigen::Vector2d& from, const Eigen::Vector2d& by, const std::vector<std::string>& mods = {})
{
    Json events = Json::array();
    Json m = move(from);
    if (!mods.empty()) m["mods"] = mods;
    events.push_back(m);
    events.push_back(buttonEvent("press", button, from, mods));
    events.push_back(frames(1));
    for (int s = 1; s <= 4; ++s) {
        Json step = move(from + by * s / 4.0);
        if (!mods.empty()) step["mods"] = mods;
        events.push_back(step);
        events.push_back(frames(1));
    }
    events.push_back(buttonEvent("release", button, from + by, mods));
    events.push_back(frames(2));
    return events;
}

} // namespace

TEST_CASE("the camera table: axis-view keys, isometric, perspective/orthographic, pan by three inputs, the 3-pixel orbit threshold", "[render][replay][camera]")
{
    // A perspective camera from the front right above at distance 10, target (1, 2, 3); two short
    // lines, (5, 5, 5) to (7, 9, 5) and (-5, -3, 0) to (-3, -3, 0), aside of the target, so that
    // every press at the window's centre lands on empty space.
    Json camera = frontRightCamera(Eigen::Vector3d(1, 2, 3), 10);
    const std::string doc = cat(kTmp, "/promises_more_camera.json");
    const Json line = {{"name", "l"}, {"type", "bezier_curve"}, {"points", {{5, 5, 5}, {7, 9, 5}}}};
    const Json other = {{"name", "m"}, {"type", "bezier_curve"}, {"points", {{-5, -3, 0}, {-3, -3, 0}}}};
    test::writeText(doc, Json{{"format", "freeform"}, {"version", 1}, {"objects", Json::array({line, other})},
                              {"editor", {{"camera", camera}, {"display", {{"grid", false}, {"axes", false}}}}}}
                             .dump(1));
    const Axes start = savedCamera(replayRun(doc, "camera_start", Json::array({frames(1)})).saved);
    REQUIRE(start.distance == Approx(10));
    const Eigen::Vector3d x = Eigen::Vector3d::UnitX(), y = Eigen::Vector3d::UnitY(), z = Eigen::Vector3d::UnitZ();

    SECTION("1 3 7 and with Ctrl the opposite sides: the eye's right and up axes, by hand; the target and distance stay")
    {
        struct View {
            const char* key;
            bool ctrl;
            Eigen::Vector3d right, up; // the view direction is -(right x up)
        };
        const View views[] = {{"1", false, x, z},  {"3", false, y, z},  {"7", false, x, y},
                              {"1", true, -x, z},  {"3", true, -y, z},  {"7", true, x, -y}};
        for (const View& v : views) {
            INFO((v.ctrl ? "Ctrl+" : "") << v.key);
            const Axes a = savedCamera(replayRun(doc, "camera_view", Json::array({key(v.key, v.ctrl ? std::vector<std::string>{"ctrl"} : std::vector<std::string>{}), frames(2)})).saved);
            CHECK((a.right - v.right).norm() < 1e-9);
            CHECK((a.up - v.up).norm() < 1e-9);
            CHECK((a.target - start.target).norm() < 1e-9);
            CHECK(a.distance == Approx(start.distance));
        }
        // 1 looks along +y, 3 (right) along -x, 7 (top) along -z: -back.
        const Axes front = savedCamera(replayRun(doc, "camera_front", Json::array({key("1"), frames(2)})).saved);
        CHECK((-front.back - y).norm() < 1e-9);
    }
    SECTION("9: the isometric view from the front right above, back = (1, -1, 1) / sqrt 3, the horizon level")
    {
        const Axes a = savedCamera(replayRun(doc, "camera_iso", Json::array({key("1"), frames(1), key("9"), frames(2)})).saved);
        CHECK((a.back - Eigen::Vector3d(1, -1, 1) / std::sqrt(3.0)).norm() < 1e-9);
        CHECK((a.right - Eigen::Vector3d(1, 1, 0) / std::sqrt(2.0)).norm() < 1e-9);
        CHECK(std::abs(a.right.z()) < 1e-12);
    }
    SECTION("5 switches perspective and orthographic, and back")
    {
        CHECK(start.projection == "perspective");
        CHECK(savedCamera(replayRun(doc, "camera_5", Json::array({key("5"), frames(2)})).saved).projection == "orthographic");
        CHECK(savedCamera(replayRun(doc, "camera_55", Json::array({key("5"), frames(2), key("5"), frames(2)})).saved).projection == "perspective");
    }
    SECTION("middle drag, right drag and Shift + left drag pan: the target moves in the view plane, the point under the pointer follows it")
    {
        // In a perspective view a pixel at the target's depth is 2 d tan(fovy / 2) / H world units.
        const double s = 2 * 10 * std::tan(35.0 / 2 * M_PI / 180) / kH;
        const Eigen::Vector2d from(640, 400), by(60, -40);
        // The scene under the pointer moves with it: the target moves the other way, by -60 px
        // along right and -40 px along up (pixel y points down).
        const Eigen::Vector3d expected = start.target - s * (by.x() * start.right - by.y() * start.up);
        for (const auto& [button, mods] : std::vector<std::pair<const char*, std::vector<std::string>>>{
                 {"middle", {}}, {"right", {}}, {"left", {"shift"}}}) {
            INFO(button << (mods.empty() ? "" : " with Shift"));
            const Axes a = savedCamera(replayRun(doc, "camera_pan", dragWith(button, from, by, mods)).saved);
            INFO("target moved by " << (a.target - start.target).transpose() << ", expected " << (expected - start.target).transpose());
            CHECK((a.target - expected).norm() < 1e-6 * 10);
            CHECK((a.right - start.right).norm() < 1e-12);
            CHECK((a.up - start.up).norm() < 1e-12);
            CHECK(a.distance == Approx(start.distance));
        }
    }
    SECTION("Home fits everything: the target is the centre of both lines' box (1, 3, 2.5); F with line l selected: its centre (6, 7, 5)")
    {
        const std::vector<Eigen::Vector3d> ends{{5, 5, 5}, {7, 9, 5}, {-5, -3, 0}, {-3, -3, 0}};
        const Axes a = savedCamera(replayRun(doc, "camera_home", Json::array({key("Home"), frames(2)})).saved);
        CHECK((a.target - Eigen::Vector3d(1, 3, 2.5)).norm() < 1e-9);
        CHECK((a.right - start.right).norm() < 1e-12);
        const Scene home = Scene::load(cat(kTmp, "/promises_more_camera_home.out.json"));
        for (const Eigen::Vector3d& p : ends) {
            const Eigen::Vector2d q = worldToPixel(home, kW, kH, p);
            CHECK(q.x() > 0);
            CHECK(q.x() < kW);
            CHECK(q.y() > 0);
            CHECK(q.y() < kH);
        }
        // F: a click on line l's middle selects it (as the table's "left click on a curve"), F
        // fits it.
        Json events = Json::array();
        clickAt(events, worldToPixel(Scene::load(doc), kW, kH, Eigen::Vector3d(6, 7, 5)));
        events.push_back(key("F"));
        events.push_back(frames(2));
        const Run f = replayRun(doc, "camera_f", events);
        REQUIRE(f.state["selection"].is_object());
        CHECK(f.state["selection"]["item"] == "l");
        const Axes fa = savedCamera(f.saved);
        CHECK((fa.target - Eigen::Vector3d(6, 7, 5)).norm() < 1e-9);
        CHECK(fa.distance < a.distance); // one line is smaller than both
    }
    SECTION("left drag on empty space orbits (turntable: the horizon stays level) only past 3 pixels of motion")
    {
        const Eigen::Vector2d from(640, 400);
        const Axes small = savedCamera(replayRun(doc, "camera_orbit_2px", dragWith("left", from, {2, 0})).saved);
        CHECK((small.right - start.right).norm() < 1e-12);
        CHECK((small.up - start.up).norm() < 1e-12);
        const Axes big = savedCamera(replayRun(doc, "camera_orbit_40px", dragWith("left", from, {40, 25})).saved);
        CHECK((big.back - start.back).norm() > 0.05);  // it turned
        CHECK(std::abs(big.right.z()) < 1e-9);          // turntable: the eye's x stays horizontal
        CHECK((big.target - start.target).norm() < 1e-9); // about the target, at the same distance
        CHECK(big.distance == Approx(start.distance));
    }
}

// ------------------------------------------------------------- keyboard table: view and file keys

TEST_CASE("the keyboard table's Z, W, R, Ctrl+N and Ctrl+S do what their rows say", "[render][replay][keys]")
{
    const Json display = {{"shading", "flat"}, {"wireframe", false}, {"analysis", "none"}, {"grid", false}, {"axes", false}};
    const Json objects = Json::array({{{"name", "c"}, {"type", "bezier_curve"}, {"points", {{0, 0, 0}, {1, 1, 0}, {2, 0, 0}}}}});
    const Json original = {{"format", "freeform"}, {"version", 1}, {"objects", objects},
                           {"editor", {{"camera", frontRightCamera(Eigen::Vector3d(1, 0, 0), 8)}, {"display", display}}}};
    const std::string doc = cat(kTmp, "/promises_more_keys.json");
    test::writeText(doc, original.dump(1));

    SECTION("Z steps the shading flat -> Gouraud -> Phong -> flat")
    {
        const char* expected[] = {"gouraud", "phong", "flat"};
        Json events = Json::array();
        for (const char* want : expected) {
            events.push_back(key("Z"));
            events.push_back(frames(1));
            INFO(want);
            CHECK(replayRun(doc, "keys_z", events).saved["editor"]["display"]["shading"] == want);
        }
    }
    SECTION("W turns the wireframe on and off; R the reflection lines")
    {
        const Json w = replayRun(doc, "keys_w", Json::array({key("W"), frames(1)})).saved["editor"]["display"];
        CHECK(w["wireframe"] == true);
        CHECK(replayRun(doc, "keys_ww", Json::array({key("W"), frames(1), key("W"), frames(1)})).saved["editor"]["display"]["wireframe"] == false);
        CHECK(replayRun(doc, "keys_r", Json::array({key("R"), frames(1)})).saved["editor"]["display"]["analysis"] == "reflection_lines");
        CHECK(replayRun(doc, "keys_rr", Json::array({key("R"), frames(1), key("R"), frames(1)})).saved["editor"]["display"]["analysis"] == "none");
    }
    SECTION("Ctrl+N: a new, empty document")
    {
        const Run r = replayRun(doc, "keys_new", Json::array({key("N", {"ctrl"}), frames(2)}));
        CHECK(r.state["objects"] == 0);
        CHECK(r.saved["objects"].empty());
    }
    SECTION("Ctrl+S writes the document to its own file: the file then equals what --save writes")
    {
        const std::string copy = cat(kTmp, "/promises_more_keys_copy.json");
        test::writeText(copy, original.dump(1));
        const std::string before = test::slurp(copy);
        // A change first (W), so that the saved file differs from the one written here.
        const Run r = replayRun(copy, "keys_save", Json::array({key("W"), frames(1), key("S", {"ctrl"}), frames(2)}));
        CHECK(r.state["modified"] == false);
        const Json written = Json::parse(test::slurp(copy));
        CHECK(test::slurp(copy) != before);
        CHECK(written == r.saved);
        CHECK(written["editor"]["display"]["wireframe"] == true);
        REQUIRE(written["objects"].size() == 1);
        CHECK(written["objects"][0]["points"][2][0] == 2.0); // the curve, untouched
    }
}

} // namespace test_render_promises_more
