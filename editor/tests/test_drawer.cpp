// The scene drawer through the recording backend (render/recording_renderer.h): what a frame would
// draw and when buffers are uploaded, without a GL context or a display. The expected counts are
// worked out from the documents written here (a cubic curve has 4 control points and a control
// polygon of 3 segments; a tetrahedron has 4 vertices and 4 triangles).

#include <catch2/catch.hpp>

#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "freeform/core/error.h"
#include "render/recording_renderer.h"
#include "scene/overlay.h"
#include "scene/scene.h"
#include "scene/scene_drawer.h"
#include "support/process.h"

namespace test_drawer {

using namespace freeform;
using namespace freeform::editor;
using Kind = RecordingRenderer::Kind;

namespace {

const std::string kTmp = FREEFORM_TEST_TMP;

Scene curveScene()
{
    const std::string path = kTmp + "/drawer-curve.json";
    test::writeText(path, R"({"format": "freeform", "version": 1, "objects": [
      {"name": "c", "type": "bezier_curve", "points": [[-2, 0, 0.5], [-1, 1, 1.5], [0.5, -1, 2], [2, 0.3, -0.5]]}]})");
    return Scene::load(path);
}

Scene tetrahedron()
{
    const std::string path = kTmp + "/drawer-tetra.obj";
    test::writeText(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
    return Scene::load(path);
}

} // namespace

TEST_CASE("recording renderer: a selected cubic curve draws its polyline, its 3 net segments and 4 points", "[editor][drawer]")
{
    Scene scene = curveScene();
    scene.display.grid = false;
    scene.display.axes = false;
    RecordingRenderer r;
    SceneDrawer drawer(r);
    CHECK(drawer.draw(scene, 640, 480, 0) == 0); // no triangles
    CHECK(r.frames() == 1);
    CHECK(r.frame().width == 640);
    CHECK(r.frame().height == 480);

    const auto lines = r.calls(Kind::Lines);
    REQUIRE(lines.size() == 2); // the curve (depth-tested), the net (on top)
    CHECK(lines[0].depthTested);
    CHECK(lines[0].vertices == 2 * (scene.item(0).geometry.curve.cols() - 1));
    CHECK(lines[0].vertices >= 2);
    CHECK_FALSE(lines[1].depthTested);
    CHECK(lines[1].vertices == 2 * 3);
    const auto points = r.calls(Kind::Points);
    REQUIRE(points.size() == 1);
    CHECK(points[0].vertices == 4);
    CHECK(points[0].diameter == scene.display.pointSize);
    REQUIRE(points[0].colors.size() == 1);
    const Vec3f selectedColor = points[0].colors[0];

    // Not selected and control points hidden: no net, no points.
    drawer.draw(scene, 640, 480, -1);
    CHECK(r.calls(Kind::Lines).size() == 1);
    CHECK(r.calls(Kind::Points).empty());
    // Control points of every object shown: the unselected colour differs from the selected one.
    scene.display.controlPoints = true;
    drawer.draw(scene, 640, 480, -1);
    REQUIRE(r.calls(Kind::Points).size() == 1);
    REQUIRE(r.calls(Kind::Points)[0].colors.size() == 1);
    CHECK(r.calls(Kind::Points)[0].colors[0] != selectedColor);
    // Grid and axes come first when shown.
    scene.display.grid = scene.display.axes = true;
    drawer.draw(scene, 640, 480, -1);
    CHECK(r.calls(Kind::Lines).size() == 3);
}

