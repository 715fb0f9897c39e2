// The up axis of imported meshes (issue 12; docs/format.md, editor `meshes[].up`; docs/editor.md,
// "Documents"), without a display:
//   - the rotation by hand: a Y-up file's +y is the world's +z, (x, y, z) -> (x, -z, y);
//   - a glTF tetrahedron written by the library, with its apex on +y at (0, 2, 0), imported into a
//     scene: Y up by the glTF convention, its four vertices at the hand-turned places, the apex at
//     (0, 0, 2), so it stands up in the Z-up world; an OBJ of the same vertices stays as it is;
//   - save and load: the field "up": "y" is written for it, read back, the geometry the same; a
//     Z-up mesh writes no field (files without it read as before); a wrong value is an error
//     naming the field; Properties' change of the axis is one undo step;
//   - an export through a dragged lattice writes the file's own (Y-up) coordinates: each vertex
//     equals R^T D(R p) with D the world lattice's Lattice::deform, R the turn, computed here; with
//     the lattice at rest the written vertices are the file's exactly.

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "freeform/core/error.h"
#include "freeform/io/geometry_data.h"
#include "freeform/io/mesh_io.h"
#include "freeform/io/up_axis.h"
#include "interaction/selection.h"
#include "scene/overlay.h"
#include "scene/scene.h"
#include "support/process.h"
#include "tools/tool_util.h"
#include "tools/tools.h"

