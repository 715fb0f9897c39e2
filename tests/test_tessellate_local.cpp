// Local refinement (issue 15): the certified bound on random patches of degrees 1-7, the teapot, a
// de Boor torus and a subdivision cage, checked against independent computations (the library's
// de Casteljau evaluate at the triangles' (u, v), point-triangle distances from the surface);
// conformity counted from the face list (in (u, v): every edge with one face lies on the square's
// boundary, the others have two, the triangles tile the square); closed inputs give closed meshes;
// the triangle count at 1e-3 as a regression guard; the maxTriangles refusal.

#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <unordered_map>

#include "freeform/io/bpt.h"
#include "freeform/io/geometry_data.h"
#include "freeform/subdivision/subdivision_surface.h"
#include "freeform/tessellate/tessellate.h"
#include "support/random.h"
#include "support/sanitizers.h"
#include "support/tessellation_checks.h"

namespace test_tessellate_local {

using namespace freeform;
using namespace freeform::test;
using V3 = Eigen::Vector3d;
using V2 = Eigen::Vector2d;

namespace {
const std::string kTeapot = std::string(FREEFORM_SOURCE_DIR) + "/data/teapot.bpt";

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

/// Conformity of a one-patch mesh in (u, v): every triangle counter-clockwise and not degenerate,
/// the areas sum to 1, every edge has one or two faces and the edges with one face lie on the
/// boundary of the unit square (a vertex inside another triangle's edge would leave that edge
/// with one face inside the square).
void checkConformingInUv(const PolygonMesh& mesh)
{
    std::map<std::pair<int, int>, int> incidence;
    double area = 0;
    for (int f = 0; f < mesh.faceCount(); ++f) {
        const int* v = mesh.face(f);
        const V2 a = mesh.texcoords.col(v[0]), b = mesh.texcoords.col(v[1]), c = mesh.texcoords.col(v[2]);
        const double twice = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
        REQUIRE(twice > 0);
        area += twice / 2;
        for (int k = 0; k < 3; ++k) ++incidence[{std::min(v[k], v[(k + 1) % 3]), std::max(v[k], v[(k + 1) % 3])}];
    }
    CHECK(area == Approx(1).epsilon(1e-12));
    long inside = 0;
    for (const auto& [e, n] : incidence) {
        REQUIRE(n <= 2);
        if (n == 2) continue;
        const V2 a = mesh.texcoords.col(e.first), b = mesh.texcoords.col(e.second);
        const bool onSide = (a.x() == 0 && b.x() == 0) || (a.x() == 1 && b.x() == 1) || (a.y() == 0 && b.y() == 0) ||
                            (a.y() == 1 && b.y() == 1);
        if (!onSide) ++inside;
    }
    CHECK(inside == 0);
}
} // namespace

TEST_CASE("local refinement: the bound holds on random patches of degrees 1-7", "[tessellate][local]")
{
    const std::array<int, 2> degrees[] = {{1, 1}, {1, 7}, {2, 3}, {3, 3}, {4, 2}, {5, 5}, {6, 4}, {7, 7}};
    std::uint32_t seed = 100;
    for (const auto& [m, n] : degrees) {
        ++seed;
        CAPTURE(m, n, seed);
        PointMatrix<double, 3> pts = test::randomPoints<double, 3>((m + 1) * (n + 1), seed, -0.25, 0.25);
        for (int i = 0; i <= m; ++i)
            for (int j = 0; j <= n; ++j) pts.col(i * (n + 1) + j) += V3(double(i) / m, double(j) / n, 0);
        const Patch patch(m, n, pts);
        const double tolerance = 2e-3;
        TessellationOptions o;
        o.tolerance = tolerance;
        TessellationReport report;
        const PolygonMesh mesh = tessellate(PatchComplex{{patch}}, o, &report);
        mesh.validate("random patch");
        CHECK(report.errorBound <= tolerance);
        // Both directions of the certificate, computed independently.
        const double meshToSurface = parametricDeviation(patch, mesh);
        CHECK(meshToSurface <= tolerance);
        CHECK(meshToSurface <= report.errorBound * (1 + 1e-9));
        CHECK(surfaceToMesh(patch, mesh, 60, 2 * tolerance) <= tolerance);
        checkConformingInUv(mesh);
        // Vertices and normals lie on the surface.
        for (int k = 0; k < mesh.vertexCount(); ++k) {
            const V2 uv = mesh.texcoords.col(k);
            CHECK((V3(mesh.positions.col(k)) - patch.evaluate(uv.x(), uv.y())).norm() < 1e-12);
            CHECK((V3(mesh.normals.col(k)) - patch.normal(uv.x(), uv.y())).norm() < 1e-9);
        }
        // Adaptive inside the patch: fewer triangles than the one grid the whole net's bound asks for
        // (except for a bilinear patch, whose one grid is already what it needs).
        const auto grid = adaptiveSegments(patch, tolerance);
        if (m > 1 || n > 1) CHECK(mesh.faceCount() < 2 * grid[0] * grid[1]);
    }
}

TEST_CASE("the geometric measure: every triangle point within the tolerance of the surface, fewer triangles",
          "[tessellate][local][geometric]")
{
    const std::array<int, 2> degrees[] = {{1, 2}, {2, 2}, {3, 3}, {4, 5}, {7, 3}};
    std::uint32_t seed = 300;
    for (const auto& [m, n] : degrees) {
        ++seed;
        CAPTURE(m, n, seed);
        PointMatrix<double, 3> pts = test::randomPoints<double, 3>((m + 1) * (n + 1), seed, -0.2, 0.2);
        for (int i = 0; i <= m; ++i)
            for (int j = 0; j <= n; ++j) pts.col(i * (n + 1) + j) += V3(double(i) / m, double(j) / n, 0);
        const Patch patch(m, n, pts);
        for (double tolerance : {1e-2, 1e-3}) {
            CAPTURE(tolerance);
            TessellationOptions o;
            o.tolerance = tolerance;
            o.measure = TessellationMeasure::Geometric;
            TessellationReport report;
            const PolygonMesh mesh = tessellate(PatchComplex{{patch}}, o, &report);
            CHECK(report.errorBound <= tolerance);
            CHECK(meshToSurface(patch, mesh) <= tolerance);
            checkConformingInUv(mesh);
            o.measure = TessellationMeasure::Parametric;
            CHECK(mesh.faceCount() <= tessellate(PatchComplex{{patch}}, o).faceCount());
        }
    }
    // Under the sanitizers (support/sanitizers.h) the teapot part is left out: the same code on 32
    // patches took about 20 s of ASan + UBSan, and "local refinement: the teapot at 1e-3" still
    // tessellates the teapot there. It runs in Release.
    if (test::underSanitizers) return;
    // The teapot: within the tolerance, tight within 2x, and the count under issue 15's goal of
    // 46,000 (43,166 when written, with the pointwise leaf bound; 52,564 with the bound from the
    // leaf's maxima and the whole patch's remainder; 56,070 before the side leaves' one-direction
    // bound).
    const PatchComplex teapot = readBpt(kTeapot);
    TessellationOptions o;
    o.tolerance = 1e-3;
    o.measure = TessellationMeasure::Geometric;
    o.sampleDeviation = true;
    TessellationReport report;
    const PolygonMesh mesh = tessellate(teapot, o, &report);
    CHECK(report.errorBound <= 1e-3);
    CHECK(report.measuredGeometric <= 1e-3);
    CHECK(report.measuredGeometric >= 0.5e-3);
    CHECK(mesh.faceCount() <= 46000);
    CHECK(topology(mesh).nonManifoldEdges == 0);
}

TEST_CASE("the geometric measure: the pointwise bound holds where the parametrisation is uneven", "[tessellate][local][geometric]")
{
    // Half cylinders of radius 1 whose control points bunch towards one side in u (rows at x = 0,
    // 0.05, 0.1, 1): the parametric error is mostly tangential there, so the geometric measure leaves
    // it out (the pointwise bound of docs/surfaces.md). Perturbed by random offsets; distances by
    // Gauss-Newton foot points from every triangle sample (tests/support/tessellation_checks.h).
    const double xs[4] = {0, 0.05, 0.1, 1};
    std::uint32_t seed = 700;
    for (int variant = 0; variant < 4; ++variant) {
        ++seed;
        CAPTURE(variant, seed);
        PointMatrix<double, 3> pts(3, 16);
        const PointMatrix<double, 3> noise = test::randomPoints<double, 3>(16, seed, -0.03, 0.03);
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) {
                // The rational-free cubic arc through (1, 0), (0, 1), (-1, 0): control points of a half circle.
                const double y[4] = {1, 1, -1, -1}, z[4] = {0, 4.0 / 3, 4.0 / 3, 0};
                pts.col(i * 4 + j) = V3(variant % 2 ? xs[i] : 1 - xs[3 - i], y[j], z[j]) + V3(noise.col(i * 4 + j));
            }
        const Patch patch = variant < 2 ? Patch(3, 3, pts) : Patch(3, 3, pts).transposed();
        for (double tolerance : {1e-3, 2e-4}) {
            // Under the sanitizers (support/sanitizers.h) 2e-4 does not run: its meshes have about
            // five times the triangles, and the foot-point search from every triangle sample took
            // 117 s of ASan + UBSan for the four variants (73 s with variant 0 alone). The same code
            // and checks run there at 1e-3 on all four variants; the full set runs in Release.
            if (test::underSanitizers && tolerance < 1e-3) continue;
            CAPTURE(tolerance);
            TessellationOptions o;
            o.tolerance = tolerance;
            o.measure = TessellationMeasure::Geometric;
            TessellationReport report;
            const PolygonMesh mesh = tessellate(PatchComplex{{patch}}, o, &report);
            CHECK(report.errorBound <= tolerance);
            const double distance = meshToSurface(patch, mesh);
            CHECK(distance <= tolerance);
            CHECK(distance <= report.errorBound * (1 + 1e-9));
            checkConformingInUv(mesh);
            o.measure = TessellationMeasure::Parametric;
            CHECK(mesh.faceCount() < tessellate(PatchComplex{{patch}}, o).faceCount());
        }
    }
}

