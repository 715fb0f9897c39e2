// Stable item ids and derived items (scene/scene.h, scene/derived.h), without tools or a window:
// ids survive undo/redo and reordering and are never reused; a lattice's link to the mesh it
// deforms is the mesh's id; the deformed mesh is written by Scene::updateGeometry only (the one
// path), from the lattice's points, and put back to the file's vertices when the link goes away.
// The reference for the deformed positions is Lattice::deform evaluated point by point in double
// (the scene computes in float: 1e-6 is a few float roundings for coordinates of size ~1).

#include <catch2/catch.hpp>

#include <freeform/io/geometry_data.h>
#include <freeform/volume/lattice.h>
#include <freeform/io/geometry_data.h>

#include <set>
#include <string>

#include "render/recording_renderer.h"
#include "scene/scene.h"
#include "scene/scene_drawer.h"
#include "support/process.h"

namespace test_scene_ids {

using namespace freeform;
using namespace freeform::editor;

namespace {

const std::string kTmp = FREEFORM_TEST_TMP;

const double kBox[8][3] = {{-1.0, -0.5, -0.25}, {1.2, -0.6, -0.2}, {1.1, 0.7, -0.3}, {-0.9, 0.5, -0.1},
                           {-1.05, -0.45, 0.8}, {1.0, -0.55, 0.9}, {1.15, 0.65, 0.75}, {-0.95, 0.55, 0.85}};

Eigen::Vector3d boxVertex(int v) { return {kBox[v][0], kBox[v][1], kBox[v][2]}; }

std::string writeBox(const std::string& name)
{
    std::string text;
    for (const auto& v : kBox) text += "v " + std::to_string(v[0]) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) + "\n";
    text += "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
    const std::string path = kTmp + "/" + name;
    test::writeText(path, text);
    return path;
}

Scene threeCurves()
{
    const std::string path = kTmp + "/ids-three.json";
    test::writeText(path, R"({"format": "freeform", "version": 1, "objects": [
      {"name": "a", "type": "bezier_curve", "points": [[0, 0, 0], [1, 1, 0]]},
      {"name": "b", "type": "bezier_curve", "points": [[0, 0, 1], [1, 1, 1]]},
      {"name": "c", "type": "bezier_curve", "points": [[0, 0, 2], [1, 1, 2]]}]})");
    return Scene::load(path);
}

/// A scene with the box mesh and a trilinear lattice "cage" around it (after a curve "first"),
/// linked to the mesh through the lattice's settings as the tools do it.
struct LinkedScene {
    Scene scene;
    int lattice = -1, mesh = -1;
    LinkedScene()
    {
        scene.addObject({"first", BezierCurveData{PointColumns::Identity(3, 2)}, ""});
        scene.importFile(writeBox("ids-box.obj"));
        scene.updateGeometry();
        mesh = scene.indexOf(std::string("ids-box"));
        REQUIRE(mesh >= 0);
        const Lattice fitted = Lattice::fit(scene.item(mesh).geometry.surface->positions, {1, 1, 1}, 0.1);
        lattice = scene.addObject({"cage", latticeToData(fitted), ""});
        mesh = scene.indexOf(std::string("ids-box")); // document objects come before meshes
        ObjectSettings settings;
        settings.ffd.mesh = "ids-box";
        scene.setSettings(lattice, settings);
        scene.updateGeometry();
    }
    Lattice latticeNow() const { return latticeFromData(std::get<LatticeData>(scene.object(lattice).data)); }
    double maxError() const
    {
        const Lattice l = latticeNow();
        const auto& p = scene.item(mesh).geometry.surface->positions;
        double worst = 0;
        for (int v = 0; v < 8; ++v) worst = std::max(worst, (Eigen::Vector3d(p.col(v)) - l.deform(boxVertex(v)).point).norm());
        return worst;
    }
    bool atRest() const
    {
        const auto& p = scene.item(mesh).geometry.surface->positions;
        for (int v = 0; v < 8; ++v)
            if (Eigen::Vector3d(p.col(v)) != boxVertex(v)) return false;
        return true;
    }
};

} // namespace