namespace test_up_axis {

using namespace freeform;
using namespace freeform::editor;
using Json = nlohmann::ordered_json;
namespace fs = std::filesystem;

namespace {

const std::string kTmp = FREEFORM_TEST_TMP;

/// A tetrahedron with its apex on the file's +y (a Y-up file's "up").
PolygonMesh tetrahedron()
{
    PolygonMesh m;
    m.positions.resize(3, 4);
    m.positions.col(0) << 0, 0, 0;
    m.positions.col(1) << 1, 0, 0;
    m.positions.col(2) << 0, 2, 0; // the apex, up in a Y-up file
    m.positions.col(3) << 0, 0, 3;
    m.addFace({0, 2, 1});
    m.addFace({0, 1, 3});
    m.addFace({0, 3, 2});
    m.addFace({1, 2, 3});
    return m;
}

/// The world places by hand: (x, y, z) -> (x, -z, y).
std::set<std::vector<double>> turnedByHand()
{
    return {{0, 0, 0}, {1, 0, 0}, {0, 0, 2}, {0, -3, 0}};
}

std::set<std::vector<double>> positionsOf(const Scene& scene, int item)
{
    std::set<std::vector<double>> out;
    const auto& p = scene.item(item).geometry.surface->positions;
    for (Eigen::Index v = 0; v < p.cols(); ++v) out.insert({p(0, v), p(1, v), p(2, v)});
    return out;
}

std::string written(const std::string& name, const PolygonMesh& mesh)
{
    const std::string path = kTmp + "/up_axis_" + name;
    writePolygonMesh(mesh, path);
    return path;
}

} // namespace

TEST_CASE("up axis: a Y-up file's +y is the world's +z", "[editor][up]")
{
    const Eigen::Matrix3d r = upAxisToWorld(UpAxis::Y);
    CHECK(r * Eigen::Vector3d(0, 1, 0) == Eigen::Vector3d(0, 0, 1));
    CHECK(r * Eigen::Vector3d(1, 0, 0) == Eigen::Vector3d(1, 0, 0));
    CHECK(r * Eigen::Vector3d(0, 0, 1) == Eigen::Vector3d(0, -1, 0)); // glTF's front (+z) faces -y
    CHECK(upAxisToWorld(UpAxis::Z) == Eigen::Matrix3d::Identity());
    CHECK(formatUpAxis("a/b.GLTF") == UpAxis::Y);
    CHECK(formatUpAxis("b.glb") == UpAxis::Y);
    CHECK_FALSE(formatUpAxis("b.obj").has_value());
    CHECK(parseUpAxis("y", "w") == UpAxis::Y);
    CHECK_THROWS_WITH(parseUpAxis("x", "meshes[0].up"), Catch::Contains("meshes[0].up") && Catch::Contains("\"z\" or \"y\""));
}

TEST_CASE("up axis: a Y-up glTF stands up along +z; an OBJ stays as it is", "[editor][up]")
{
    const std::string gltf = written("tetra.gltf", tetrahedron()), obj = written("tetra.obj", tetrahedron());
    Scene scene;
    scene.importFile(gltf);
    scene.importFile(obj);
    scene.updateGeometry();
    REQUIRE(scene.itemCount() == 2);
    CHECK(scene.item(0).up == UpAxis::Y);
    CHECK(scene.item(1).up == UpAxis::Z);
    CHECK(positionsOf(scene, 0) == turnedByHand());
    CHECK(positionsOf(scene, 1) == std::set<std::vector<double>>{{0, 0, 0}, {1, 0, 0}, {0, 2, 0}, {0, 0, 3}});
    // The bounding box: the apex is the highest point, 2 above the base.
    CHECK(scene.item(0).geometry.bounds.max().z() == 2);
    // An OBJ imported as Y up (the Import dialog's choice) turns the same way.
    Scene chosen;
    chosen.importFile(obj, UpAxis::Y);
    chosen.updateGeometry();
    CHECK(positionsOf(chosen, 0) == turnedByHand());
}

TEST_CASE("up axis: the sample sphere.gltf (Y up) imports as the same sphere as sphere.obj (Z up), poles along z", "[editor][up]")
{
    // data/meshes/sphere.gltf stores the OBJ's point (x, y, z) as (x, z, -y) in float (glTF's own
    // Y-up axes, scripts/make_sample_meshes.py). Imported Y up it must land on the OBJ's points,
    // rounded to float, and its poles at (0, 0, +-1) as the OBJ's (the old file, written in Z-up
    // axes, had them at (0, -+1, 0) after the import).
    const std::string dir = std::string(FREEFORM_SOURCE_DIR) + "/data/meshes/";
    Scene scene;
    scene.importFile(dir + "sphere.gltf");
    scene.importFile(dir + "sphere.obj");
    scene.updateGeometry();
    REQUIRE(scene.itemCount() == 2);
    CHECK(scene.item(0).up == UpAxis::Y);
    CHECK(scene.item(1).up == UpAxis::Z);
    // Each of the glTF's points is one of the OBJ's rounded to float: within half a float step
    // (2^-24 for coordinates below 2 in size) in every coordinate, and no two share one.
    const std::set<std::vector<double>> gltfPoints = positionsOf(scene, 0), objPoints = positionsOf(scene, 1);
    REQUIRE(gltfPoints.size() == 266);
    REQUIRE(objPoints.size() == 266);
    std::set<std::vector<double>> matched;
    for (const std::vector<double>& p : gltfPoints) {
        int near = 0;
        for (const std::vector<double>& q : objPoints)
            if (std::abs(p[0] - q[0]) <= 0x1p-24 && std::abs(p[1] - q[1]) <= 0x1p-24 && std::abs(p[2] - q[2]) <= 0x1p-24) {
                ++near;
                matched.insert(q);
            }
        INFO(p[0] << " " << p[1] << " " << p[2]);
        CHECK(near == 1);
    }
    CHECK(matched.size() == 266);
    for (int i = 0; i < 2; ++i) {
        CHECK(positionsOf(scene, i).count({0, 0, 1}) == 1);
        CHECK(positionsOf(scene, i).count({0, 0, -1}) == 1);
    }
}

TEST_CASE("up axis: saved as meshes[].up, read back; absent means Z; a wrong value names the field", "[editor][up]")
{
    const std::string gltf = written("tetra2.gltf", tetrahedron()), obj = written("tetra2.obj", tetrahedron());
    Scene scene;
    scene.importFile(gltf);
    scene.importFile(obj);
    const std::string doc = kTmp + "/up_axis_doc.json";
    scene.save(doc);
    const Json saved = Json::parse(test::slurp(doc));
    REQUIRE(saved["editor"]["meshes"].size() == 2);
    CHECK(saved["editor"]["meshes"][0]["up"] == "y");
    CHECK_FALSE(saved["editor"]["meshes"][1].contains("up")); // Z: no field, as files were before

    Scene again = Scene::load(doc);
    REQUIRE(again.itemCount() == 2);
    CHECK(again.item(0).up == UpAxis::Y);
    CHECK(again.item(1).up == UpAxis::Z);
    CHECK(positionsOf(again, 0) == turnedByHand());
    const std::string doc2 = kTmp + "/up_axis_doc2.json";
    again.save(doc2);
    CHECK(test::slurp(doc2) == test::slurp(doc)); // save -> load -> save: the same bytes

    // Changing it (Properties > up axis) is one undo step and reads the file again.
    again.setUpAxis(0, UpAxis::Z);
    again.updateGeometry();
    CHECK(positionsOf(again, 0) == std::set<std::vector<double>>{{0, 0, 0}, {1, 0, 0}, {0, 2, 0}, {0, 0, 3}});
    again.undo();
    again.updateGeometry();
    CHECK(again.item(0).up == UpAxis::Y);
    CHECK(positionsOf(again, 0) == turnedByHand());

    Json bad = saved;
    bad["editor"]["meshes"][0]["up"] = "x";
    const std::string badDoc = kTmp + "/up_axis_bad.json";
    test::writeText(badDoc, bad.dump(1));
    CHECK_THROWS_WITH(Scene::load(badDoc), Catch::Contains("editor.meshes[0].up"));
    bad["editor"]["meshes"][0]["up"] = 1;
    test::writeText(badDoc, bad.dump(1));
    CHECK_THROWS_WITH(Scene::load(badDoc), Catch::Contains("editor.meshes[0].up"));
}

TEST_CASE("up axis: an export through the lattice writes the file's own coordinates", "[editor][up][ffd]")
{
    // An OBJ read as Y up (OBJ keeps every digit of a double; glTF stores float).
    const PolygonMesh file = tetrahedron();
    const std::string obj = written("tetra3.obj", file);
    Scene scene;
    scene.importFile(obj, UpAxis::Y);
    Selection selection;
    Tools tools;
    ToolContext context{scene, selection, 800, 500, Eigen::Matrix4d::Identity()};
    REQUIRE(tools.lattice().fitLattice(context, 0));
    const int li = selection.item;
    REQUIRE(li >= 0);
    const Eigen::Matrix3d r = upAxisToWorld(UpAxis::Y);

    // At rest: the file's vertices exactly.
    const std::string rest = kTmp + "/up_axis_rest.obj";
    REQUIRE(tools.lattice().exportDeformed(context, li, rest));
    const PolygonMesh atRest = readPolygonMesh(rest);
    REQUIRE(atRest.positions.cols() == 4);
    CHECK(atRest.positions == file.positions);

    // Every lattice point moved in the world (not an affine map): each written vertex is R^T D(R p).
    LatticeData data = std::get<LatticeData>(scene.object(li).data);
    std::vector<int> all;
    Eigen::Matrix3Xd points(3, data.points.cols());
    for (Eigen::Index k = 0; k < data.points.cols(); ++k) {
        const double t = double(k);
        all.push_back(static_cast<int>(k));
        points.col(k) = Eigen::Vector3d(data.points.col(k)) + 0.2 * Eigen::Vector3d(std::sin(t), std::cos(2 * t), std::sin(3 * t));
    }
    scene.setControlPoints(li, all, points, "move points");
    scene.updateGeometry();
    data = std::get<LatticeData>(scene.object(li).data);
    const Lattice world = latticeFromData(data);
    const std::string out = kTmp + "/up_axis_moved.obj";
    REQUIRE(tools.lattice().exportDeformed(context, li, out));
    const PolygonMesh moved = readPolygonMesh(out);
    REQUIRE(moved.positions.cols() == 4);
    double largest = 0;
    for (Eigen::Index v = 0; v < 4; ++v) {
        const Eigen::Vector3d expected = r.transpose() * world.deform(r * Eigen::Vector3d(file.positions.col(v))).point;
        INFO("vertex " << v << ": " << moved.positions.col(v).transpose() << " vs " << expected.transpose());
        CHECK((Eigen::Vector3d(moved.positions.col(v)) - expected).norm() < 1e-12);
        largest = std::max(largest, (expected - file.positions.col(v)).norm());
    }
    CHECK(largest > 0.05); // the drag did reach the mesh
}

} // namespace test_up_axis
