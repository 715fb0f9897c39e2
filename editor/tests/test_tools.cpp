// The editing tools without a window: driven through the entry points the application uses
// (Tools::onKey / onPointer / update and the operations of the tool classes, tools/*_tool.h) on a Scene, and
// checked against independent computations: ray/plane hits worked out by hand, the library's own
// evaluation of curves and splines (elevation and splitting keep the shape), its continuity
// analysis (joint handle modes), Lattice::deform evaluated point by point (the reference for the
// batched FFD the tools use), deformCurve, and the interaction layer's own ray/mesh intersection.
// Every operation must be one undo step that gives the document text back byte for byte, and bad
// input must leave the document as it was, with a message.

#include <catch2/catch.hpp>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <freeform/core/transform.h>
#include <freeform/io/mesh_io.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "freeform/io/geometry_data.h"
#include "interaction/picking.h"
#include "support/process.h"
#include "support/tool_bench.h"
#include "tools/tools.h"

namespace test_tools {

using namespace freeform;
using namespace freeform::editor;
using namespace freeform::editor::tool_test;
using Catch::Matchers::WithinAbs;

namespace {

const std::string kTmp = FREEFORM_TEST_TMP;

/// A 3D cubic "c", a cubic spline "s" of three segments on intervals (1, 2, 0.5) whose joints are
/// neither C1 nor G1, and a lattice "box".
Scene curveScene(const std::string& name)
{
    const std::string path = cat(kTmp, "/", name);
    test::writeText(path, R"({"format": "freeform", "version": 1, "objects": [
      {"name": "c", "type": "bezier_curve", "points": [[-2, 0, 0.5], [-1, 1, 1.5], [0.5, -1, 2], [2, 0.3, -0.5]]},
      {"name": "s", "type": "bezier_spline", "degree": 3, "intervals": [1, 2, 0.5], "points": [
        [-3, 0, 0], [-2.5, 1, 0.2], [-1.8, 1.2, 0.1], [-1, 0.5, 0], [-0.2, 0.9, 0.3], [0.4, -0.6, 0.2],
        [1, -0.5, 0], [1.6, 0.1, -0.2], [2.4, 1.1, 0], [3, 0.2, 0.1]]},
      {"name": "box", "type": "lattice", "degree": [1, 1, 1], "origin": [0, 0, 0], "axes": [[1, 0, 0], [0, 1, 0], [0, 0, 1]],
       "points": [[0,0,0],[0,0,1],[0,1,0],[0,1,1],[1,0,0],[1,0,1],[1,1,0],[1,1,1]]}]})");
    return Scene::load(path);
}

BezierCurve<double, 3> curveOf(const Scene& scene, const std::string& name)
{
    return BezierCurve<double, 3>(Points3(std::get<BezierCurveData>(scene.object(findItem(scene, name)).data).points));
}

const BezierSplineData& splineData(const Scene& scene, const std::string& name)
{
    return std::get<BezierSplineData>(scene.object(findItem(scene, name)).data);
}

BezierSpline<double, 3> splineOf(const Scene& scene, const std::string& name)
{
    const BezierSplineData& d = splineData(scene, name);
    return BezierSpline<double, 3>(d.degree, d.closed, Points3(d.points), d.intervals);
}

/// The continuity report of joint j (the library's analysis of the spline as saved).
JointContinuity<double> jointReport(const Scene& scene, const std::string& name, int j)
{
    for (const auto& c : continuityReport(splineOf(scene, name)))
        if (c.joint == j) return c;
    FAIL("no joint " << j);
    return {};
}

double maxDistance(const BezierSpline<double, 3>& a, double a0, const BezierSpline<double, 3>& b, double b0, double length)
{
    double worst = 0;
    for (int i = 0; i <= 200; ++i) {
        const double u = length * i / 200.0;
        worst = std::max(worst, (a.evaluate(std::min(a0 + u, a.domainEnd())) - b.evaluate(std::min(b0 + u, b.domainEnd()))).norm());
    }
    return worst;
}

PointerEvent press(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, int button = 0, double x = 0, double y = 0)
{
    PointerEvent e;
    e.type = PointerEvent::Type::Press;
    e.button = button;
    e.x = x;
    e.y = y;
    e.rayOrigin = origin;
    e.rayDirection = direction.normalized();
    return e;
}

} // namespace

// ------------------------------------------------------------------ curves