TEST_CASE("ids: every item has its own id; undo, redo and reordering keep it; a new item never reuses one", "[editor][ids]")
{
    Scene scene = threeCurves();
    REQUIRE(scene.itemCount() == 3);
    std::set<long> ids;
    for (int i = 0; i < 3; ++i) {
        CHECK(scene.item(i).id != 0);
        ids.insert(scene.item(i).id);
    }
    CHECK(ids.size() == 3);
    const long a = scene.item(0).id, b = scene.item(1).id, c = scene.item(2).id;
    CHECK(scene.indexOf(b) == 1);

    // Removing "a" moves b and c to indices 0 and 1 with their ids.
    scene.remove(0);
    CHECK(scene.item(0).id == b);
    CHECK(scene.item(1).id == c);
    CHECK(scene.indexOf(a) == -1);
    CHECK(scene.indexOf(c) == 1);
    // Undo brings "a" back with its id, at index 0; redo removes it again.
    REQUIRE(scene.undo());
    CHECK(scene.item(0).id == a);
    CHECK(scene.item(0).name == "a");
    CHECK(scene.indexOf(c) == 2);
    REQUIRE(scene.redo());
    CHECK(scene.indexOf(a) == -1);
    // An edit keeps the id (the content key changes, the id does not).
    const long key = scene.item(0).key;
    scene.setControlPoint(0, 1, Eigen::Vector3d(2, 2, 1));
    CHECK(scene.item(0).id == b);
    CHECK(scene.item(0).key != key);
    // A new object named like the removed one gets a new id.
    const int added = scene.addObject({"a", BezierCurveData{PointColumns::Identity(3, 2)}, ""});
    CHECK(scene.item(added).id != a);
    CHECK(scene.item(added).id != b);
    CHECK(scene.item(added).id != c);
}

