// A subdivision surface tessellated per region to the view (docs/editor.md, "Tessellation to the
// view"; SubdivisionTessellationOptions::toleranceOf): each cell of the certified path to the
// pixel size at its own nearest depth, one box per cage face for the staleness test, and a zoom
// re-tessellates it in the background as for Bézier surfaces. Expected values by hand: the box of a
// face's vertices and their neighbours, the pixel size at the box's nearest depth; the meshes
// compared with the synchronous path's buildGeometry and with the one view tolerance.

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "freeform/document/document.h"
#include "scene/scene.h"

namespace test_subdivision_view_tolerance {

using namespace freeform;
using namespace freeform::editor;

namespace {

const std::string kTmp = FREEFORM_TEST_TMP;
constexpr int kNx = 18, kNy = 4; // vertices along x and y: 17 x 3 quads, x in [0, 6.8]

Eigen::Vector3d vertex(int r, int c) { return {0.4 * r, 0.4 * c, 0.3 * std::sin(1.3 * r + 0.7 * c * c)}; }

/// A long wavy open Catmull-Clark grid along x, written as a document.
std::string writeLongGrid()
{
    const std::string path = kTmp + "/view-tolerance-grid.json";
    std::ostringstream s;
    s.precision(17);
    s << R"({"format": "freeform", "version": 1, "objects": [{"name": "grid", "type": "subdivision_surface", "scheme": "catmark", "vertices": [)";
    for (int r = 0; r < kNx; ++r)
        for (int c = 0; c < kNy; ++c) {
            const Eigen::Vector3d p = vertex(r, c);
            s << (r + c > 0 ? "," : "") << "[" << p.x() << "," << p.y() << "," << p.z() << "]";
        }
    s << R"(], "faces": [)";
    for (int r = 0; r + 1 < kNx; ++r)
        for (int c = 0; c + 1 < kNy; ++c)
            s << (r + c > 0 ? "," : "") << "[" << r * kNy + c << "," << (r + 1) * kNy + c << "," << (r + 1) * kNy + c + 1 << "," << r * kNy + c + 1
              << "]";
    s << "]}]}";
    std::ofstream(path) << s.str();
    return path;
}

/// The camera looking down at 45 degrees along -x at the grid's middle: the near end (x = 6.8) at
/// a depth of about 1.8, the far end (x = 0) at about 6.6.
void obliqueView(Scene& scene, double distance)
{
    scene.camera.projection = Projection::Perspective;
    scene.camera.orientation = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), Eigen::Vector3d(1, 0, 1).normalized());
    scene.camera.target = Eigen::Vector3d(3.4, 0.6, 0);
    scene.camera.distance = distance;
    scene.camera.fovyDegrees = 35;
}

/// 0.5 px at the nearest corner of box, by hand (as PixelScale::tolerance says).
double halfPixelAt(const Scene& scene, const Eigen::AlignedBox3d& box)
{
    const Eigen::Vector3d forward = -Eigen::Vector3d(1, 0, 1).normalized();
    const Eigen::Vector3d eye = scene.camera.target - scene.camera.distance * forward;
    double z = std::numeric_limits<double>::infinity();
    for (int c = 0; c < 8; ++c) z = std::min(z, (box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)) - eye).dot(forward));
    z = std::max(z, scene.camera.distance / 20);
    return 0.5 * 2 * z * std::tan(17.5 * 3.14159265358979323846 / 180) / 800;
}

} // namespace

