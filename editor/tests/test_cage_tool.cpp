// The cage tool without a window (tools/cage_tool.h): on a document's subdivision_surface whose
// cage lives in a mesh file beside it (data/cages copied to the test folder), the keys of the
// keymap set and clear edge creases (a file cage made inline, its other tags kept) and sharp
// corners; scheme, boundary and level change the surface as the library builds it, and a scheme the
// cage refuses changes nothing; in edge mode a click picks the nearest projected cage edge. The
// cages are read here by hand and the surfaces compared with the library's SubdivisionSurface.
// Every edit must be one undo step that gives the document text back byte for byte and must never
// rewrite the cage file.

#include <catch2/catch.hpp>

#include <freeform/io/mesh_io.h>
#include <freeform/subdivision/subdivision_surface.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "freeform/io/geometry_data.h"
#include "interaction/keymap.h"
#include "support/process.h"
#include "support/tool_bench.h"
#include "tools/tools.h"

namespace test_cage_tool {

using namespace freeform;
using namespace freeform::editor;
using namespace freeform::editor::cage_test;

// ------------------------------------------------------------------ the cage tool

namespace {

/// The library's limit surface of a cage with the given scheme and boundary (as libraryTessellation).
PolygonMesh librarySurface(const SubdivisionCage& cage, SubdivisionScheme scheme, BoundaryInterpolation boundary,
                           double tolerance, int level = 8)
{
    const SubdivisionSurface surface(cage, scheme, boundary);
    SubdivisionTessellationOptions options;
    options.tolerance = tolerance;
    options.level = level;
    return surface.tessellate(options);
}

/// The first keymap entry of an action (its key and modifiers), so the tests press what the table says.
const KeyBinding& keyOf(KeyAction action)
{
    for (const KeyBinding& b : keymap())
        if (b.action == action) return b;
    FAIL("no keymap entry for an action");
    return keymap().front();
}

bool press(Bench& b, KeyAction action)
{
    const KeyBinding& k = keyOf(action);
    return b.tools.onKey(b.context, k.key, k.mods);
}

using Creases = std::vector<std::array<double, 3>>;
using Corners = std::vector<std::array<double, 2>>;

} // namespace

TEST_CASE("CageTool: S sets the picked edge's crease on a file cage (made inline), Shift+S clears it; one undo step each",
          "[subdivision][tools][cage][undo]")
{
    const std::string dir = folderWith("cage_tool_crease", {"cube.obj"});
    const std::string obj = dir + "/cube.obj";
    const std::string doc = dir + "/cube.json";
    test::writeText(doc, document(R"({"name": "cube", "type": "subdivision_surface", "mesh": "cube.obj"})"));
    const std::string fileBytes = test::slurp(obj);
    const ObjCage file = readObjByHand(obj);
    Bench b{Scene::load(doc)};
    b.scene.updateGeometry();
    const PolygonMesh smooth = *b.scene.item(0).geometry.surface;
    const std::string original = b.scene.text();
    const std::size_t steps = b.scene.history().size();
    CageTool& tool = b.tools.cage();

    // Not selected: the cage keys are not taken (they go on to the other handlers).
    CHECK_FALSE(press(b, KeyAction::SetCrease));
    b.selection.selectItem(0);
    // Nothing picked yet: S says so and changes nothing.
    CHECK(press(b, KeyAction::SetCrease));
    CHECK(b.tools.message().find("pick a cage edge") != std::string::npos);
    CHECK(b.scene.text() == original);
    // 0-7 is a diagonal of the cube, not an edge (file faces: 0 1 3 2, 4 6 7 5, ...).
    CHECK_FALSE(tool.pickEdge(b.context, 0, 0, 7));
    CHECK(b.tools.message().find("no cage edge 0-7") != std::string::npos);
    REQUIRE(tool.pickEdge(b.context, 0, 1, 0));
    REQUIRE(tool.pickedEdge());
    CHECK(*tool.pickedEdge() == std::array<int, 2>{0, 1});

    // S with the default sharpness (10, infinitely sharp).
    CHECK(tool.sharpness == 10);
    REQUIRE(press(b, KeyAction::SetCrease));
    INFO(b.tools.message());
    {
        const auto& d = std::get<SubdivisionSurfaceData>(b.scene.object(0).data);
        CHECK(d.mesh.empty());
        CHECK(d.vertices == file.vertices);
        CHECK(d.faces == file.faces);
        CHECK(d.creases == Creases{{0, 1, 10}});
        CHECK(d.corners.empty());
    }
    CHECK(test::slurp(obj) == fileBytes);
    CHECK(b.scene.history().size() == steps + 1);
    b.scene.updateGeometry();
    SubdivisionCage cage = readCage(obj);
    cage.creases.push_back({0, 1, 10});
    REQUIRE(b.scene.item(0).geometry.surface);
    const PolygonMesh creased = *b.scene.item(0).geometry.surface;
    CHECK(meshDistance(creased, libraryTessellation(cage, 1e-3)) <= 1e-12);
    CHECK(meshDistance(creased, smooth) > 1e-3); // the crease did change the surface
    const std::string once = b.scene.text();

    // Again with sharpness 2.5: the edge's entry is replaced, not repeated.
    tool.sharpness = 2.5;
    REQUIRE(press(b, KeyAction::SetCrease));
    CHECK(std::get<SubdivisionSurfaceData>(b.scene.object(0).data).creases == Creases{{0, 1, 2.5}});
    b.scene.updateGeometry();
    cage.creases.back().sharpness = 2.5;
    REQUIRE(b.scene.item(0).geometry.surface);
    CHECK(meshDistance(*b.scene.item(0).geometry.surface, libraryTessellation(cage, 1e-3)) <= 1e-12);
    const std::string twice = b.scene.text();

    // Shift+S clears it: no crease left, the inline cage is the file's cage again.
    REQUIRE(press(b, KeyAction::ClearCrease));
    CHECK(std::get<SubdivisionSurfaceData>(b.scene.object(0).data).creases.empty());
    b.scene.updateGeometry();
    REQUIRE(b.scene.item(0).geometry.surface);
    CHECK(meshDistance(*b.scene.item(0).geometry.surface, smooth) <= 1e-12);
    CHECK(b.scene.history().size() == steps + 3);
    // Clearing an edge without a crease is no edit.
    REQUIRE(press(b, KeyAction::ClearCrease));
    CHECK(b.scene.history().size() == steps + 3);

    // Undo walks back byte for byte: 2.5, 10, the file cage as read.
    REQUIRE(b.scene.undo());
    CHECK(b.scene.text() == twice);
    REQUIRE(b.scene.undo());
    CHECK(b.scene.text() == once);
    REQUIRE(b.scene.undo());
    CHECK(b.scene.text() == original);
    CHECK(std::get<SubdivisionSurfaceData>(b.scene.object(0).data).mesh == "cube.obj");
    REQUIRE(b.scene.redo());
    CHECK(b.scene.text() == once);
    CHECK(test::slurp(obj) == fileBytes);
}

TEST_CASE("CageTool: clearing one of a file's crease tags keeps the others and the corners", "[subdivision][tools][cage][undo]")
{
    const std::string dir = folderWith("cage_tool_tags", {"creased_cube.obj"});
    const std::string obj = dir + "/creased_cube.obj";
    const std::string doc = dir + "/creased_cube.json";
    test::writeText(doc, document(R"({"name": "cage", "type": "subdivision_surface", "mesh": "creased_cube.obj"})"));
    Bench b{Scene::load(doc)};
    b.selection.selectItem(0);
    const std::string original = b.scene.text();
    CageTool& tool = b.tools.cage();

    // "t crease 8/1 1 3 3 7 7 5 5 1 10" (0-based): 1-3, 3-7, 7-5, 5-1, all 10.
    const std::optional<SubdivisionCage> before = CageTool::cageOf(b.scene, 0);
    REQUIRE(before);
    CHECK(CageTool::edgeSharpness(*before, 3, 1) == 10);
    CHECK(CageTool::edgeSharpness(*before, 0, 1) == 0);

    REQUIRE(tool.pickEdge(b.context, 0, 3, 1));
    REQUIRE(press(b, KeyAction::ClearCrease));
    const auto& d = std::get<SubdivisionSurfaceData>(b.scene.object(0).data);
    CHECK(d.mesh.empty());
    CHECK(d.creases == Creases{{3, 7, 10}, {7, 5, 10}, {5, 1, 10}});
    CHECK(d.corners == Corners{{1, 10}, {7, 10}});
    b.scene.updateGeometry();
    SubdivisionCage cage = readCage(obj);
    cage.creases = {{3, 7, 10}, {7, 5, 10}, {5, 1, 10}};
    REQUIRE(b.scene.item(0).geometry.surface);
    CHECK(meshDistance(*b.scene.item(0).geometry.surface, libraryTessellation(cage, 1e-3)) <= 1e-12);
    // Corners 1 and 7 are still infinitely sharp: limit points at the cage vertices.
    CHECK(nearestVertex(*b.scene.item(0).geometry.surface, Eigen::Vector3d(-1, -1, 1)) <= 1e-12);
    CHECK(nearestVertex(*b.scene.item(0).geometry.surface, Eigen::Vector3d(1, 1, 1)) <= 1e-12);

    REQUIRE(b.scene.undo());
    CHECK(b.scene.text() == original);
}

TEST_CASE("CageTool: Alt+S makes the selected cage vertices sharp corners (limit points), Alt+Shift+S clears them",
          "[subdivision][tools][cage][undo]")
{
    const std::string dir = folderWith("cage_tool_corners", {"cube.obj"});
    const std::string obj = dir + "/cube.obj";
    const std::string doc = dir + "/cube.json";
    test::writeText(doc, document(R"({"name": "cube", "type": "subdivision_surface", "mesh": "cube.obj"})"));
    Bench b{Scene::load(doc)};
    b.selection.selectItem(0);
    b.scene.updateGeometry();
    const std::string original = b.scene.text();
    const std::size_t steps = b.scene.history().size();

    // No point selected: nothing happens.
    CHECK(press(b, KeyAction::SetCorner));
    CHECK(b.scene.text() == original);
    // Vertices 0 (-1, -1, -1) and 6 (1, 1, -1): smooth valence-3 vertices, not on the surface.
    CHECK(nearestVertex(*b.scene.item(0).geometry.surface, Eigen::Vector3d(-1, -1, -1)) > 0.1);
    b.selection.setPoints({6, 0});
    REQUIRE(press(b, KeyAction::SetCorner));
    CHECK(std::get<SubdivisionSurfaceData>(b.scene.object(0).data).corners == Corners{{0, 10}, {6, 10}});
    CHECK(b.scene.history().size() == steps + 1); // two corners, one step
    b.scene.updateGeometry();
    SubdivisionCage cage = readCage(obj);
    cage.corners = {{0, 10}, {6, 10}};
    const PolygonMesh& sharp = *b.scene.item(0).geometry.surface;
    CHECK(meshDistance(sharp, libraryTessellation(cage, 1e-3)) <= 1e-12);
    CHECK(nearestVertex(sharp, Eigen::Vector3d(-1, -1, -1)) <= 1e-12);
    CHECK(nearestVertex(sharp, Eigen::Vector3d(1, 1, -1)) <= 1e-12);
    const std::string sharpText = b.scene.text();

    b.selection.setPoints({0});
    REQUIRE(press(b, KeyAction::ClearCorner));
    CHECK(std::get<SubdivisionSurfaceData>(b.scene.object(0).data).corners == Corners{{6, 10}});
    REQUIRE(b.scene.undo());
    CHECK(b.scene.text() == sharpText);
    REQUIRE(b.scene.undo());
    CHECK(b.scene.text() == original);
}

TEST_CASE("CageTool: scheme, boundary and level as the library builds them; a scheme the cage refuses changes nothing",
          "[subdivision][tools][cage][undo]")
{
    const std::string dir = folderWith("cage_tool_options", {"cube.obj", "octahedron.obj"});
    // A 3 x 3 grid of unit quads (vertex 4 r + c): only the middle face touches no boundary.
    std::string grid = R"({"name": "grid", "type": "subdivision_surface", "vertices": [)";
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) grid += cat(r || c ? ", " : "", "[", c, ", ", r, ", 0]");
    grid += R"(], "faces": [)";
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            const int v = 4 * r + c;
            grid += cat(r || c ? ", " : "", "[", v, ", ", v + 1, ", ", v + 5, ", ", v + 4, "]");
        }
    grid += "]}";
    const std::string doc = dir + "/options.json";
    test::writeText(doc, document(R"({"name": "cube", "type": "subdivision_surface", "mesh": "cube.obj"},
        {"name": "octa", "type": "subdivision_surface", "mesh": "octahedron.obj"}, )" + grid));
    Bench b{Scene::load(doc)};
    CageTool& tool = b.tools.cage();
    const std::string original = b.scene.text();
    const std::size_t steps = b.scene.history().size();

    // Loop on the cube's quads: refused by the library, nothing changes, the status says why.
    CHECK_FALSE(tool.setScheme(b.context, 0, "loop"));
    INFO(b.tools.message());
    CHECK(b.tools.message().find("cube") != std::string::npos);
    CHECK(b.tools.message().find("triangle") != std::string::npos);
    CHECK(b.scene.text() == original);
    CHECK(b.scene.history().size() == steps);

    // Loop on the octahedron: the library's Loop surface of the file's cage.
    REQUIRE(tool.setScheme(b.context, 1, "loop"));
    CHECK(std::get<SubdivisionSurfaceData>(b.scene.object(1).data).scheme == "loop");
    CHECK(std::get<SubdivisionSurfaceData>(b.scene.object(1).data).mesh == "octahedron.obj"); // no need to inline
    b.scene.updateGeometry();
    const SubdivisionCage octa = readCage(dir + "/octahedron.obj");
    REQUIRE(b.scene.item(1).geometry.surface);
    CHECK(meshDistance(*b.scene.item(1).geometry.surface,
                       librarySurface(octa, SubdivisionScheme::Loop, BoundaryInterpolation::EdgeOnly, 1e-3)) <= 1e-12);
    CHECK(meshDistance(*b.scene.item(1).geometry.surface,
                       librarySurface(octa, SubdivisionScheme::Catmark, BoundaryInterpolation::EdgeOnly, 1e-3)) > 1e-3);

    // Level 4 on the cube: 4 x 4 quads per face, 2 triangles each; V + 3 E + 9 F shared vertices.
    REQUIRE(tool.setLevel(b.context, 0, 4));
    CHECK(b.scene.item(0).settings.tessellation.mode == Tessellation::Mode::Uniform);
    CHECK(b.scene.item(0).settings.tessellation.segments == 4);
    b.scene.updateGeometry();
    REQUIRE(b.scene.item(0).geometry.surface);
    CHECK(b.scene.item(0).geometry.surface->faceCount() == 6 * 16 * 2);
    CHECK(b.scene.item(0).geometry.surface->positions.cols() == 8 + 3 * 12 + 9 * 6);
    CHECK_FALSE(tool.setLevel(b.context, 0, -1));

    // Boundary "none" on the grid at level 4: only the middle face has a limit surface, 32 triangles.
    REQUIRE(tool.setLevel(b.context, 2, 4));
    REQUIRE(tool.setBoundary(b.context, 2, "none"));
    CHECK(std::get<SubdivisionSurfaceData>(b.scene.object(2).data).boundary == "none");
    b.scene.updateGeometry();
    SubdivisionCage gridCage;
    gridCage.mesh.positions = std::get<SubdivisionSurfaceData>(b.scene.object(2).data).vertices;
    for (const auto& f : std::get<SubdivisionSurfaceData>(b.scene.object(2).data).faces) gridCage.mesh.addFace(f.begin(), f.end());
    REQUIRE(b.scene.item(2).geometry.surface);
    CHECK(b.scene.item(2).geometry.surface->faceCount() == 32);
    CHECK(meshDistance(*b.scene.item(2).geometry.surface,
                       librarySurface(gridCage, SubdivisionScheme::Catmark, BoundaryInterpolation::None, 0, 4)) <= 1e-12);
    // Edge only: all nine faces, 9 x 32 triangles.
    REQUIRE(tool.setBoundary(b.context, 2, "edge_only"));
    b.scene.updateGeometry();
    CHECK(b.scene.item(2).geometry.surface->faceCount() == 9 * 32);

    // Five edits, five steps; undone, the text is the original byte for byte.
    CHECK(b.scene.history().size() == steps + 5);
    for (int k = 0; k < 5; ++k) REQUIRE(b.scene.undo());
    CHECK(b.scene.text() == original);
}

