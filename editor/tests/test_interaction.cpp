// Selection and manipulation without a display: picking (nearest point on screen within the
// radius, boxes, rays against triangles, distance to a polyline) on a hand-built orthographic view
// whose pixels are known in closed form; the drag math (view plane, axis, plane), snapping,
// the proportional falloff and the grid step against hand-computed values; and the Interaction
// controller driven like the application drives it (press, move, release, keys) on a document in
// an orthographic front view, where one pixel is 2 h / H world units (h: the camera's half
// height, H: the view's height) - an independent way to state where a dragged point must land.

#include <catch2/catch.hpp>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <freeform/core/transform.h>

#include <cmath>
#include <string>

#include "interaction/interaction.h"
#include "interaction/manipulation.h"
#include "interaction/picking.h"
#include "interaction/replay.h"
#include "support/process.h"

namespace test_interaction {

using namespace freeform;
using namespace freeform::editor;
using Catch::Matchers::WithinAbs;

namespace {

const std::string kTmp = FREEFORM_TEST_TMP;

/// An orthographic view of x in [-4, 4], y in [-2.5, 2.5] looking down -z, 800 x 500 pixels:
/// world (x, y, z) is at pixel (100 (x + 4), 100 (2.5 - y)).
ViewTransform handView()
{
    const Eigen::Matrix4d p = orthographic<double>(-4, 4, -2.5, 2.5, 1, 21);
    const Eigen::Matrix4d v = lookAt<double>(Eigen::Vector3d(0, 0, 10), Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitY());
    return ViewTransform(p * v, -Eigen::Vector3d::UnitZ(), 800, 500);
}

/// A 3D cubic in the plane y = 0, seen from the front (looking along +y), orthographic, 800 x 600.
Scene curveScene()
{
    const std::string path = kTmp + "/interaction_curve.json";
    test::writeText(path, R"({"format": "freeform", "version": 1, "objects": [
      {"name": "c", "type": "bezier_curve", "points": [[-2, 0, 0], [-1, 0, 1.5], [1, 0, 1.5], [2, 0, 0]]}]})");
    Scene scene = Scene::load(path);
    scene.camera.setView("front");
    scene.camera.projection = Projection::Orthographic;
    scene.camera.target = Eigen::Vector3d::Zero();
    scene.camera.distance = 10;
    scene.updateGeometry();
    return scene;
}

constexpr int kW = 800, kH = 600;

/// Pixels per world unit of curveScene's view, and where a point of the plane y = 0 appears.
double scale(const Scene& scene)
{
    return (kH / 2.0) / scene.camera.halfHeight();
}
Eigen::Vector2d pixel(const Scene& scene, double x, double z)
{
    return {kW / 2.0 + x * scale(scene), kH / 2.0 - z * scale(scene)};
}

struct Session {
    Scene scene = curveScene();
    Selection selection;
    EditSettings settings;
    Interaction interaction{settings};
    ViewTransform view() const { return ViewTransform::of(scene, kW, kH); }
    bool press(double x, double y, int mods = 0)
    {
        return interaction.press(scene, selection, view(), GLFW_MOUSE_BUTTON_LEFT, mods, x, y);
    }
    void move(double x, double y) { interaction.move(scene, selection, view(), x, y); }
    void release(double x, double y) { interaction.release(scene, selection, view(), GLFW_MOUSE_BUTTON_LEFT, 0, x, y); }
    void drag(Eigen::Vector2d from, Eigen::Vector2d to, int mods = 0)
    {
        REQUIRE(press(from.x(), from.y(), mods));
        move(0.5 * (from.x() + to.x()), 0.5 * (from.y() + to.y()));
        move(to.x(), to.y());
        release(to.x(), to.y());
    }
    bool key(int k, int mods = 0, double x = 0, double y = 0) { return interaction.key(scene, selection, view(), k, mods, x, y); }
};

} // namespace

TEST_CASE("ViewTransform maps world points to the pixels of the closed form and back", "[interaction]")
{
    const ViewTransform v = handView();
    const auto p = v.toPixel(Eigen::Vector3d(1, 0.5, 3));
    REQUIRE(p);
    CHECK_THAT(p->x(), WithinAbs(500, 1e-9));
    CHECK_THAT(p->y(), WithinAbs(200, 1e-9));
    CHECK(v.unproject(500, 200, p->z()).isApprox(Eigen::Vector3d(1, 0.5, 3), 1e-12));
    CHECK_THAT(v.worldPerPixel(Eigen::Vector3d::Zero()), WithinAbs(0.01, 1e-12));
    Eigen::Vector3d o, d;
    v.ray(250, 125, o, d);
    CHECK(d.isApprox(Eigen::Vector3d(0, 0, -1), 1e-12));
    CHECK_THAT(o.x(), WithinAbs(-1.5, 1e-12));
    CHECK_THAT(o.y(), WithinAbs(1.25, 1e-12));
}

