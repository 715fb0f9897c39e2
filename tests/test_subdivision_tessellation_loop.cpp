// Certified tessellation of Loop limit surfaces (SubdivisionSurface::tessellate with a tolerance on
// a closed triangle cage; docs/subdivision.md, "Loop cages"), checked against independent
// computations:
//   - the regular Loop patch's Bézier form (loopPatchToBezier) against OpenSubdiv's own patch
//     evaluation (Far::PatchTable::EvaluateBasis) at random parameters, rotated cells included;
//   - the triangle net bound (triangleNetErrorBound): exact on s^2, and never exceeded by the
//     linear interpolation error on random sub-triangles of random nets;
//   - the meshes against OpenSubdiv Far's *uniform* Loop refinement of the whole cage to level 7
//     and its limit masks (exact limit points; the library's adaptive path is not used): surface to
//     mesh and mesh to surface within the reported bound, certified at 1e-2 and 1e-3 (the
//     icosahedron at 1e-3 through local cages past depth 10), closed, Euler characteristic 2, no
//     T-junction, unit outward normals; triangle counts guarded;
//   - cages with features (open under edge_only, edge_and_corner and none, a hole, infinitely sharp
//     and semi-sharp creases and corners, Chaikin) against the same kind of reference built by Far
//     with the cage's own tags and boundary rule: the bound both ways, every face certified,
//     conforming, closed cages closed; and OpenSubdiv's own per-level stencils for those cages have
//     no negative weight (the hull bound's premise, docs/subdivision.md "Loop cages").

#include <catch2/catch.hpp>

#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTable.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/stencilTableFactory.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <random>

#include "freeform/io/geometry_data.h"
#include "freeform/subdivision/loop_bezier.h"
#include "freeform/subdivision/subdivision_surface.h"
#include "support/sanitizers.h"
#include "support/subdivision_reference.h"
#include "support/tessellation_checks.h"

namespace test_subdivision_tessellation_loop {

using namespace freeform;
using freeform::test::V3;

namespace {

namespace osd = OpenSubdiv::OPENSUBDIV_VERSION;
const std::string kCages = std::string(FREEFORM_SOURCE_DIR) + "/data/cages/";

SubdivisionCage cageOf(const PolygonMesh& mesh)
{
    SubdivisionCage cage;
    cage.mesh = mesh;
    return cage;
}

/// OpenSubdiv's own refiner of a Loop cage with its creases, corners, holes and boundary rule,
/// built here from the cage (not through the library).
std::unique_ptr<osd::Far::TopologyRefiner> loopRefiner(const SubdivisionCage& cage,
                                                       BoundaryInterpolation boundary = BoundaryInterpolation::EdgeOnly)
{
    return test::farRefiner(cage, SubdivisionScheme::Loop, boundary);
}

/// The reference grid's cell, and the distance searches' first radius (test::nearest): the dense
/// grids hold many triangles per searched cell.
constexpr double kCell = 0.02, kNear = 0.004;

/// A triangle cage from vertices and faces, each face turned to run counter-clockwise seen from
/// outside (the cages are convex around the origin).
PolygonMesh convexCage(const std::vector<V3>& points, const std::vector<std::array<int, 3>>& faces)
{
    PolygonMesh m;
    m.positions.resize(3, static_cast<Eigen::Index>(points.size()));
    for (std::size_t i = 0; i < points.size(); ++i) m.positions.col(static_cast<Eigen::Index>(i)) = points[i];
    for (auto f : faces) {
        const V3 a = points[static_cast<std::size_t>(f[0])], b = points[static_cast<std::size_t>(f[1])], c = points[static_cast<std::size_t>(f[2])];
        if ((b - a).cross(c - a).dot(a + b + c) < 0) std::swap(f[1], f[2]);
        m.addFace({f[0], f[1], f[2]});
    }
    return m;
}

PolygonMesh tetrahedron()
{
    return convexCage({V3(1, 1, 1), V3(1, -1, -1), V3(-1, 1, -1), V3(-1, -1, 1)}, {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}});
}

PolygonMesh icosahedron()
{
    const double g = (1 + std::sqrt(5.0)) / 2;
    std::vector<V3> p;
    for (int s1 : {-1, 1})
        for (int s2 : {-1, 1}) {
            p.emplace_back(0, s1, s2 * g);
            p.emplace_back(s1, s2 * g, 0);
            p.emplace_back(s2 * g, 0, s1);
        }
    // Faces: the 20 triples of mutually adjacent vertices (edge length 2).
    std::vector<std::array<int, 3>> faces;
    auto adjacent = [&](int i, int j) { return std::abs((p[static_cast<std::size_t>(i)] - p[static_cast<std::size_t>(j)]).norm() - 2) < 1e-9; };
    for (int i = 0; i < 12; ++i)
        for (int j = i + 1; j < 12; ++j)
            for (int k = j + 1; k < 12; ++k)
                if (adjacent(i, j) && adjacent(j, k) && adjacent(i, k)) faces.push_back({i, j, k});
    REQUIRE(faces.size() == 20);
    return convexCage(p, faces);
}

} // namespace