TEST_CASE("Tools: C, clicks and Enter create a bezier_curve through the ray/plane hits; one undo step", "[tools]")
{
    Bench b{Scene()};
    b.scene.camera.setView("front"); // the click plane: through the empty scene's centre (the
                                     // origin), facing the camera: y = 0
    const std::string empty = b.scene.text();
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_C, 0));
    CHECK(b.tools.curve().creating());
    // Oblique rays from y = -10 along (a, 1, c) meet y = 0 at (x0 + 10 a, 0, z0 + 10 c).
    const double rays[4][4] = {{-1, 0.5, 0.1, -0.02}, {0, 1, 0.03, 0.01}, {2, -0.5, -0.05, 0.04}, {9, 9, 0, 0}};
    for (const auto& r : rays)
        CHECK(b.tools.onPointer(b.context, press(Eigen::Vector3d(r[0], -10, r[1]), Eigen::Vector3d(r[2], 1, r[3]))));
    CHECK(b.tools.curve().newPoints().cols() == 4);
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_BACKSPACE, 0)); // drops the last click
    CHECK(b.tools.curve().newPoints().cols() == 3);
    b.update();
    CHECK(b.overlay.points.positions.cols() == 3); // the clicked points are drawn
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_ENTER, 0));
    CHECK_FALSE(b.tools.curve().creating());

    REQUIRE(b.scene.itemCount() == 1);
    CHECK(b.scene.item(0).type == "bezier_curve");
    CHECK(b.selection.item == 0);
    const PointColumns& p = std::get<BezierCurveData>(b.scene.object(0).data).points;
    REQUIRE(p.rows() == 3);
    REQUIRE(p.cols() == 3);
    for (int i = 0; i < 3; ++i) {
        const Eigen::Vector3d expected(rays[i][0] + 10 * rays[i][2], 0, rays[i][1] + 10 * rays[i][3]);
        CHECK((Eigen::Vector3d(p.col(i)) - expected).norm() < 1e-12);
    }
    CHECK(b.scene.history().size() == 1);
    REQUIRE(b.scene.undo());
    CHECK(b.scene.text() == empty);

    // Right click ends too; Escape cancels without a trace; one click is not a curve.
    b.tools.onKey(b.context, GLFW_KEY_C, 0);
    b.tools.onPointer(b.context, press(Eigen::Vector3d(0, -10, 0), Eigen::Vector3d(0, 1, 0)));
    b.tools.onPointer(b.context, press(Eigen::Vector3d(1, -10, 0), Eigen::Vector3d(0, 1, 0)));
    CHECK(b.tools.onPointer(b.context, press(Eigen::Vector3d(0, -10, 0), Eigen::Vector3d(0, 1, 0), 1)));
    CHECK(b.scene.itemCount() == 1);
    b.scene.undo();
    b.tools.onKey(b.context, GLFW_KEY_C, 0);
    b.tools.onPointer(b.context, press(Eigen::Vector3d(0, -10, 0), Eigen::Vector3d(0, 1, 0)));
    b.tools.onPointer(b.context, press(Eigen::Vector3d(1, -10, 0), Eigen::Vector3d(0, 1, 0)));
    b.tools.onKey(b.context, GLFW_KEY_ESCAPE, 0);
    CHECK_FALSE(b.tools.curve().creating());
    CHECK(b.scene.itemCount() == 0);
    b.tools.onKey(b.context, GLFW_KEY_C, 0);
    b.tools.onPointer(b.context, press(Eigen::Vector3d(0, -10, 0), Eigen::Vector3d(0, 1, 0)));
    b.tools.onKey(b.context, GLFW_KEY_ENTER, 0);
    CHECK_FALSE(b.tools.message().empty());
    CHECK(b.scene.text() == empty);
}

TEST_CASE("Tools: Shift+C, clicks and Enter create a C2 cubic spline through the hits, joints in mode C2", "[tools]")
{
    Bench b{Scene()};
    b.scene.camera.setView("front"); // the click plane is y = 0 (see above)
    const std::string empty = b.scene.text();
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_C, GLFW_MOD_SHIFT));
    CHECK(b.tools.curve().creating());
    CHECK(b.tools.curve().creatingSpline());
    // Vertical rays hit y = 0 at (x, 0, z); the chords are 5, 10 and 3 (3-4-5 and 6-8-10 triangles).
    const Eigen::Vector3d hits[4] = {{-4, 0, 0}, {-1, 0, 4}, {5, 0, -4}, {5, 0, -1}};
    for (const auto& h : hits) b.tools.onPointer(b.context, press(Eigen::Vector3d(h.x(), -10, h.z()), Eigen::Vector3d(0, 1, 0)));
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_ENTER, 0));
    CHECK_FALSE(b.tools.curve().creating());

    REQUIRE(b.scene.itemCount() == 1);
    CHECK(b.scene.item(0).type == "bezier_spline");
    const BezierSplineData& d = std::get<BezierSplineData>(b.scene.object(0).data);
    CHECK(d.degree == 3);
    CHECK_FALSE(d.closed);
    CHECK(d.intervals == std::vector<double>{5, 10, 3}); // chord lengths, exact here
    REQUIRE(d.points.cols() == 10);
    for (int j = 0; j < 4; ++j) CHECK((Eigen::Vector3d(d.points.col(3 * j)) - hits[j]).norm() < 1e-12); // through the clicks
    const BezierSpline<double, 3> spline(3, false, Points3(d.points), d.intervals);
    for (const auto& c : continuityReport(spline)) {
        CHECK(c.C >= 2);
        CHECK(c.G == 2);
    }
    // Natural ends: f'' = 6 (b0 - 2 b1 + b2) / h^2 vanishes at both ends.
    const auto second = [&](int a, int m, int z, double h) {
        return (6 * (d.points.col(a) - 2 * d.points.col(m) + d.points.col(z)) / (h * h)).norm();
    };
    CHECK(second(0, 1, 2, 5) < 1e-12);
    CHECK(second(9, 8, 7, 3) < 1e-12);
    CHECK(jointModes(b.scene, 0) == std::vector<JointMode>{JointMode::Free, JointMode::C2, JointMode::C2, JointMode::Free});
    CHECK(b.scene.history().size() == 1); // the spline and its modes: one step
    REQUIRE(b.scene.undo());
    CHECK(b.scene.text() == empty);

    // Clicks on one spot cannot make a spline: a message, nothing added.
    b.tools.onKey(b.context, GLFW_KEY_C, GLFW_MOD_SHIFT);
    b.tools.onPointer(b.context, press(Eigen::Vector3d(1, -10, 1), Eigen::Vector3d(0, 1, 0)));
    b.tools.onPointer(b.context, press(Eigen::Vector3d(1, -10, 1), Eigen::Vector3d(0, 1, 0)));
    CHECK_FALSE(b.tools.curve().createFromClicks(b.context));
    CHECK_FALSE(b.tools.message().empty());
    CHECK(b.scene.text() == empty);
}

