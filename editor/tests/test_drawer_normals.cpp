// The normals overlay of docs/editor.md ("Overlays": surface normals as short lines; Display:
// "normals", "normal length" as a fraction of the scene's diameter), through the recording backend
// (render/recording_renderer.h): what a frame draws, without a GL context or a display.
//
// The surface is the bilinear patch with corners (0,0,0), (1,0,0), (0,1,0), (1,1,1), which is
// f(u, v) = (u, v, uv) (docs/format.md, `bezier_surface`). By hand: f_u = (1, 0, v),
// f_v = (0, 1, u), so the unit normal f_u x f_v / |f_u x f_v| (docs/surfaces.md) at the point
// (x, y, xy) is (-y, -x, 1) / sqrt(1 + x^2 + y^2). The scene's bounding box is the unit cube, of
// diameter sqrt(3). Tessellated uniformly in 4 x 4 cells, the vertices are the 25 points
// (i/4, j/4, ij/16).

#include <catch2/catch.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <utility>

#include "render/recording_renderer.h"
#include "scene/scene.h"
#include "scene/scene_drawer.h"
#include "support/process.h"

namespace test_drawer_normals {

using namespace freeform;
using namespace freeform::editor;
using Kind = RecordingRenderer::Kind;

namespace {

const std::string kTmp = FREEFORM_TEST_TMP;

Scene saddle()
{
    const std::string path = kTmp + "/drawer-normals-saddle.json";
    test::writeText(path, R"({"format": "freeform", "version": 1, "objects": [
      {"name": "s", "type": "bezier_surface", "degree": [1, 1],
       "points": [[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 1]]],
       "editor": {"tessellation": {"mode": "uniform", "segments": 4}}}]})");
    return Scene::load(path);
}

} // namespace

TEST_CASE("recording renderer: the normals overlay draws one line per vertex, from the vertex along the hand-derived unit normal, normal length x diameter long",
          "[editor][drawer][normals]")
{
    Scene scene = saddle();
    scene.display.grid = false;
    scene.display.axes = false;
    scene.display.normals = false;
    scene.display.normalLength = 0.25f; // a fraction of the diameter sqrt(3)
    RecordingRenderer r;
    SceneDrawer drawer(r);
    drawer.draw(scene, 640, 480, -1);
    const auto off = r.calls(Kind::Lines);

    scene.display.normals = true;
    drawer.draw(scene, 640, 480, -1);
    const auto on = r.calls(Kind::Lines);
    // One more lines call with the overlay on: the normals.
    REQUIRE(on.size() == off.size() + 1);
    const RecordingRenderer::DrawCall* normals = nullptr;
    for (const auto& call : on) {
        bool before = false;
        for (const auto& o : off) before = before || o.handle == call.handle;
        if (!before) normals = &call;
    }
    REQUIRE(normals != nullptr);
    CHECK(normals->depthTested);
    const auto& lines = r.buffer(normals->handle).lines.positions;
    // 2 line vertices per surface vertex: 25 surface vertices.
    REQUIRE(lines.cols() == 2 * 25);
    CHECK(normals->vertices == 2 * 25);

    const double length = 0.25 * std::sqrt(3.0);
    std::set<std::pair<int, int>> seen;
    double worstStart = 0, worstEnd = 0;
    for (int k = 0; k < 25; ++k) {
        const Eigen::Vector3d a = lines.col(2 * k).cast<double>(), b = lines.col(2 * k + 1).cast<double>();
        // The start is one of the grid points (i/4, j/4, ij/16).
        const int i = static_cast<int>(std::lround(4 * a.x())), j = static_cast<int>(std::lround(4 * a.y()));
        REQUIRE(i >= 0);
        REQUIRE(i <= 4);
        REQUIRE(j >= 0);
        REQUIRE(j <= 4);
        seen.insert({i, j});
        const double x = i / 4.0, y = j / 4.0;
        worstStart = std::max(worstStart, (a - Eigen::Vector3d(x, y, x * y)).norm());
        const Eigen::Vector3d n = Eigen::Vector3d(-y, -x, 1) / std::sqrt(1 + x * x + y * y);
        worstEnd = std::max(worstEnd, (b - (Eigen::Vector3d(x, y, x * y) + length * n)).norm());
    }
    INFO("start " << worstStart << ", end " << worstEnd);
    CHECK(seen.size() == 25); // every vertex has its line, once
    CHECK(worstStart <= 1e-6); // float positions
    CHECK(worstEnd <= 1e-6);

    // Twice the normal length: the lines are twice as long, from the same points.
    scene.display.normalLength = 0.5f;
    drawer.draw(scene, 640, 480, -1);
    const auto longer = r.calls(Kind::Lines);
    REQUIRE(longer.size() == on.size());
    double worstLonger = 0;
    const auto& p = r.buffer(normals->handle).lines.positions;
    REQUIRE(p.cols() == 2 * 25);
    for (int k = 0; k < 25; ++k) {
        const Eigen::Vector3d a = p.col(2 * k).cast<double>(), b = p.col(2 * k + 1).cast<double>();
        const double x = a.x(), y = a.y();
        const Eigen::Vector3d n = Eigen::Vector3d(-y, -x, 1) / std::sqrt(1 + x * x + y * y);
        worstLonger = std::max(worstLonger, (b - (a + 2 * length * n)).norm());
    }
    CHECK(worstLonger <= 1e-6);
}

} // namespace test_drawer_normals
