// Tessellation: the certified bound (tight on the saddle, kept on the teapot against independently
// computed point-triangle distances), normals at the teapot's collapsed edges, closed complexes to
// closed meshes (torus chi = 0, rounded box chi = 2, counted here from the faces), no cracks where
// patches of very different curvature meet.

#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <unordered_map>

#include "freeform/io/bpt.h"
#include "freeform/tessellate/tessellate.h"
#include "support/random.h"
#include "support/tessellation_checks.h"

namespace test_tessellate {

using namespace freeform;
using namespace freeform::test;
using V3 = Eigen::Vector3d;

namespace {
const std::string kTeapot = std::string(FREEFORM_SOURCE_DIR) + "/data/teapot.bpt";

/// Six bicubic patches of a rounded box: the cube [-1,1]^3 faces on a 4 x 4 grid of control
/// points, each pushed part of the way to the sphere through the cube's corners. A control point
/// on a cube edge is computed from the same coordinates by every face that has it, so shared
/// sides coincide exactly. u x v points outwards.
PatchComplex roundedBox()
{
    const double g[4] = {-1.0, -1.0 / 3, 1.0 / 3, 1.0};
    auto push = [](V3 q) { return V3(0.6 * q + 0.4 * std::sqrt(3.0) * q.normalized()); };
    PatchComplex box;
    for (int axis = 0; axis < 3; ++axis) {
        for (int sign : {-1, 1}) {
            // u along axis a, v along axis b with e_a x e_b = sign * e_axis.
            int a = (axis + 1) % 3, b = (axis + 2) % 3;
            if (sign < 0) std::swap(a, b);
            PointMatrix<double, 3> pts(3, 16);
            for (int i = 0; i < 4; ++i)
                for (int j = 0; j < 4; ++j) {
                    V3 q;
                    q[axis] = sign;
                    q[a] = g[i];
                    q[b] = g[j];
                    pts.col(i * 4 + j) = push(q);
                }
            box.patches.emplace_back(3, 3, pts);
        }
    }
    return box;
}

/// A closed torus-like de Boor grid: rows around the tube's axis, cols around the tube.
PatchComplex torus(int rows, int cols)
{
    PointMatrix<double, 3> d(3, rows * cols);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
            const double a = 2 * M_PI * r / rows, b = 2 * M_PI * c / cols;
            const double rad = 3 + std::cos(b);
            d.col(r * cols + c) = V3(rad * std::cos(a), rad * std::sin(a), std::sin(b));
        }
    return deboorSurfacePatches(d, rows, cols, EndCondition::Closed, EndCondition::Closed);
}
} // namespace

TEST_CASE("the bound is exact on the saddle z = uv", "[tessellate]")
{
    PointMatrix<double, 3> p(3, 4);
    p << 0, 0, 1, 1, 0, 1, 0, 1, 0, 0, 0, 1;
    const Patch saddle(1, 1, p); // f(u, v) = (u, v, uv)
    // M_uu = M_vv = 0, M_uv = 1: bound 1/(4 nu nv); the triangles miss z = uv by exactly a
    // quarter of the cell's twist hu hv at the cell centre.
    CHECK(tessellationErrorBound(saddle, 4, 5) == Approx(1.0 / 80).epsilon(1e-15));
    const auto mesh = tessellateUniform(PatchComplex{{saddle}}, 4, 5);
    CHECK(mesh.vertexCount() == 5 * 6);
    CHECK(mesh.faceCount() == 2 * 4 * 5);
    TriangleGrid tri(mesh, 0.1);
    double worst = 0;
    for (int i = 0; i <= 80; ++i)
        for (int j = 0; j <= 100; ++j) {
            const double u = i / 80.0, v = j / 100.0;
            // The vertical distance to the triangles at the same (u, v) is what the bound measures.
            worst = std::max(worst, tri.distance(saddle.evaluate(u, v), 0.2));
        }
    CHECK(worst <= 1.0 / 80);
    CHECK(worst > 0.5 / 80); // and the bound is not loose by more than the projection
    CHECK(adaptiveSegments(saddle, 1e-3) == std::array<int, 2>{16, 16});
}