TEST_CASE("pickPoint: the nearest projection within the radius, nothing outside it", "[interaction]")
{
    const ViewTransform v = handView();
    Eigen::Matrix3Xd points(3, 3);
    points << 0, 1, 0.06, //
        0, 0, 0,          //
        0, 0, 5;          // columns: pixel (400, 250), (500, 250), (406, 250) nearer the eye
    CHECK(pickPoint(v, points, 398, 250, 10) == 0);           // 2 px from 0, 8 px from 2
    CHECK(pickPoint(v, points, 405, 250, 10) == 2);           // 1 px from 2
    CHECK(pickPoint(v, points, 492, 254, 10) == 1);           // hypot(8, 4) = 8.94 < 10
    CHECK_FALSE(pickPoint(v, points, 491, 256, 10).has_value()); // hypot(9, 6) = 10.8 > 10
    CHECK_FALSE(pickPoint(v, points, 450, 250, 10).has_value());
    // Equal distance: the point nearer the eye wins.
    Eigen::Matrix3Xd twins(3, 2);
    twins << 0.5, 0.5, 0, 0, -1, 2;
    CHECK(pickPoint(v, twins, 450, 250, 3) == 1);
}

TEST_CASE("pointsInBox, rayMesh and pixelDistanceToPolyline against hand values", "[interaction]")
{
    const ViewTransform v = handView();
    Eigen::Matrix3Xd points(3, 4);
    points << -1, 0, 1, 2, //
        1, 0, -1, 0,       //
        0, 0, 0, 0;        // pixels (300,150) (400,250) (500,350) (600,250)
    CHECK(pointsInBox(v, points, 290, 140, 410, 260) == std::vector<int>{0, 1});
    CHECK(pointsInBox(v, points, 610, 360, 390, 240) == std::vector<int>{1, 2, 3}); // corners in any order
    CHECK(pointsInBox(v, points, 0, 0, 10, 10).empty());

    PolygonMesh mesh;
    mesh.positions.resize(3, 3);
    mesh.positions << 0, 2, 0, 0, 0, 2, 1, 1, 1; // the triangle (0,0,1) (2,0,1) (0,2,1)
    const std::vector<int> face{0, 1, 2};
    mesh.addFace(face.begin(), face.end());
    const auto t = rayMesh(Eigen::Vector3d(0.5, 0.5, 5), Eigen::Vector3d(0, 0, -1), mesh);
    REQUIRE(t);
    CHECK_THAT(*t, WithinAbs(4, 1e-12));
    CHECK_FALSE(rayMesh(Eigen::Vector3d(1.5, 1.5, 5), Eigen::Vector3d(0, 0, -1), mesh).has_value()); // beyond the hypotenuse
    CHECK_FALSE(rayMesh(Eigen::Vector3d(0.5, 0.5, 0), Eigen::Vector3d(0, 0, -1), mesh).has_value()); // behind the origin

    Eigen::Matrix3Xd line(3, 3);
    line << 0, 1, 1, 0, 0, 1, 0, 0, 0; // pixels (400,250) (500,250) (500,150)
    CHECK_THAT(*pixelDistanceToPolyline(v, line, 450, 260), WithinAbs(10, 1e-9));
    CHECK_THAT(*pixelDistanceToPolyline(v, line, 530, 200), WithinAbs(30, 1e-9));
    CHECK_THAT(*pixelDistanceToPolyline(v, line, 390, 250), WithinAbs(10, 1e-9));
}