TEST_CASE("CageTool: in edge mode (E) a click picks the nearest projected cage edge; the overlay marks creases and the pick",
          "[subdivision][tools][cage]")
{
    const std::string dir = folderWith("cage_tool_pick", {"creased_cube.obj"});
    const std::string doc = dir + "/cube.json";
    test::writeText(doc, document(R"({"name": "cage", "type": "subdivision_surface", "mesh": "creased_cube.obj"})"));
    Bench b{Scene::load(doc)};
    b.scene.updateGeometry();
    b.selection.selectItem(0);
    // A view that maps (x, y, z) to clip (0.3 x + 0.1 z, 0.3 y + 0.17 z): no two cube edges overlap.
    Eigen::Matrix4d vp = Eigen::Matrix4d::Zero();
    vp(0, 0) = 0.3, vp(0, 2) = 0.1, vp(1, 1) = 0.3, vp(1, 2) = 0.17, vp(2, 2) = 0.1, vp(3, 3) = 1;
    b.context.viewProjection = vp;
    const auto pixel = [&](const Eigen::Vector3d& p) {
        const double cx = 0.3 * p.x() + 0.1 * p.z(), cy = 0.3 * p.y() + 0.17 * p.z();
        return Eigen::Vector2d((cx * 0.5 + 0.5) * 800, (0.5 - cy * 0.5) * 500);
    };
    // The middle of edge 0-2, (-1, -1, -1) to (-1, 1, -1), plus 3 pixels off to the side.
    const Eigen::Vector2d middle = 0.5 * (pixel({-1, -1, -1}) + pixel({-1, 1, -1})) + Eigen::Vector2d(3, 0);
    PointerEvent click;
    click.type = PointerEvent::Type::Press;
    click.button = 0;
    click.x = middle.x();
    click.y = middle.y();
    // Without edge mode the click is not the tool's (the generic picking gets it).
    CHECK_FALSE(b.tools.onPointer(b.context, click));
    REQUIRE(press(b, KeyAction::CageEdgeMode));
    CHECK(b.tools.cage().edgeMode);
    REQUIRE(b.tools.onPointer(b.context, click));
    REQUIRE(b.tools.cage().pickedEdge());
    CHECK(*b.tools.cage().pickedEdge() == std::array<int, 2>{0, 2});
    // Far from every edge: not taken, the pick stays.
    click.x = 5, click.y = 5;
    CHECK_FALSE(b.tools.onPointer(b.context, click));
    CHECK(*b.tools.cage().pickedEdge() == std::array<int, 2>{0, 2});

    // The overlay: the four infinitely sharp top edges and the picked edge as lines, the two corners as points.
    Overlay overlay;
    b.tools.update(b.context, overlay);
    CHECK(overlay.linesOnTop.positions.cols() == 2 * 5);
    CHECK(overlay.points.positions.cols() == 2);
    const Eigen::Vector3f v1(-1, -1, 1), v7(1, 1, 1);
    CHECK(((overlay.points.positions.col(0) - v1).norm() == 0 || (overlay.points.positions.col(0) - v7).norm() == 0));
    // E again: edge mode off.
    REQUIRE(press(b, KeyAction::CageEdgeMode));
    CHECK_FALSE(b.tools.cage().edgeMode);
}

} // namespace test_cage_tool