TEST_CASE("uniform: vertices, normals and (u, v) come from the surface", "[tessellate]")
{
    // A gently curved patch (random heights over a regular grid).
    PointMatrix<double, 3> pts = test::randomPoints<double, 3>(12, 4, -0.2, 0.2);
    for (int i = 0; i <= 3; ++i)
        for (int j = 0; j <= 2; ++j) pts.col(i * 3 + j) += V3(i / 3.0, j / 2.0, 0);
    const Patch s(3, 2, pts);
    const auto mesh = tessellateUniform(PatchComplex{{s}}, 6, 3);
    REQUIRE(mesh.vertexCount() == 7 * 4);
    REQUIRE(mesh.faceCount() == 36);
    REQUIRE(mesh.isTriangleMesh());
    mesh.validate();
    for (int k = 0; k < mesh.vertexCount(); ++k) {
        const double u = mesh.texcoords(0, k), v = mesh.texcoords(1, k);
        CHECK((V3(mesh.positions.col(k)) - s.evaluate(u, v)).norm() < 1e-14);
        CHECK((V3(mesh.normals.col(k)) - s.normal(u, v)).norm() < 1e-12);
    }
    // Faces wind counter-clockwise in (u, v): the face normal agrees with the vertex normals.
    for (int f = 0; f < mesh.faceCount(); ++f) {
        const int* v = mesh.face(f);
        const V3 a = mesh.positions.col(v[0]), b = mesh.positions.col(v[1]), c = mesh.positions.col(v[2]);
        CHECK((b - a).cross(c - a).dot(V3(mesh.normals.col(v[0]))) > 0);
    }
    TessellationOptions flip;
    flip.segmentsU = 6;
    flip.segmentsV = 3;
    flip.flipNormals = true;
    const auto flipped = tessellate(PatchComplex{{s}}, flip);
    CHECK(flipped.normals == -mesh.normals);
    CHECK(flipped.face(0)[1] == mesh.face(0)[2]);
    CHECK_THROWS_WITH(tessellateUniform(PatchComplex{{s}}, 0, 3), Catch::Contains("at least 1"));
    CHECK_THROWS_WITH(tessellateAdaptive(PatchComplex{{s}}, -1), Catch::Contains("positive"));
}

TEST_CASE("teapot at 1e-3: every surface sample lies within the tolerance of the mesh", "[tessellate][teapot]")
{
    const PatchComplex teapot = readBpt(kTeapot);
    TessellationOptions o;
    o.tolerance = 1e-3;
    TessellationReport report;
    const auto mesh = tessellate(teapot, o, &report);
    mesh.validate("teapot");
    CHECK(report.errorBound <= 1e-3);
    const TriangleGrid tri(mesh, 0.05);
    double worst = 0;
    // 33 x 33 parameters per patch, off the tessellation's grid (irrational steps).
    for (const Patch& p : teapot.patches)
        for (int i = 0; i <= 32; ++i)
            for (int j = 0; j <= 32; ++j) {
                const double u = std::fmod(i * 0.030901699 + 0.0071, 1.0), v = std::fmod(j * 0.0314159 + 0.0029, 1.0);
                const double d = tri.distance(p.evaluate(i == 32 ? 1.0 : u, j == 32 ? 1.0 : v), 1e-3);
                worst = std::max(worst, d);
            }
    INFO("worst distance " << worst);
    CHECK(worst <= 1e-3);
    // Welded: the body's seams are shared vertices, no duplicated positions on shared sides.
    const Topology t = topology(mesh);
    CHECK(t.nonManifoldEdges == 0);
}

TEST_CASE("teapot: normals at the collapsed lid top and bottom centre", "[tessellate][teapot][normal]")
{
    const PatchComplex teapot = readBpt(kTeapot);
    // Analytic normals: f_u x f_v points into the teapot (as the file is oriented).
    bool sawLid = false, sawBottom = false;
    for (const Patch& p : teapot.patches) {
        for (int s = 0; s < 4; ++s) {
            const auto side = static_cast<PatchSide>(s);
            if (!isCollapsedEdge(p, side)) continue;
            const V3 pole = edgeCurve(p, side).controlPoint(0);
            CHECK(std::abs(pole.x()) + std::abs(pole.y()) == 0); // on the axis
            for (double t : {0.0, 0.3, 0.5, 1.0}) {
                const double u = side == PatchSide::U0 ? 0 : side == PatchSide::U1 ? 1 : t;
                const double v = side == PatchSide::V0 ? 0 : side == PatchSide::V1 ? 1 : t;
                const V3 n = p.normal(u, v);
                REQUIRE(n.allFinite());
                CHECK(std::abs(std::abs(n.z()) - 1) < 1e-12); // vertical
                const double du = side == PatchSide::U0 ? 1e-3 : side == PatchSide::U1 ? -1e-3 : 0;
                const double dv = side == PatchSide::V0 ? 1e-3 : side == PatchSide::V1 ? -1e-3 : 0;
                CHECK(n.dot(p.normal(u + du, v + dv)) > 0.99); // like its neighbours
                // Inward: at the lid's top it points down, at the bottom's centre up.
                if (pole.z() > 1) {
                    sawLid = true;
                    CHECK(n.z() < 0);
                } else {
                    sawBottom = true;
                    CHECK(n.z() > 0);
                }
            }
        }
    }
    CHECK(sawLid);
    CHECK(sawBottom);
    // In the mesh, with outward normals: one vertex at each pole, normal vertical and agreeing
    // with its neighbours; with either measure.
    for (const TessellationMeasure measure : {TessellationMeasure::Parametric, TessellationMeasure::Geometric}) {
        CAPTURE(static_cast<int>(measure));
        TessellationOptions o;
        o.tolerance = 1e-3;
        o.flipNormals = true;
        o.measure = measure;
        const auto mesh = tessellate(teapot, o);
        int poles = 0;
        for (int k = 0; k < mesh.vertexCount(); ++k) {
            const V3 q = mesh.positions.col(k);
            if (q.x() != 0 || q.y() != 0) continue;
            ++poles;
            const V3 n = mesh.normals.col(k);
            REQUIRE(n.allFinite());
            CHECK(std::abs(n.z()) > 1 - 1e-12);
            CHECK(n.z() * (q.z() > 1 ? 1 : -1) > 0); // outward: up at the lid, down at the bottom
            for (int f = 0; f < mesh.faceCount(); ++f)
                for (int c = 0; c < 3; ++c)
                    if (mesh.face(f)[c] == k)
                        for (int e = 0; e < 3; ++e) CHECK(n.dot(V3(mesh.normals.col(mesh.face(f)[e]))) > 0.9);
        }
        CHECK(poles == 2);
    }
}

