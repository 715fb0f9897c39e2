// Undo and redo: the History container (steps, redo cleared by a new step, merging, the limit,
// cancelling a merge) and the Scene's use of it: every kind of change is one step, undoing all of
// them gives the original document byte for byte (Scene::text), redoing all gives the edited one,
// a drag inside beginMerge/endMerge is one step, camera moves are no steps, a failed change
// records nothing, and undo rebuilds only the items whose content changed.

#include <catch2/catch.hpp>

#include <filesystem>
#include <limits>
#include <optional>
#include <string>

#include "freeform/document/operations.h"
#include "scene/history.h"
#include "scene/scene.h"
#include "support/process.h"

namespace test_history {

using namespace freeform;
using namespace freeform::editor;

namespace {

const std::string kSource = FREEFORM_SOURCE_DIR;
const std::string kTmp = FREEFORM_TEST_TMP;

/// A document with a 2D curve, a 3D spline and a lattice.
std::string writeDocument(const std::string& name)
{
    const std::string path = kTmp + "/" + name;
    test::writeText(path, R"({"format": "freeform", "version": 1, "objects": [
      {"name": "c", "type": "bezier_curve", "points": [[0, 0], [1, 2], [3, 2], [4, 0]]},
      {"name": "s", "type": "bezier_spline", "degree": 2, "points": [[0, 0, 0], [1, 1, 0], [2, 0, 0], [3, -1, 1], [4, 0, 1]]},
      {"name": "box", "type": "lattice", "degree": [1, 1, 1], "origin": [0, 0, 0], "axes": [[1, 0, 0], [0, 1, 0], [0, 0, 1]],
       "points": [[0,0,0],[0,0,1],[0,1,0],[0,1,1],[1,0,0],[1,0,1],[1,1,0],[1,1,1]]}]})");
    return path;
}

/// The object's data as the format writes it (to compare two ObjectData).
std::string dataText(const std::string& name, const ObjectData& data)
{
    Document d;
    d.objects.push_back(DocumentObject{name, data, ""});
    return formatDocument(d);
}

/// The scene's typed document against one built afresh from the scene's data, object by object:
/// a valid object is in it under its item's id, with the item's name, the same data and the same
/// control net; an object the document layer refuses has no id and the layer's message; nothing
/// else is in it.
void checkModel(const Scene& scene)
{
    std::size_t valid = 0;
    for (int i = 0; i < scene.itemCount(); ++i) {
        const SceneItem& it = scene.item(i);
        if (it.kind != SceneItem::Kind::DocumentObject) continue;
        INFO("item " << i << " " << it.name);
        TypedDocument fresh;
        fresh.directory = scene.documentDirectory();
        std::optional<ObjectId> id;
        std::string error;
        try {
            id = fresh.add(it.name, scene.object(i).data);
        } catch (const Error& e) {
            error = e.what();
        }
        const TypedObject* typed = scene.typed(i);
        if (!id) {
            CHECK(typed == nullptr);
            CHECK(it.object == 0);
            REQUIRE_FALSE(it.invalid.empty());
            CHECK(error.find(it.invalid) != std::string::npos);
            CHECK_THROWS_WITH(scene.typedObject(i), Catch::Contains(it.invalid));
            continue;
        }
        ++valid;
        REQUIRE(typed != nullptr);
        CHECK(it.invalid.empty());
        CHECK(typed->id() == it.object);
        CHECK(scene.itemOfObject(it.object) == i); // the way back from an object to its item
        CHECK(typed->name() == it.name);
        CHECK(dataText(it.name, typed->data()) == dataText(it.name, scene.object(i).data));
        CHECK(controlNet(*typed).points == controlNet(fresh.object(*id)).points);
    }
    CHECK(scene.model().objects().size() == valid);
    CHECK(scene.itemOfObject(0) == -1);
}

} // namespace