TEST_CASE("recording renderer: a mesh is uploaded once; changed scalars update its vertices, not its triangles", "[editor][drawer]")
{
    Scene scene = tetrahedron();
    REQUIRE(scene.itemCount() == 1);
    RecordingRenderer r;
    SceneDrawer drawer(r);
    CHECK(drawer.draw(scene, 320, 200) == 4);
    const auto meshes = r.calls(Kind::Mesh);
    REQUIRE(meshes.size() == 1);
    CHECK(meshes[0].triangles == 4);
    CHECK(meshes[0].vertices >= 4);
    CHECK(r.counters().meshUploads == 1);

    // Nothing changed: the next frame uploads nothing.
    r.clearCounters();
    drawer.draw(scene, 320, 200);
    CHECK(r.counters().meshUploads == 0);
    CHECK(r.counters().vertexUpdates == 0);
    CHECK(r.counters().lineUploads == 0);

    // Scalars (a det J colour map) change the vertex data only: updateVertices, same triangles.
    const auto v = static_cast<std::size_t>(scene.item(0).geometry.surface->vertexCount());
    std::vector<float> scalars(v);
    for (std::size_t i = 0; i < v; ++i) scalars[i] = float(i);
    scene.setScalars(0, scalars);
    scene.display.scalarAuto = true; // the colour range is the scalars' own (the default is a fixed [0, 2])
    drawer.draw(scene, 320, 200);
    CHECK(r.counters().meshUploads == 0);
    CHECK(r.counters().vertexUpdates == 1);
    const auto& buffer = r.buffer(r.calls(Kind::Mesh)[0].handle);
    CHECK(buffer.mesh.scalars == scalars);
    CHECK(buffer.mesh.triangles.size() == 3 * 4);
    CHECK(r.calls(Kind::Mesh)[0].style.scalarMin == 0.0f);
    CHECK(r.calls(Kind::Mesh)[0].style.scalarMax == float(v - 1));
    // The default fixed range (issue 12: colours do not rescale while a lattice is dragged).
    scene.display.scalarAuto = false;
    drawer.draw(scene, 320, 200);
    CHECK(r.calls(Kind::Mesh)[0].style.scalarMin == 0.0f);
    CHECK(r.calls(Kind::Mesh)[0].style.scalarMax == 2.0f);

    // clear() releases every buffer the drawer made.
    drawer.clear();
    CHECK(r.liveBuffers() == 0);
}

TEST_CASE("recording renderer: the overlay is drawn last, its lines depth-tested or on top, its points as discs", "[editor][drawer]")
{
    Scene scene = curveScene();
    RecordingRenderer r;
    SceneDrawer drawer(r);
    Overlay overlay;
    overlay.addLine(Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(1, 0, 0), false);
    overlay.addLine(Vec3f(0, 0, 0), Vec3f(0, 1, 0), Vec3f(0, 1, 0), true);
    overlay.addLine(Vec3f(0, 1, 0), Vec3f(0, 1, 1), Vec3f(0, 0, 1), true);
    overlay.addPoint(Vec3f(0, 0, 0), Vec3f(1, 1, 0));
    overlay.pointDiameter = 11;
    drawer.draw(scene, 100, 100, -1, &overlay);
    const auto& calls = r.calls();
    REQUIRE(calls.size() >= 3);
    const auto& last = calls[calls.size() - 1];
    const auto& top = calls[calls.size() - 2];
    const auto& depth = calls[calls.size() - 3];
    CHECK(last.kind == Kind::Points);
    CHECK(last.vertices == 1);
    CHECK(last.diameter == 11);
    CHECK(top.kind == Kind::Lines);
    CHECK_FALSE(top.depthTested);
    CHECK(top.vertices == 4);
    CHECK(top.colors.size() == 2);
    CHECK(depth.kind == Kind::Lines);
    CHECK(depth.depthTested);
    CHECK(depth.vertices == 2);
    REQUIRE(depth.colors.size() == 1);
    CHECK(depth.colors[0] == Vec3f(1, 0, 0));
}

TEST_CASE("recording renderer: a buffer that is not live cannot be drawn, updated or released", "[editor][drawer]")
{
    RecordingRenderer r;
    CHECK_THROWS_AS(r.release(BufferHandle{7}), Error);
    LineData lines;
    lines.positions = Eigen::Matrix<float, 3, 2>::Zero();
    lines.colors = Eigen::Matrix<float, 3, 2>::Ones();
    const BufferHandle h = r.uploadLines({}, lines);
    CHECK_THROWS_AS(r.drawMesh(h, Mat4f::Identity(), {}), Error); // lines, not a mesh
    MeshData mesh;
    mesh.positions = Eigen::Matrix<float, 3, 3>::Zero();
    mesh.normals = mesh.positions;
    mesh.triangles = {0, 1, 2};
    const BufferHandle m = r.uploadMesh({}, mesh);
    MeshData fewer = mesh;
    fewer.positions.resize(3, 2);
    fewer.normals.resize(3, 2);
    CHECK_THROWS_AS(r.updateVertices(m, fewer), Error);
    r.release(h);
    CHECK_THROWS_AS(r.drawLines(h, Mat4f::Identity()), Error);
    CHECK(r.liveBuffers() == 1);
}