TEST_CASE("dragDelta in the view plane, along an axis, in a plane", "[interaction]")
{
    const ViewTransform v = handView();
    const Eigen::Vector3d grab(0, 0, 1);
    // 100 pixels per unit, y up on screen.
    CHECK(dragDelta(v, Constraint::View, grab, 400, 250, 450, 220).isApprox(Eigen::Vector3d(0.5, 0.3, 0), 1e-12));
    CHECK(dragDelta(v, Constraint::AxisX, grab, 400, 250, 450, 220).isApprox(Eigen::Vector3d(0.5, 0, 0), 1e-12));
    CHECK(dragDelta(v, Constraint::AxisY, grab, 400, 250, 450, 220).isApprox(Eigen::Vector3d(0, 0.3, 0), 1e-12));
    CHECK(dragDelta(v, Constraint::PlaneZ, grab, 400, 250, 450, 220).isApprox(Eigen::Vector3d(0.5, 0.3, 0), 1e-12));
    // Seen end on (z points at the eye): the axis and the planes containing the view direction give nothing.
    CHECK(dragDelta(v, Constraint::AxisZ, grab, 400, 250, 450, 220) == Eigen::Vector3d::Zero());
    CHECK(dragDelta(v, Constraint::PlaneX, grab, 400, 250, 450, 220) == Eigen::Vector3d::Zero());
}

TEST_CASE("dragDelta in the view plane of an axis view (top, front, right, perspective too) has exactly 0 along the view", "[interaction]")
{
    // Issue 25: a flat curve in the top view got z values like 6.8e-34 from view-plane drags.
    Scene scene = curveScene();
    for (const char* name : {"top", "front", "right", "bottom"})
        for (Projection projection : {Projection::Orthographic, Projection::Perspective}) {
            scene.camera.setView(name);
            scene.camera.projection = projection;
            const ViewTransform v = ViewTransform::of(scene, kW, kH);
            int along = 0;
            for (int r = 1; r < 3; ++r)
                if (std::abs(v.viewDirection[r]) > std::abs(v.viewDirection[along])) along = r;
            for (const Eigen::Vector3d& grab : {Eigen::Vector3d(0.3, -0.7, 0.11), Eigen::Vector3d(-1.9, 1.3, 0.77)}) {
                const Eigen::Vector3d d = dragDelta(v, Constraint::View, grab, 401.3, 297.1, 463.9, 211.7);
                INFO(name << (projection == Projection::Orthographic ? " orthographic" : " perspective") << ": " << d.transpose());
                CHECK(d[along] == 0);
                CHECK(d.norm() > 0.1);
            }
        }
}

TEST_CASE("snapDelta puts the grabbed point on the grid in the coordinates the constraint moves", "[interaction]")
{
    const Eigen::Vector3d grab(0.13, 0.27, -0.4);
    const Eigen::Vector3d delta(0.5, 0.5, 0.06);
    Eigen::Vector3d t = grab + snapDelta(grab, delta, Constraint::View, 0.25);
    CHECK_THAT(t.x(), WithinAbs(0.75, 1e-15)); // 0.63 -> 0.75
    CHECK_THAT(t.y(), WithinAbs(0.75, 1e-15)); // 0.77 -> 0.75
    CHECK_THAT(t.z(), WithinAbs(-0.25, 1e-15)); // -0.34 -> -0.25
    t = grab + snapDelta(grab, Eigen::Vector3d(0.5, 0, 0), Constraint::AxisX, 0.25);
    CHECK_THAT(t.x(), WithinAbs(0.75, 1e-15));
    CHECK(t.y() == grab.y());
    CHECK(t.z() == grab.z());
    t = grab + snapDelta(grab, Eigen::Vector3d(0.5, 0.5, 0), Constraint::PlaneZ, 0.25);
    CHECK(t.z() == grab.z());
    CHECK(snapDelta(grab, delta, Constraint::View, 0) == delta);
}

TEST_CASE("falloff is 1 - 3t^2 + 2t^3, smooth at both ends; softWeights take the nearest selected point", "[interaction]")
{
    CHECK(falloff(0, 2) == 1);
    CHECK_THAT(falloff(0.5, 2), WithinAbs(0.84375, 1e-15)); // t = 1/4
    CHECK_THAT(falloff(1, 2), WithinAbs(0.5, 1e-15));
    CHECK(falloff(2, 2) == 0);
    CHECK(falloff(3, 2) == 0);
    CHECK(falloff(0.1, 0) == 0);
    const double h = 1e-6; // zero slope at the point and at the radius (central differences)
    CHECK_THAT((falloff(h, 1) - 1) / h, WithinAbs(0, 1e-5));
    CHECK_THAT((falloff(1, 1) - falloff(1 - h, 1)) / h, WithinAbs(0, 1e-5));
    Eigen::Matrix3Xd points(3, 4);
    points << 0, 1, 3, 10, 0, 0, 0, 0, 0, 0, 0, 0;
    const std::vector<double> w = softWeights(points, {0, 2}, 2);
    CHECK(w[0] == 1);
    CHECK(w[2] == 1);
    CHECK_THAT(w[1], WithinAbs(0.5, 1e-15)); // distance 1 to both
    CHECK(w[3] == 0);
    CHECK(softWeights(points, {0}, 0) == std::vector<double>{1, 0, 0, 0});
}