TEST_CASE("History: the scene's typed document follows every edit, undo, redo, addition and removal; a refused object is held as data and mended", "[history][model]")
{
    Scene scene = Scene::load(writeDocument("history_model.json"));
    checkModel(scene);
    CHECK(&scene.lattice(2) == &std::get<Lattice>(scene.typed(2)->geometry()));
    CHECK_THROWS_WITH(scene.lattice(0), Catch::Contains("\"c\" is a bezier_curve, not a lattice"));
    scene.setControlPoint(1, 2, Eigen::Vector3d(2, 0.5, 0.25));
    scene.setControlPoint(2, 7, Eigen::Vector3d(1.5, 1, 1));
    checkModel(scene);
    CHECK(scene.lattice(2).controlPoints().col(7) == Eigen::Vector3d(1.5, 1, 1));

    // A cage whose second face uses a vertex twice: the reader takes it, the document layer does not.
    SubdivisionSurfaceData cage;
    cage.vertices = PointColumns(3, 4);
    cage.vertices << 0, 1, 1, 0, 0, 0, 1, 1, 0, 0, 0, 0;
    cage.faces = {{0, 1, 2}, {0, 2, 2}};
    const int bad = scene.addObject(DocumentObject{"cage", cage, ""});
    CHECK(bad == 3);
    checkModel(scene);
    CHECK(scene.typed(bad) == nullptr);
    CHECK(scene.item(bad).invalid.find("uses vertex 2 twice") != std::string::npos);
    scene.updateGeometry();
    CHECK(scene.item(bad).geometry.error == scene.item(bad).invalid);
    CHECK(scene.item(bad).geometry.netPoints.cols() == 4); // shown as stored, so it can be mended

    // Mended: the second face made a proper triangle.
    DocumentObject mended = scene.object(bad);
    std::get<SubdivisionSurfaceData>(mended.data).faces[1] = {0, 2, 3};
    scene.replaceObject(bad, mended, "mend");
    checkModel(scene);
    REQUIRE(scene.typed(bad) != nullptr);
    scene.updateGeometry();
    CHECK(scene.item(bad).geometry.error.empty());
    CHECK(scene.item(bad).geometry.surface);

    REQUIRE(scene.undo()); // the broken cage again
    checkModel(scene);
    CHECK(scene.typed(bad) == nullptr);
    REQUIRE(scene.redo());
    checkModel(scene);
    CHECK(scene.typed(bad) != nullptr);

    scene.remove(1);
    checkModel(scene);
    CHECK(scene.model().objects().size() == 3);
    REQUIRE(scene.undo()); // the spline back in its place, between c and box
    checkModel(scene);
    CHECK(scene.item(1).name == "s");
    while (scene.undo()) checkModel(scene);
    CHECK(scene.itemCount() == 3);
    CHECK(scene.lattice(2).isRest());
    while (scene.redo()) checkModel(scene); // the last step redone is the removal of s
    CHECK(scene.itemCount() == 3);
    CHECK(scene.indexOf("s") == -1);
    CHECK(scene.typed(scene.indexOf("cage")) != nullptr);
}

TEST_CASE("History: undo hands back the state before, redo the state after, a new step clears redo", "[history]")
{
    History<int> h;
    int state = 0;
    auto change = [&](int to, const std::string& label) {
        h.record(label, state);
        state = to;
    };
    change(1, "one");
    change(2, "two");
    change(3, "three");
    CHECK(h.size() == 3);
    CHECK(h.undoLabel() == "three");
    state = *h.undo(state);
    CHECK(state == 2);
    CHECK(h.redoLabel() == "three");
    state = *h.undo(state);
    CHECK(state == 1);
    state = *h.redo(state);
    CHECK(state == 2);
    CHECK(h.redoSize() == 1);
    change(7, "seven"); // a new change forgets the undone "three"
    CHECK(h.redoSize() == 0);
    CHECK_FALSE(h.redo(state).has_value());
    state = *h.undo(state);
    CHECK(state == 2);
    state = *h.undo(state);
    state = *h.undo(state);
    CHECK(state == 0);
    CHECK_FALSE(h.undo(state).has_value());
    CHECK(h.undoLabel().empty());
}

TEST_CASE("History: a merge is one step whatever the number of changes; cancelMerge drops it", "[history]")
{
    History<int> h;
    int state = 10;
    h.beginMerge();
    for (int k = 1; k <= 50; ++k) {
        if (h.wantsStep()) h.record("drag", state);
        state = 10 + k;
    }
    CHECK(h.endMerge());
    CHECK(h.size() == 1);
    state = *h.undo(state);
    CHECK(state == 10); // the state from before the first change of the drag
    state = *h.redo(state);
    CHECK(state == 60);

    h.beginMerge();
    h.record("drag", state);
    state = 99;
    h.record("drag", state);
    const auto before = h.cancelMerge();
    REQUIRE(before.has_value());
    CHECK(*before == 60);
    CHECK(h.size() == 1);
    CHECK(h.redoSize() == 0);
    // A merge without changes records nothing and cancels to nothing.
    h.beginMerge();
    CHECK_FALSE(h.endMerge());
    h.beginMerge();
    CHECK_FALSE(h.cancelMerge().has_value());
    CHECK(h.size() == 1);
}

TEST_CASE("History: the limit drops the oldest steps", "[history]")
{
    History<int> h(1000);
    CHECK(h.limit() == 1000);
    int state = 0;
    for (int k = 1; k <= 1005; ++k) {
        h.record("step", state);
        state = k;
    }
    CHECK(h.size() == 1000);
    int undone = 0;
    while (auto s = h.undo(state)) {
        state = *s;
        ++undone;
    }
    CHECK(undone == 1000);
    CHECK(state == 5); // steps from 0..4 were dropped
    CHECK(History<int>(0).limit() == 1);
}