TEST_CASE("recording renderer: surfaces are drawn nearest first, whatever their order in the document", "[editor][drawer]")
{
    // Two flat bilinear patches, "low" in the plane z = 0 and "high" in z = 5, low first in the
    // document. Seen from above (view "top", the eye on +z), high is nearer and must be drawn first;
    // seen from below, low. A hidden fragment is then rejected by the depth test before it is shaded.
    const std::string path = kTmp + "/drawer-two-patches.json";
    test::writeText(path, R"({"format": "freeform", "version": 1, "objects": [
      {"name": "low", "type": "bezier_surface", "degree": [1, 1], "points": [[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 0]]]},
      {"name": "high", "type": "bezier_surface", "degree": [1, 1], "points": [[[0, 0, 5], [0, 1, 5]], [[1, 0, 5], [1, 1, 5]]]}]})");
    Scene scene = Scene::load(path);
    REQUIRE(scene.itemCount() == 2);
    RecordingRenderer r;
    SceneDrawer drawer(r);
    // The z of the first vertex of each mesh drawn, in drawing order.
    auto drawnHeights = [&]() {
        std::vector<float> z;
        for (const auto& call : r.calls(Kind::Mesh)) z.push_back(r.buffer(call.handle).mesh.positions(2, 0));
        return z;
    };
    for (const auto& [view, first, second] : {std::tuple{"top", 5.0f, 0.0f}, std::tuple{"bottom", 0.0f, 5.0f}}) {
        scene.camera.setView(view);
        scene.camera.fit(scene.bounds(), 4.0 / 3.0);
        CHECK(drawer.draw(scene, 400, 300) == 4); // 2 triangles each
        const std::vector<float> z = drawnHeights();
        INFO("view " << view);
        REQUIRE(z.size() == 2);
        CHECK(z[0] == first);
        CHECK(z[1] == second);
    }
}

TEST_CASE("renderer names: llvmpipe, softpipe and swrast are software renderers, GPUs are not", "[editor][drawer]")
{
    CHECK(isSoftwareRenderer("llvmpipe (LLVM 15.0.6, 256 bits)"));
    CHECK(isSoftwareRenderer("softpipe"));
    CHECK(isSoftwareRenderer("Software Rasterizer"));
    CHECK(isSoftwareRenderer("zink (llvmpipe (LLVM 15.0.6, 256 bits))"));
    CHECK_FALSE(isSoftwareRenderer("NVIDIA GeForce RTX 3080/PCIe/SSE2"));
    CHECK_FALSE(isSoftwareRenderer("AMD Radeon RX 6800 XT (navi21, LLVM 15.0.6, DRM 3.49, 6.1.0-13-amd64)"));
    CHECK_FALSE(isSoftwareRenderer("Mesa Intel(R) UHD Graphics 620 (KBL GT2)"));
    CHECK_FALSE(isSoftwareRenderer("recording"));
}

TEST_CASE("recording renderer: auto anti-aliasing multisamples a GPU's frames and screenshots, not a software renderer's frames",
          "[editor][drawer]")
{
    Scene scene = tetrahedron();
    for (const auto& [name, frameSamples] : {std::pair<const char*, int>{"llvmpipe (LLVM 15.0.6, 256 bits)", 0},
                                             std::pair<const char*, int>{"NVIDIA GeForce RTX 3080/PCIe/SSE2", 4}}) {
        INFO(name);
        RecordingRenderer r;
        r.rendererName = name;
        SceneDrawer drawer(r);
        scene.display.antialiasing = Antialiasing::Auto;
        scene.display.samples = 4;
        drawer.draw(scene, 320, 200);
        CHECK(r.samples() == frameSamples);
        CHECK(drawer.samples() == frameSamples);
        drawer.draw(scene, 320, 200, -1, nullptr, true); // a screenshot
        CHECK(r.samples() == 4);
        scene.display.antialiasing = Antialiasing::Always;
        scene.display.samples = 2;
        drawer.draw(scene, 320, 200);
        CHECK(r.samples() == 2);
    }
}

} // namespace test_drawer