TEST_CASE("gridStep is 1, 2 or 5 times a power of ten at or above an eighth of the extent", "[interaction]")
{
    // [-1,1]^3: extent max(1, 0.5 * 2 sqrt 3 = 1.732) / 8 = 0.2165 -> 0.5.
    CHECK(gridStep(Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-1), Eigen::Vector3d::Constant(1))) == 0.5);
    // [0,16] x [0,1] x [0,1]: extent 16 / 8 = 2 -> 2.
    CHECK(gridStep(Eigen::AlignedBox3d(Eigen::Vector3d::Zero(), Eigen::Vector3d(16, 1, 1))) == 2);
    // [-30, 30]^2 x 0: extent max(30, 42.4) / 8 = 5.3 -> 10.
    CHECK(gridStep(Eigen::AlignedBox3d(Eigen::Vector3d(-30, -30, 0), Eigen::Vector3d(30, 30, 0))) == 10);
}

TEST_CASE("Gizmo: arrows and plane squares are picked in screen space", "[interaction]")
{
    const ViewTransform v = handView();
    Gizmo g; // 90 px arrows at the origin: pixel (400, 250)
    CHECK(g.pick(v, 470, 252) == Constraint::AxisX);
    CHECK(g.pick(v, 398, 190) == Constraint::AxisY);
    CHECK(g.pick(v, 430, 220) == Constraint::PlaneZ); // x and y between 0.22 and 0.42 of 90 px
    CHECK_FALSE(g.pick(v, 470, 262).has_value());     // 12 px off the x arrow
    CHECK_FALSE(g.pick(v, 330, 320).has_value());
    Overlay overlay;
    g.draw(v, overlay, Constraint::AxisX);
    CHECK(overlay.linesOnTop.positions.cols() == 3 * (3 + 4) * 2); // per axis: shaft, 2 head strokes, 4 square edges
}

TEST_CASE("Interaction: clicking the curve selects it, dragging a point moves exactly that point", "[interaction]")
{
    Session s;
    const Eigen::Matrix3Xd before = s.scene.controlPoints(0);
    const std::string original = s.scene.text();
    // Nothing selected, points of unselected objects hidden: a press on a point is the camera's.
    const Eigen::Vector2d p1 = pixel(s.scene, -1, 1.5);
    CHECK_FALSE(s.press(p1.x(), p1.y()));
    // A click on the curve (it passes through its first control point) selects it.
    const Eigen::Vector2d end = pixel(s.scene, -2, 0);
    s.interaction.click(s.scene, s.selection, s.view(), 0, end.x() + 1, end.y() - 2);
    CHECK(s.selection.item == 0);
    CHECK(s.selection.points.empty());

    // Press 3 px off point 1, move by (+50, -30) px: the view plane is y = const, so the point
    // moves by (50, 0, 30) pixels' worth of world units.
    s.drag(p1 + Eigen::Vector2d(2, 1), p1 + Eigen::Vector2d(52, -29));
    CHECK(s.selection.points == std::vector<int>{1});
    const Eigen::Matrix3Xd after = s.scene.controlPoints(0);
    const double unit = 1 / scale(s.scene);
    CHECK_THAT(after(0, 1) - before(0, 1), WithinAbs(50 * unit, 1e-12));
    CHECK_THAT(after(1, 1) - before(1, 1), WithinAbs(0, 1e-12));
    CHECK_THAT(after(2, 1) - before(2, 1), WithinAbs(30 * unit, 1e-12));
    for (int k : {0, 2, 3}) CHECK(after.col(k) == before.col(k));
    CHECK(s.scene.history().size() == 1); // the whole drag is one step
    s.scene.undo();
    CHECK(s.scene.text() == original);
}