TEST_CASE("subdivision to the view: one box per cage face, fewer triangles than the one view tolerance, a zoom "
          "re-tessellates in the background",
          "[editor][per-patch][subdivision]")
{
    Scene scene = Scene::load(writeLongGrid(), 1280.0 / 800.0);
    REQUIRE(scene.itemCount() == 1);
    obliqueView(scene, 4);
    scene.pixelTolerance = 0.5;
    scene.updateViewTolerance(800);
    scene.updateGeometry();
    REQUIRE(scene.pixelScale().on());
    const double old = scene.tessellationTolerance(); // the rule before: one tolerance for the view
    const ItemGeometry& g = scene.item(0).geometry;
    REQUIRE(g.surface);
    REQUIRE(g.error.empty());

    // One box per cage face: the face's vertices and their neighbours (the 3 x 3 faces around it,
    // clipped at the grid's border), and its tolerance 0.5 px at that box's nearest depth.
    REQUIRE(g.patchBoxes.size() == static_cast<std::size_t>((kNx - 1) * (kNy - 1)));
    REQUIRE(g.patchTolerance.size() == g.patchBoxes.size());
    for (int r = 0; r + 1 < kNx; ++r)
        for (int c = 0; c + 1 < kNy; ++c) {
            Eigen::AlignedBox3d box;
            box.setEmpty();
            for (int i = std::max(r - 1, 0); i <= std::min(r + 2, kNx - 1); ++i)
                for (int j = std::max(c - 1, 0); j <= std::min(c + 2, kNy - 1); ++j) box.extend(vertex(i, j));
            const std::size_t f = static_cast<std::size_t>(r * (kNy - 1) + c);
            CHECK(g.patchBoxes[f].min().isApprox(box.min(), 1e-12));
            CHECK(g.patchBoxes[f].max().isApprox(box.max(), 1e-12));
            CHECK(g.patchTolerance[f] == Approx(halfPixelAt(scene, box)).epsilon(1e-9));
            CHECK(g.patchTolerance[f] >= old * (1 - 1e-12)); // never finer than the one view tolerance
        }
    // The far faces get about 3.7 times the near ones' tolerance.
    CHECK(g.patchTolerance.front() > 3 * g.patchTolerance.back());

    // Fewer triangles than the one view tolerance everywhere (the synchronous path without a
    // PixelScale is the rule before).
    const ItemGeometry perView = buildGeometry(scene, 0, old);
    REQUIRE(perView.surface);
    INFO("per region " << g.surface->faceCount() << " triangles, one tolerance per view " << perView.surface->faceCount());
    CHECK(perView.patchBoxes.empty());
    CHECK(g.surface->faceCount() < perView.surface->faceCount());
    // The far half of the surface (x below the middle) gets fewer triangles than the near half.
    int nearHalf = 0, farHalf = 0;
    const PolygonMesh& m = *g.surface;
    for (int f = 0; f < m.faceCount(); ++f) {
        const double x = (m.positions(0, m.face(f)[0]) + m.positions(0, m.face(f)[1]) + m.positions(0, m.face(f)[2])) / 3;
        (x < 3.4 ? farHalf : nearHalf)++;
    }
    INFO("near half " << nearHalf << ", far half " << farHalf);
    CHECK(farHalf < nearHalf);

    // A small move (< 2x at every face) rebuilds nothing.
    scene.setBackgroundTessellation(true);
    const int revision = scene.item(0).revision;
    const std::vector<double> built = g.patchTolerance;
    const int builtTriangles = g.surface->faceCount();
    obliqueView(scene, 4.4);
    scene.updateViewTolerance(800);
    scene.updateGeometry();
    CHECK_FALSE(scene.tessellationPending());
    CHECK(scene.item(0).revision == revision);

    // Zooming in 4x: every face's tolerance moves past 2x; the surface is re-tessellated in the
    // background, onto the synchronous path's mesh for the new view.
    obliqueView(scene, 1);
    scene.updateViewTolerance(800);
    const long appliedBefore = scene.backgroundStats().applied;
    scene.updateGeometry(); // submits the job; the old mesh stays meanwhile
    CHECK(scene.item(0).geometry.surface->faceCount() == builtTriangles);
    scene.finishTessellation();
    CHECK(scene.backgroundStats().applied == appliedBefore + 1);
    CHECK(scene.item(0).revision != revision);
    const ItemGeometry& after = scene.item(0).geometry;
    REQUIRE(after.patchTolerance.size() == built.size());
    for (std::size_t f = 0; f < built.size(); ++f) CHECK(after.patchTolerance[f] < built[f]);
    const ItemGeometry expected =
        buildGeometry(scene, 0, scene.tessellationTolerance(), scene.pixelScale());
    REQUIRE(expected.surface);
    CHECK(expected.surface->faceCount() == after.surface->faceCount());
    CHECK(expected.surface->positions == after.surface->positions);
    INFO("after the zoom " << after.surface->faceCount() << " triangles, before " << builtTriangles);
    CHECK(after.surface->faceCount() > builtTriangles);
}

} // namespace test_subdivision_view_tolerance
