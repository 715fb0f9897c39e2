// The editor's scene layer without a display: the document round trip (save -> open -> save gives
// the same bytes, through the freeform-editor binary and through Scene), the camera (matrices
// against core/transform.h built by hand, zoom keeps the point under the cursor, fit, the axis
// views), the JSON of the settings, and "nothing lost" on unreadable files.

#include <catch2/catch.hpp>

#include <freeform/core/transform.h>

#include <cmath>
#include <numbers>
#include <filesystem>

#include "scene/camera.h"
#include "scene/scene.h"
#include "support/process.h"

namespace test_scene {

using namespace freeform;
using namespace freeform::editor;
using Catch::Matchers::WithinAbs;

namespace {

namespace fs = std::filesystem;
const std::string kSource = FREEFORM_SOURCE_DIR;
const std::string kTmp = FREEFORM_TEST_TMP;

test::ProcessResult editorBinary(const std::string& arguments)
{
    return test::run(std::string("'") + FREEFORM_EDITOR + "' " + arguments);
}

/// Window coordinates of a world point for a camera and a viewport.
Eigen::Vector3d project(const Camera& c, const Eigen::Vector3d& p, double width, double height)
{
    const Eigen::Matrix4d m = viewport<double>(0, 0, width, height) * c.projectionMatrix(width / height, 0.1, 100) * c.viewMatrix();
    return transformPoint<double>(m, p);
}

} // namespace

TEST_CASE("document round trip: save, open, save gives the same file", "[editor]")
{
    const std::string a = kTmp + "/roundtrip_a.json", b = kTmp + "/roundtrip_b.json", c = kTmp + "/roundtrip_c.json";
    for (const auto& p : {a, b, c}) fs::remove(p);
    SECTION("through the binary (--save needs no display)")
    {
        REQUIRE(editorBinary("'" + kSource + "/examples/data/demo-scene.json' --save '" + a + "'").status == 0);
        REQUIRE(editorBinary("'" + a + "' --save '" + b + "'").status == 0);
        REQUIRE(editorBinary("'" + b + "' --save '" + c + "'").status == 0);
        const std::string first = test::slurp(a);
        CHECK(first == test::slurp(b));
        CHECK(first == test::slurp(c));
        CHECK(first.find("\"camera\"") != std::string::npos);
        CHECK(first.find("\"display\"") != std::string::npos);
    }
    SECTION("with changed settings, object settings and an imported mesh")
    {
        const std::string mesh = kTmp + "/roundtrip_quad.obj";
        test::writeText(mesh, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
        Scene scene = Scene::load(kSource + "/examples/data/demo-scene.json");
        scene.importFile(mesh);
        scene.display.shading = Shading::Gouraud;
        scene.display.lights.push_back({Vec3f(1, 2, 3), Vec3f(0.1f, 0.2f, 0.3f), false});
        scene.camera.setView("top");
        scene.camera.projection = Projection::Orthographic;
        ObjectSettings s;
        s.visible = false;
        s.ownMaterial = true;
        s.material.shininess = 7.5f;
        s.tessellation.mode = Tessellation::Mode::Uniform;
        s.tessellation.segments = 5;
        s.tessellation.flip = true;
        scene.setSettings(3, s);
        REQUIRE(scene.modified());
        scene.save(a);
        CHECK_FALSE(scene.modified());
        Scene reopened = Scene::load(a);
        CHECK(reopened.display == scene.display);
        CHECK(reopened.camera == scene.camera);
        CHECK(reopened.item(3).settings == s);
        CHECK(reopened.itemCount() == scene.itemCount());
        CHECK(reopened.item(reopened.itemCount() - 1).type == "mesh");
        CHECK(reopened.item(reopened.itemCount() - 1).geometry.surface->faceCount() == 2);
        reopened.save(b);
        CHECK(test::slurp(a) == test::slurp(b));
    }
}

TEST_CASE("an unreadable file leaves the open scene as it was", "[editor]")
{
    Scene scene = Scene::load(kSource + "/examples/data/demo-scene.json");
    const std::string before = scene.text();
    const std::string bad = kTmp + "/bad_import.obj";
    test::writeText(bad, "v 0 0 0\nf 1 2 3\n");
    REQUIRE_THROWS_AS(scene.importFile(bad), Error);
    REQUIRE_THROWS_AS(scene.importFile(kTmp + "/missing.bpt"), Error);
    REQUIRE_THROWS_AS(Scene::load(bad), Error);
    CHECK(scene.text() == before);
    // An invalid edit is refused and changes nothing either.
    REQUIRE_THROWS_AS(scene.setControlPoint(0, 99, Eigen::Vector3d::Zero()), Error);
    REQUIRE_THROWS_AS(scene.setControlPoint(0, 0, Eigen::Vector3d(NAN, 0, 0)), Error);
    CHECK(scene.text() == before);
    // A valid edit changes exactly that point.
    scene.setControlPoint(33, 1, Eigen::Vector3d(1.5, 2.5, 3.5));
    const auto& curve = std::get<BezierCurveData>(scene.object(33).data);
    CHECK(curve.points.col(1) == Eigen::Vector3d(1.5, 2.5, 3.5));
    CHECK(scene.modified());
}

TEST_CASE("importing a .bpt orients the teapot outwards", "[editor]")
{
    Scene scene;
    scene.importFile(kSource + "/data/teapot.bpt");
    REQUIRE(scene.itemCount() == 32);
    scene.updateGeometry();
    // Enclosed volume of all patches' triangles, each patch on its own: positive = outward.
    double volume6 = 0;
    for (int i = 0; i < scene.itemCount(); ++i) {
        const PolygonMesh& m = *scene.item(i).geometry.surface;
        for (int f = 0; f < m.faceCount(); ++f)
            volume6 += m.positions.col(m.face(f)[0]).dot(m.positions.col(m.face(f)[1]).cross(m.positions.col(m.face(f)[2])));
    }
    CHECK(volume6 > 0);
    // And the normals agree with the triangles' orientation.
    const PolygonMesh& body = *scene.item(5).geometry.surface;
    const int* t = body.face(body.faceCount() / 2);
    const Eigen::Vector3d faceNormal = (body.positions.col(t[1]) - body.positions.col(t[0])).cross(body.positions.col(t[2]) - body.positions.col(t[0]));
    CHECK(faceNormal.dot(body.normals.col(t[0])) > 0);
}

TEST_CASE("a part opens shaded face by face, its points not editable, and saves back the same bytes", "[editor]")
{
    // data/parts/plate.json: a 40 x 30 x 10 plate with a hole of radius 6 (docs/cad.md, "Documents").
    Scene scene = Scene::load(kSource + "/data/parts/plate.json");
    REQUIRE(scene.itemCount() == 1);
    scene.updateGeometry();
    const ItemGeometry& g = scene.item(0).geometry;
    INFO(g.error);
    CHECK(g.error.empty());
    REQUIRE(g.surface);
    CHECK(g.netPoints.cols() == 0); // a part draws no control net
    const PolygonMesh& m = *g.surface;
    REQUIRE(m.normals.cols() == m.vertexCount());
    // Each face on vertices of its own (ObjectTessellation::splitFaces): on the top face z = 10
    // every vertex normal is +z (to the rounding of the slivers at the hole's rim), on the bottom -z, though the rims join other faces.
    int top = 0, bottom = 0;
    for (int f = 0; f < m.faceCount(); ++f) {
        const int* t = m.face(f);
        const bool flat = m.positions(2, t[0]) == m.positions(2, t[1]) && m.positions(2, t[1]) == m.positions(2, t[2]);
        if (!flat) continue;
        const double z = m.positions(2, t[0]);
        for (int k = 0; k < 3; ++k) {
            INFO(m.normals.col(t[k]).transpose() << " at " << m.positions.col(t[k]).transpose());
            if (z == 10) CHECK(m.normals.col(t[k]).isApprox(Eigen::Vector3d(0, 0, 1), 1e-9));
            if (z == 0) CHECK(m.normals.col(t[k]).isApprox(Eigen::Vector3d(0, 0, -1), 1e-9));
        }
        top += z == 10, bottom += z == 0;
    }
    CHECK(top > 0);
    CHECK(bottom > 0);
    // The outline drawn on the shading (faceOutline): every face's boundary, so each edge of the
    // part twice (once per face): 2 (12 box edges, 4 x 40 + 4 x 30 + 4 x 10 = 320, and two circles
    // of radius 6, 24 pi), the circles as chords within the tolerance. The hole's seam is not in
    // it: both of its sides on the cylinder take the seam edge's samples, so the face's mesh closes
    // across it (a seam drawn would be a line the part does not have).
    double outline = 0;
    for (const auto& [a, b] : g.outline) outline += (m.positions.col(a) - m.positions.col(b)).norm();
    const double expected = 2 * (320 + 24 * std::numbers::pi);
    INFO("outline " << outline << " of " << expected << " (" << g.outline.size() << " segments)");
    CHECK(std::abs(outline - expected) < 1e-3 * expected);
    CHECK(scene.controlPointCount(0) == 0);
    CHECK_THROWS_WITH(scene.setControlPoint(0, 0, Eigen::Vector3d::Zero()), Catch::Contains("no control points to edit"));
    const std::string out = kTmp + "/plate_saved.json";
    fs::remove(out);
    scene.save(out);
    const std::string saved = test::slurp(out);
    // The part's object is the file's, byte for byte (the editor adds its settings after it).
    const std::string original = test::slurp(kSource + "/data/parts/plate.json");
    const std::string objectText = original.substr(original.find("\"faces\""), original.find("\"solids\"") - original.find("\"faces\""));
    CHECK(saved.find(objectText) != std::string::npos);
}

TEST_CASE("camera matrices are the transform.h matrices of its frame", "[editor][camera]")
{
    Camera c;
    c.target = Eigen::Vector3d(1, 2, 3);
    c.distance = 5;
    c.setView("front"); // right +x, up +z, looking along +y
    CHECK((c.eye() - Eigen::Vector3d(1, -3, 3)).norm() < 1e-15);
    const Eigen::Matrix4d expected = lookAt<double>({1, -3, 3}, {1, 2, 3}, {0, 0, 1});
    CHECK((c.viewMatrix() - expected).cwiseAbs().maxCoeff() < 1e-14);
    // The target is in the middle of the picture; a point one half-height above it at the top edge (orthographic).
    c.projection = Projection::Orthographic;
    const Eigen::Vector3d centre = project(c, c.target, 400, 300);
    CHECK_THAT(centre.x(), WithinAbs(200, 1e-9));
    CHECK_THAT(centre.y(), WithinAbs(150, 1e-9));
    const Eigen::Vector3d top = project(c, c.target + c.halfHeight() * Eigen::Vector3d::UnitZ(), 400, 300);
    CHECK_THAT(top.y(), WithinAbs(300, 1e-9));

    for (const char* view : {"front", "back", "left", "right", "top", "bottom", "iso"}) {
        c.setView(view);
        const Eigen::Matrix3d r = c.orientation.toRotationMatrix();
        CHECK((r * r.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-12);
        CHECK_THAT(r.determinant(), WithinAbs(1, 1e-12));
    }
    c.setView("top");
    CHECK((c.back() - Eigen::Vector3d::UnitZ()).norm() < 1e-15);
    c.setView("right");
    CHECK((c.back() - Eigen::Vector3d::UnitX()).norm() < 1e-15);
    REQUIRE_THROWS_AS(c.setView("sideways"), Error);
}

TEST_CASE("zoom keeps the point under the cursor where it is", "[editor][camera]")
{
    for (const Projection projection : {Projection::Perspective, Projection::Orthographic}) {
        Camera c;
        c.projection = projection;
        c.setView("iso");
        c.distance = 8;
        const Eigen::Vector2d cursor(0.4, -0.3);
        const double width = 640, height = 480, aspect = width / height;
        // The world point in the target plane under the cursor.
        const double h = c.halfHeight();
        const Eigen::Vector3d under = c.target + cursor.x() * aspect * h * c.right() + cursor.y() * h * c.up();
        const Eigen::Vector3d before = project(c, under, width, height);
        c.zoom(0.5, cursor, aspect);
        const Eigen::Vector3d after = project(c, under, width, height);
        CHECK_THAT(c.distance, WithinAbs(4, 1e-12));
        CHECK_THAT(before.x(), WithinAbs(320 + 0.4 * 320, 1e-9));
        CHECK_THAT(after.x(), WithinAbs(before.x(), 1e-9));
        CHECK_THAT(after.y(), WithinAbs(before.y(), 1e-9));
    }
}

TEST_CASE("fit puts the whole box in view; orbits keep the target and distance", "[editor][camera]")
{
    const Eigen::AlignedBox3d box(Eigen::Vector3d(-2, -3, 0), Eigen::Vector3d(4, 1, 2.5));
    const Eigen::Vector3d centre = box.center();
    Camera c;
    for (const Projection projection : {Projection::Perspective, Projection::Orthographic})
        for (const char* view : {"iso", "front", "top", "left"}) {
            c.projection = projection;
            c.setView(view);
            c.fit(box, 2.0);
            CAPTURE(view);
            // Every corner is inside the picture (and in front of the camera) ...
            double widest = 0;
            for (int k = 0; k < 8; ++k) {
                const Eigen::Vector3d p = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(k));
                const Eigen::Vector3d w = project(c, p, 800, 400);
                CHECK(w.x() >= 0);
                CHECK(w.x() <= 800);
                CHECK(w.y() >= 0);
                CHECK(w.y() <= 400);
                if (projection == Projection::Perspective) CHECK((c.eye() - p).dot(c.back()) > 0);
                widest = std::max({widest, std::abs(w.x() - 400) / 400, std::abs(w.y() - 200) / 200});
            }
            // ... and the box fills it up to the 5% margin.
            if (projection == Projection::Orthographic) CHECK_THAT(widest, WithinAbs(1 / 1.05, 1e-9));
            else CHECK(widest > 0.9);
        }
    c.projection = Projection::Perspective;
    c.setView("iso");
    c.fit(box, 2.0);
    const double distance = c.distance;
    c.orbitTurntable(0.3, -0.2);
    c.orbitArcball({0.1, 0.2}, {-0.3, 0.5});
    CHECK((c.target - centre).norm() < 1e-12);
    CHECK(c.distance == distance);
    CHECK_THAT(c.orientation.norm(), WithinAbs(1, 1e-12));
    // Turntable keeps the horizon level: the camera's right axis stays horizontal.
    c.setView("iso");
    c.orbitTurntable(0.7, 0.4);
    CHECK_THAT(c.right().z(), WithinAbs(0, 1e-12));
    // ... and never tips over the pole.
    c.orbitTurntable(0, 10);
    CHECK(c.back().z() < 1);
    CHECK(c.up().z() > 0);
}

TEST_CASE("camera and display settings read back what they write; bad values are named", "[editor]")
{
    Camera c;
    c.target = Eigen::Vector3d(0.1, 0.2, 0.3);
    c.setView("left");
    c.fovyDegrees = 50;
    c.orbit = OrbitMode::Arcball;
    CHECK(Camera::fromJson(c.toJson()) == c);

    DisplaySettings d;
    d.shading = Shading::Flat;
    d.analysis = SurfaceAnalysis::ReflectionLines;
    d.material.diffuse = Vec3f(0.1f, 0.7f, 0.3f);
    CHECK(DisplaySettings::fromJson(d.toJson()) == d);
    CHECK(DisplaySettings::fromJson(d.toJson()).toJson().dump() == d.toJson().dump());

    Json bad = d.toJson();
    bad["shading"] = "toon";
    REQUIRE_THROWS_WITH(DisplaySettings::fromJson(bad), Catch::Contains("editor.display.shading"));
    bad = d.toJson();
    bad["colour"] = 1;
    REQUIRE_THROWS_WITH(DisplaySettings::fromJson(bad), Catch::Contains("unknown field"));
    Json cam = c.toJson();
    cam["distance"] = 0;
    REQUIRE_THROWS_WITH(Camera::fromJson(cam), Catch::Contains("editor.camera.distance"));
}

TEST_CASE("display: anti-aliasing is auto unless the document says always; auto drops multisampling only for a software renderer's frames",
          "[editor]")
{
    // A document written before the field existed (samples 4, no "antialiasing") reads as auto.
    Json old = DisplaySettings{}.toJson();
    old.erase("antialiasing");
    CHECK(DisplaySettings::fromJson(old).antialiasing == Antialiasing::Auto);
    CHECK(DisplaySettings{}.toJson()["antialiasing"] == "auto");
    DisplaySettings d;
    d.antialiasing = Antialiasing::Always;
    d.samples = 2;
    CHECK(d.toJson()["antialiasing"] == "always");
    CHECK(DisplaySettings::fromJson(d.toJson()) == d);
    Json bad = d.toJson();
    bad["antialiasing"] = "sometimes";
    REQUIRE_THROWS_WITH(DisplaySettings::fromJson(bad), Catch::Contains("editor.display.antialiasing"));

    // The rule, case by case: (antialiasing, software renderer, still image) -> samples used.
    DisplaySettings a; // auto, 4
    CHECK(effectiveSamples(a, false, false) == 4);
    CHECK(effectiveSamples(a, false, true) == 4);
    CHECK(effectiveSamples(a, true, false) == 0);
    CHECK(effectiveSamples(a, true, true) == 4);
    a.samples = 0; // off stays off
    CHECK(effectiveSamples(a, false, true) == 0);
    CHECK(effectiveSamples(d, true, false) == 2); // always: everywhere
    CHECK(effectiveSamples(d, false, false) == 2);
}

TEST_CASE("scene: the pixel tolerance gives the world size of that many pixels at the nearest depth, redone only past 2x",
          "[editor][scene]")
{
    // An empty scene's bounds are the box [-1, 1]^3; the camera looks at the origin down -z from
    // distance 10, so the nearest corner is at depth 9. One pixel there in a view 800 pixels high:
    // 2 * 9 * tan(17.5 deg) / 800 (fovy 35 degrees).
    Scene scene;
    scene.camera.target = Eigen::Vector3d::Zero();
    scene.camera.orientation = Eigen::Quaterniond::Identity();
    scene.camera.distance = 10;
    scene.camera.fovyDegrees = 35;
    scene.camera.projection = Projection::Perspective;
    scene.pixelTolerance = 0.5;
    scene.updateViewTolerance(800);
    const double expected = 0.5 * 2 * 9 * std::tan(17.5 * 3.14159265358979323846 / 180) / 800;
    CHECK(scene.tessellationTolerance() == Approx(expected).epsilon(1e-12));
    // Zooming in by 1.5x keeps it (within 2x); by 3x more it is recomputed.
    scene.camera.distance = 10 / 1.5; // nearest depth 10/1.5 - 1 = 5.67: 1.59 times closer than 9
    scene.updateViewTolerance(800);
    CHECK(scene.tessellationTolerance() == Approx(expected).epsilon(1e-12));
    scene.camera.distance = 2.5; // nearest depth 1.5: 6 times closer than 9
    scene.updateViewTolerance(800);
    CHECK(scene.tessellationTolerance() == Approx(expected * 1.5 / 9).epsilon(1e-12));
    // Off: the world tolerance.
    scene.pixelTolerance = 0;
    scene.updateViewTolerance(800);
    CHECK(scene.tessellationTolerance() == scene.display.tolerance);
}

} // namespace test_scene