TEST_CASE("Loop patch to Bézier: equals OpenSubdiv's Loop patch evaluation", "[subdivision][tessellation][loop]")
{
    // A triangulated 8 x 8 grid with random heights: interior vertices have valence 6 except four
    // around the one square cut the other way, so faces away from them are regular Loop patches at
    // depth 0, and the adaptive refinement around them gives regular patches at depths 1 and 2,
    // some of them rotated.
    const int n = 8;
    std::mt19937 rng(15);
    std::uniform_real_distribution<double> h(-0.3, 0.3), unit(0, 1);
    PolygonMesh grid;
    grid.positions.resize(3, (n + 1) * (n + 1));
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) grid.positions.col(i * (n + 1) + j) = V3(0.3 * j + 0.05 * h(rng), 0.3 * i, h(rng));
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const int a = i * (n + 1) + j, b = a + 1, c = a + n + 1, d = c + 1;
            if (i == n / 2 && j == n / 2) { // the other diagonal: two valence-5 and two valence-7 vertices
                grid.addFace({a, b, c});
                grid.addFace({b, d, c});
            } else {
                grid.addFace({a, b, d});
                grid.addFace({a, d, c});
            }
        }
    auto refiner = loopRefiner(cageOf(grid));
    refiner->RefineAdaptive(osd::Far::TopologyRefiner::AdaptiveOptions(3));
    osd::Far::PatchTableFactory::Options po(3);
    po.SetEndCapType(osd::Far::PatchTableFactory::Options::ENDCAP_BILINEAR_BASIS);
    std::unique_ptr<osd::Far::PatchTable> table(osd::Far::PatchTableFactory::Create(*refiner, po));
    REQUIRE(table);
    const std::vector<test::FarPoint> all = test::refinedPoints(*refiner, grid);
    const osd::Far::PatchMap map(*table);
    int tested = 0, rotated = 0;
    double worst = 0;
    for (int array = 0; array < table->GetNumPatchArrays(); ++array) {
        if (table->GetPatchArrayDescriptor(array).GetType() != osd::Far::PatchDescriptor::LOOP) continue;
        for (int patch = 0; patch < table->GetNumPatches(array); ++patch) {
            const osd::Far::PatchParam param = table->GetPatchParam(array, patch);
            if (param.GetBoundary() != 0) continue;
            const auto cvs = table->GetPatchVertices(array, patch);
            std::array<V3, 12> points;
            for (int c = 0; c < 12; ++c) points[static_cast<std::size_t>(c)] = all[static_cast<std::size_t>(cvs[c])].vec();
            const QuarticTriangleNet net = loopPatchToBezier(points);
            ++tested;
            rotated += param.IsTriangleRotated() ? 1 : 0;
            for (int sample = 0; sample < 20; ++sample) {
                // A random point of the cell in its own (s, t), and the face's (u, v) of it.
                double s = unit(rng), t = unit(rng);
                if (s + t > 1) s = 1 - s, t = 1 - t;
                double u = s, v = t;
                param.UnnormalizeTriangle(u, v);
                const osd::Far::PatchTable::PatchHandle* handle = map.FindPatch(param.GetFaceId(), u, v);
                REQUIRE(handle);
                double w[12];
                table->EvaluateBasis(*handle, u, v, w);
                const auto hcvs = table->GetPatchVertices(*handle);
                V3 expected = V3::Zero();
                for (int c = 0; c < hcvs.size(); ++c) expected += w[c] * all[static_cast<std::size_t>(hcvs[c])].vec();
                worst = std::max(worst, (evaluateTriangleNet(net, s, t) - expected).norm());
            }
        }
    }
    std::printf("Loop -> Bézier: %d regular patches (%d rotated), worst difference %.3g\n", tested, rotated, worst);
    CHECK(tested > 40);
    CHECK(rotated > 0);
    CHECK(worst < 1e-12);
}