TEST_CASE("Tools: elevating a curve adds one degree and keeps every point of it (key E)", "[tools]")
{
    Bench b{curveScene("tools_elevate.json")};
    const std::string original = b.scene.text();
    const BezierCurve<double, 3> before = curveOf(b.scene, "c");
    b.select("c");
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_E, 0));
    const BezierCurve<double, 3> after = curveOf(b.scene, "c");
    CHECK(after.degree() == before.degree() + 1);
    double worst = 0;
    for (int i = 0; i <= 1000; ++i) worst = std::max(worst, (after.evaluate(i / 1000.0) - before.evaluate(i / 1000.0)).norm());
    CHECK(worst < 1e-12);
    CHECK(b.scene.history().size() == 1);
    b.scene.undo();
    CHECK(b.scene.text() == original);

    // A spline: every segment one degree up, the same curve.
    const BezierSpline<double, 3> spline = splineOf(b.scene, "s");
    b.select("s");
    REQUIRE(b.tools.curve().elevateSelected(b.context));
    const BezierSpline<double, 3> raised = splineOf(b.scene, "s");
    CHECK(raised.degree() == 4);
    CHECK(raised.segmentCount() == 3);
    CHECK(maxDistance(raised, 0, spline, 0, spline.domainEnd()) < 1e-12);
    b.scene.undo();
    CHECK(b.scene.text() == original);
}

TEST_CASE("Tools: splitting a curve at t gives pieces that are the original on [0, t] and [t, 1] (key K)", "[tools]")
{
    Bench b{curveScene("tools_split.json")};
    const std::string original = b.scene.text();
    const BezierCurve<double, 3> whole = curveOf(b.scene, "c");
    const double t = 0.3;
    b.tools.curve().t = t;
    b.select("c");
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_K, 0));
    REQUIRE(b.scene.itemCount() == 4);
    const BezierCurve<double, 3> left = curveOf(b.scene, "c");
    const std::string rightName = b.scene.item(b.selection.item).name;
    CHECK(rightName != "c");
    const BezierCurve<double, 3> right = curveOf(b.scene, rightName);
    CHECK(left.degree() == 3);
    CHECK(right.degree() == 3);
    double worst = 0;
    for (int i = 0; i <= 500; ++i) {
        const double u = i / 500.0;
        worst = std::max(worst, (left.evaluate(u) - whole.evaluate(t * u)).norm());
        worst = std::max(worst, (right.evaluate(u) - whole.evaluate(t + (1 - t) * u)).norm());
    }
    CHECK(worst < 1e-12);
    CHECK(b.scene.history().size() == 1);
    b.scene.undo();
    CHECK(b.scene.text() == original);

    // An open spline at the fraction 0.5 of its domain [0, 3.5]: T = 1.75 inside segment 1.
    const BezierSpline<double, 3> spline = splineOf(b.scene, "s");
    b.tools.curve().t = 0.5;
    b.select("s");
    REQUIRE(b.tools.curve().splitSelected(b.context));
    const BezierSpline<double, 3> first = splineOf(b.scene, "s");
    const BezierSpline<double, 3> second = splineOf(b.scene, b.scene.item(b.selection.item).name);
    CHECK(first.domainEnd() == Approx(1.75).margin(1e-15));
    CHECK(second.domainEnd() == Approx(1.75).margin(1e-15));
    CHECK(first.segmentCount() == 2);
    CHECK(second.segmentCount() == 2);
    CHECK(maxDistance(first, 0, spline, 0, 1.75) < 1e-12);
    CHECK(maxDistance(second, 0, spline, 1.75, 1.75) < 1e-12);
    CHECK(b.scene.history().size() == 1);
    b.scene.undo();
    CHECK(b.scene.text() == original);
}

TEST_CASE("Tools: inserting and deleting curve points changes the count and nothing else (keys I, Delete)", "[tools]")
{
    Bench b{curveScene("tools_insert_curve.json")};
    const std::string original = b.scene.text();
    const PointColumns before = std::get<BezierCurveData>(b.scene.object(0).data).points;
    b.select("c", {1});
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_I, 0));
    PointColumns after = std::get<BezierCurveData>(b.scene.object(0).data).points;
    REQUIRE(after.cols() == 5);
    CHECK(after.col(0) == before.col(0));
    CHECK(after.col(1) == before.col(1));
    CHECK(after.col(2) == 0.5 * (before.col(1) + before.col(2))); // midway to the next point
    CHECK(after.col(3) == before.col(2));
    CHECK(after.col(4) == before.col(3));
    CHECK(b.scene.history().size() == 1);

    // Delete the inserted point: the original points again, bit for bit (a second step).
    b.selection.setPoints({2});
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_DELETE, 0));
    after = std::get<BezierCurveData>(b.scene.object(0).data).points;
    CHECK(after == before);
    CHECK(b.selection.points.empty());
    CHECK(b.scene.history().size() == 2);
    CHECK(b.scene.text() == original);
    b.scene.undo();
    b.scene.undo();
    CHECK(b.scene.text() == original);

    // The last point selected: a new end point continuing the last leg.
    b.selection.setPoints({3});
    REQUIRE(b.tools.curve().insertAtSelected(b.context));
    after = std::get<BezierCurveData>(b.scene.object(0).data).points;
    REQUIRE(after.cols() == 5);
    CHECK(after.leftCols(4) == before);
    CHECK((after.col(4) - (2 * before.col(3) - before.col(2))).norm() < 1e-15);
}

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