TEST_CASE("local refinement: refines where the curvature is, not uniformly", "[tessellate][local]")
{
    // Flat except for a bump near the corner u = v = 0: (i, j, z) with z only at point (1, 1).
    PointMatrix<double, 3> pts(3, 16);
    for (int i = 0; i <= 3; ++i)
        for (int j = 0; j <= 3; ++j) pts.col(i * 4 + j) = V3(i / 3.0, j / 3.0, i == 1 && j == 1 ? 0.5 : 0);
    const Patch patch(3, 3, pts);
    TessellationOptions o;
    o.tolerance = 1e-4;
    const PolygonMesh mesh = tessellate(PatchComplex{{patch}}, o);
    checkConformingInUv(mesh);
    CHECK(parametricDeviation(patch, mesh) <= 1e-4);
    // More triangles in the quarter at the bump than in the far quarter (u, v > 1/2), where the
    // surface is z = 0.5 B_1(u) B_1(v): small but not zero.
    long nearBump = 0, far = 0;
    for (int f = 0; f < mesh.faceCount(); ++f) {
        V2 c = V2::Zero();
        for (int k = 0; k < 3; ++k) c += V2(mesh.texcoords.col(mesh.face(f)[k])) / 3;
        if (c.x() < 0.5 && c.y() < 0.5) ++nearBump;
        if (c.x() > 0.5 && c.y() > 0.5) ++far;
    }
    INFO("near the bump " << nearBump << ", far " << far);
    CHECK(nearBump > 3 * far); // one grid: equal counts
}