TEST_CASE("a closed periodic bicubic torus gives a closed manifold mesh with chi = 0", "[tessellate][closed]")
{
    const PatchComplex t = torus(6, 5);
    for (const auto& mesh : {tessellateUniform(t, 3, 4), tessellateAdaptive(t, 1e-3)}) {
        const Topology top = topology(mesh);
        CHECK(top.boundaryEdges == 0);
        CHECK(top.nonManifoldEdges == 0);
        CHECK(top.euler() == 0); // genus 1
        CHECK(top.vertices == mesh.vertexCount());
    }
}

TEST_CASE("six patches of a rounded box give a closed mesh with chi = 2", "[tessellate][closed]")
{
    const PatchComplex box = roundedBox();
    CHECK(sharedEdges(box).size() == 12);
    for (const auto& mesh : {tessellateUniform(box, 4, 4), tessellateAdaptive(box, 1e-4)}) {
        const Topology top = topology(mesh);
        CHECK(top.boundaryEdges == 0);
        CHECK(top.nonManifoldEdges == 0);
        CHECK(top.euler() == 2); // genus 0
        // Outward: the normal at every vertex points away from the centre.
        for (int k = 0; k < mesh.vertexCount(); ++k) CHECK(V3(mesh.normals.col(k)).dot(V3(mesh.positions.col(k))) > 0);
    }
}

TEST_CASE("no cracks between a flat and a strongly curved patch sharing an edge", "[tessellate][cracks]")
{
    // Shared side: the curve along v at u = 1 of A and u = 0 of B.
    PointMatrix<double, 3> a(3, 16), b(3, 16);
    for (int i = 0; i <= 3; ++i)
        for (int j = 0; j <= 3; ++j) {
            const double y = j / 3.0, z = 0.05 * j * (3 - j);
            a.col(i * 4 + j) = V3(-1 + i / 3.0, y, z * (i / 3.0));
            b.col(i * 4 + j) = V3(i / 3.0, y, z + (i == 0 ? 0 : 3.0 * std::sin(2.0 * i + j)));
        }
    const PatchComplex pair{{Patch(3, 3, a), Patch(3, 3, b)}};
    REQUIRE(sharedEdges(pair).size() == 1);
    TessellationOptions o;
    o.tolerance = 1e-3;
    o.refinement = TessellationRefinement::PatchGrid; // one grid per patch (local refinement: test_tessellate_local.cpp)
    TessellationReport report;
    const auto mesh = tessellate(pair, o, &report);
    // The patches ask for very different refinements along the shared side...
    CHECK(report.required[0][1] * 4 < report.required[1][1]);
    // ...and get the same one.
    CHECK(report.segments[0][1] == report.segments[1][1]);
    const Topology top = topology(mesh);
    CHECK(top.nonManifoldEdges == 0);
    // No boundary edge lies on the shared side (x = 0 on both patches' shared curve).
    const auto shared = edgeCurve(pair.patches[0], PatchSide::U1);
    for (const auto& [p, q] : top.boundary) {
        const V3 mid = (V3(mesh.positions.col(p)) + V3(mesh.positions.col(q))) / 2;
        CHECK(shared.closestPoint(mid).distance > 1e-6);
    }
    // The union is a disk: V - E + F = 1.
    CHECK(top.euler() == 1);
}

} // namespace test_tessellate