TEST_CASE("Tools: the de Casteljau construction and the curvature comb are drawn on request (keys T, V)", "[tools]")
{
    Bench b{curveScene("tools_overlay.json")};
    b.select("c");
    b.tools.curve().t = 0.25;
    b.update();
    CHECK(b.overlay.empty());
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_T, 0));
    b.update();
    // A cubic: levels of 3, 2 and 1 points (6 points), polygons of 2 + 1 segments.
    REQUIRE(b.overlay.points.positions.cols() == 6);
    CHECK(b.overlay.linesOnTop.positions.cols() == 6);
    const BezierCurve<double, 3> curve = curveOf(b.scene, "c");
    const Eigen::Vector3d f = curve.evaluate(0.25);
    CHECK((b.overlay.points.positions.col(5).cast<double>() - f).norm() < 1e-6); // float overlay
    for (int i = 0; i < 3; ++i) { // the first level: P_i + t (P_(i+1) - P_i)
        const Eigen::Vector3d p = curve.controlPoints().col(i) + 0.25 * (curve.controlPoints().col(i + 1) - curve.controlPoints().col(i));
        CHECK((b.overlay.points.positions.col(i).cast<double>() - p).norm() < 1e-6);
    }
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_T, 0));
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_V, 0));
    b.update();
    CHECK(b.overlay.points.positions.cols() == 0);
    CHECK(b.overlay.linesOnTop.positions.cols() == 2 * (201 + 200)); // 201 teeth, 200 links
    // Tooth i (columns 4i, 4i + 1) starts on the curve at t = i / 200 and points away from the
    // centre of curvature, its length proportional to the curvature |f' x f''| / |f'|^3.
    const auto kappa = [&](double t) {
        const Eigen::Matrix3d d = curve.derivatives(t, 2);
        return Eigen::Vector3d(d.col(1)).cross(Eigen::Vector3d(d.col(2))).norm() / std::pow(d.col(1).norm(), 3);
    };
    const auto tooth = [&](int i) -> Eigen::Vector3d {
        return (b.overlay.linesOnTop.positions.col(4 * i + 1) - b.overlay.linesOnTop.positions.col(4 * i)).cast<double>();
    };
    for (int i : {0, 37, 100, 163}) {
        const double t = i / 200.0;
        CHECK((b.overlay.linesOnTop.positions.col(4 * i).cast<double>() - curve.evaluate(t)).norm() < 1e-6);
        CHECK(tooth(i).norm() / tooth(100).norm() == Approx(kappa(t) / kappa(0.5)).epsilon(1e-5));
        const Eigen::Matrix3d d = curve.derivatives(t, 2);
        const Eigen::Vector3d unit = d.col(1).normalized();
        const Eigen::Vector3d towardCentre = Eigen::Vector3d(d.col(2)) - d.col(2).dot(unit) * unit;
        CHECK(tooth(i).dot(towardCentre) < 0);
        CHECK(std::abs(tooth(i).dot(unit)) < 1e-5 * tooth(i).norm());
    }
    const std::string original = b.scene.text();
    CHECK(b.scene.history().size() == 0); // display aids are not edits
    CHECK_FALSE(b.scene.modified());
    CHECK(b.scene.text() == original);
}

// ------------------------------------------------------------------ surfaces

TEST_CASE("Tools: a patch of the chosen degrees; edge continuity of two patches sharing an edge", "[tools]")
{
    Bench b{Scene()};
    b.scene.camera.setView("front");
    b.tools.patch().degree[0] = 2;
    b.tools.patch().degree[1] = 3;
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_P, 0));
    REQUIRE(b.scene.itemCount() == 1);
    const auto& d = std::get<BezierSurfaceData>(b.scene.object(0).data);
    CHECK(d.degree[0] == 2);
    CHECK(d.degree[1] == 3);
    CHECK(d.points.cols() == 12);
    // In the view plane through the empty scene's centre: y = 0 for the front view.
    CHECK(d.points.row(1).cwiseAbs().maxCoeff() < 1e-12);
    CHECK(b.scene.history().size() == 1);

    // A second patch continuing the first across its edge u = 1 with a C1 (mirrored) row.
    BezierSurfaceData next = d;
    for (int j = 0; j <= 3; ++j) {
        next.points.col(0 * 4 + j) = d.points.col(2 * 4 + j);
        next.points.col(1 * 4 + j) = 2 * d.points.col(2 * 4 + j) - d.points.col(1 * 4 + j);
        next.points.col(2 * 4 + j) = 3 * d.points.col(2 * 4 + j) - 2 * d.points.col(1 * 4 + j) + Eigen::Vector3d(0, 0.3, 0);
    }
    b.scene.addObject({"patch", next, ""});
    REQUIRE(b.tools.patch().computeEdgeContinuity(b.context));
    REQUIRE(b.tools.patch().edges().size() == 1);
    CHECK(b.tools.patch().edgePatchNames().size() == 2);
    CHECK(b.tools.patch().edges()[0].c0);
    CHECK(b.tools.patch().edges()[0].c1);
    CHECK(b.tools.patch().edges()[0].g1);
    // A kink: the second patch's first inner row pulled off the tangent plane.
    next.points.col(1 * 4 + 1) += Eigen::Vector3d(0, 0.5, 0);
    DocumentObject kinked = b.scene.object(1);
    kinked.data = next;
    b.scene.replaceObject(1, kinked);
    REQUIRE(b.tools.patch().computeEdgeContinuity(b.context));
    REQUIRE(b.tools.patch().edges().size() == 1);
    CHECK(b.tools.patch().edges()[0].c0);
    CHECK_FALSE(b.tools.patch().edges()[0].g1);
}

// ------------------------------------------------------------------ FFD

