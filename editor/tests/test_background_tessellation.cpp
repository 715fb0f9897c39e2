// Background tessellation (scene/tessellation_worker.h, docs/editor.md "Tessellation to the view"),
// driven deterministically through the worker's hold: a job that has built its items waits there
// until the test releases it, so an edit, a removal or a new zoom can be made "while it runs"
// without any timing. The expected meshes are the synchronous path's: buildGeometry of the same
// object at the same tolerance, called here on the test's thread, compared number for number.

#include <catch2/catch.hpp>

#include <Eigen/Core>

#include <fstream>
#include <string>
#include <vector>

#include "freeform/io/mesh_io.h"
#include "scene/scene.h"
#include "scene/tessellation_worker.h"

namespace test_background_tessellation {

using namespace freeform;
using namespace freeform::editor;

namespace {

const std::string kSource = FREEFORM_SOURCE_DIR;
const std::string kTmp = FREEFORM_TEST_TMP;

/// The teapot (32 bicubic patches) loaded as the editor loads it: built at the world tolerance
/// display.tolerance = 1e-3, the camera fitted to it.
Scene teapot()
{
    Scene scene = Scene::load(kSource + "/data/teapot.bpt", 1280.0 / 800.0);
    REQUIRE(scene.itemCount() == 32);
    return scene;
}

/// The same triangles: positions, normals and faces equal number for number.
bool sameMesh(const PolygonMesh& a, const PolygonMesh& b)
{
    if (a.positions.cols() != b.positions.cols() || a.faceCount() != b.faceCount()) return false;
    if (a.positions != b.positions || a.normals != b.normals) return false;
    for (int f = 0; f < a.faceCount(); ++f) {
        if (a.faceSize(f) != b.faceSize(f)) return false;
        for (int k = 0; k < a.faceSize(f); ++k)
            if (a.face(f)[k] != b.face(f)[k]) return false;
    }
    return true;
}

/// What the synchronous path builds for item i's object at tolerance t (per patch with `view` on:
/// the scene's pixelScale() for the meshes drawn, off for the world tolerance of exports).
ItemGeometry synchronous(const Scene& scene, int i, double t, const PixelScale& view = {})
{
    return buildGeometry(scene, i, t, view);
}

/// The same for an object's data that the scene no longer holds (the document layer builds it).
ItemGeometry fromData(const ObjectData& data, const ObjectSettings& settings, double t, const std::string& directory, const PixelScale& view)
{
    TypedDocument doc;
    doc.directory = directory;
    return buildGeometry(doc.object(doc.add("old", data)), settings, t, view);
}

long triangles(const Scene& scene)
{
    long n = 0;
    for (int i = 0; i < scene.itemCount(); ++i)
        if (scene.item(i).geometry.surface) n += scene.item(i).geometry.surface->faceCount();
    return n;
}

} // namespace

TEST_CASE("background: the old meshes are drawn until the job is done; the meshes swapped in equal the synchronous "
          "tessellation triangle for triangle",
          "[editor][background]")
{
    Scene scene = teapot();
    const double world = scene.display.tolerance;
    std::vector<PolygonMesh> before;
    std::vector<int> revisions;
    for (int i = 0; i < scene.itemCount(); ++i) {
        REQUIRE(scene.item(i).geometry.surface);
        REQUIRE(scene.item(i).builtTolerance == world);
        before.push_back(*scene.item(i).geometry.surface);
        revisions.push_back(scene.item(i).revision);
    }
    const long worldTriangles = triangles(scene);

    scene.setBackgroundTessellation(true);
    scene.tessellationWorker().setHold(true);
    scene.pixelTolerance = 0.5;
    scene.updateViewTolerance(800);
    const double view = scene.tessellationTolerance();
    REQUIRE(view != world);
    scene.updateGeometry(); // submits the 32 patches
    CHECK(scene.backgroundStats().jobs == 1);
    scene.tessellationWorker().waitUntilHeld(); // built, not yet handed over
    scene.updateGeometry();
    // Still the old meshes, unchanged revisions (the drawer uploads nothing), and pending.
    CHECK(scene.tessellationPending());
    for (int i = 0; i < scene.itemCount(); ++i) {
        CHECK(sameMesh(*scene.item(i).geometry.surface, before[static_cast<std::size_t>(i)]));
        CHECK(scene.item(i).revision == revisions[static_cast<std::size_t>(i)]);
        CHECK(scene.item(i).builtTolerance == world);
    }

    scene.tessellationWorker().setHold(false);
    scene.finishTessellation();
    CHECK_FALSE(scene.tessellationPending());
    CHECK(scene.backgroundStats().jobs == 1);
    CHECK(scene.backgroundStats().applied == 32);
    CHECK(scene.backgroundStats().dropped == 0);
    for (int i = 0; i < scene.itemCount(); ++i) {
        INFO("patch " << i);
        const ItemGeometry expected = synchronous(scene, i, view, scene.pixelScale());
        REQUIRE(expected.surface);
        REQUIRE(scene.item(i).geometry.surface);
        CHECK(sameMesh(*scene.item(i).geometry.surface, *expected.surface));
        CHECK(scene.item(i).builtTolerance == view);
        CHECK(scene.item(i).revision != revisions[static_cast<std::size_t>(i)]); // the drawer uploads it
        CHECK(scene.item(i).geometry.bounds.isApprox(expected.bounds));
    }
    // The view's tolerance is not the world's: the meshes really were replaced.
    CHECK(triangles(scene) != worldTriangles);

    // Nothing more to do: no new job, nothing rebuilt.
    const int revision = scene.item(0).revision;
    scene.updateViewTolerance(800);
    scene.updateGeometry();
    CHECK(scene.backgroundStats().jobs == 1);
    CHECK(scene.item(0).revision == revision);
}

TEST_CASE("background: an edit or a removal made while the job runs is not overwritten by the job's stale result",
          "[editor][background]")
{
    Scene scene = teapot();
    scene.setBackgroundTessellation(true);
    scene.tessellationWorker().setHold(true);
    scene.updateViewTolerance(800);
    const double view = scene.tessellationTolerance();
    scene.updateGeometry();
    scene.tessellationWorker().waitUntilHeld(); // the job has tessellated every patch as it was

    // Patch 5 (the body) is edited: its first control point moves up by 0.3.
    const DocumentObject old = scene.object(5);
    const Eigen::Vector3d p = scene.controlPoints(5).col(0);
    scene.setControlPoint(5, 0, p + Eigen::Vector3d(0, 0, 0.3));
    scene.updateGeometry(); // the edit is rebuilt at once, at the view's tolerance
    const long bodyId = scene.item(5).id;
    // Patch 31 is deleted; the patches after it keep their ids, the job finds them by id.
    const long removedId = scene.item(31).id;
    scene.remove(31);
    REQUIRE(scene.itemCount() == 31);

    scene.tessellationWorker().setHold(false);
    scene.finishTessellation();
    CHECK(scene.backgroundStats().applied == 30);
    CHECK(scene.backgroundStats().dropped == 2); // the edited patch and the deleted one
    CHECK(scene.indexOf(removedId) == -1);
    REQUIRE(scene.indexOf(bodyId) == 5);

    // The edited patch shows the edit, at the view's tolerance; the stale result (the old patch at
    // the same tolerance) differs from it, so showing it would have failed this check.
    const ItemGeometry edited = synchronous(scene, 5, view, scene.pixelScale());
    const ItemGeometry stale = fromData(old.data, scene.item(5).settings, view, scene.documentDirectory(), scene.pixelScale());
    REQUIRE(edited.surface);
    REQUIRE(stale.surface);
    REQUIRE_FALSE(sameMesh(*edited.surface, *stale.surface));
    CHECK(sameMesh(*scene.item(5).geometry.surface, *edited.surface));
    CHECK(scene.item(5).builtTolerance == view);
    for (int i = 0; i < scene.itemCount(); ++i) {
        INFO("patch " << i);
        CHECK(sameMesh(*scene.item(i).geometry.surface, *synchronous(scene, i, view, scene.pixelScale()).surface));
    }

    // Undo puts the old patch back (its old content key): still the synchronous result for it.
    REQUIRE(scene.undo()); // the removal
    REQUIRE(scene.undo()); // the edit
    scene.finishTessellation();
    REQUIRE(scene.itemCount() == 32);
    for (int i = 0; i < scene.itemCount(); ++i) {
        INFO("patch " << i << " after undo");
        CHECK(sameMesh(*scene.item(i).geometry.surface, *synchronous(scene, i, view, scene.pixelScale()).surface));
    }
}

TEST_CASE("background: a new zoom supersedes the job in flight, whose result is never shown", "[editor][background]")
{
    Scene scene = teapot();
    scene.setBackgroundTessellation(true);
    scene.tessellationWorker().setHold(true);
    scene.updateViewTolerance(800);
    const double first = scene.tessellationTolerance();
    scene.updateGeometry();
    scene.tessellationWorker().waitUntilHeld();
    // Zoom in 4x: the pixel is much smaller in the world, past the 2x hysteresis.
    scene.camera.distance /= 4;
    scene.updateViewTolerance(800);
    const double second = scene.tessellationTolerance();
    REQUIRE(second < first / 2);
    scene.updateGeometry(); // supersedes the held job
    CHECK(scene.backgroundStats().jobs == 2);
    scene.tessellationWorker().setHold(false);
    scene.finishTessellation();
    CHECK(scene.backgroundStats().applied == 32); // the second job's; the first never published
    CHECK(scene.backgroundStats().dropped == 0);
    for (int i = 0; i < scene.itemCount(); ++i) {
        INFO("patch " << i);
        CHECK(scene.item(i).builtTolerance == second);
        CHECK(sameMesh(*scene.item(i).geometry.surface, *synchronous(scene, i, second, scene.pixelScale()).surface));
    }
}

TEST_CASE("background: objects with a tolerance of their own are not re-tessellated for the view", "[editor][background]")
{
    Scene scene = teapot();
    ObjectSettings own = scene.item(0).settings;
    own.tessellation.tolerance = 1e-2;
    scene.setSettings(0, own);
    scene.updateGeometry();
    const int revision = scene.item(0).revision;
    scene.setBackgroundTessellation(true);
    scene.updateViewTolerance(800);
    scene.finishTessellation();
    CHECK(scene.item(0).revision == revision);
    CHECK(scene.backgroundStats().applied == 31);
}

TEST_CASE("background: an export is tessellated to the world tolerance and leaves the view's meshes as they are",
          "[editor][background]")
{
    Scene scene = teapot();
    scene.setBackgroundTessellation(true);
    scene.updateViewTolerance(800);
    scene.finishTessellation();
    REQUIRE(scene.tessellationTolerance() != scene.display.tolerance);
    std::vector<int> revisions;
    long expected = 0;
    for (int i = 0; i < scene.itemCount(); ++i) {
        revisions.push_back(scene.item(i).revision);
        expected += synchronous(scene, i, scene.display.tolerance).surface->faceCount();
    }
    const std::string path = kTmp + "/background-export.obj";
    scene.exportMesh(path);
    CHECK(readPolygonMesh(path).faceCount() == expected);
    for (int i = 0; i < scene.itemCount(); ++i) CHECK(scene.item(i).revision == revisions[static_cast<std::size_t>(i)]);
    CHECK_FALSE(scene.tessellationPending());
}

TEST_CASE("background: a subdivision surface follows the view's tolerance too, with the synchronous result", "[editor][background]")
{
    // An inline Catmull-Clark cube cage (8 vertices, 6 quads, counter-clockwise from outside).
    const std::string path = kTmp + "/background-cube.json";
    {
        std::ofstream out(path);
        out << R"({"format": "freeform", "version": 1, "objects": [
          {"name": "cube", "type": "subdivision_surface", "scheme": "catmark",
           "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0],[0,0,1],[1,0,1],[1,1,1],[0,1,1]],
           "faces": [[0,3,2,1],[4,5,6,7],[0,1,5,4],[1,2,6,5],[2,3,7,6],[3,0,4,7]]}]})";
    }
    Scene scene = Scene::load(path, 1280.0 / 800.0);
    REQUIRE(scene.itemCount() == 1);
    REQUIRE(scene.item(0).geometry.surface);
    const int worldFaces = scene.item(0).geometry.surface->faceCount();
    scene.setBackgroundTessellation(true);
    // Closer: the view's half pixel differs from the world tolerance 1e-3, and the cage is
    // re-tessellated for it in the background.
    scene.camera.distance /= 2;
    scene.updateViewTolerance(800);
    const double view = scene.tessellationTolerance();
    REQUIRE(view != scene.display.tolerance);
    scene.finishTessellation();
    CHECK(scene.backgroundStats().applied == 1);
    CHECK(scene.item(0).builtTolerance == view);
    const ItemGeometry expected = synchronous(scene, 0, view, scene.pixelScale());
    REQUIRE(expected.surface);
    CHECK(sameMesh(*scene.item(0).geometry.surface, *expected.surface));
    INFO("faces at the world tolerance " << worldFaces << ", at the view's " << expected.surface->faceCount());
    CHECK(expected.surface->faceCount() != worldFaces); // the tolerance reaches the subdivision tessellation
}