TEST_CASE("derived: the lattice links to its mesh by id; the deformed mesh is written by updateGeometry only", "[editor][ids][ffd]")
{
    LinkedScene s;
    Scene& scene = s.scene;
    CHECK(scene.item(s.lattice).deforms == scene.item(s.mesh).id);
    REQUIRE(scene.ffdLink(s.lattice));
    CHECK(scene.ffdLink(s.lattice)->meshId == scene.item(s.mesh).id);
    CHECK(s.atRest()); // the rest lattice is the identity, bit for bit

    // A moved lattice point: nothing happens to the mesh until updateGeometry evaluates the link.
    const Lattice rest = s.latticeNow();
    scene.setControlPoint(s.lattice, rest.index(1, 1, 1), rest.restPoint(1, 1, 1) + Eigen::Vector3d(0.3, -0.2, 0.25));
    CHECK(s.atRest());
    const int revision = scene.item(s.mesh).revision;
    scene.updateGeometry();
    CHECK_FALSE(s.atRest());
    CHECK(s.maxError() < 1e-6);
    CHECK(scene.item(s.mesh).revision != revision);
    // Nothing changed: nothing is computed again.
    const int after = scene.item(s.mesh).revision;
    scene.updateGeometry();
    CHECK(scene.item(s.mesh).revision == after);

    // Reordering: removing the curve before the lattice moves both items; the link holds.
    const long latticeId = scene.item(s.lattice).id, meshId = scene.item(s.mesh).id;
    scene.remove(scene.indexOf(std::string("first")));
    s.lattice = scene.indexOf(latticeId);
    s.mesh = scene.indexOf(meshId);
    CHECK(s.lattice == 0);
    CHECK(scene.item(s.lattice).deforms == meshId);
    scene.setControlPoint(s.lattice, rest.index(0, 0, 0), rest.restPoint(0, 0, 0) + Eigen::Vector3d(-0.1, 0.1, 0.05));
    scene.updateGeometry();
    CHECK(s.maxError() < 1e-6);

    // The saved document names the mesh in the lattice's editor member, as before ids.
    const std::string text = scene.text();
    CHECK(text.find(R"("mesh": "ids-box")") != std::string::npos);
    const std::string path = kTmp + "/ids-linked.json";
    scene.save(path);
    Scene reread = Scene::load(path);
    const int rl = reread.indexOf(std::string("cage")), rm = reread.indexOf(std::string("ids-box"));
    REQUIRE(rl >= 0);
    REQUIRE(rm >= 0);
    CHECK(reread.item(rl).deforms == reread.item(rm).id);

    // Undo of every step back to the link's creation: the mesh is at rest again after the update.
    for (int steps = 0; !s.latticeNow().isRest() && steps < 3; ++steps) {
        REQUIRE(scene.undo());
        s.lattice = scene.indexOf(latticeId);
        s.mesh = scene.indexOf(meshId);
        REQUIRE(s.lattice >= 0);
    }
    scene.updateGeometry();
    REQUIRE(s.lattice >= 0);
    CHECK(s.latticeNow().isRest());
    CHECK(s.atRest());

    // Unlinking (no mesh) puts the file's vertices back and drops the link.
    scene.setControlPoint(s.lattice, rest.index(1, 1, 1), rest.restPoint(1, 1, 1) + Eigen::Vector3d(0.2, 0.2, 0.2));
    scene.updateGeometry();
    CHECK_FALSE(s.atRest());
    ObjectSettings none = scene.item(s.lattice).settings;
    none.ffd.mesh.clear();
    scene.setSettings(s.lattice, none);
    CHECK(scene.item(s.lattice).deforms == 0);
    scene.updateGeometry();
    CHECK(s.atRest());
    CHECK(scene.ffdLink(s.lattice) == nullptr);
    CHECK(scene.item(s.mesh).scalars.empty());
    // Undo links it again (the id comes back with the settings) and deforms the mesh again.
    REQUIRE(scene.undo());
    CHECK(scene.item(s.lattice).deforms == meshId);
    scene.updateGeometry();
    CHECK(s.maxError() < 1e-6);
    CHECK_FALSE(s.atRest());
}

TEST_CASE("derived: a lattice drag reaches the drawer as a vertex update of the same mesh buffer", "[editor][ids][ffd][drawer]")
{
    LinkedScene s;
    Scene& scene = s.scene;
    RecordingRenderer r;
    SceneDrawer drawer(r);
    drawer.draw(scene, 200, 150);
    const auto first = r.calls(RecordingRenderer::Kind::Mesh);
    REQUIRE(first.size() == 1);
    const int handle = first[0].handle;
    r.clearCounters();

    // One frame of a drag: a lattice point moves; the frame's draw evaluates the link (through
    // updateGeometry) and updates the vertices of the buffer it drew before.
    const Lattice rest = s.latticeNow();
    scene.setControlPoint(s.lattice, rest.index(1, 0, 1), rest.restPoint(1, 0, 1) + Eigen::Vector3d(0.25, 0.1, -0.2));
    drawer.draw(scene, 200, 150);
    CHECK(r.counters().vertexUpdates == 1);
    CHECK(r.counters().meshUploads == 0);
    REQUIRE(r.calls(RecordingRenderer::Kind::Mesh).size() == 1);
    CHECK(r.calls(RecordingRenderer::Kind::Mesh)[0].handle == handle);
    // What the buffer holds is the deformed mesh: Lattice::deform of each file vertex (in float).
    const Lattice moved = s.latticeNow();
    const MeshData& gpu = r.buffer(handle).mesh;
    REQUIRE(gpu.positions.cols() == 8);
    for (int v = 0; v < 8; ++v)
        CHECK((gpu.positions.col(v).cast<double>() - moved.deform(boxVertex(v)).point).norm() < 1e-6);
    // det J as the colour scalars: one per vertex.
    CHECK(gpu.scalars.size() == 8);
}

} // namespace test_scene_ids