namespace {

/// A distorted box: eight vertices, six quads (none axis-aligned).
const double kBox[8][3] = {{-1.0, -0.5, -0.25}, {1.2, -0.6, -0.2}, {1.1, 0.7, -0.3}, {-0.9, 0.5, -0.1},
                           {-1.05, -0.45, 0.8}, {1.0, -0.55, 0.9}, {1.15, 0.65, 0.75}, {-0.95, 0.55, 0.85}};

std::string writeBox(const std::string& name)
{
    std::string text;
    for (const auto& v : kBox) text += cat("v ", v[0], " ", v[1], " ", v[2], "\n");
    text += "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
    const std::string path = cat(kTmp, "/", name);
    test::writeText(path, text);
    return path;
}

Eigen::Vector3d boxVertex(int v) { return {kBox[v][0], kBox[v][1], kBox[v][2]}; }

Lattice latticeOf(const Scene& scene, int item)
{
    return latticeFromData(std::get<LatticeData>(scene.object(item).data));
}

} // namespace

TEST_CASE("Tools: fit a lattice to an imported mesh, move a point, the mesh follows Lattice::deform", "[tools][ffd]")
{
    const std::string obj = writeBox("ffd_box.obj");
    Bench b{Scene()};
    b.scene.importFile(obj);
    int mesh = findItem(b.scene, "ffd_box");
    REQUIRE(mesh >= 0);
    const std::string imported = b.scene.text();
    const std::size_t steps = b.scene.history().size();

    b.selection.selectItem(mesh);
    b.tools.lattice().degree[0] = 2;
    b.tools.lattice().degree[1] = 3;
    b.tools.lattice().degree[2] = 1;
    b.tools.lattice().margin = 0.1;
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_L, 0));
    const int li = findItem(b.scene, "ffd_box_lattice");
    REQUIRE(li >= 0);
    CHECK(b.selection.item == li);
    CHECK(b.scene.item(li).settings.ffd.mesh == "ffd_box");
    CHECK(b.scene.history().size() == steps + 1);
    const LatticeData& fit = std::get<LatticeData>(b.scene.object(li).data);
    CHECK(fit.degree == std::array<int, 3>{2, 3, 1});
    // Bounds x [-1.05, 1.2], y [-0.6, 0.7], z [-0.3, 0.9]; largest extent 2.25, margin 0.225.
    CHECK((fit.origin - Eigen::Vector3d(-1.275, -0.825, -0.525)).norm() < 1e-12);
    CHECK((fit.axes - Eigen::Vector3d(2.7, 1.75, 1.65).asDiagonal().toDenseMatrix()).norm() < 1e-12);
    CHECK(latticeOf(b.scene, li).isRest());
    mesh = findItem(b.scene, "ffd_box"); // document objects come before the imported meshes
    CHECK(mesh == li + 1);

    // At rest the mesh is the file's vertices, in the file's order.
    b.update();
    const PolygonMesh& shown = *b.scene.item(mesh).geometry.surface;
    REQUIRE(shown.positions.cols() == 8);
    for (int v = 0; v < 8; ++v) CHECK(Eigen::Vector3d(shown.positions.col(v)) == boxVertex(v));

    // Move control point (1, 2, 1).
    const Lattice rest = latticeOf(b.scene, li);
    const int k = rest.index(1, 2, 1);
    b.scene.setControlPoint(li, k, rest.restPoint(1, 2, 1) + Eigen::Vector3d(0.3, -0.2, 0.25));
    b.update();
    const Lattice moved = latticeOf(b.scene, li);
    CHECK_FALSE(moved.isRest());
    // Rest normals: the library's area-weighted normals of the file's quads cut into fans, as the
    // scene shows them (the corners of each triangle get its area).
    const PolygonMesh quads = readPolygonMesh(obj);
    PolygonMesh fans;
    fans.positions = quads.positions;
    for (int f = 0; f < quads.faceCount(); ++f)
        for (int k = 1; k + 1 < quads.faceSize(f); ++k)
            fans.addFace({quads.face(f)[0], quads.face(f)[k], quads.face(f)[k + 1]});
    const Eigen::Matrix3Xd restNormals = areaWeightedNormals(fans);
    const SceneItem& item = b.scene.item(mesh);
    REQUIRE(item.scalars.size() == 8);
    // The live view computes in float (the GPU's precision; exports are double, tested below):
    // coordinates of size ~1 agree to a few float roundings, 1e-6 (float epsilon is 1.2e-7).
    constexpr double kFloat = 1e-6;
    for (int v = 0; v < 8; ++v) {
        const Lattice::PointJet jet = moved.deform(boxVertex(v));
        CHECK((Eigen::Vector3d(item.geometry.surface->positions.col(v)) - jet.point).norm() < kFloat);
        const Eigen::Vector3d n = item.geometry.surface->normals.col(v);
        CHECK(std::abs(n.norm() - 1) < kFloat);
        CHECK((n - transformNormal(jet.jacobian, restNormals.col(v)).normalized()).norm() < kFloat);
        CHECK(item.scalars[static_cast<std::size_t>(v)] == Approx(jet.jacobian.determinant()).epsilon(1e-6));
    }
    CHECK((item.geometry.surface->positions - shown.positions).norm() == 0); // same storage, updated
    // Nothing changed: nothing recomputed (the mesh's revision stays).
    const int revision = b.scene.item(mesh).revision;
    b.update();
    CHECK(b.scene.item(mesh).revision == revision);

    // Reset: the rest lattice, the mesh back to the file's vertices bit for bit; one step.
    const std::string deformed = b.scene.text();
    const std::size_t before = b.scene.history().size();
    REQUIRE(b.tools.lattice().resetLattice(b.context, li));
    b.update();
    CHECK(latticeOf(b.scene, li).isRest());
    for (int v = 0; v < 8; ++v) CHECK(Eigen::Vector3d(b.scene.item(mesh).geometry.surface->positions.col(v)) == boxVertex(v));
    CHECK(b.scene.history().size() == before + 1);
    b.scene.undo();
    b.update();
    CHECK(b.scene.text() == deformed);
    for (int v = 0; v < 8; ++v)
        CHECK((Eigen::Vector3d(b.scene.item(mesh).geometry.surface->positions.col(v)) - moved.deform(boxVertex(v)).point).norm() < kFloat);

    // Undo everything: the imported document, and the mesh at rest once the lattice is gone.
    while (b.scene.history().size() > steps) b.scene.undo();
    b.update();
    mesh = findItem(b.scene, "ffd_box");
    CHECK(b.scene.text() == imported);
    for (int v = 0; v < 8; ++v) CHECK(Eigen::Vector3d(b.scene.item(mesh).geometry.surface->positions.col(v)) == boxVertex(v));
}

