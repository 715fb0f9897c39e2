// The spline tool's joints without a window (tools/spline_tool.h), driven as test_tools.cpp drives
// the tools: inserting and deleting a joint keeps the shape and the modes; the handle modes (free,
// aligned, mirrored, C2) checked against the library's continuity analysis of the spline as saved
// (aligned G1, mirrored C1, C2 on every joint a C2 spline) after a handle is dragged, moved through
// the scene or set by number; and, for issue 12, all joints set at once prefer no side. Every
// operation must be one undo step that gives the document text back byte for byte.

#include <catch2/catch.hpp>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cmath>
#include <string>
#include <vector>

#include "support/process.h"
#include "support/tool_bench.h"
#include "tools/tools.h"

namespace test_spline_joints {

using namespace freeform;
using namespace freeform::editor;
using namespace freeform::editor::tool_test;

namespace {

const std::string kTmp = FREEFORM_TEST_TMP;

} // namespace

// ------------------------------------------------------------------ spline joints

TEST_CASE("Tools: inserting a spline joint keeps the shape and the modes; deleting it restores the counts", "[tools]")
{
    Bench b{curveScene("tools_insert_spline.json")};
    b.select("s", {4});
    REQUIRE(b.tools.spline().setJointMode(b.context, JointMode::Mirrored));
    const std::string mirrored = b.scene.text();
    const BezierSpline<double, 3> before = splineOf(b.scene, "s");
    const std::size_t steps = b.scene.history().size();

    b.select("s", {7}); // in segment 2 (knots 0, 1, 3, 3.5): a joint at T = 3.25
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_I, 0));
    const BezierSpline<double, 3> after = splineOf(b.scene, "s");
    CHECK(after.segmentCount() == 4);
    CHECK(splineData(b.scene, "s").points.cols() == 13);
    CHECK(after.knot(3) == Approx(3.25).margin(1e-15));
    CHECK(maxDistance(after, 0, before, 0, before.domainEnd()) < 1e-12);
    const std::vector<JointMode> modes = jointModes(b.scene, findItem(b.scene, "s"));
    REQUIRE(modes.size() == 5);
    CHECK(modes[1] == JointMode::Mirrored);
    CHECK(modes[3] == JointMode::Free);
    CHECK(b.scene.history().size() == steps + 1); // points and modes: one step
    b.scene.undo();
    CHECK(b.scene.text() == mirrored);
    b.scene.redo();

    // Delete the new joint (select its point, column 9): three segments and four modes again.
    b.selection.setPoints({9});
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_DELETE, 0));
    CHECK(splineData(b.scene, "s").points.cols() == 10);
    const std::vector<JointMode> back = jointModes(b.scene, findItem(b.scene, "s"));
    REQUIRE(back.size() == 4);
    CHECK(back[1] == JointMode::Mirrored);
    CHECK(b.scene.history().size() == steps + 2);
    b.scene.undo();
    b.scene.undo();
    CHECK(b.scene.text() == mirrored);
}

// ------------------------------------------------------------------ joint handle modes

