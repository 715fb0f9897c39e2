// The editing tools without a window: driven through the entry points the application uses
// (Tools::onKey / onPointer / update and the operations of the tool classes, tools/*_tool.h) on a Scene, and
// checked against independent computations: ray/plane hits worked out by hand, the library's own
// evaluation of curves (elevation and splitting keep the shape), its edge continuity analysis of
// patches, and the First steps' C0 patch pair. Every operation must be one undo step that gives the
// document text back byte for byte, and bad input must leave the document as it was, with a
// message. The spline joints and their handle modes are in test_spline_joints.cpp, the lattice
// (FFD) tool in test_lattice_tool.cpp.

#include <catch2/catch.hpp>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cmath>
#include <string>
#include <vector>

#include "freeform/io/geometry_data.h"
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