TEST_CASE("Tools: exportDeformed writes the file's faces with Lattice::deform's positions", "[tools][ffd]")
{
    const std::string obj = writeBox("ffd_export.obj");
    Bench b{Scene()};
    b.scene.importFile(obj);
    const int mesh = findItem(b.scene, "ffd_export");
    REQUIRE(b.tools.lattice().fitLattice(b.context, mesh));
    const int li = b.selection.item;
    Lattice lattice = latticeOf(b.scene, li);
    b.scene.setControlPoint(li, lattice.index(3, 0, 3), lattice.restPoint(3, 0, 3) + Eigen::Vector3d(-0.4, 0.1, 0.2));
    b.scene.setControlPoint(li, lattice.index(1, 2, 2), lattice.restPoint(1, 2, 2) + Eigen::Vector3d(0, 0.3, -0.1));
    b.update();
    lattice = latticeOf(b.scene, li);
    const std::string text = b.scene.text();
    const std::string out = cat(kTmp, "/ffd_export_out.obj");
    REQUIRE(b.tools.lattice().exportDeformed(b.context, li, out));
    CHECK(b.scene.text() == text);
    const PolygonMesh written = readPolygonMesh(out), input = readPolygonMesh(obj);
    REQUIRE(written.positions.cols() == 8);
    for (int v = 0; v < 8; ++v) CHECK((Eigen::Vector3d(written.positions.col(v)) - lattice.deform(boxVertex(v)).point).norm() < 1e-12);
    REQUIRE(written.faceCount() == input.faceCount());
    for (int f = 0; f < input.faceCount(); ++f) {
        REQUIRE(written.faceSize(f) == 4); // quads stay quads
        for (int c = 0; c < 4; ++c) CHECK(written.face(f)[c] == input.face(f)[c]);
    }
}

TEST_CASE("Tools: applyLatticeToObjects turns a curve inside the box into deformCurve's curve", "[tools][ffd]")
{
    const std::string obj = writeBox("ffd_apply.obj");
    Bench b{Scene()};
    b.scene.importFile(obj);
    REQUIRE(b.tools.lattice().fitLattice(b.context, findItem(b.scene, "ffd_apply")));
    const int li = b.selection.item;
    Lattice lattice = latticeOf(b.scene, li);
    b.scene.setControlPoint(li, lattice.index(2, 1, 1), lattice.restPoint(2, 1, 1) + Eigen::Vector3d(0.2, 0.3, -0.1));
    lattice = latticeOf(b.scene, li);
    Points3 inside(3, 3), outside(3, 2);
    inside << -0.5, 0, 0.6, -0.2, 0.4, -0.1, 0, 0.3, 0.5;
    outside << 5, 6, 5, 6, 5, 6;
    b.scene.addObject({"in", BezierCurveData{inside}, ""});
    b.scene.addObject({"out", BezierCurveData{outside}, ""});
    const std::string before = b.scene.text();
    const std::size_t steps = b.scene.history().size();

    REQUIRE(b.tools.lattice().applyLatticeToObjects(b.context, li));
    // One rule with `freeform ffd DOC` (docs/ffd.md, "Documents"): the curve outside the box is
    // composed too (the lattice polynomial continued), and the status line says it is outside.
    CHECK(b.tools.message().find("1 of them outside the box") != std::string::npos);
    const BezierCurve<double, 3> original(inside), composed = curveOf(b.scene, "in");
    CHECK(composed.degree() == 2 * 9); // degree d (l + m + n) for the cubic lattice
    const BezierCurve<double, 3> library = deformCurve(lattice, original);
    CHECK((composed.controlPoints() - library.controlPoints()).norm() < 1e-12);
    double worst = 0; // and point by point through the lattice map
    for (int i = 0; i <= 100; ++i)
        worst = std::max(worst, (composed.evaluate(i / 100.0) - lattice.deform(original.evaluate(i / 100.0)).point).norm());
    CHECK(worst < 1e-12);
    const BezierCurve<double, 3> outsideComposed = curveOf(b.scene, "out");
    CHECK(outsideComposed.degree() == 1 * 9);
    CHECK((outsideComposed.controlPoints() - deformCurve(lattice, BezierCurve<double, 3>(outside)).controlPoints()).norm() < 1e-9);
    CHECK(b.scene.history().size() == steps + 1);
    b.scene.undo();
    CHECK(b.scene.text() == before);
}

