// Certified tessellation of Catmull-Clark cages with the features that took the estimate path
// before (docs/subdivision.md, "Certified tessellation", "What is certified and what not"): holes,
// boundary interpolation `none`, `smoothtriangles`, and `edge_only` with a boundary vertex of one
// face. Checked as in test_subdivision_tessellation.cpp against an independent evaluation: OpenSubdiv
// Far's *uniform* refinement of the whole cage (with the same holes, boundary rule and triangle
// rule) to level 7 (level 6 for tolerance 1e-2) and its limit masks, which the library's adaptive path does not use.
//   - surface to mesh: every reference limit point of a face with a limit surface lies within the
//     bound of the mesh (exact limit points: no slack);
//   - mesh to surface: 10 points per triangle lie within the bound (plus the reference's own chord
//     error, measured from the level below) of the reference's triangles;
//   - every face is certified, the bound is within the tolerance;
//   - conforming: no edge with more than two triangles, no vertex inside another triangle's edge,
//     no two vertices at one place, the Euler characteristic of the expected surface.
// Also: every first-level stencil weight under `smoothtriangles` is non-negative (Far's
// StencilTableFactory), which the hull bound's convexity argument uses.

#include <catch2/catch.hpp>

#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/stencilTable.h>
#include <opensubdiv/far/stencilTableFactory.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "freeform/io/geometry_data.h"
#include "freeform/subdivision/subdivision_surface.h"
#include "support/subdivision_reference.h"
#include "support/tessellation_checks.h"