TEST_CASE("local refinement: the teapot at 1e-3", "[tessellate][local][teapot]")
{
    const PatchComplex teapot = readBpt(kTeapot);
    TessellationOptions o;
    o.tolerance = 1e-3;
    o.sampleDeviation = true;
    TessellationReport report;
    const PolygonMesh mesh = tessellate(teapot, o, &report);
    mesh.validate("teapot");
    CHECK(report.errorBound <= 1e-3);
    // Surface to mesh, 33 x 33 parameters per patch off any dyadic grid.
    const TriangleGrid tri(mesh, 0.05);
    double worst = 0;
    for (const Patch& p : teapot.patches)
        for (int i = 0; i <= 32; ++i)
            for (int j = 0; j <= 32; ++j) {
                const double u = std::fmod(i * 0.030901699 + 0.0071, 1.0), v = std::fmod(j * 0.0314159 + 0.0029, 1.0);
                worst = std::max(worst, tri.distance(p.evaluate(i == 32 ? 1.0 : u, j == 32 ? 1.0 : v), 1e-3));
            }
    INFO("worst surface-to-mesh distance " << worst);
    CHECK(worst <= 1e-3);
    // The bound is tight within 2x: triangle points 0.5e-3 and more from the surface exist.
    CHECK(report.measuredParametric <= report.errorBound);
    CHECK(report.measuredGeometric <= report.measuredParametric);
    CHECK(report.measuredGeometric >= 0.5e-3);
    const Topology t = topology(mesh);
    CHECK(t.nonManifoldEdges == 0);
    // Regression guard on the count with the parametric measure (83,570 when written, 83,566 with
    // ear clipping; one grid per patch: 161,144; the goal of 46,000 is met by the geometric
    // measure, above: docs/performance.md).
    CHECK(mesh.faceCount() <= 86000);
    TessellationOptions grid = o;
    grid.refinement = TessellationRefinement::PatchGrid;
    grid.sampleDeviation = false;
    CHECK(mesh.faceCount() * 1.9 < tessellate(teapot, grid).faceCount());
}