TEST_CASE("Scene: undoing every kind of change restores the document byte for byte, redo the edited one", "[history]")
{
    Scene scene = Scene::load(writeDocument("history_all.json"));
    const std::string original = scene.text();
    const Camera cameraBefore = scene.camera;
    CHECK(scene.history().limit() >= 1000);

    scene.setControlPoint(0, 1, Eigen::Vector3d(1.5, 2.5, 7)); // 2D: z is ignored
    ObjectSettings settings = scene.item(1).settings;
    settings.visible = false;
    scene.setSettings(1, settings);
    DocumentObject spline = scene.object(1);
    std::get<BezierSplineData>(spline.data).points(1, 4) = -3;
    scene.replaceObject(1, spline, "edit spline");
    DocumentObject extra{"c", BezierCurveData{PointColumns::Random(3, 3)}, ""};
    const int added = scene.addObject(extra);
    CHECK(scene.item(added).name == "c_2");
    scene.importFile(kSource + "/data/teapot.bpt");
    scene.remove(2); // the lattice
    Eigen::Matrix3Xd moved(3, 2);
    moved << 9, 8, 7, 6, 5, 4;
    scene.setControlPoints(0, {0, 3}, moved);
    const std::string edited = scene.text();
    CHECK(edited != original);
    CHECK(scene.history().size() == 7);
    CHECK(scene.history().undoLabel() == "move points");

    // Camera moves are not steps.
    scene.camera.orbitTurntable(0.3, 0.1);
    scene.touch();
    CHECK(scene.history().size() == 7);
    scene.camera = cameraBefore; // the camera is not part of what undo restores

    int undone = 0;
    while (scene.undo()) ++undone;
    CHECK(undone == 7);
    CHECK(scene.text() == original);
    int redone = 0;
    while (scene.redo()) ++redone;
    CHECK(redone == 7);
    CHECK(scene.text() == edited);
    scene.updateGeometry();
    for (int i = 0; i < scene.itemCount(); ++i) CHECK(scene.item(i).geometry.error.empty());
}

TEST_CASE("Scene: a failed change records no step and changes nothing", "[history]")
{
    Scene scene = Scene::load(writeDocument("history_fail.json"));
    const std::string original = scene.text();
    CHECK_THROWS_AS(scene.setControlPoint(0, 4, Eigen::Vector3d(1, 1, 1)), Error); // only 4 points
    Eigen::Matrix3Xd bad(3, 1);
    bad << 1, std::numeric_limits<double>::quiet_NaN(), 0;
    CHECK_THROWS_AS(scene.setControlPoints(1, {0}, bad), Error);
    DocumentObject renamed = scene.object(0);
    renamed.name = "other";
    CHECK_THROWS_AS(scene.replaceObject(0, renamed), Error);
    DocumentObject wrong = scene.object(2);
    std::get<LatticeData>(wrong.data).points.resize(3, 5); // not (1+1)^3 points
    CHECK_THROWS_AS(scene.replaceObject(2, wrong), Error);
    CHECK_THROWS_AS(scene.importFile(kTmp + "/does-not-exist.bpt"), Error);
    CHECK(scene.history().size() == 0);
    CHECK(scene.text() == original);
    CHECK_FALSE(scene.modified());
}

TEST_CASE("Scene: a drag in beginMerge/endMerge is one step; cancelMerge takes it back without redo", "[history]")
{
    Scene scene = Scene::load(writeDocument("history_merge.json"));
    const std::string original = scene.text();
    scene.beginMerge();
    for (int k = 1; k <= 20; ++k) scene.setControlPoint(1, 2, Eigen::Vector3d(2, 0.1 * k, 0));
    scene.endMerge();
    CHECK(scene.history().size() == 1);
    CHECK(scene.controlPoints(1).col(2).isApprox(Eigen::Vector3d(2, 2, 0)));
    const std::string dragged = scene.text();
    scene.undo();
    CHECK(scene.text() == original);
    scene.redo();
    CHECK(scene.text() == dragged);

    scene.beginMerge();
    for (int k = 1; k <= 5; ++k) scene.setControlPoint(0, 0, Eigen::Vector3d(-k, 0, 0));
    scene.cancelMerge();
    CHECK(scene.text() == dragged);
    CHECK(scene.history().size() == 1);
    CHECK_FALSE(scene.history().canRedo());
}

TEST_CASE("Scene: undo rebuilds only the items whose content changed", "[history]")
{
    Scene scene = Scene::load(writeDocument("history_rebuild.json"));
    scene.updateGeometry();
    const int revision0 = scene.item(0).revision, revision2 = scene.item(2).revision;
    scene.setControlPoint(1, 0, Eigen::Vector3d(0, 0, 1));
    CHECK(scene.item(1).geometryDirty);
    CHECK_FALSE(scene.item(0).geometryDirty);
    scene.updateGeometry();
    const int revision1 = scene.item(1).revision;
    scene.undo();
    CHECK_FALSE(scene.item(0).geometryDirty);
    CHECK_FALSE(scene.item(2).geometryDirty);
    CHECK(scene.item(1).geometryDirty);
    scene.updateGeometry();
    CHECK(scene.item(0).revision == revision0);
    CHECK(scene.item(2).revision == revision2);
    CHECK(scene.item(1).revision != revision1);
    // Settings that do not touch the geometry (visibility) do not rebuild it either way.
    ObjectSettings hidden = scene.item(2).settings;
    hidden.visible = false;
    scene.setSettings(2, hidden);
    scene.undo();
    CHECK_FALSE(scene.item(2).geometryDirty);
    CHECK(scene.item(2).settings.visible);
}

} // namespace test_history