TEST_CASE("Tools: mirrored makes the joint C1, aligned G1 but not C1, free changes nothing", "[tools]")
{
    Bench b{curveScene("tools_modes.json")};
    const std::string original = b.scene.text();
    const PointColumns p0 = splineData(b.scene, "s").points;
    CHECK(jointReport(b.scene, "s", 1).G == 0); // the joints start with corners
    CHECK(jointReport(b.scene, "s", 2).G == 0);

    // Joint 1 (column 3), its right handle (column 4) selected: the left handle follows.
    b.select("s", {4});
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_3, 0)); // mirrored
    const PointColumns p1 = splineData(b.scene, "s").points;
    // C1 with intervals h0 = 1, h1 = 2: (P3 - P2) / 1 = (P4 - P3) / 2.
    const Eigen::Vector3d expected = p0.col(3) - 0.5 * (p0.col(4) - p0.col(3));
    CHECK((Eigen::Vector3d(p1.col(2)) - expected).norm() < 1e-12);
    for (int k = 0; k < 10; ++k)
        if (k != 2) CHECK(p1.col(k) == p0.col(k));
    const JointContinuity<double> c1 = jointReport(b.scene, "s", 1);
    CHECK(c1.C >= 1);
    CHECK(c1.G >= 1);
    CHECK(jointReport(b.scene, "s", 2).G == 0);
    CHECK(jointModes(b.scene, findItem(b.scene, "s"))[1] == JointMode::Mirrored);
    CHECK(b.scene.history().size() == 1);
    b.scene.undo();
    CHECK(b.scene.text() == original);
    b.scene.redo();

    // Joint 2 (column 6) aligned keeping its left handle (column 5): the right handle (column 7)
    // turns onto the line and keeps its length, which differs from the C1 length.
    b.selection.setPoints({5});
    REQUIRE(b.tools.spline().setJointMode(b.context, JointMode::Aligned));
    const PointColumns p2 = splineData(b.scene, "s").points;
    const Eigen::Vector3d dir = (p0.col(6) - p0.col(5)).normalized();
    const Eigen::Vector3d aligned = Eigen::Vector3d(p0.col(6)) + (p0.col(7) - p0.col(6)).norm() * dir;
    CHECK((Eigen::Vector3d(p2.col(7)) - aligned).norm() < 1e-12);
    const JointContinuity<double> g1 = jointReport(b.scene, "s", 2);
    CHECK(g1.G >= 1);
    CHECK(g1.C == 0);
    CHECK(jointReport(b.scene, "s", 1).C >= 1); // the other joint is as it was

    // Free: the points stay bit for bit, only the mode changes.
    const std::string beforeFree = b.scene.text();
    b.select("s", {3});
    REQUIRE(b.tools.spline().setJointMode(b.context, JointMode::Free));
    CHECK(splineData(b.scene, "s").points == p2);
    CHECK(jointModes(b.scene, findItem(b.scene, "s"))[1] == JointMode::Free);
    CHECK(jointReport(b.scene, "s", 1).C >= 1);
    b.scene.undo();
    CHECK(b.scene.text() == beforeFree);
    while (b.scene.undo()) {}
    CHECK(b.scene.text() == original);
}

TEST_CASE("Tools: C2 on every joint gives a C2 spline; dragging a de Boor point keeps it C2", "[tools]")
{
    Bench b{curveScene("tools_c2.json")};
    b.scene.camera.setView("top"); // the drag plane faces +z
    b.select("s");
    const PointColumns before = splineData(b.scene, "s").points;
    REQUIRE(b.tools.spline().setAllJointModes(b.context, JointMode::C2));
    for (const auto& c : continuityReport(splineOf(b.scene, "s"))) {
        CHECK(c.C >= 2);
        CHECK(c.G == 2);
    }
    // No joint moves; the end handles (the end tangents) stay up to rounding.
    const PointColumns& after = splineData(b.scene, "s").points;
    for (int k : {0, 3, 6, 9}) CHECK(after.col(k) == before.col(k));
    for (int k : {1, 8}) CHECK((after.col(k) - before.col(k)).norm() < 1e-12);
    const std::vector<JointMode> modes = jointModes(b.scene, findItem(b.scene, "s"));
    REQUIRE(modes.size() == 4);
    CHECK(modes[1] == JointMode::C2);
    CHECK(modes[2] == JointMode::C2);
    const std::string c2 = b.scene.text();
    CHECK(b.scene.history().size() == 1);

    // The de Boor points are drawn; grab the third at its pixel and drag it by (0.5, -0.25, 0).
    const Points3 deboor = splineOf(b.scene, "s").deBoorPoints(EndCondition::Clamped);
    REQUIRE(deboor.cols() == 6);
    b.update();
    CHECK(b.overlay.points.positions.cols() == 6);
    const Eigen::Vector3d grab = deboor.col(2);
    const Eigen::Vector3d down(0, 0, -1);
    PointerEvent e = press(Eigen::Vector3d(grab.x(), grab.y(), 10), down, 0, 100 * (grab.x() + 4), 100 * (2.5 - grab.y()));
    REQUIRE(b.tools.onPointer(b.context, e));
    e.type = PointerEvent::Type::Move;
    e.rayOrigin = Eigen::Vector3d(grab.x() + 0.2, grab.y(), 10);
    b.tools.onPointer(b.context, e);
    e.rayOrigin = Eigen::Vector3d(grab.x() + 0.5, grab.y() - 0.25, 10);
    b.tools.onPointer(b.context, e);
    e.type = PointerEvent::Type::Release;
    b.tools.onPointer(b.context, e);
    b.update();

    const Points3 moved = splineOf(b.scene, "s").deBoorPoints(EndCondition::Clamped);
    for (int i = 0; i < 6; ++i) {
        const Eigen::Vector3d want = i == 2 ? Eigen::Vector3d(grab + Eigen::Vector3d(0.5, -0.25, 0)) : Eigen::Vector3d(deboor.col(i));
        CHECK((Eigen::Vector3d(moved.col(i)) - want).norm() < 1e-12);
    }
    for (const auto& c : continuityReport(splineOf(b.scene, "s"))) CHECK(c.C >= 2);
    CHECK(b.scene.history().size() == 2); // the whole drag is one step
    b.scene.undo();
    CHECK(b.scene.text() == c2);

    // C2 needs a cubic: elevation is refused while a joint is C2, and nothing changes.
    CHECK_FALSE(b.tools.curve().elevateSelected(b.context));
    CHECK_FALSE(b.tools.message().empty());
    CHECK(b.scene.text() == c2);
}