TEST_CASE("Tools: the certificate of a lattice: injective for a small move, folds for a crossing one", "[tools][ffd]")
{
    const std::string obj = writeBox("ffd_certify.obj");
    Bench b{Scene()};
    b.scene.importFile(obj);
    b.tools.lattice().degree[0] = b.tools.lattice().degree[1] = b.tools.lattice().degree[2] = 1;
    REQUIRE(b.tools.lattice().fitLattice(b.context, findItem(b.scene, "ffd_certify")));
    const int li = b.selection.item;
    const Lattice rest = latticeOf(b.scene, li);
    b.scene.setControlPoint(li, rest.index(1, 1, 1), rest.restPoint(1, 1, 1) + Eigen::Vector3d(0.1, 0.05, -0.1));
    b.update();
    REQUIRE(b.tools.lattice().certifyLattice(b.context, li));
    REQUIRE(b.scene.ffdLink(li));
    const auto& link = *b.scene.ffdLink(li);
    REQUIRE(link.certificate);
    CHECK(link.certificate->verdict == Verdict::CertifiedInjective);
    // The corner (1, 1, 1) pulled through the opposite corner (0, 0, 0): the trilinear map folds.
    b.scene.setControlPoint(li, rest.index(1, 1, 1), rest.restPoint(0, 0, 0) - 0.5 * (rest.restPoint(1, 1, 1) - rest.restPoint(0, 0, 0)));
    b.update();
    REQUIRE(b.tools.lattice().certifyLattice(b.context, li));
    REQUIRE(b.scene.ffdLink(li)->certificate);
    CHECK(b.scene.ffdLink(li)->certificate->verdict == Verdict::Folds);
    CHECK(b.tools.message().find("folds") != std::string::npos);
}

TEST_CASE("Tools: direct manipulation drags a point of the mesh and the lattice follows exactly (key D)", "[tools][ffd]")
{
    const std::string obj = writeBox("ffd_direct.obj");
    Bench b{Scene()};
    b.scene.camera.setView("top"); // the drag plane faces +z
    b.scene.importFile(obj);
    REQUIRE(b.tools.lattice().fitLattice(b.context, findItem(b.scene, "ffd_direct")));
    const int li = b.selection.item, mesh = findItem(b.scene, "ffd_direct");
    b.update();
    const std::string fitted = b.scene.text();
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_D, 0));

    // The grabbed point: where the ray meets the rest mesh (the picking code's ray/mesh test).
    const Eigen::Vector3d origin(0.1, 0.05, 10), down(0, 0, -1);
    const auto distance = rayMesh(origin, down, *b.scene.item(mesh).geometry.surface);
    REQUIRE(distance);
    const Eigen::Vector3d grabbed = origin + *distance * down;
    PointerEvent e = press(origin, down);
    REQUIRE(b.tools.onPointer(b.context, e));
    e.type = PointerEvent::Type::Move;
    e.rayOrigin = Eigen::Vector3d(0.3, 0.05, 10);
    b.tools.onPointer(b.context, e);
    e.rayOrigin = Eigen::Vector3d(0.4, -0.1, 10);
    b.tools.onPointer(b.context, e);
    e.type = PointerEvent::Type::Release;
    b.tools.onPointer(b.context, e);
    b.update();

    const Eigen::Vector3d target = grabbed + Eigen::Vector3d(0.3, -0.15, 0);
    CHECK((latticeOf(b.scene, li).deform(grabbed).point - target).norm() < 1e-9);
    // The mesh shows the new lattice (computed in float for the view, see above).
    const Lattice moved = latticeOf(b.scene, li);
    for (int v = 0; v < 8; ++v)
        CHECK((Eigen::Vector3d(b.scene.item(mesh).geometry.surface->positions.col(v)) - moved.deform(boxVertex(v)).point).norm() < 1e-6);
    CHECK(b.scene.history().undoLabel() == "direct manipulation");
    b.scene.undo();
    CHECK(b.scene.text() == fitted);
}

// ------------------------------------------------------------------ bad input