namespace test_subdivision_tessellation_features {

using namespace freeform;
using freeform::test::V3;

namespace {

namespace osd = OpenSubdiv::OPENSUBDIV_VERSION;
const std::string kCages = std::string(FREEFORM_SOURCE_DIR) + "/data/cages/";

/// OpenSubdiv's own topology of a Catmull-Clark cage, with every tag the library passes (holes,
/// boundary, triangle rule), built independently of the library.
std::unique_ptr<osd::Far::TopologyRefiner> refinerOf(const SubdivisionCage& cage, BoundaryInterpolation boundary)
{
    return test::farRefiner(cage, SubdivisionScheme::Catmark, boundary);
}

/// A 6 x 6 open grid with random heights (25 quads; its four corner vertices have one face each).
SubdivisionCage openGrid() { return test::wavyGrid(6, 6); }

/// The open grid with its centre quad (face 12) cut into two triangles: not all quads, so the
/// library works on the cage refined once, where holes and one-face corners must be carried.
SubdivisionCage gridWithTriangles()
{
    SubdivisionCage grid = openGrid();
    SubdivisionCage cage;
    cage.mesh.positions = grid.mesh.positions;
    for (int f = 0; f < grid.mesh.faceCount(); ++f) {
        const int* v = grid.mesh.face(f);
        if (f == 12) {
            cage.mesh.addFace({v[0], v[1], v[2]});
            cage.mesh.addFace({v[0], v[2], v[3]});
        } else {
            cage.mesh.addFace({v[0], v[1], v[2], v[3]});
        }
    }
    return cage;
}

/// A closed triangular prism: two triangles and three quads (the triangles' centres become
/// valence-3 vertices after the first refinement; the triangle rule acts there).
SubdivisionCage triangularPrism()
{
    SubdivisionCage cage;
    cage.mesh.positions.resize(3, 6);
    for (int k = 0; k < 3; ++k) {
        const double a = 2 * M_PI * k / 3;
        cage.mesh.positions.col(k) = V3(std::cos(a), std::sin(a), -0.7);
        cage.mesh.positions.col(k + 3) = V3(std::cos(a), std::sin(a), 0.7);
    }
    cage.mesh.addFace({2, 1, 0});
    cage.mesh.addFace({3, 4, 5});
    for (int k = 0; k < 3; ++k) cage.mesh.addFace({k, (k + 1) % 3, (k + 1) % 3 + 3, k + 3});
    return cage;
}

struct Case {
    std::string name;
    SubdivisionCage cage;
    BoundaryInterpolation boundary;
    double tol;
    long euler;        // of the limit surface's mesh
    int maxTriangles;  // regression guard: about 1.1 x the count measured when written
};

void checkCase(const Case& c)
{
    const SubdivisionSurface s(c.cage, SubdivisionScheme::Catmark, c.boundary);
    SubdivisionTessellationOptions o;
    o.tolerance = c.tol;
    SubdivisionTessellationReport report;
    const PolygonMesh mesh = s.tessellate(o, &report);
    // Level 7 at 1e-3, level 6 at 1e-2 (a quarter of the points; its own chord error, against the
    // next level, is still under a twentieth of the tolerance). The reference's grid has cells of
    // the tolerance; its chord error is searched within tol / 2 (first within tol / 16), the
    // deviation within 2 tol (first within tol / 4).
    const int level = c.tol < 5e-3 ? 7 : 6;
    const test::MeasuredReference ref(c.cage, SubdivisionScheme::Catmark, c.boundary, level, c.tol, c.tol / 16, c.tol / 2);
    const double slack = ref.slack;
    const test::Deviation d = test::deviation(mesh, ref.ref, ref.grid, c.tol / 4, 2 * c.tol, c.tol);
    int certified = 0, limitFaces = 0;
    for (char f : report.faceCertified) certified += f;
    for (int f = 0; f < s.faceCount(); ++f) limitFaces += s.hasLimitSurface(f) ? 1 : 0;
    std::printf("%-48s tol %.0e: %6d triangles, %6lld leaves, %5lld cells (%lld irregular, depth %d), bound %.3g, measured "
                "surface->mesh %.3g, mesh->surface %.3g, vertices off %.2g (reference level %d, slack %.2g), faces certified %d of %zu "
                "(%d with a limit surface)\n",
                c.name.c_str(), c.tol, mesh.faceCount(), report.leaves, report.cells, report.irregularCells, report.depth,
                report.errorBound, d.surfaceToMesh, d.meshToSurface, d.vertexOff, level, slack, certified, report.faceCertified.size(),
                limitFaces);
    CHECK(slack < c.tol / 20);
    REQUIRE(report.certifiedPath);
    CHECK(report.errorBound <= c.tol);
    CHECK(certified == s.faceCount());
    for (int f = 0; f < s.faceCount(); ++f)
        if (!s.hasLimitSurface(f)) CHECK(report.faceBounds[static_cast<std::size_t>(f)] == 0);
    // The bound holds both ways (surface to mesh against exact limit points, no slack).
    CHECK(d.surfaceToMesh <= report.errorBound);
    CHECK(d.meshToSurface <= report.errorBound + slack);
    CHECK(d.vertexOff <= slack);
    // Conforming: no non-manifold edge, no T-junction, each vertex once, the expected topology.
    const auto t = test::topology(mesh);
    CHECK(t.nonManifoldEdges == 0);
    CHECK(t.vertices == mesh.vertexCount());
    CHECK(t.euler() == c.euler);
    CHECK(test::tJunctions(mesh) == 0);
    CHECK(test::distinctPositions(mesh) == mesh.vertexCount());
    test::checkUnitNormals(mesh);
    CHECK(mesh.faceCount() <= c.maxTriangles);
}

} // namespace

TEST_CASE("certified tessellation with holes: the other faces as before, a boundary at the hole", "[subdivision][tessellation]")
{
    SubdivisionCage cube = readCage(kCages + "cube.obj");
    cube.holes = {2};
    // The cube without face 2: a disc (Euler 1); its five faces certified, the hole vacuously.
    checkCase({"cube, face 2 a hole", cube, BoundaryInterpolation::EdgeOnly, 1e-2, 1, 2160});
    // The faces next to the hole keep their limit surface: the mesh of the four others and the
    // top is the whole cube's mesh without the hole's triangles.
    const SubdivisionSurface whole(readCage(kCages + "cube.obj"), SubdivisionScheme::Catmark);
    const SubdivisionSurface holed(cube, SubdivisionScheme::Catmark);
    SubdivisionTessellationOptions o;
    o.tolerance = 1e-2;
    const PolygonMesh a = whole.tessellate(o), b = holed.tessellate(o);
    const test::TriangleGrid grid(a, 0.02);
    double off = 0;
    for (int v = 0; v < b.vertexCount(); ++v) off = std::max(off, grid.distance(b.positions.col(v), 0.01));
    CHECK(off < 1e-12); // every vertex of the holed mesh is a vertex of the whole cube's mesh
    CHECK(b.faceCount() < a.faceCount());

    // Not all quads: the holes reach the quad base as their level-1 children (the prism's bottom
    // triangle; a quad of the grid with triangles).
    SubdivisionCage prism = triangularPrism();
    prism.holes = {0};
    checkCase({"triangular prism, the bottom triangle a hole", prism, BoundaryInterpolation::EdgeOnly, 1e-2, 1, 1300});
    SubdivisionCage mixed = gridWithTriangles();
    mixed.holes = {7};
    checkCase({"grid with two triangles, one hole", mixed, BoundaryInterpolation::EdgeAndCorner, 1e-2, 0, 1730});
}

TEST_CASE("certified tessellation under boundary none: only faces away from the boundary", "[subdivision][tessellation]")
{
    // The 6 x 6 grid: the 16 faces touching the boundary have no limit surface, the 3 x 3 inside do.
    checkCase({"open grid, boundary none", openGrid(), BoundaryInterpolation::None, 1e-2, 1, 390});
    // Not all quads: the boundary faces' children stay holes in the quad base.
    checkCase({"grid with two triangles, boundary none", gridWithTriangles(), BoundaryInterpolation::None, 1e-2, 1, 1280});
}

TEST_CASE("certified tessellation with smoothtriangles", "[subdivision][tessellation]")
{
    SubdivisionCage prism = triangularPrism();
    prism.smoothTriangles = true;
    checkCase({"triangular prism, smoothtriangles", prism, BoundaryInterpolation::EdgeOnly, 1e-2, 2, 1670});
    SubdivisionCage octa = readCage(kCages + "octahedron.obj");
    octa.smoothTriangles = true;
    checkCase({"octahedron (Catmark), smoothtriangles", octa, BoundaryInterpolation::EdgeOnly, 1e-2, 2, 1800});
    // The two rules give different surfaces (so the reference above tells them apart).
    SubdivisionCage plain = triangularPrism();
    const SubdivisionSurface a(prism, SubdivisionScheme::Catmark), b(plain, SubdivisionScheme::Catmark);
    double diff = 0;
    for (int f = 0; f < 2; ++f) diff = std::max(diff, (a.evaluate(f, 0.3, 0.3).position - b.evaluate(f, 0.3, 0.3).position).norm());
    CHECK(diff > 1e-3);
}

TEST_CASE("smoothtriangles: every first-level stencil weight is non-negative and they sum to 1", "[subdivision][tessellation]")
{
    // The refinement from the cage to the quad base is the one place the triangle rule acts; its
    // weights, read from Far's stencil tables (not the library's code), are convex combinations.
    // Cages: triangles next to triangles, to quads, on a boundary, along a crease.
    SubdivisionCage prism = triangularPrism();
    prism.smoothTriangles = true;
    SubdivisionCage octa = readCage(kCages + "octahedron.obj");
    octa.smoothTriangles = true;
    SubdivisionCage open; // a triangle and a quad on one edge, both on the boundary
    open.mesh.positions.resize(3, 5);
    open.mesh.positions << 0, 1, 0.5, 0, 1, 0, 0, -0.8, 0, 0, 0, 0, 0.2, 1, 1.1;
    open.mesh.addFace({0, 2, 1});
    open.mesh.addFace({0, 1, 4, 3});
    open.smoothTriangles = true;
    SubdivisionCage creased = octa;
    creased.creases.push_back({creased.mesh.face(0)[0], creased.mesh.face(0)[1], 1.5});
    int cages = 0;
    for (const SubdivisionCage* cage : {&prism, &octa, &open, &creased}) {
        validateCage(*cage, SubdivisionScheme::Catmark);
        for (const int levels : {1, 3}) {
            auto refiner = refinerOf(*cage, BoundaryInterpolation::EdgeOnly);
            refiner->RefineUniform(osd::Far::TopologyRefiner::UniformOptions(levels));
            osd::Far::StencilTableFactoryReal<double>::Options so;
            so.generateIntermediateLevels = false;
            so.factorizeIntermediateLevels = true;
            std::unique_ptr<const osd::Far::StencilTableReal<double>> table(
                osd::Far::StencilTableFactoryReal<double>::Create(*refiner, so));
            REQUIRE(table);
            double least = 1, worstSum = 0;
            for (int i = 0; i < table->GetNumStencils(); ++i) {
                const auto st = table->GetStencil(i);
                double sum = 0;
                for (int k = 0; k < st.GetSize(); ++k) {
                    least = std::min(least, st.GetWeights()[k]);
                    sum += st.GetWeights()[k];
                }
                worstSum = std::max(worstSum, std::abs(sum - 1));
            }
            CHECK(table->GetNumStencils() == refiner->GetLevel(levels).GetNumVertices());
            CHECK(least >= 0);
            CHECK(worstSum < 1e-12);
            if (levels == 1) std::printf("smoothtriangles stencils, cage %d: least weight %.4g\n", cages, least);
        }
        ++cages;
    }
}

TEST_CASE("certified tessellation under edge_only with boundary vertices of one face", "[subdivision][tessellation]")
{
    // The 6 x 6 grid's four corners have one face each: OpenSubdiv's corner patch there misses the
    // limit surface (0.024 on this grid), so the cells whose 1-ring holds such a corner are bounded
    // by their hull and refined apart; the reference here is uniform refinement, right at corners.
    checkCase({"open grid, edge_only (four one-face corners)", openGrid(), BoundaryInterpolation::EdgeOnly, 1e-2, 1, 1580});
    // At 1e-3 (7,693 triangles, depth 10, bound 9.99e-4, measured 9.29e-4 / 9.34e-4 against level 7;
    // docs/subdivision.md) the case passes too; not run here, for the sanitizer build's time.
    // Not all quads (two triangles in the middle): the base is the cage refined once, and the four
    // corners' children there carry the mark.
    checkCase({"grid with two triangles, edge_only", gridWithTriangles(), BoundaryInterpolation::EdgeOnly, 1e-2, 1, 2510});
}

TEST_CASE("OpenSubdiv's corner patch under edge_only misses the limit at a one-face corner", "[subdivision][tessellation]")
{
    // Why such cells are never taken from the patch table: at the grid's corner vertex X = 0 (one
    // face, its two boundary edges sharp: the crease rule), the limit point is the crease limit mask
    // (A + 4 X + B) / 6 of X and its boundary neighbours; the patch table's patch of face 0 (depth 3)
    // evaluated at that corner, (u, v) = (0, 0), misses it by 1.9e-3 (float weights: 1e-6 noise).
    const SubdivisionCage cage = openGrid();
    auto refiner = refinerOf(cage, BoundaryInterpolation::EdgeOnly);
    osd::Far::TopologyRefiner::AdaptiveOptions adaptive(3);
    adaptive.useInfSharpPatch = true;
    refiner->RefineAdaptive(adaptive);
    osd::Far::PatchTableFactory::Options po(3);
    po.SetEndCapType(osd::Far::PatchTableFactory::Options::ENDCAP_BILINEAR_BASIS);
    po.useInfSharpPatch = true;
    std::unique_ptr<osd::Far::PatchTable> table(osd::Far::PatchTableFactory::Create(*refiner, po));
    REQUIRE(table);
    const std::vector<test::FarPoint> all = test::refinedPoints(*refiner, cage.mesh);
    const osd::Far::PatchMap map(*table);
    const osd::Far::PatchTable::PatchHandle* handle = map.FindPatch(0, 0.0, 0.0);
    REQUIRE(handle);
    float w[20];
    table->EvaluateBasis(*handle, 0.0f, 0.0f, w);
    const auto cvs = table->GetPatchVertices(*handle);
    V3 patch = V3::Zero();
    for (int k = 0; k < cvs.size(); ++k) patch += static_cast<double>(w[k]) * all[static_cast<std::size_t>(cvs[k])].vec();
    // The crease limit mask by hand: vertex 0's boundary neighbours are 1 and 6.
    const V3 X = cage.mesh.positions.col(0), A = cage.mesh.positions.col(1), B = cage.mesh.positions.col(6);
    const V3 limit = (A + 4 * X + B) / 6;
    // And the library's limit evaluation (Bfr) agrees with the hand mask.
    const SubdivisionSurface s(cage, SubdivisionScheme::Catmark, BoundaryInterpolation::EdgeOnly);
    CHECK((s.evaluate(0, 0, 0).position - limit).norm() < 1e-12);
    std::printf("edge_only corner: patch table %.4g off the limit point (vertex itself %.4g off)\n", (patch - limit).norm(),
                (X - limit).norm());
    CHECK((patch - limit).norm() > 1e-3);
}

} // namespace test_subdivision_tessellation_features