TEST_CASE("triangle net bound: exact on s^2, never exceeded on random sub-triangles", "[subdivision][tessellation][loop]")
{
    auto net = [](auto f) {
        QuarticTriangleNet b;
        for (int j = 0; j <= 4; ++j)
            for (int k = 0; k <= 4 - j; ++k) b[static_cast<std::size_t>(bezierIndex(j, k))] = f(j, k);
        return b;
    };
    // (s, t, s^2): s^2's Bézier ordinates of degree 4 are C(j, 2) / C(4, 2) = j (j - 1) / 12. The
    // linear interpolant of the corners is (s, t, s), which misses s^2 by s - s^2, 1/4 at s = 1/2.
    const QuarticTriangleNet parabola = net([](int j, int k) { return V3(j / 4.0, k / 4.0, j * (j - 1) / 12.0); });
    CHECK(evaluateTriangleNet(parabola, 0.3, 0.5).z() == Approx(0.09).margin(1e-15));
    CHECK(triangleNetErrorBound(parabola) == Approx(0.25).margin(1e-15));

    std::mt19937 rng(7);
    std::uniform_real_distribution<double> coord(-1, 1), unit(0, 1);
    auto point = [&]() {
        double s = unit(rng), t = unit(rng);
        if (s + t > 1) s = 1 - s, t = 1 - t;
        return Eigen::Vector2d(s, t);
    };
    double worstRatio = 0;
    for (int trial = 0; trial < 200; ++trial) {
        const QuarticTriangleNet b = net([&](int, int) { return V3(coord(rng), coord(rng), coord(rng)); });
        const double bound = triangleNetErrorBound(b);
        for (int tri = 0; tri < 20; ++tri) {
            // The whole triangle first, then random triangles with vertices in it.
            std::array<Eigen::Vector2d, 3> x{Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0), Eigen::Vector2d(0, 1)};
            if (tri > 0) x = {point(), point(), point()};
            std::array<V3, 3> f;
            for (int i = 0; i < 3; ++i) f[static_cast<std::size_t>(i)] = evaluateTriangleNet(b, x[static_cast<std::size_t>(i)].x(), x[static_cast<std::size_t>(i)].y());
            for (int sample = 0; sample < 30; ++sample) {
                double l1 = unit(rng), l2 = unit(rng);
                if (l1 + l2 > 1) l1 = 1 - l1, l2 = 1 - l2;
                const double l0 = 1 - l1 - l2;
                const Eigen::Vector2d y = l0 * x[0] + l1 * x[1] + l2 * x[2];
                const double err = (l0 * f[0] + l1 * f[1] + l2 * f[2] - evaluateTriangleNet(b, y.x(), y.y())).norm();
                worstRatio = std::max(worstRatio, err / bound);
            }
        }
    }
    std::printf("triangle net bound: worst sampled error / bound %.3f\n", worstRatio);
    CHECK(worstRatio <= 1.0);
    CHECK(worstRatio > 0.05); // the bound is not vacuous (and exact on s^2 above)
}