TEST_CASE("Tools: a handle moved through the scene keeps its joint's mode after Tools::update", "[tools]")
{
    Bench b{curveScene("tools_handle_drag.json")};
    b.select("s", {4});
    REQUIRE(b.tools.spline().setJointMode(b.context, JointMode::Mirrored));
    b.update();
    const std::string mirrored = b.scene.text();
    const int s = findItem(b.scene, "s");

    // A drag of the left handle (as the interaction does it: one merged gesture, a frame each move).
    const Eigen::Vector3d p3 = b.scene.controlPoints(s).col(3);
    const Eigen::Vector3d handle(-1.5, 0.2, -0.4);
    b.selection.setPoints({2});
    b.scene.beginMerge();
    b.scene.setControlPoint(s, 2, Eigen::Vector3d(-1.6, 0.3, -0.2));
    b.update();
    b.scene.setControlPoint(s, 2, handle);
    b.update();
    b.scene.endMerge();
    Eigen::Matrix3Xd p = b.scene.controlPoints(s);
    CHECK(Eigen::Vector3d(p.col(2)) == handle);
    CHECK((Eigen::Vector3d(p.col(4)) - (p3 + 2 * (p3 - handle))).norm() < 1e-12); // h1 / h0 = 2
    CHECK(jointReport(b.scene, "s", 1).C >= 1);
    CHECK(b.scene.history().size() == 2);
    b.scene.undo();
    b.update();
    CHECK(b.scene.text() == mirrored);
    CHECK(b.scene.history().canRedo()); // the tool did not answer the undo with an edit of its own

    // The joint point moved alone carries its handles: still C1.
    const Eigen::Vector3d delta(0.1, -0.2, 0.3);
    const Eigen::Matrix3Xd q = b.scene.controlPoints(s);
    b.selection.setPoints({3});
    b.scene.beginMerge();
    b.scene.setControlPoint(s, 3, Eigen::Vector3d(q.col(3) + delta));
    b.update();
    b.scene.endMerge();
    p = b.scene.controlPoints(s);
    for (int k = 2; k <= 4; ++k) CHECK((Eigen::Vector3d(p.col(k) - q.col(k)) - delta).norm() < 1e-15);
    CHECK(jointReport(b.scene, "s", 1).C >= 1);
    b.scene.undo();
    b.update();
    CHECK(b.scene.text() == mirrored);
}

TEST_CASE("Tools: a handle set by number (no merge) then undone and redone: no stray edits", "[tools]")
{
    // The properties panel moves a point as a step of its own; the next update enforces the mode
    // inside that step, so one undo takes both back. Undo and redo add no steps.
    Bench b{curveScene("tools_handle_number.json")};
    b.select("s", {4});
    REQUIRE(b.tools.spline().setJointMode(b.context, JointMode::Mirrored));
    b.update();
    const std::string mirrored = b.scene.text();
    const int s = findItem(b.scene, "s");
    b.selection.setPoints({2});
    b.scene.setControlPoint(s, 2, Eigen::Vector3d(-1.5, 0.2, -0.4), "set point");
    b.update();
    CHECK(jointReport(b.scene, "s", 1).C >= 1);
    const std::string enforced = b.scene.text();
    const std::size_t steps = b.scene.history().size();
    int undone = 0;
    while (b.scene.text() != mirrored && undone < 10 && b.scene.undo()) {
        b.update();
        ++undone;
    }
    CHECK(b.scene.text() == mirrored);
    CHECK(undone == 1);
    CHECK(steps == 2); // the mode, the typed point with its fix-up
    while (b.scene.redo()) b.update();
    CHECK(b.scene.text() == enforced);
    CHECK(b.scene.history().size() == steps);
}