TEST_CASE("local refinement: a de Boor torus and a subdivision cage give closed meshes within the bound",
          "[tessellate][local][closed]")
{
    SECTION("closed x closed de Boor torus")
    {
        const PatchComplex t = torus(6, 5);
        for (double tolerance : {1e-2, 1e-3}) {
            TessellationOptions o;
            o.tolerance = tolerance;
            const PolygonMesh mesh = tessellate(t, o);
            const TriangleGrid tri(mesh, 0.25);
            const Topology top = topology(mesh);
            CHECK(top.boundaryEdges == 0);
            CHECK(top.nonManifoldEdges == 0);
            CHECK(top.euler() == 0);
            double worst = 0;
            for (const Patch& p : t.patches)
                for (int i = 0; i <= 16; ++i)
                    for (int j = 0; j <= 16; ++j)
                        worst = std::max(worst, tri.distance(p.evaluate(std::fmod(i * 0.0613 + 0.001, 1.0),
                                                                        std::fmod(j * 0.0587 + 0.002, 1.0)),
                                                             2 * tolerance));
            CHECK(worst <= tolerance);
            // The geometric measure (ear-clipped rings, other leaves) keeps it closed and of genus 1.
            o.measure = TessellationMeasure::Geometric;
            TessellationReport report;
            const Topology g = topology(tessellate(t, o, &report));
            CHECK(report.errorBound <= tolerance);
            CHECK(g.boundaryEdges == 0);
            CHECK(g.nonManifoldEdges == 0);
            CHECK(g.euler() == 0);
        }
    }
    SECTION("the Bézier patches of a regular Catmull-Clark torus cage")
    {
        const SubdivisionSurface s(readCage(std::string(FREEFORM_SOURCE_DIR) + "/data/cages/torus.obj"),
                                   SubdivisionScheme::Catmark);
        const PatchComplex patches = s.regularBezierPatches();
        REQUIRE(static_cast<int>(patches.patches.size()) == s.faceCount()); // every face regular
        TessellationOptions o;
        o.tolerance = 1e-3;
        const PolygonMesh mesh = tessellate(patches, o);
        const Topology top = topology(mesh);
        CHECK(top.boundaryEdges == 0);
        CHECK(top.nonManifoldEdges == 0);
        CHECK(top.euler() == 0);
        const TriangleGrid tri(mesh, 0.1);
        double worst = 0;
        for (const Patch& p : patches.patches)
            for (int i = 0; i <= 12; ++i)
                for (int j = 0; j <= 12; ++j)
                    worst = std::max(worst, tri.distance(p.evaluate(std::fmod(i * 0.0813 + 0.001, 1.0),
                                                                    std::fmod(j * 0.0787 + 0.002, 1.0)),
                                                         2e-3));
        CHECK(worst <= 1e-3);
    }
}