TEST_CASE("certified Loop tessellation: the bound holds both ways and the mesh is closed", "[subdivision][tessellation][loop]")
{
    struct Case {
        std::string name;
        PolygonMesh cage;
        int maxTriangles[2]; // regression guard at 1e-2, 1e-3: about 1.1 x the counts measured when written
    };
    const std::vector<Case> cases = {
        {"tetrahedron (valence 3)", tetrahedron(), {1180, 10130}},
        {"octahedron (valence 4)", readCage(kCages + "octahedron.obj").mesh, {1890, 11440}},
        {"icosahedron (valence 5)", icosahedron(), {6690, 31110}},
    };
    // The references, their grids and slacks (level 6 against 7, centroids searched within 0.01),
    // built once per cage (Catch runs this body once per section).
    static std::map<std::string, test::MeasuredReference> references;
    for (const Case& c : cases)
        for (int ti = 0; ti < 2; ++ti) {
            const double tol = ti == 0 ? 1e-2 : 1e-3;
            // Under the sanitizers (support/sanitizers.h) 1e-3 runs on the octahedron only: the
            // tetrahedron's and the icosahedron's at 1e-3 took 26 s and more of ASan + UBSan each.
            // All three cages run at 1e-2 there, and every case runs in Release.
            if (test::underSanitizers && ti == 1 && c.name.rfind("octahedron", 0) != 0) continue;
            DYNAMIC_SECTION(c.name << " at " << tol)
            {
                const SubdivisionCage cage = cageOf(c.cage);
                const test::MeasuredReference& ref =
                    references.try_emplace(c.name, cage, SubdivisionScheme::Loop, BoundaryInterpolation::EdgeOnly, 7, kCell, kNear, 0.01)
                        .first->second;
                const double slack = ref.slack;
                const SubdivisionSurface s(cage, SubdivisionScheme::Loop);
                SubdivisionTessellationOptions o;
                o.tolerance = tol;
                SubdivisionTessellationReport report;
                const PolygonMesh mesh = s.tessellate(o, &report);
                const test::Deviation d = test::deviation(mesh, ref.ref, ref.grid, kNear, 4 * tol, kCell);
                int certified = 0;
                for (char f : report.faceCertified) certified += f;
                std::printf("%-26s tol %.0e: %7d triangles, %6lld leaves, %5lld cells (%lld irregular, depth %d), bound %.3g, "
                            "measured surface->mesh %.3g, mesh->surface %.3g, vertices off %.2g (reference slack %.2g), "
                            "faces certified %d of %zu\n",
                            c.name.c_str(), tol, mesh.faceCount(), report.leaves, report.cells, report.irregularCells, report.depth,
                            report.errorBound, d.surfaceToMesh, d.meshToSurface, d.vertexOff, slack, certified,
                            report.faceCertified.size());
                CHECK(slack < 1e-4);
                CHECK(report.certifiedPath);
                REQUIRE(report.faceCertified.size() == static_cast<std::size_t>(c.cage.faceCount()));
                REQUIRE(report.faceBounds.size() == static_cast<std::size_t>(c.cage.faceCount()));
                for (int f = 0; f < c.cage.faceCount(); ++f)
                    CHECK((report.faceCertified[static_cast<std::size_t>(f)] != 0) == (report.faceBounds[static_cast<std::size_t>(f)] <= tol));
                // The measured deviation never exceeds the certified bound (reference slack < 1e-4).
                CHECK(d.surfaceToMesh <= report.errorBound);
                CHECK(d.meshToSurface <= report.errorBound + slack);
                CHECK(d.vertexOff <= slack);
                if (ti == 0) CHECK(certified == c.cage.faceCount());
                // Certified at 1e-3 as well, the icosahedron's valence-5 cells through local cages past
                // depth 10 (docs/subdivision.md, "Deeper than level 10").
                CHECK(certified == c.cage.faceCount());
                CHECK(report.errorBound <= tol);
                // Only the icosahedron at 1e-3 needs cells past OpenSubdiv's level 10.
                CHECK((report.depth > 10) == (ti == 1 && c.name.rfind("icosahedron", 0) == 0));
                // Closed, genus 0, every vertex used.
                test::checkClosed(mesh);
                CHECK(test::tJunctions(mesh) == 0);
                // Unit normals, on the side of every triangle at the vertex, and outward (the limit
                // surfaces of these cages are convex around the origin).
                test::checkNormals(mesh, false);
                int inward = 0;
                for (int v = 0; v < mesh.vertexCount() && v < mesh.normals.cols(); ++v) inward += mesh.normals.col(v).dot(mesh.positions.col(v)) > 0 ? 0 : 1;
                CHECK(inward == 0);
                CHECK(mesh.faceCount() <= c.maxTriangles[ti]);
            }
        }
}