// ------------------------------------------------------------------ issue 12: joint modes

namespace {

/// A cubic spline "m" of four segments, mirror-symmetric about the plane x = 0 (point k and point
/// 12 - k are reflections of each other, intervals 1, 2, 2, 1), with corners at its inner joints.
Scene mirrorScene(const std::string& name)
{
    const std::string path = cat(kTmp, "/", name);
    test::writeText(path, R"({"format": "freeform", "version": 1, "objects": [
      {"name": "m", "type": "bezier_spline", "degree": 3, "intervals": [1, 2, 2, 1], "points": [
        [-4, 0, 0], [-3.6, 1, 0.2], [-3.2, 1.5, 0.1], [-2.5, 0.5, 0], [-2.1, -0.7, 0.3], [-1.2, 0.9, 0.2],
        [0, 1, 0], [1.2, 0.9, 0.2], [2.1, -0.7, 0.3], [2.5, 0.5, 0], [3.2, 1.5, 0.1], [3.6, 1, 0.2], [4, 0, 0]]}]})");
    return Scene::load(path);
}

} // namespace

TEST_CASE("Tools: all joints aligned or mirrored at once prefer no side (a symmetric spline stays symmetric)", "[tools]")
{
    for (JointMode mode : {JointMode::Aligned, JointMode::Mirrored}) {
        Bench b{mirrorScene("tools_all_symmetric.json")};
        const PointColumns before = splineData(b.scene, "m").points;
        b.select("m", {});
        REQUIRE(b.tools.spline().setAllJointModes(b.context, mode));
        b.update();
        const PointColumns p = splineData(b.scene, "m").points;
        // The reflection x -> -x with the order reversed gives the same points.
        for (int k = 0; k <= 12; ++k) {
            INFO(toString(mode) << ": point " << k << " " << p.col(k).transpose() << ", mirror " << p.col(12 - k).transpose());
            CHECK(std::abs(p(0, k) + p(0, 12 - k)) < 1e-12);
            CHECK(std::abs(p(1, k) - p(1, 12 - k)) < 1e-12);
            CHECK(std::abs(p(2, k) - p(2, 12 - k)) < 1e-12);
        }
        for (int j = 0; j <= 4; ++j) CHECK(p.col(3 * j) == before.col(3 * j)); // the joints stay
        for (int j = 1; j <= 3; ++j) {
            const JointContinuity<double> c = jointReport(b.scene, "m", j);
            CHECK(c.G >= 1);
            if (mode == JointMode::Mirrored) CHECK(c.C >= 1);
        }
    }
}

TEST_CASE("Tools: mixed modes (C2, aligned, mirrored) all hold after a handle is moved through the scene", "[tools]")
{
    Bench b{mirrorScene("tools_mixed.json")};
    const int m = findItem(b.scene, "m");
    ObjectSettings settings = b.scene.item(m).settings;
    settings.joints = {JointMode::Free, JointMode::C2, JointMode::Aligned, JointMode::Mirrored, JointMode::Free};
    b.scene.setSettings(m, settings, "modes");
    b.select("m", {});
    b.update(); // the tool sees the spline (the modes are enforced from the first move on)
    for (int k : {4, 7, 8, 2}) { // the handle after joint 1, after joint 2, before joint 3, before joint 1
        const Eigen::Vector3d target = b.scene.controlPoints(m).col(k) + Eigen::Vector3d(0.13, -0.21, 0.05);
        b.selection.setPoints({k});
        b.scene.beginMerge();
        b.scene.setControlPoint(m, k, target);
        b.update();
        b.scene.endMerge();
        const Eigen::Matrix3Xd p = b.scene.controlPoints(m);
        INFO("moved point " << k);
        CHECK((Eigen::Vector3d(p.col(k)) - target).norm() < 1e-12); // the moved handle stays where it was put
        CHECK(jointReport(b.scene, "m", 1).C >= 2);
        CHECK(jointReport(b.scene, "m", 2).G >= 1);
        CHECK(jointReport(b.scene, "m", 3).C >= 1);
    }
}

} // namespace test_spline_joints