TEST_CASE("local refinement: no cracks or T-junctions where a flat and a curved patch meet", "[tessellate][local][cracks]")
{
    PointMatrix<double, 3> a(3, 16), b(3, 16);
    for (int i = 0; i <= 3; ++i)
        for (int j = 0; j <= 3; ++j) {
            const double y = j / 3.0, z = 0.05 * j * (3 - j);
            a.col(i * 4 + j) = V3(-1 + i / 3.0, y, z * (i / 3.0));
            b.col(i * 4 + j) = V3(i / 3.0, y, z + (i == 0 ? 0 : 3.0 * std::sin(2.0 * i + j)));
        }
    // B reversed in v, so the shared side runs opposite ways in the two patches.
    PointMatrix<double, 3> br(3, 16);
    for (int i = 0; i <= 3; ++i)
        for (int j = 0; j <= 3; ++j) br.col(i * 4 + j) = b.col(i * 4 + (3 - j));
    for (const auto& second : {b, br}) {
        const PatchComplex pair{{Patch(3, 3, a), Patch(3, 3, second)}};
        REQUIRE(sharedEdges(pair).size() == 1);
        TessellationOptions o;
        o.tolerance = 1e-3;
        const PolygonMesh mesh = tessellate(pair, o);
        const Topology top = topology(mesh);
        CHECK(top.nonManifoldEdges == 0);
        const auto shared = edgeCurve(pair.patches[0], PatchSide::U1);
        for (const auto& [p, q] : top.boundary) {
            const V3 mid = (V3(mesh.positions.col(p)) + V3(mesh.positions.col(q))) / 2;
            CHECK(shared.closestPoint(mid).distance > 1e-6);
        }
        CHECK(top.euler() == 1);
    }
}

TEST_CASE("maxTriangles: a huge patch is refused with the estimate, before the mesh is built", "[tessellate][limits]")
{
    PointMatrix<double, 3> pts = test::randomPoints<double, 3>(16, 7, -0.3, 0.3);
    for (int i = 0; i <= 3; ++i)
        for (int j = 0; j <= 3; ++j) pts.col(i * 4 + j) += V3(i / 3.0, j / 3.0, 0);
    const Patch huge(3, 3, 1e6 * pts); // a patch a million units large
    TessellationOptions o;
    o.tolerance = 1e-2;
    o.maxTriangles = 200000;
    CHECK_THROWS_WITH(tessellate(PatchComplex{{huge}}, o),
                      Catch::Contains("maxTriangles = 200000") && Catch::Contains("estimate") &&
                          Catch::Contains("--max-triangles"));
    // One grid per patch: the count is known before anything is built (default limit 10^7).
    o.maxTriangles = TessellationOptions{}.maxTriangles;
    o.refinement = TessellationRefinement::PatchGrid;
    CHECK_THROWS_WITH(tessellate(PatchComplex{{huge}}, o), Catch::Contains("33554432 triangles"));
    // Within the limit nothing changes; 0 means no limit; negative is an error.
    o.refinement = TessellationRefinement::Local;
    o.tolerance = 1e5;
    o.maxTriangles = 0;
    CHECK(tessellate(PatchComplex{{huge}}, o).faceCount() > 0);
    o.maxTriangles = -1;
    CHECK_THROWS_WITH(tessellate(PatchComplex{{huge}}, o), Catch::Contains("maxTriangles"));
}