namespace {

/// A fan of six triangles around a raised centre, radius r (an open cage: one boundary loop, the
/// centre regular).
PolygonMesh fan(double r = 1)
{
    PolygonMesh m;
    m.positions.resize(3, 7);
    m.positions.col(0) = V3(0, 0, 0.5 * r);
    for (int k = 0; k < 6; ++k) m.positions.col(k + 1) = r * V3(std::cos(k * M_PI / 3), std::sin(k * M_PI / 3), 0);
    for (int k = 0; k < 6; ++k) m.addFace({0, k + 1, (k + 1) % 6 + 1});
    return m;
}

/// An n x n grid of squares of side h, each cut into two triangles along the same diagonal, the
/// points raised by a bump: corners (0, 0) and (n, n) have two faces, (n, 0) and (0, n) one (a
/// corner under edge_and_corner).
PolygonMesh grid(int n, double h)
{
    PolygonMesh m;
    const int w = n + 1;
    m.positions.resize(3, w * w);
    for (int j = 0; j < w; ++j)
        for (int i = 0; i < w; ++i) {
            const double x = i - n / 2.0, y = j - n / 2.0;
            m.positions.col(w * j + i) = h * V3(x, y, 0.6 * std::exp(-(x * x + y * y)) * (1 + 0.2 * x));
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const int a = w * j + i;
            m.addFace({a, a + 1, a + w + 1});
            m.addFace({a, a + w + 1, a + w});
        }
    return m;
}

/// The number of weights below zero in OpenSubdiv's per-level stencils (each level from the one
/// before, not factorised) of the cage's uniform refinement to `levels`, and the largest
/// |sum - 1| of a stencil's weights.
std::pair<long, double> negativeStencilWeights(const SubdivisionCage& cage, BoundaryInterpolation boundary, int levels)
{
    auto refiner = loopRefiner(cage, boundary);
    refiner->RefineUniform(osd::Far::TopologyRefiner::UniformOptions(levels));
    using StencilFactory = osd::Far::StencilTableFactoryReal<double>;
    StencilFactory::Options o;
    o.generateIntermediateLevels = true;
    o.factorizeIntermediateLevels = false;
    o.generateOffsets = true;
    std::unique_ptr<const osd::Far::StencilTableReal<double>> table(StencilFactory::Create(*refiner, o));
    REQUIRE(table);
    long negative = 0;
    double sumOff = 0;
    for (int i = 0; i < table->GetNumStencils(); ++i) {
        const auto st = table->GetStencil(i);
        double sum = 0;
        for (int k = 0; k < st.GetSize(); ++k) {
            negative += st.GetWeights()[k] < 0 ? 1 : 0;
            sum += st.GetWeights()[k];
        }
        sumOff = std::max(sumOff, std::abs(sum - 1));
    }
    return {negative, sumOff};
}

} // namespace