TEST_CASE("per-patch screen tolerance: a close-up of the teapot's nearest patch keeps it as fine as before and makes the "
          "far ones coarser",
          "[editor][per-patch]")
{
    Scene scene = teapot(); // 32 bezier_surface items of one patch each
    // Look along -x at the patch that reaches farthest in +x, from close by: the scene box's nearest
    // corner is then on that patch's box, so its tolerance is the old one-per-view tolerance.
    int near = 0;
    for (int i = 1; i < scene.itemCount(); ++i)
        if (scene.item(i).geometry.bounds.max().x() > scene.item(near).geometry.bounds.max().x()) near = i;
    scene.camera.projection = Projection::Perspective;
    scene.camera.orientation = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX());
    scene.camera.target = scene.item(near).geometry.bounds.center();
    scene.camera.distance = 1.5;
    scene.camera.fovyDegrees = 35;
    scene.pixelTolerance = 0.5;
    scene.updateViewTolerance(800);
    scene.updateGeometry();
    const double old = scene.tessellationTolerance(); // the rule before: one tolerance for the view
    REQUIRE(scene.pixelScale().on());

    // Each patch: 0.5 px at its own nearest depth, by hand: the depth of the nearest corner of its
    // control-point box along -x, one pixel there 2 depth tan(17.5 deg) / 800.
    const double eyeX = scene.camera.target.x() + 1.5;
    long perPatch = 0, perView = 0;
    for (int i = 0; i < scene.itemCount(); ++i) {
        const ItemGeometry& g = scene.item(i).geometry;
        REQUIRE(g.patchTolerance.size() == 1);
        const double depth = std::max(eyeX - g.netPoints.row(0).maxCoeff(), 1.5 / 20);
        const double expected = 0.5 * 2 * depth * std::tan(17.5 * 3.14159265358979323846 / 180) / 800;
        CHECK(g.patchTolerance[0] == Approx(expected).epsilon(1e-12));
        CHECK(g.patchTolerance[0] >= old * (1 - 1e-12));
        perPatch += g.surface->faceCount();
        perView += synchronous(scene, i, old).surface->faceCount();
    }
    // The near patch: the same tolerance as before, so the same mesh.
    CHECK(scene.item(near).geometry.patchTolerance[0] == Approx(old).epsilon(1e-12));
    CHECK(scene.item(near).geometry.surface->faceCount() == synchronous(scene, near, old).surface->faceCount());
    // The teapot as a whole: fewer triangles (the far patches are coarser).
    INFO("per patch " << perPatch << " triangles, one tolerance per view " << perView);
    CHECK(perPatch < perView);

    // A box twice as far gets twice the tolerance (perspective); orthographic: the same everywhere.
    const PixelScale& s = scene.pixelScale();
    const Eigen::Vector3d e = s.eye;
    const Eigen::AlignedBox3d a(e + Eigen::Vector3d(-2, -0.1, -0.1), e + Eigen::Vector3d(-1, 0.1, 0.1));
    const Eigen::AlignedBox3d b(e + Eigen::Vector3d(-4, -0.1, -0.1), e + Eigen::Vector3d(-2, 0.1, 0.1));
    CHECK(s.tolerance(b) == Approx(2 * s.tolerance(a)).epsilon(1e-12));
    PixelScale ortho = s;
    ortho.perspective = false;
    CHECK(ortho.tolerance(a) == ortho.tolerance(b));

    // Re-tessellation only past 2x: the same view rebuilds nothing; a view 3x farther (every depth
    // grows more than 2x) rebuilds the patches.
    const int revision = scene.item(near).revision;
    scene.updateViewTolerance(800);
    scene.updateGeometry();
    CHECK(scene.item(near).revision == revision);
    scene.camera.distance = 1.5 * 8;
    scene.updateViewTolerance(800);
    scene.updateGeometry();
    CHECK(scene.item(near).revision != revision);
    CHECK(scene.item(near).geometry.patchTolerance[0] > 2 * old);
}