TEST_CASE("per-patch tolerances: each patch within its own tolerance, the mesh still conforming", "[tessellate][local][per-patch]")
{
    const PatchComplex teapot = readBpt(kTeapot);
    const int count = static_cast<int>(teapot.patches.size());
    // 1e-3, 2e-3, 3e-3, 4e-3, 1e-3, ... (neighbours differ).
    std::vector<double> tolerances;
    for (int p = 0; p < count; ++p) tolerances.push_back(1e-3 * (1 + p % 4));
    // In a section of its own: Catch runs the test case's body once per section, and this part
    // (six teapot tessellations) ran again before each of the two sections below when it stood
    // outside them.
    SECTION("mixed tolerances: each patch within its own, between the uniform meshes")
    {
        for (const TessellationMeasure measure : {TessellationMeasure::Parametric, TessellationMeasure::Geometric}) {
            // Under the sanitizers (support/sanitizers.h) the geometric measure is left out here
            // (about 25 s of ASan + UBSan); it runs per patch in Release, and the geometric measure
            // runs under the sanitizers in the test cases above.
            if (test::underSanitizers && measure == TessellationMeasure::Geometric) continue;
            TessellationOptions o;
            o.tolerance = 1e-3;
            o.measure = measure;
            o.patchTolerance = tolerances;
            TessellationReport report;
            const PolygonMesh mesh = tessellate(teapot, o, &report);
            mesh.validate("teapot, per-patch tolerances");
            REQUIRE(report.patchBound.size() == tolerances.size());
            for (int p = 0; p < count; ++p) CHECK(report.patchBound[p] <= tolerances[p]);
            CHECK(report.worstRatio <= 1);
            const Topology t = topology(mesh);
            CHECK(t.nonManifoldEdges == 0);
            // Between the uniform meshes at the smallest and the largest tolerance.
            TessellationOptions fine = o, coarse = o;
            fine.patchTolerance.clear();
            coarse.patchTolerance.clear();
            coarse.tolerance = 4e-3;
            const int nFine = tessellate(teapot, fine).faceCount(), nCoarse = tessellate(teapot, coarse).faceCount();
            INFO("mixed " << mesh.faceCount() << ", all 1e-3 " << nFine << ", all 4e-3 " << nCoarse);
            CHECK(mesh.faceCount() < nFine);
            CHECK(mesh.faceCount() > nCoarse);
            if (measure == TessellationMeasure::Parametric) {
                // The parametric bound holds both ways: every surface point of patch p is within
                // tolerances[p] of the mesh (the nearest triangle may be a neighbour's: nearer still).
                const TriangleGrid grid(mesh, 0.02); // one grid for the 32 patches
                for (int p = 0; p < count; ++p) {
                    const double d = surfaceToMesh(teapot.patches[p], grid, 24, 2 * tolerances[p]);
                    INFO("patch " << p << " tolerance " << tolerances[p] << " surface to mesh " << d);
                    CHECK(d <= tolerances[p]);
                }
            }
        }
    }
    SECTION("the same tolerance for every patch is the one tolerance")
    {
        TessellationOptions one;
        one.tolerance = 2e-3;
        TessellationOptions each = one;
        each.tolerance = 0; // adaptive all the same: patchTolerance is given
        each.patchTolerance.assign(teapot.patches.size(), 2e-3);
        const PolygonMesh a = tessellate(teapot, one), b = tessellate(teapot, each);
        CHECK(a.faceVertices == b.faceVertices);
        CHECK(a.positions == b.positions);
    }
    SECTION("bad per-patch tolerances are refused, naming the field")
    {
        TessellationOptions o;
        o.tolerance = 1e-3;
        o.patchTolerance.assign(3, 1e-3);
        CHECK_THROWS_WITH(tessellate(teapot, o), Catch::Contains("patchTolerance has 3 entries for 32 patches"));
        o.patchTolerance.assign(teapot.patches.size(), 1e-3);
        o.patchTolerance[5] = 0;
        CHECK_THROWS_WITH(tessellate(teapot, o), Catch::Contains("patchTolerance[5]"));
    }
}

TEST_CASE("per-patch tolerances: a de Boor torus stays closed and of genus 1", "[tessellate][local][per-patch][closed]")
{
    const PatchComplex t = torus(6, 5);
    std::vector<double> tolerances;
    for (std::size_t p = 0; p < t.patches.size(); ++p) tolerances.push_back(p % 3 == 0 ? 1e-3 : 1e-2);
    for (const TessellationMeasure measure : {TessellationMeasure::Parametric, TessellationMeasure::Geometric}) {
        TessellationOptions o;
        o.tolerance = 1e-3;
        o.measure = measure;
        o.patchTolerance = tolerances;
        TessellationReport report;
        const PolygonMesh mesh = tessellate(t, o, &report);
        for (std::size_t p = 0; p < t.patches.size(); ++p) CHECK(report.patchBound[p] <= tolerances[p]);
        const Topology top = topology(mesh);
        CHECK(top.boundaryEdges == 0); // a crack or T-junction would leave edges with one face
        CHECK(top.nonManifoldEdges == 0);
        CHECK(top.euler() == 0);
        if (measure == TessellationMeasure::Parametric) {
            const TriangleGrid grid(mesh, 0.25);
            for (std::size_t p = 0; p < t.patches.size(); ++p) CHECK(surfaceToMesh(t.patches[p], grid, 16, 2 * tolerances[p]) <= tolerances[p]);
        }
    }
}

} // namespace test_tessellate_local