TEST_CASE("Tools: operations on the wrong object or an empty selection fail with a message and change nothing", "[tools]")
{
    const std::string obj = writeBox("tools_bad.obj");
    Bench b{curveScene("tools_bad.json")};
    b.scene.importFile(obj);
    const std::string original = b.scene.text();
    const std::size_t imported = b.scene.history().size();
    const int c = findItem(b.scene, "c"), s = findItem(b.scene, "s"), box = findItem(b.scene, "box"),
              mesh = findItem(b.scene, "tools_bad");
    auto& st = b.tools;
    const auto fails = [&](bool ok, const char* what) {
        INFO(what);
        CHECK_FALSE(ok);
        CHECK_FALSE(st.message().empty());
        CHECK(b.scene.text() == original);
        CHECK(b.scene.history().size() == imported);
        st.message().clear();
    };

    b.selection.clear();
    fails(b.tools.curve().elevateSelected(b.context), "elevate, nothing selected");
    fails(b.tools.curve().splitSelected(b.context), "split, nothing selected");
    fails(b.tools.curve().insertAtSelected(b.context), "insert, nothing selected");
    fails(b.tools.curve().deleteSelected(b.context), "delete, nothing selected");
    fails(b.tools.spline().setJointMode(b.context, JointMode::Mirrored), "mode, nothing selected");
    fails(b.tools.spline().setAllJointModes(b.context, JointMode::C2), "all modes, nothing selected");

    b.select("box", {0});
    fails(b.tools.curve().elevateSelected(b.context), "elevate a lattice");
    fails(b.tools.curve().splitSelected(b.context), "split a lattice");
    fails(b.tools.curve().insertAtSelected(b.context), "insert into a lattice");
    fails(b.tools.curve().deleteSelected(b.context), "delete from a lattice");
    fails(b.tools.spline().setJointMode(b.context, JointMode::Aligned), "mode of a lattice");
    CHECK_FALSE(b.tools.onKey(b.context, GLFW_KEY_E, 0)); // not taken for a lattice

    b.select("c", {1});
    fails(b.tools.spline().setJointMode(b.context, JointMode::Mirrored), "mode of a bezier_curve");
    b.tools.curve().t = 0;
    fails(b.tools.curve().splitSelected(b.context), "split at t = 0");
    b.tools.curve().t = 0.5;
    b.select("s", {0});
    fails(b.tools.spline().setJointMode(b.context, JointMode::Mirrored), "mode of an end joint");
    b.select("s");
    fails(b.tools.curve().deleteSelected(b.context), "delete without a point");
    b.select("s", {2});
    b.tools.curve().t = 1;
    fails(b.tools.curve().splitSelected(b.context), "split a spline at its end");
    b.tools.curve().t = 0.5;

    fails(b.tools.lattice().fitLattice(b.context, c), "fit a lattice to a curve");
    fails(b.tools.lattice().fitLattice(b.context, -1), "fit a lattice to nothing");
    fails(b.tools.lattice().resetLattice(b.context, c), "reset a curve");
    fails(b.tools.lattice().resetLattice(b.context, mesh), "reset a mesh");
    fails(b.tools.lattice().resetLattice(b.context, 99), "reset an item that does not exist");
    fails(b.tools.lattice().exportDeformed(b.context, s, cat(kTmp, "/tools_bad_out.obj")), "export through a spline");
    fails(b.tools.lattice().exportDeformed(b.context, box, cat(kTmp, "/tools_bad_out.obj")), "export through a lattice bound to nothing");
    fails(b.tools.lattice().applyLatticeToObjects(b.context, c), "apply a curve as a lattice");
    fails(b.tools.lattice().applyLatticeToObjects(b.context, mesh), "apply a mesh as a lattice");
    fails(b.tools.lattice().certifyLattice(b.context, c), "certify a curve");
    fails(b.tools.lattice().certifyLattice(b.context, 99), "certify an item that does not exist");
    // The lattice operations name the item that is not a lattice.
    for (int i : {c, s, mesh}) {
        CHECK_FALSE(b.tools.lattice().resetLattice(b.context, i));
        CHECK(st.message() == cat(b.scene.item(i).name, " is not a lattice"));
        CHECK_FALSE(b.tools.lattice().applyLatticeToObjects(b.context, i));
        CHECK(st.message() == cat(b.scene.item(i).name, " is not a lattice"));
        CHECK_FALSE(b.tools.lattice().exportDeformed(b.context, i, cat(kTmp, "/tools_bad_out.obj")));
        CHECK(st.message() == cat(b.scene.item(i).name, " is not a lattice"));
        CHECK_FALSE(b.tools.lattice().certifyLattice(b.context, i));
        CHECK(st.message() == cat(b.scene.item(i).name, " is not a lattice"));
    }
    CHECK(b.scene.text() == original);

    // A two-point curve keeps its points.
    b.scene.addObject({"line", BezierCurveData{PointColumns::Identity(3, 2)}, ""});
    const std::string withLine = b.scene.text();
    const std::size_t steps = b.scene.history().size();
    b.select("line", {0});
    CHECK_FALSE(b.tools.curve().deleteSelected(b.context));
    CHECK_FALSE(st.message().empty());
    CHECK(b.scene.text() == withLine);
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

TEST_CASE("Tools: First steps, the C0 patch pair: the edge is C0 only, rows made collinear make it C1 and G1", "[tools]")
{
    // examples/data/c0-patches.json (docs/editor.md, "First steps"): "left" rises to the shared
    // edge x = 0 by 0.3 per row of 0.5 in x, "right" falls from it likewise: a crease whose
    // tangent planes meet at 2 atan(0.6) where the edge is level (v = 1/2), less elsewhere.
    Bench b{Scene::load(std::string(FREEFORM_SOURCE_DIR) + "/examples/data/c0-patches.json")};
    REQUIRE(b.tools.patch().computeEdgeContinuity(b.context));
    REQUIRE(b.tools.patch().edges().size() == 1);
    const EdgeContinuity& e = b.tools.patch().edges()[0];
    CHECK(e.c0);
    CHECK_FALSE(e.g1);
    CHECK_FALSE(e.c1);
    CHECK(e.angle <= 2 * std::atan(0.6) + 1e-9);
    CHECK(e.angle > 1.0); // 2 atan(0.6) = 1.0808
    // The task's step: the net rows on both sides of the edge (row 2 of left, row 1 of right) moved
    // in z until the points across the edge are collinear (each to its edge point's height).
    const int left = findItem(b.scene, "left"), right = findItem(b.scene, "right");
    for (int j = 0; j < 4; ++j) {
        const Eigen::Vector3d edge = b.scene.controlPoints(left).col(3 * 4 + j);
        Eigen::Vector3d p = b.scene.controlPoints(left).col(2 * 4 + j);
        b.scene.setControlPoint(left, 2 * 4 + j, Eigen::Vector3d(p.x(), p.y(), edge.z()));
        p = b.scene.controlPoints(right).col(1 * 4 + j);
        b.scene.setControlPoint(right, 1 * 4 + j, Eigen::Vector3d(p.x(), p.y(), edge.z()));
    }
    b.update(); // the table follows the change by itself (the tool's per-frame update)
    REQUIRE(b.tools.patch().edges().size() == 1);
    CHECK(b.tools.patch().edges()[0].g1);
    CHECK(b.tools.patch().edges()[0].c1); // equal row spacing on both sides
    CHECK(b.tools.patch().edges()[0].angle < 1e-6); // an angle from a cosine near 1: resolution about 1.5e-8
}

} // namespace test_tools