TEST_CASE("Interaction: with snapping the grabbed point lands exactly on the grid", "[interaction]")
{
    Session s;
    s.selection.selectItem(0);
    s.settings.snap = true;
    // Bounds: x in [-2, 2], y = 0, z in [0, 1.5]: extent max(2, 0.5 sqrt(16 + 2.25)) / 8 = 0.267 -> 0.5.
    REQUIRE(gridStep(s.scene.bounds()) == 0.5);
    const Eigen::Vector2d p1 = pixel(s.scene, -1, 1.5);
    const Eigen::Matrix3Xd before = s.scene.controlPoints(0);
    s.drag(p1, p1 + Eigen::Vector2d(37, 23)); // about (+0.39, 0, -0.24) world
    const Eigen::Matrix3Xd after = s.scene.controlPoints(0);
    for (int r = 0; r < 3; ++r) CHECK(after(r, 1) / 0.5 == std::round(after(r, 1) / 0.5));
    CHECK(after(0, 1) == -0.5);
    CHECK(after(1, 1) == 0);
    CHECK(after(2, 1) == 1.5);
    for (int k : {0, 2, 3}) CHECK(after.col(k) == before.col(k));
}

TEST_CASE("Interaction: proportional editing moves neighbours by the falloff weight", "[interaction]")
{
    Session s;
    s.selection.selectItem(0);
    s.settings.soft = true;
    s.settings.softRadius = 2.5;
    const Eigen::Matrix3Xd before = s.scene.controlPoints(0);
    const Eigen::Vector2d p1 = pixel(s.scene, -1, 1.5);
    s.drag(p1, p1 + Eigen::Vector2d(40, 0));
    const Eigen::Matrix3Xd after = s.scene.controlPoints(0);
    const double dx = 40 / scale(s.scene);
    auto weight = [](double d) { // 1 - 3t^2 + 2t^3, t = d / 2.5
        const double t = d / 2.5;
        return t < 1 ? 1 - 3 * t * t + 2 * t * t * t : 0.0;
    };
    CHECK_THAT(after(0, 1) - before(0, 1), WithinAbs(dx, 1e-12));
    CHECK_THAT(after(0, 0) - before(0, 0), WithinAbs(weight(std::sqrt(1 + 2.25)) * dx, 1e-12)); // distance 1.80
    CHECK_THAT(after(0, 2) - before(0, 2), WithinAbs(weight(2) * dx, 1e-12));
    CHECK(after.col(3) == before.col(3)); // 3.35 away: outside the radius
    CHECK((after.row(2) - before.row(2)).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("Interaction: shift-click toggles, ctrl-drag boxes, A and Alt+A, Escape", "[interaction]")
{
    Session s;
    s.selection.selectItem(0);
    const Eigen::Vector2d p0 = pixel(s.scene, -2, 0), p2 = pixel(s.scene, 1, 1.5), p3 = pixel(s.scene, 2, 0);
    CHECK(s.press(p0.x(), p0.y(), GLFW_MOD_SHIFT));
    s.release(p0.x(), p0.y());
    CHECK(s.press(p2.x() + 3, p2.y() - 3, GLFW_MOD_SHIFT));
    s.release(p2.x(), p2.y());
    CHECK(s.selection.points == std::vector<int>{0, 2});
    CHECK(s.press(p0.x(), p0.y(), GLFW_MOD_SHIFT));
    s.release(p0.x(), p0.y());
    CHECK(s.selection.points == std::vector<int>{2});
    CHECK(s.scene.history().size() == 0); // selecting changes no document

    // A box around points 2 and 3 (ctrl), then one around point 0 added (ctrl+shift).
    s.drag(p2 - Eigen::Vector2d(10, 10), p3 + Eigen::Vector2d(10, 10), GLFW_MOD_CONTROL);
    CHECK(s.selection.points == std::vector<int>{2, 3});
    s.drag(p0 - Eigen::Vector2d(10, 10), p0 + Eigen::Vector2d(10, 10), GLFW_MOD_CONTROL | GLFW_MOD_SHIFT);
    CHECK(s.selection.points == std::vector<int>{0, 2, 3});

    CHECK(s.key(GLFW_KEY_A, GLFW_MOD_ALT));
    CHECK(s.selection.points.empty());
    CHECK(s.key(GLFW_KEY_A));
    CHECK(s.selection.points == std::vector<int>{0, 1, 2, 3});
    CHECK(s.key(GLFW_KEY_ESCAPE));
    CHECK(s.selection.points.empty());
    CHECK(s.selection.item == 0);
    CHECK(s.key(GLFW_KEY_ESCAPE));
    CHECK(s.selection.item == -1);
    CHECK(s.scene.history().size() == 0);
}

TEST_CASE("Interaction: the gizmo constrains to an axis or a plane", "[interaction]")
{
    Session s;
    s.selection.selectItem(0);
    s.selection.setPoints({1});
    const Eigen::Matrix3Xd before = s.scene.controlPoints(0);
    const Eigen::Vector2d p1 = pixel(s.scene, -1, 1.5);
    const double unit = 1 / scale(s.scene);
    // The x arrow points right on screen; drag it diagonally: only x changes.
    s.drag(p1 + Eigen::Vector2d(70, 0), p1 + Eigen::Vector2d(100, 40));
    Eigen::Matrix3Xd after = s.scene.controlPoints(0);
    CHECK_THAT(after(0, 1) - before(0, 1), WithinAbs(30 * unit, 1e-12));
    CHECK(after(1, 1) == before(1, 1));
    CHECK(after(2, 1) == before(2, 1));
    // The square of the y-normal plane (the view plane here), 29 px right and up of the centre.
    const Eigen::Vector2d c = pixel(s.scene, after(0, 1), after(2, 1));
    s.drag(c + Eigen::Vector2d(29, -29), c + Eigen::Vector2d(39, -49));
    const Eigen::Matrix3Xd twice = s.scene.controlPoints(0);
    CHECK_THAT(twice(0, 1) - after(0, 1), WithinAbs(10 * unit, 1e-12));
    CHECK_THAT(twice(2, 1) - after(2, 1), WithinAbs(20 * unit, 1e-12));
    CHECK(twice(1, 1) == after(1, 1));
    CHECK(s.scene.history().size() == 2);
}

TEST_CASE("Interaction: a selected point under a gizmo arrow is dragged as a point, not along the arrow (issue 25)", "[interaction]")
{
    Session s;
    s.scene.camera.distance = 15; // about 64 pixels per unit: point 2 lies on the x arrow (90 pixels)
    s.selection.selectItem(0);
    s.selection.setPoints({1, 2}); // (-1, 0, 1.5) and (1, 0, 1.5): the gizmo at (0, 0, 1.5)
    const Eigen::Matrix3Xd before = s.scene.controlPoints(0);
    const Eigen::Vector2d p2 = pixel(s.scene, 1, 1.5);
    Gizmo g;
    g.centre = Eigen::Vector3d(0, 0, 1.5);
    REQUIRE(g.pick(s.view(), p2.x(), p2.y()) == Constraint::AxisX); // the arrow passes over the point
    // Hovering the point highlights the point, not the arrow.
    s.move(p2.x(), p2.y());
    CHECK(s.selection.hoverPoint == 2);
    // Dragged by (+16, +50) pixels: both selected points follow in the view plane (x and z here).
    s.drag(p2, p2 + Eigen::Vector2d(16, 50));
    const Eigen::Matrix3Xd after = s.scene.controlPoints(0);
    const double unit = 1 / scale(s.scene);
    for (int k : {1, 2}) {
        INFO("point " << k);
        CHECK_THAT(after(0, k) - before(0, k), WithinAbs(16 * unit, 1e-12));
        CHECK_THAT(after(2, k) - before(2, k), WithinAbs(-50 * unit, 1e-12));
        CHECK(after(1, k) == before(1, k));
    }
    CHECK(after.col(0) == before.col(0));
    CHECK(after.col(3) == before.col(3));
    // Further along the arrow, off the point, the arrow is still taken: along x only.
    const Eigen::Vector2d centre = pixel(s.scene, after(0, 1) / 2 + after(0, 2) / 2, after(2, 1));
    s.drag(centre + Eigen::Vector2d(30, 0), centre + Eigen::Vector2d(40, 30));
    const Eigen::Matrix3Xd again = s.scene.controlPoints(0);
    CHECK_THAT(again(0, 1) - after(0, 1), WithinAbs(10 * unit, 1e-12));
    CHECK(again(2, 1) == after(2, 1));
}

TEST_CASE("Interaction: G grabs, X constrains, a click confirms; Escape during a drag takes it back", "[interaction]")
{
    Session s;
    s.selection.selectItem(0);
    s.selection.setPoints({2});
    const std::string original = s.scene.text();
    const Eigen::Matrix3Xd before = s.scene.controlPoints(0);
    CHECK(s.key(GLFW_KEY_G, 0, 500, 300));
    CHECK(s.interaction.busy());
    s.move(560, 250);
    CHECK(s.key(GLFW_KEY_X)); // along x only from now on
    s.move(580, 240);
    CHECK(s.press(580, 240));
    CHECK_FALSE(s.interaction.busy());
    const Eigen::Matrix3Xd after = s.scene.controlPoints(0);
    CHECK_THAT(after(0, 2) - before(0, 2), WithinAbs(80 / scale(s.scene), 1e-12));
    CHECK(after(2, 2) == before(2, 2));
    CHECK(s.scene.history().size() == 1);

    s.scene.undo();
    REQUIRE(s.scene.text() == original);
    const Eigen::Vector2d p2 = pixel(s.scene, 1, 1.5);
    CHECK(s.press(p2.x(), p2.y()));
    s.move(p2.x() + 40, p2.y() + 40);
    CHECK(s.scene.text() != original);
    CHECK(s.key(GLFW_KEY_ESCAPE));
    CHECK(s.scene.text() == original);
    CHECK_FALSE(s.scene.history().canRedo());
    CHECK(s.scene.history().size() == 0);
}

TEST_CASE("Interaction: a click on nothing clears the points, then the object", "[interaction]")
{
    Session s;
    s.selection.selectItem(0);
    s.selection.setPoints({1, 2});
    s.interaction.click(s.scene, s.selection, s.view(), 0, 5, 5);
    CHECK(s.selection.item == 0);
    CHECK(s.selection.points.empty());
    s.interaction.click(s.scene, s.selection, s.view(), 0, 5, 5);
    CHECK(s.selection.item == -1);
}

TEST_CASE("worldToPixel agrees with the closed form of the orthographic front view", "[interaction]")
{
    const Scene scene = curveScene();
    const Eigen::Vector2d p = worldToPixel(scene, kW, kH, Eigen::Vector3d(1, 0.3, 1.5));
    const Eigen::Vector2d expected = pixel(scene, 1, 1.5);
    CHECK_THAT(p.x(), WithinAbs(expected.x(), 1e-9));
    CHECK_THAT(p.y(), WithinAbs(expected.y(), 1e-9));
}

TEST_CASE("parseReplay reads every event type and rejects malformed files naming the event", "[interaction]")
{
    const auto events = parseReplay(R"({"events": [
      {"type": "move", "x": 640, "y": 400},
      {"type": "press", "button": "left", "x": 640, "y": 400, "mods": ["shift"]},
      {"type": "release", "button": "right", "x": 700, "y": 380},
      {"type": "key", "key": "Z", "mods": ["ctrl", "shift"]},
      {"type": "key_press", "key": "F12"}, {"type": "key_release", "key": "Escape"},
      {"type": "text", "text": "out.obj"},
      {"type": "scroll", "dy": -1, "x": 640, "y": 400},
      {"type": "frame", "count": 3},
      {"type": "open", "path": "file.json"}]})");
    REQUIRE(events.size() == 10);
    CHECK(events[1].type == ReplayEvent::Type::Press);
    CHECK(events[1].mods == GLFW_MOD_SHIFT);
    CHECK(events[2].button == GLFW_MOUSE_BUTTON_RIGHT);
    CHECK(events[3].key == GLFW_KEY_Z);
    CHECK(events[3].mods == (GLFW_MOD_CONTROL | GLFW_MOD_SHIFT));
    CHECK(events[4].key == GLFW_KEY_F12);
    CHECK(events[7].dy == -1);
    CHECK(events[8].count == 3);
    CHECK(events[9].text == "file.json");
    CHECK(keyCode("Plus") == GLFW_KEY_KP_ADD);
    CHECK(keyCode("7") == GLFW_KEY_7);
    CHECK(keyCode("F13") == -1);

    auto message = [](const std::string& text) {
        try {
            parseReplay(text, "e.json");
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK(message("{\"events\": [{\"type\": \"jump\"}]}").find("events[0].type") != std::string::npos);
    CHECK(message("{\"events\": [{\"type\": \"frame\"}, {\"type\": \"key\", \"key\": \"Hyper\"}]}").find("events[1].key") != std::string::npos);
    CHECK(message("{\"events\": [{\"type\": \"move\", \"x\": 1}]}").find("missing \"y\"") != std::string::npos);
    CHECK(message("{\"events\": [{\"type\": \"move\", \"x\": 1, \"y\": 2, \"z\": 3}]}").find("events[0].z") != std::string::npos);
    CHECK(message("{\"events\": [{\"type\": \"press\", \"button\": \"left\", \"x\": 1, \"y\": 2, \"mods\": [\"meta\"]}]}").find("mods") != std::string::npos);
    CHECK(message("{\"events\": [{\"type\": \"frame\", \"count\": 0}]}").find("count") != std::string::npos);
    CHECK(message("[1, 2]").find("expected an object") != std::string::npos);
    CHECK(message("{\"events\": [").find("not valid JSON") != std::string::npos);
}

TEST_CASE("parseReplay reads tooltip_audit (the tooltip test's hook) and rejects a bad step or window list", "[interaction]")
{
    const auto events = parseReplay(R"({"events": [{"type": "tooltip_audit"}, {"type": "tooltip_audit", "step": 4.5, "windows": ["Properties", "Scene"]}]})");
    REQUIRE(events.size() == 2);
    CHECK(events[0].type == ReplayEvent::Type::TooltipAudit);
    CHECK(events[0].step == 0); // the default: half a line height
    CHECK(events[0].windows.empty());
    CHECK(events[1].step == 4.5);
    CHECK(events[1].windows == std::vector<std::string>{"Properties", "Scene"});
    auto message = [](const std::string& text) {
        try {
            parseReplay(text, "e.json");
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK(message(R"({"events": [{"type": "tooltip_audit", "step": 0}]})").find("events[0].step") != std::string::npos);
    CHECK(message(R"({"events": [{"type": "tooltip_audit", "step": 101}]})").find("events[0].step") != std::string::npos);
    CHECK(message(R"({"events": [{"type": "tooltip_audit", "windows": []}]})").find("events[0].windows") != std::string::npos);
    CHECK(message(R"({"events": [{"type": "tooltip_audit", "windows": [3]}]})").find("events[0].windows") != std::string::npos);
    CHECK(message(R"({"events": [{"type": "tooltip_audit", "count": 3}]})").find("events[0].count") != std::string::npos);
}

} // namespace test_interaction

namespace test_interaction {

TEST_CASE("Interaction: a click on a part picks the face under the pointer (top, side, then none)", "[interaction][cad]")
{
    // data/parts/plate.json: which face is the top (every control point at z = 10) and which the
    // side x = min or max facing the camera is read from the part's data, not from the picking.
    Scene scene = Scene::load(std::string(FREEFORM_SOURCE_DIR) + "/data/parts/plate.json");
    scene.camera.setView("iso");
    scene.camera.fit(scene.bounds(), double(kW) / kH);
    scene.updateGeometry();
    REQUIRE(scene.item(0).geometry.vertexFace.size() == static_cast<std::size_t>(scene.item(0).geometry.surface->vertexCount()));
    const PartData& part = std::get<PartData>(scene.object(0).data);
    Eigen::AlignedBox3d box; // of the control points: the planes' own coordinates, exactly
    for (const auto& f : part.faces)
        for (Eigen::Index k = 0; k < f.surface.surface.points.cols(); ++k) box.extend(Eigen::Vector3d(f.surface.surface.points.col(k)));
    auto faceWhere = [&](int axis, double value) {
        int found = -1;
        for (std::size_t f = 0; f < part.faces.size(); ++f) {
            const auto& p = part.faces[f].surface.surface.points;
            if ((p.row(axis).array() == value).all()) found = static_cast<int>(f);
        }
        return found;
    };
    const ViewTransform view = ViewTransform::of(scene, kW, kH);
    const bool minSide = view.viewDirection.x() > 0; // looking towards +x: the side x = min faces the eye
    const double sideX = minSide ? box.min().x() : box.max().x();
    const int top = faceWhere(2, box.max().z()), side = faceWhere(0, sideX);
    REQUIRE(view.viewDirection.z() < 0); // the top faces the eye
    REQUIRE(top >= 0);
    REQUIRE(side >= 0);
    REQUIRE(top != side);
    EditSettings settings;
    Interaction interaction{settings};
    Selection selection;
    auto clickAt = [&](const Eigen::Vector3d& p) {
        const auto px = view.toPixel(p);
        REQUIRE(px);
        interaction.click(scene, selection, view, 0, px->x(), px->y());
    };
    const Eigen::Vector3d d = box.diagonal();
    clickAt(box.min() + Eigen::Vector3d(0.1 * d.x(), 0.1 * d.y(), d.z())); // on the top, away from the hole
    CHECK(selection.item == 0);
    CHECK(selection.face == top);
    // (Counted from 1, as errors and Open CASCADE count faces.)
    CHECK(faceSummary(part, top).rfind("face " + std::to_string(top + 1) + ": plane, degree 1 x 1, ", 0) == 0);
    clickAt(Eigen::Vector3d(sideX, box.center().y(), box.center().z())); // the middle of that side
    CHECK(selection.face == side);
    interaction.click(scene, selection, view, 0, 2, 2); // the corner of the view: nothing
    CHECK(selection.item == -1);
    CHECK(selection.face == -1);
}

} // namespace test_interaction
