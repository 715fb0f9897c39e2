// Subdivision surfaces in the editor without a window: a document's subdivision_surface whose cage
// lives in a mesh file beside it (data/cages copied to the test folder) is loaded into a Scene and
// checked against independent computations: the cage's vertices and edges read from the OBJ text by
// hand here, the library's SubdivisionSurface built from readCage with the options the editor uses
// (the surface must be the same mesh), the library's topology report (closed, genus), hand counts of
// the uniform tessellation, the creases of the file's tags written out by hand, and Lattice::deform
// evaluated vertex by vertex (the reference for applying a lattice to a cage). Every edit must be one
// undo step that gives the document text back byte for byte and must never rewrite the cage file;
// a bad cage must leave the rest of the document drawable. The cage tool (creases, corners, scheme,
// boundary, level, edge picking) is in test_cage_tool.cpp.

#include <catch2/catch.hpp>

#include <freeform/io/mesh_io.h>
#include <freeform/mesh/topology.h>
#include <freeform/subdivision/subdivision_surface.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "freeform/io/geometry_data.h"
#include "support/process.h"
#include "support/tool_bench.h"
#include "tools/tools.h"

namespace test_subdivision_editing {

using namespace freeform;
using namespace freeform::editor;
using namespace freeform::editor::cage_test;

namespace fs = std::filesystem;

namespace {

const std::string kTmp = FREEFORM_TEST_TMP;

/// The undirected edges (low, high) of a list of faces.
std::set<std::pair<int, int>> edgesOf(const std::vector<std::vector<int>>& faces)
{
    std::set<std::pair<int, int>> edges;
    for (const auto& f : faces)
        for (std::size_t k = 0; k < f.size(); ++k) {
            const int a = f[k], b = f[(k + 1) % f.size()];
            edges.insert({std::min(a, b), std::max(a, b)});
        }
    return edges;
}

} // namespace

// ------------------------------------------------------------------ a cage in a mesh file

TEST_CASE("Subdivision: a cube cage in a file gives its vertices, its 12 edges and the library's closed genus-0 limit surface",
          "[subdivision][scene]")
{
    const std::string dir = folderWith("subdiv_cube", {"cube.obj"});
    const std::string doc = dir + "/cube.json";
    test::writeText(doc, document(R"({"name": "cube", "type": "subdivision_surface", "mesh": "cube.obj"})"));
    Scene scene = Scene::load(doc);
    scene.updateGeometry();
    REQUIRE(scene.itemCount() == 1);
    const SceneItem& item = scene.item(0);
    REQUIRE(item.geometry.error.empty());
    REQUIRE(item.geometry.surface);

    // The net: the file's 8 vertices in file order, the cube's 12 edges.
    const ObjCage file = readObjByHand(dir + "/cube.obj");
    REQUIRE(file.vertices.cols() == 8);
    REQUIRE(file.faces.size() == 6);
    CHECK(item.geometry.netPoints == file.vertices);
    CHECK(scene.controlPointCount(0) == 8);
    CHECK(scene.controlPoints(0) == file.vertices);
    const std::set<std::pair<int, int>> edges(item.geometry.netEdges.begin(), item.geometry.netEdges.end());
    CHECK(item.geometry.netEdges.size() == 12); // no edge twice
    CHECK(edges == edgesOf(file.faces));
    for (const auto& [a, b] : edges) // every cube edge is parallel to an axis and 2 long
        CHECK((file.vertices.col(a) - file.vertices.col(b)).norm() == 2.0);

    // The surface: default settings are adaptive to the display tolerance.
    REQUIRE(scene.display.tolerance == 1e-3);
    const PolygonMesh reference = libraryTessellation(readCage(dir + "/cube.obj"), 1e-3);
    const PolygonMesh& surface = *item.geometry.surface;
    CHECK(surface.positions.cols() == reference.positions.cols());
    CHECK(meshDistance(surface, reference) <= 1e-12);
    CHECK(surface.normals.cols() == surface.positions.cols());

    const MeshReport report = meshReport(surface);
    CHECK(report.components == 1);
    CHECK(report.manifold);
    CHECK(report.closed);
    CHECK(report.boundaryEdges == 0);
    CHECK(report.euler == 2);
    REQUIRE(report.genus);
    CHECK(*report.genus == 0);
}

TEST_CASE("Subdivision: a torus cage in uniform mode has the hand-counted vertices and genus 1", "[subdivision][scene]")
{
    const std::string dir = folderWith("subdiv_torus", {"torus.obj"});
    const std::string doc = dir + "/torus.json";
    test::writeText(doc, document(R"({"name": "torus", "type": "subdivision_surface", "mesh": "torus.obj", "scheme": "catmark",
        "editor": {"tessellation": {"mode": "uniform", "segments": 6}}})"));
    Scene scene = Scene::load(doc);
    scene.updateGeometry();
    const SceneItem& item = scene.item(0);
    REQUIRE(item.geometry.error.empty());
    REQUIRE(item.geometry.surface);

    // 8 x 4 quads: V = 32, E = 64, F = 32.
    const ObjCage file = readObjByHand(dir + "/torus.obj");
    REQUIRE(file.vertices.cols() == 32);
    REQUIRE(file.faces.size() == 32);
    CHECK(item.geometry.netPoints == file.vertices);
    CHECK(item.geometry.netEdges.size() == 64);
    CHECK(std::set<std::pair<int, int>>(item.geometry.netEdges.begin(), item.geometry.netEdges.end()) == edgesOf(file.faces));

    // 6 segments per edge, shared: V + 5 E + 25 F = 32 + 320 + 800 vertices, 2 * 36 triangles a quad.
    const PolygonMesh& surface = *item.geometry.surface;
    CHECK(surface.positions.cols() == 1152);
    CHECK(surface.faceCount() == 32 * 72);
    CHECK(meshDistance(surface, libraryTessellation(readCage(dir + "/torus.obj"), 0, 6)) <= 1e-12);

    const MeshReport report = meshReport(surface);
    CHECK(report.components == 1);
    CHECK(report.closed);
    CHECK(report.manifold);
    CHECK(report.euler == 0);
    REQUIRE(report.genus);
    CHECK(*report.genus == 1);
}

// ------------------------------------------------------------------ editing the cage

TEST_CASE("Subdivision: moving a vertex of a file cage makes it inline with the file's creases; the file stays, undo restores",
          "[subdivision][scene][undo]")
{
    const std::string dir = folderWith("subdiv_move", {"creased_cube.obj"});
    const std::string obj = dir + "/creased_cube.obj";
    const std::string doc = dir + "/creased_cube.json";
    test::writeText(doc, document(R"({"name": "cage", "type": "subdivision_surface", "mesh": "creased_cube.obj"},
        {"name": "c", "type": "bezier_curve", "points": [[0, 0, 3], [1, 0, 3], [2, 1, 3]]})"));
    const std::string fileBytes = test::slurp(obj);
    Scene scene = Scene::load(doc);
    scene.updateGeometry();
    REQUIRE(scene.item(0).geometry.surface);
    const PolygonMesh before = *scene.item(0).geometry.surface;
    const std::string text = scene.text();
    const ObjCage file = readObjByHand(obj);

    // The top face's edges and corners 1, 7 are infinitely sharp: those corners are limit points.
    CHECK(nearestVertex(before, Eigen::Vector3d(-1, -1, 1)) <= 1e-12);
    CHECK(nearestVertex(before, Eigen::Vector3d(1, 1, 1)) <= 1e-12);

    const Eigen::Vector3d moved(-1.5, -1.25, -1.75);
    scene.setControlPoint(0, 0, moved);
    scene.updateGeometry();

    const auto& d = std::get<SubdivisionSurfaceData>(scene.object(0).data);
    CHECK(d.mesh.empty());
    REQUIRE(d.vertices.cols() == 8);
    REQUIRE(d.vertices.rows() == 3);
    CHECK(Eigen::Vector3d(d.vertices.col(0)) == moved);
    CHECK(d.vertices.rightCols(7) == file.vertices.rightCols(7)); // only vertex 0 moved
    CHECK(d.faces == file.faces);
    // "t crease 8/1 1 3 3 7 7 5 5 1 10" and "t corner 2/1 1 7 10", indices 0-based.
    const std::vector<std::array<double, 3>> creases{{1, 3, 10}, {3, 7, 10}, {7, 5, 10}, {5, 1, 10}};
    const std::vector<std::array<double, 2>> corners{{1, 10}, {7, 10}};
    CHECK(d.creases == creases);
    CHECK(d.corners == corners);
    CHECK(d.scheme == "catmark");
    CHECK(test::slurp(obj) == fileBytes);

    // The new surface is the library's limit surface of the moved cage, and it did change.
    SubdivisionCage cage = readCage(obj);
    cage.mesh.positions.col(0) = moved;
    REQUIRE(scene.item(0).geometry.surface);
    const PolygonMesh& after = *scene.item(0).geometry.surface;
    CHECK(meshDistance(after, libraryTessellation(cage, 1e-3)) <= 1e-12);
    // Vertex 0 is a smooth valence-3 vertex: its limit point has the weight n / (n + 5) = 3/8 in its
    // own limit mask, so it moves by 3/8 of the vertex's move, and the surface has a vertex there.
    const Eigen::Vector3d limit0 = SubdivisionSurface(readCage(obj), SubdivisionScheme::Catmark).evaluate(0, 0, 0).position;
    CHECK(nearestVertex(before, limit0) <= 1e-12);
    const Eigen::Vector3d limit0Moved = limit0 + 3.0 / 8.0 * (moved - Eigen::Vector3d(-1, -1, -1));
    CHECK(nearestVertex(after, limit0Moved) <= 1e-12);
    CHECK(nearestVertex(after, limit0) > 0.1);
    // The sharp corners are still limit points; they are outside vertex 0's one-ring, so they stay.
    CHECK(nearestVertex(after, Eigen::Vector3d(-1, -1, 1)) <= 1e-12);
    CHECK(nearestVertex(after, Eigen::Vector3d(1, 1, 1)) <= 1e-12);
    CHECK(scene.controlPoints(0).col(0) == moved);

    // Saved and read again, the inline cage gives the same surface.
    const std::string saved = dir + "/saved.json";
    scene.save(saved);
    Scene reread = Scene::load(saved);
    reread.updateGeometry();
    REQUIRE(reread.item(0).geometry.surface);
    CHECK(meshDistance(*reread.item(0).geometry.surface, after) <= 1e-12);

    // One undo step: the document text byte for byte, the file cage, the old surface.
    const std::string edited = scene.text();
    REQUIRE(scene.undo());
    CHECK(scene.text() == text);
    CHECK(std::get<SubdivisionSurfaceData>(scene.object(0).data).mesh == "creased_cube.obj");
    scene.updateGeometry();
    REQUIRE(scene.item(0).geometry.surface);
    CHECK(meshDistance(*scene.item(0).geometry.surface, before) <= 1e-12);
    CHECK_FALSE(scene.undo());
    REQUIRE(scene.redo());
    CHECK(scene.text() == edited);
    CHECK(test::slurp(obj) == fileBytes);
}

TEST_CASE("Subdivision: a bad vertex index or a non-finite point leaves a file cage as it is", "[subdivision][scene]")
{
    const std::string dir = folderWith("subdiv_bad_edit", {"cube.obj"});
    const std::string doc = dir + "/cube.json";
    test::writeText(doc, document(R"({"name": "cube", "type": "subdivision_surface", "mesh": "cube.obj"})"));
    Scene scene = Scene::load(doc);
    const std::string text = scene.text();
    const std::size_t steps = scene.history().size();
    CHECK_THROWS_AS(scene.setControlPoint(0, 8, Eigen::Vector3d(0, 0, 0)), Error);
    CHECK_THROWS_AS(scene.setControlPoint(0, 2, Eigen::Vector3d(0, std::nan(""), 0)), Error);
    CHECK(scene.text() == text);
    CHECK(scene.history().size() == steps);
}

// ------------------------------------------------------------------ a lattice applied to the cage

TEST_CASE("Subdivision: applying a lattice moves every cage vertex through Lattice::deform in one undo step",
          "[subdivision][tools][ffd][undo]")
{
    const bool fileCage = GENERATE(true, false);
    INFO((fileCage ? "cage in a mesh file" : "inline cage"));
    const std::string dir = folderWith(fileCage ? "subdiv_ffd_file" : "subdiv_ffd_inline", {"cube.obj"});
    const std::string obj = dir + "/cube.obj";
    const std::string doc = dir + "/cube.json";
    const ObjCage file = readObjByHand(obj);
    std::string cageObject;
    if (fileCage) {
        cageObject = R"({"name": "cube", "type": "subdivision_surface", "mesh": "cube.obj"})";
    } else {
        cageObject = R"({"name": "cube", "type": "subdivision_surface", "vertices": [)";
        for (Eigen::Index v = 0; v < file.vertices.cols(); ++v)
            cageObject += cat(v ? ", " : "", "[", file.vertices(0, v), ", ", file.vertices(1, v), ", ", file.vertices(2, v), "]");
        cageObject += R"(], "faces": [)";
        for (std::size_t f = 0; f < file.faces.size(); ++f) {
            const auto& face = file.faces[f];
            cageObject += cat(f ? ", " : "", "[", face[0], ", ", face[1], ", ", face[2], ", ", face[3], "]");
        }
        cageObject += "]}";
    }
    test::writeText(doc, document(cageObject));
    const std::string fileBytes = test::slurp(obj);
    Bench b{Scene::load(doc)};

    // A degree (2, 2, 2) lattice around the cube with its top centre point lifted and pushed in x:
    // not affine, so the cage's vertices move by different amounts.
    const Lattice rest = Lattice::identity({2, 2, 2}, Eigen::Vector3d(-1.5, -1.5, -1.5), 3 * Eigen::Matrix3d::Identity());
    const int li = b.scene.addObject({"box", latticeToData(rest), ""});
    b.scene.setControlPoint(li, rest.index(1, 1, 2), rest.restPoint(1, 1, 2) + Eigen::Vector3d(0.3, 0, 0.8));
    const Lattice lattice = latticeFromData(std::get<LatticeData>(b.scene.object(li).data));
    const std::string before = b.scene.text();
    const std::size_t steps = b.scene.history().size();

    REQUIRE(b.tools.lattice().applyLatticeToObjects(b.context, li));
    INFO(b.tools.message());
    CHECK(b.tools.message().find("deformed 1 object") != std::string::npos);
    const auto& d = std::get<SubdivisionSurfaceData>(b.scene.object(0).data);
    CHECK(d.mesh.empty());
    REQUIRE(d.vertices.cols() == 8);
    // By hand: the cube's corners sit at s, t, u in {1/6, 5/6} of the box, and only point (1, 1, 2)
    // moved, so a corner moves by B_1^2(s) B_1^2(t) B_2^2(u) (0.3, 0, 0.8) = (10/36)^2 u^2 (0.3, 0, 0.8).
    double worst = 0, worstByHand = 0;
    for (Eigen::Index v = 0; v < 8; ++v) {
        const Eigen::Vector3d p = file.vertices.col(v), q = d.vertices.col(v);
        worst = std::max(worst, (q - lattice.deform(p).point).norm());
        const double u = (p.z() + 1.5) / 3;
        worstByHand = std::max(worstByHand, (q - p - (10.0 / 36) * (10.0 / 36) * u * u * Eigen::Vector3d(0.3, 0, 0.8)).norm());
    }
    CHECK(worst <= 1e-12);
    CHECK(worstByHand <= 1e-12);
    CHECK(d.faces == file.faces);
    CHECK(test::slurp(obj) == fileBytes);

    // The limit surface is the library's surface of the deformed cage.
    b.scene.updateGeometry();
    SubdivisionCage cage = readCage(obj);
    cage.mesh.positions = d.vertices;
    REQUIRE(b.scene.item(0).geometry.surface);
    CHECK(meshDistance(*b.scene.item(0).geometry.surface, libraryTessellation(cage, 1e-3)) <= 1e-12);

    CHECK(b.scene.history().size() == steps + 1);
    REQUIRE(b.scene.undo());
    CHECK(b.scene.text() == before);
}

// ------------------------------------------------------------------ bad cages

TEST_CASE("Subdivision: bad cages load without a surface and with an error naming the edge or face; the rest is drawn",
          "[subdivision][scene]")
{
    const std::string dir = folderWith("subdiv_bad", {"cube.obj"});
    // Three triangles on edge 0-1: two of them run it the same way.
    test::writeText(dir + "/fin.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n");
    const std::string doc = dir + "/bad.json";
    test::writeText(doc, document(R"({"name": "fin", "type": "subdivision_surface", "mesh": "fin.obj"},
        {"name": "repeat", "type": "subdivision_surface", "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]],
         "faces": [[0, 1, 2, 3], [0, 3, 3, 2]]},
        {"name": "missing", "type": "subdivision_surface", "mesh": "no_such_cage.obj"},
        {"name": "cube", "type": "subdivision_surface", "mesh": "cube.obj"},
        {"name": "c", "type": "bezier_curve", "points": [[0, 0, 3], [1, 0, 3], [2, 1, 3]]})"));
    Scene scene = Scene::load(doc); // does not throw: the errors belong to the items
    REQUIRE(scene.itemCount() == 5);
    scene.updateGeometry();
    // Held as data plus the document layer's message, outside the typed document; the good ones in it.
    for (int i = 0; i < 3; ++i) {
        CHECK(scene.typed(i) == nullptr);
        CHECK(scene.item(i).geometry.error == scene.item(i).invalid);
    }
    CHECK(scene.typed(3) != nullptr);
    CHECK(scene.typed(4) != nullptr);
    CHECK(scene.model().objects().size() == 2);

    const ItemGeometry& fin = scene.item(0).geometry;
    CHECK_FALSE(fin.surface);
    INFO(fin.error);
    CHECK(fin.error.find("edge 0-1") != std::string::npos);
    CHECK(fin.error.find("faces 0 and 2") != std::string::npos);
    CHECK(fin.netPoints.cols() == 5); // the cage is still shown, so it can be mended

    const ItemGeometry& repeat = scene.item(1).geometry;
    CHECK_FALSE(repeat.surface);
    INFO(repeat.error);
    CHECK(repeat.error.find("face 1 uses vertex 3 twice") != std::string::npos);

    const ItemGeometry& missing = scene.item(2).geometry;
    CHECK_FALSE(missing.surface);
    INFO(missing.error);
    CHECK(missing.error.find("no_such_cage.obj") != std::string::npos);
    CHECK(scene.controlPointCount(2) == 0);

    // The good objects keep their geometry: the cube as if alone, the curve sampled.
    REQUIRE(scene.item(3).geometry.error.empty());
    REQUIRE(scene.item(3).geometry.surface);
    CHECK(meshDistance(*scene.item(3).geometry.surface, libraryTessellation(readCage(dir + "/cube.obj"), 1e-3)) <= 1e-12);
    CHECK(scene.item(4).geometry.error.empty());
    CHECK(scene.item(4).geometry.curve.cols() >= 2);

    // Editing a bad cage is not an error of its own: the vertex moves, the surface stays absent.
    scene.setControlPoint(0, 4, Eigen::Vector3d(0, 0, 2));
    scene.updateGeometry();
    CHECK(std::get<SubdivisionSurfaceData>(scene.object(0).data).vertices.col(4) == Eigen::Vector3d(0, 0, 2));
    CHECK_FALSE(scene.item(0).geometry.surface);
    CHECK_FALSE(scene.item(0).geometry.error.empty());
    CHECK_THROWS_AS(scene.setControlPoint(2, 0, Eigen::Vector3d(0, 0, 0)), Error);
}

TEST_CASE("Subdivision: a recovered autosave finds a relative cage file beside the original document", "[subdivision][scene]")
{
    const std::string dir = folderWith("subdiv_recover", {"cube.obj"});
    const std::string doc = dir + "/cube.json";
    test::writeText(doc, document(R"({"name": "cube", "type": "subdivision_surface", "mesh": "cube.obj"},
        {"name": "c", "type": "bezier_curve", "points": [[0, 0, 3], [1, 0, 3], [2, 1, 3]]})"));
    Scene scene = Scene::load(doc);
    scene.setControlPoint(1, 0, Eigen::Vector3d(0, 0.5, 3)); // an unsaved change elsewhere
    // As the application autosaves: the document elsewhere, imported mesh paths made absolute.
    const fs::path autosaveDir = fs::path(kTmp) / "subdiv_recover_state";
    fs::remove_all(autosaveDir);
    fs::create_directories(autosaveDir);
    const std::string autosave = (autosaveDir / "autosave.json").string();
    test::writeText(autosave, formatDocument(scene.toDocument(Scene::MeshPaths::Absolute)));

    Scene recovered = Scene::recover(autosave, doc);
    recovered.updateGeometry();
    CHECK(recovered.modified());
    CHECK(recovered.text() == scene.text());
    const ItemGeometry& g = recovered.item(0).geometry;
    INFO(g.error);
    CHECK(g.error.empty());
    REQUIRE(g.surface);
    CHECK(meshDistance(*g.surface, libraryTessellation(readCage(dir + "/cube.obj"), 1e-3)) <= 1e-12);
}

TEST_CASE("Subdivision: Save As into another folder rebases a relative cage path; the saved file shows the same surface",
          "[subdivision][scene]")
{
    const std::string dir = folderWith("subdiv_save_as", {"cube.obj"});
    const std::string doc = dir + "/cube.json";
    test::writeText(doc, document(R"({"name": "cube", "type": "subdivision_surface", "mesh": "cube.obj"})"));
    Scene scene = Scene::load(doc);
    scene.updateGeometry();
    REQUIRE(scene.item(0).geometry.surface);
    const PolygonMesh before = *scene.item(0).geometry.surface;

    // Saved beside itself: the path is written as it was read.
    scene.save(doc);
    CHECK(std::get<SubdivisionSurfaceData>(readDocument(doc).objects[0].data).mesh == "cube.obj");

    // Saved one folder down: "../cube.obj", and that file opens with the same limit surface.
    fs::create_directories(fs::path(dir) / "sub");
    const std::string moved = dir + "/sub/copy.json";
    scene.save(moved);
    CHECK(std::get<SubdivisionSurfaceData>(readDocument(moved).objects[0].data).mesh == "../cube.obj");
    Scene reopened = Scene::load(moved);
    reopened.updateGeometry();
    REQUIRE(reopened.item(0).geometry.error.empty());
    REQUIRE(reopened.item(0).geometry.surface);
    CHECK(meshDistance(*reopened.item(0).geometry.surface, before) == 0);
    // The scene in memory still draws the same surface after the save.
    scene.invalidateGeometry();
    scene.updateGeometry();
    REQUIRE(scene.item(0).geometry.surface);
    CHECK(meshDistance(*scene.item(0).geometry.surface, before) == 0);
}

} // namespace test_subdivision_editing