TEST_CASE("per-patch screen tolerance: a patch is rebuilt when its own tolerance moves past 2x, even where the view's "
          "one tolerance stays",
          "[editor][per-patch]")
{
    Scene scene = teapot();
    int near = 0;
    for (int i = 1; i < scene.itemCount(); ++i)
        if (scene.item(i).geometry.bounds.max().x() > scene.item(near).geometry.bounds.max().x()) near = i;
    const double front = scene.item(near).geometry.bounds.max().x();
    // Looking along -x with the target 0.5 in front of the teapot and the eye 1 behind it: every
    // depth is beyond the target, so the one view tolerance is that of depth = distance = 1.
    scene.camera.projection = Projection::Perspective;
    scene.camera.orientation = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX());
    scene.camera.target = Eigen::Vector3d(front + 0.5, 0, 0);
    scene.camera.distance = 1;
    scene.pixelTolerance = 0.5;
    scene.updateViewTolerance(800);
    scene.updateGeometry();
    const double view = scene.tessellationTolerance();
    const double built = scene.item(near).geometry.patchTolerance.at(0);
    const int revision = scene.item(near).revision;
    // Backing off by 0.3: the near patch's depth grows from about 1.5 to 1.8 (< 2x): nothing rebuilt.
    scene.camera.target.x() += 0.3;
    scene.updateViewTolerance(800);
    scene.updateGeometry();
    CHECK(scene.tessellationTolerance() == view);
    CHECK(scene.item(near).revision == revision);
    // Backing off by 5 more: its depth grows past 2x (to about 6.8), the view's tolerance stays.
    scene.camera.target.x() += 5;
    scene.updateViewTolerance(800);
    scene.updateGeometry();
    CHECK(scene.tessellationTolerance() == view);
    CHECK(scene.item(near).revision != revision);
    CHECK(scene.item(near).geometry.patchTolerance.at(0) > 2 * built);
}

} // namespace test_background_tessellation