TEST_CASE("certified Loop tessellation: boundaries, holes, creases and corners", "[subdivision][tessellation][loop]")
{
    struct Case {
        std::string name;
        SubdivisionCage cage;
        BoundaryInterpolation boundary;
        long boundaryLoops; // of the mesh
        int maxTriangles;   // regression guard at 1e-2: about 1.1 x the count measured when written
        int level = 7;      // of the reference (the small open cages: 6, as dense for their size)
    };
    std::vector<Case> cases;
    {
        SubdivisionCage c;
        // Small cages: a boundary's cells are bounded to first order, so its triangles grow with its
        // length over the tolerance (test time under ASan).
        c.mesh = fan(0.5);
        cases.push_back({"open fan, edge_only", c, BoundaryInterpolation::EdgeOnly, 1, 5770, 6});
        c.mesh = grid(2, 0.5);
        cases.push_back({"open grid, edge_only", c, BoundaryInterpolation::EdgeOnly, 1, 7620, 6});
        cases.push_back({"open grid, edge_and_corner", c, BoundaryInterpolation::EdgeAndCorner, 1, 7620, 6});
        // Boundary none: only the two faces of the middle square (no boundary vertex) have a limit surface.
        c.mesh = grid(3, 1.0);
        cases.push_back({"open 3 x 3 grid, none", c, BoundaryInterpolation::None, 1, 36});
        // Octahedron vertices: 0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z.
        c.mesh = readCage(kCages + "octahedron.obj").mesh;
        SubdivisionCage holed = c;
        holed.holes = {0};
        cases.push_back({"octahedron with a hole", holed, BoundaryInterpolation::EdgeOnly, 1, 1650});
        SubdivisionCage sharp = c;
        sharp.creases = {{0, 2, 10}, {2, 1, 10}}; // half the equator, infinitely sharp, ending at two darts
        sharp.corners = {{4, 10}};                                         // the top, an infinitely sharp corner
        cases.push_back({"octahedron, sharp half equator and corner", sharp, BoundaryInterpolation::EdgeOnly, 0, 9550});
        SubdivisionCage semi = c;
        semi.creases = {{0, 2, 2}, {2, 1, 1.5}, {1, 3, 0.5}}; // integer and fractional, Chaikin
        semi.corners = {{5, 0.7}};
        semi.chaikin = true;
        cases.push_back({"octahedron, semi-sharp, Chaikin", semi, BoundaryInterpolation::EdgeOnly, 0, 2100});
    }
    const double tol = 1e-2;
    for (const Case& c : cases)
        DYNAMIC_SECTION(c.name)
        {
            // Every refinement weight of these cages' rules is >= 0 (the hull bound's premise).
            const auto [negative, sumOff] = negativeStencilWeights(c.cage, c.boundary, 4);
            CHECK(negative == 0);
            CHECK(sumOff < 1e-12);

            const test::MeasuredReference ref(c.cage, SubdivisionScheme::Loop, c.boundary, c.level, kCell, kNear, 0.01);
            const double slack = ref.slack;
            const SubdivisionSurface s(c.cage, SubdivisionScheme::Loop, c.boundary);
            SubdivisionTessellationOptions o;
            o.tolerance = tol;
            SubdivisionTessellationReport report;
            const PolygonMesh mesh = s.tessellate(o, &report);
            const test::Deviation d = test::deviation(mesh, ref.ref, ref.grid, kNear, 4 * tol, kCell);
            int certified = 0;
            for (char f : report.faceCertified) certified += f;
            const auto t = test::topology(mesh);
            std::printf("%-36s tol %.0e: %7d triangles, %6lld leaves, %5lld cells (%lld irregular, depth %d), bound %.3g, "
                        "measured surface->mesh %.3g, mesh->surface %.3g, vertices off %.2g (reference slack %.2g), "
                        "faces certified %d of %zu, boundary edges %ld, euler %ld\n",
                        c.name.c_str(), tol, mesh.faceCount(), report.leaves, report.cells, report.irregularCells, report.depth,
                        report.errorBound, d.surfaceToMesh, d.meshToSurface, d.vertexOff, slack, certified, report.faceCertified.size(),
                        t.boundaryEdges, t.euler());
            CHECK(slack < 1e-3);
            CHECK(report.certifiedPath);
            CHECK(certified == c.cage.mesh.faceCount());
            CHECK(report.errorBound <= tol);
            CHECK(report.errorBound > 0);
            CHECK(d.surfaceToMesh <= report.errorBound);
            CHECK(d.meshToSurface <= report.errorBound + slack);
            CHECK(d.vertexOff <= slack);
            // Conforming: no edge of three faces, no vertex inside another edge; boundary edges only
            // where the surface has a boundary (Euler characteristic 2 - loops for these spheres and discs).
            CHECK(t.nonManifoldEdges == 0);
            CHECK(test::tJunctions(mesh) == 0);
            CHECK((t.boundaryEdges == 0) == (c.boundaryLoops == 0));
            CHECK(t.euler() == 2 - c.boundaryLoops);
            CHECK(t.vertices == mesh.vertexCount());
            test::checkUnitNormals(mesh);
            CHECK(mesh.faceCount() <= c.maxTriangles);
        }
}

TEST_CASE("Loop tessellation with certified = false keeps the estimate and says so", "[subdivision][tessellation][loop]")
{
    // Formerly: open cages kept the estimate. Every Loop cage is certified now; the estimate path
    // stays reachable by asking for it.
    SubdivisionCage cage;
    cage.mesh = fan();
    const SubdivisionSurface s(cage, SubdivisionScheme::Loop);
    SubdivisionTessellationOptions o;
    o.tolerance = 1e-2;
    o.certified = false;
    SubdivisionTessellationReport report;
    const PolygonMesh m = s.tessellate(o, &report);
    CHECK_FALSE(report.certifiedPath);
    CHECK(report.faceCertified.empty());
    CHECK(m.faceCount() > 0);
}

} // namespace test_subdivision_tessellation_loop
