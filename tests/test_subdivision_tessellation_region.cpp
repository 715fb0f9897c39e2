// A tolerance per region on the certified subdivision path (SubdivisionTessellationOptions::
// toleranceOf; docs/subdivision.md, "A tolerance per region"), checked against an independent
// evaluation of the limit surface: OpenSubdiv Far's *uniform* refinement of the whole cage and its
// limit masks (as tests/test_subdivision_tessellation.cpp does).
//
// The region tolerance grows with x, as a pixel grows with depth: tolAt(box) = t0 (1 + 2 (xmin - x0))
// for the box's smallest x. A cell's own tolerance is min(tolerance, tolAt(its box)); its box holds
// its part of the limit surface, so every limit point p of the cell has tolAt(cell) <= tolAt({p}).
// The facts checked:
//   - every reference limit point lies within tolAt({p}) of the mesh, and 10 points per triangle
//     within tolAt({q}) (+ the reference's own chord error) of the reference surface: each cell
//     stays within its own tolerance, and no cell got more than its region asked;
//   - every face is certified within its leaves' own tolerances, and the report's smallest
//     tolerance per face is the region's at the face's near side or less;
//   - the far half of a long cage gets fewer triangles than the near half, and the whole fewer than
//     with the near tolerance everywhere;
//   - a toleranceOf never below the tolerance changes nothing (the same mesh, bit for bit);
//   - conforming: closed cages stay closed with Euler characteristic 2, no vertex inside an edge.

#include <catch2/catch.hpp>

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <unordered_map>

#include "freeform/io/geometry_data.h"
#include "freeform/subdivision/subdivision_surface.h"
#include "support/tessellation_checks.h"

using namespace freeform;
using freeform::test::V3;

namespace {

namespace osd = OpenSubdiv::OPENSUBDIV_VERSION;
const std::string kCages = std::string(FREEFORM_SOURCE_DIR) + "/data/cages/";

struct P3 {
    double p[3] = {0, 0, 0};
    void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0; }
    void AddWithWeight(const P3& s, double w)
    {
        for (int k = 0; k < 3; ++k) p[k] += w * s.p[k];
    }
};

/// Limit points of the uniform level-N refinement, and those points joined as triangles.
struct Reference {
    std::vector<V3> points;
    PolygonMesh mesh;
};

Reference reference(const SubdivisionCage& cage, SubdivisionScheme scheme, int level)
{
    std::vector<int> counts, pairs, corners;
    std::vector<float> creaseW, cornerW;
    for (int f = 0; f < cage.mesh.faceCount(); ++f) counts.push_back(cage.mesh.faceSize(f));
    for (const auto& c : cage.creases) {
        pairs.insert(pairs.end(), {c.v0, c.v1});
        creaseW.push_back(static_cast<float>(c.sharpness));
    }
    for (const auto& c : cage.corners) {
        corners.push_back(c.vertex);
        cornerW.push_back(static_cast<float>(c.sharpness));
    }
    osd::Far::TopologyDescriptor desc;
    desc.numVertices = cage.mesh.vertexCount();
    desc.numFaces = static_cast<int>(counts.size());
    desc.numVertsPerFace = counts.data();
    desc.vertIndicesPerFace = cage.mesh.faceVertices.data();
    desc.numCreases = static_cast<int>(creaseW.size());
    desc.creaseVertexIndexPairs = pairs.data();
    desc.creaseWeights = creaseW.data();
    desc.numCorners = static_cast<int>(cornerW.size());
    desc.cornerVertexIndices = corners.data();
    desc.cornerWeights = cornerW.data();
    osd::Sdc::Options sdc;
    sdc.SetVtxBoundaryInterpolation(cage.boundary == BoundaryInterpolation::EdgeAndCorner ? osd::Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER
                                                                                          : osd::Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
    using Factory = osd::Far::TopologyRefinerFactory<osd::Far::TopologyDescriptor>;
    std::unique_ptr<osd::Far::TopologyRefiner> refiner(Factory::Create(
        desc, Factory::Options(scheme == SubdivisionScheme::Loop ? osd::Sdc::SCHEME_LOOP : osd::Sdc::SCHEME_CATMARK, sdc)));
    REQUIRE(refiner);
    osd::Far::TopologyRefiner::UniformOptions uniform(level);
    uniform.fullTopologyInLastLevel = true;
    refiner->RefineUniform(uniform);
    std::vector<P3> buffer(static_cast<std::size_t>(refiner->GetNumVerticesTotal()));
    for (int v = 0; v < cage.mesh.vertexCount(); ++v)
        for (int k = 0; k < 3; ++k) buffer[static_cast<std::size_t>(v)].p[k] = cage.mesh.positions(k, v);
    const osd::Far::PrimvarRefinerReal<double> primvar(*refiner);
    P3* src = buffer.data();
    for (int l = 1; l <= level; ++l) {
        P3* dst = src + refiner->GetLevel(l - 1).GetNumVertices();
        primvar.Interpolate(l, src, dst);
        src = dst;
    }
    const osd::Far::TopologyLevel& last = refiner->GetLevel(level);
    std::vector<P3> limit(static_cast<std::size_t>(last.GetNumVertices()));
    primvar.Limit(src, limit);
    Reference r;
    r.mesh.positions.resize(3, last.GetNumVertices());
    for (int v = 0; v < last.GetNumVertices(); ++v) {
        const V3 p(limit[static_cast<std::size_t>(v)].p[0], limit[static_cast<std::size_t>(v)].p[1], limit[static_cast<std::size_t>(v)].p[2]);
        r.points.push_back(p);
        r.mesh.positions.col(v) = p;
    }
    for (int f = 0; f < last.GetNumFaces(); ++f) {
        const auto fv = last.GetFaceVertices(f);
        r.mesh.addFace({fv[0], fv[1], fv[2]});
        if (fv.size() == 4) r.mesh.addFace({fv[0], fv[2], fv[3]});
    }
    return r;
}

/// The region tolerance: t0 at x0, growing linearly with the box's smallest x (a pixel's size
/// grows with depth the same way).
struct Region {
    double t0 = 1e-3, x0 = 0;
    double operator()(const Eigen::AlignedBox3d& box) const { return t0 * (1 + 2 * std::max(0.0, box.min().x() - x0)); }
    double at(const V3& p) const { return (*this)(Eigen::AlignedBox3d(p, p)); }
};

/// The worst ratio of a sampled deviation to the region's tolerance at the sample: surface to
/// mesh (reference limit points, exact: no slack) and mesh to surface (10 points per triangle,
/// with the reference's own chord error `slack` added to the allowance).
struct Ratios {
    double surfaceToMesh = 0, meshToSurface = 0;
};

Ratios ratios(const PolygonMesh& mesh, const Reference& ref, const Region& region, double slack, double radius)
{
    Ratios r;
    const test::TriangleGrid meshGrid(mesh, 0.05);
    for (const V3& p : ref.points) r.surfaceToMesh = std::max(r.surfaceToMesh, meshGrid.distance(p, radius) / region.at(p));
    const test::TriangleGrid refGrid(ref.mesh, 0.05);
    for (int f = 0; f < mesh.faceCount(); ++f) {
        const int* t = mesh.face(f);
        const V3 a = mesh.positions.col(t[0]), b = mesh.positions.col(t[1]), c = mesh.positions.col(t[2]);
        for (int i = 0; i <= 4; ++i)
            for (int j = 0; i + j <= 4; ++j) {
                const double x = i / 4.0, y = j / 4.0;
                const V3 q = x * a + y * b + (1 - x - y) * c;
                r.meshToSurface = std::max(r.meshToSurface, refGrid.distance(q, radius) / (region.at(q) + slack));
            }
    }
    return r;
}

/// The reference triangles' distance to the limit surface, estimated at their centroids against
/// the next level's triangles.
double referenceError(const Reference& coarse, const Reference& fine)
{
    const test::TriangleGrid grid(fine.mesh, 0.05);
    double worst = 0;
    for (int f = 0; f < coarse.mesh.faceCount(); ++f) {
        const int* t = coarse.mesh.face(f);
        const V3 c = (V3(coarse.mesh.positions.col(t[0])) + V3(coarse.mesh.positions.col(t[1])) + V3(coarse.mesh.positions.col(t[2]))) / 3;
        worst = std::max(worst, grid.distance(c, 0.05));
    }
    return worst;
}

/// Vertices lying inside another edge (every edge, vertices bucketed).
long tJunctions(const PolygonMesh& mesh)
{
    std::map<std::pair<int, int>, int> edges;
    for (int f = 0; f < mesh.faceCount(); ++f)
        for (int k = 0; k < 3; ++k) {
            const int a = mesh.face(f)[k], b = mesh.face(f)[(k + 1) % 3];
            edges[{std::min(a, b), std::max(a, b)}]++;
        }
    std::unordered_map<long, std::vector<int>> buckets;
    double cell = 0; // the longest edge: every vertex inside an edge is in a bucket next to its midpoint's
    for (const auto& [e, n] : edges) cell = std::max(cell, (V3(mesh.positions.col(e.first)) - V3(mesh.positions.col(e.second))).norm());
    auto key = [&](const V3& p) {
        return (static_cast<long>(std::floor(p.x() / cell)) + 512) * 1048576 + (static_cast<long>(std::floor(p.y() / cell)) + 512) * 1024 +
               (static_cast<long>(std::floor(p.z() / cell)) + 512);
    };
    for (int v = 0; v < mesh.vertexCount(); ++v) buckets[key(mesh.positions.col(v))].push_back(v);
    long found = 0;
    for (const auto& [e, n] : edges) {
        const V3 a = mesh.positions.col(e.first), b = mesh.positions.col(e.second);
        const double len = (b - a).norm();
        const V3 m = (a + b) / 2;
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    const auto it = buckets.find(key(m + cell * V3(dx, dy, dz)));
                    if (it == buckets.end()) continue;
                    for (int v : it->second) {
                        if (v == e.first || v == e.second) continue;
                        const V3 p = mesh.positions.col(v);
                        const double t = (p - a).dot(b - a) / (len * len);
                        if (t <= 0 || t >= 1) continue;
                        if ((a + t * (b - a) - p).norm() <= 1e-12 * std::max(1.0, len)) ++found;
                    }
                }
    }
    return found;
}

/// A long wavy open grid along x (17 x 3 quads, x in [0, 6.8]) under edge_and_corner.
SubdivisionCage longGrid()
{
    SubdivisionCage cage;
    const int nx = 18, ny = 4;
    cage.mesh.positions.resize(3, nx * ny);
    for (int r = 0; r < nx; ++r)
        for (int c = 0; c < ny; ++c) cage.mesh.positions.col(r * ny + c) = V3(0.4 * r, 0.4 * c, 0.3 * std::sin(1.3 * r + 0.7 * c * c));
    for (int r = 0; r + 1 < nx; ++r)
        for (int c = 0; c + 1 < ny; ++c) cage.mesh.addFace({r * ny + c, (r + 1) * ny + c, (r + 1) * ny + c + 1, r * ny + c + 1});
    cage.boundary = BoundaryInterpolation::EdgeAndCorner;
    return cage;
}

/// A pentagonal prism stretched along x (valence-5 extraordinary vertices: irregular cells).
SubdivisionCage longPrism()
{
    SubdivisionCage cage;
    cage.mesh.positions.resize(3, 10);
    for (int k = 0; k < 5; ++k) {
        const double a = 2 * M_PI * k / 5;
        cage.mesh.positions.col(k) = V3(3 * std::cos(a), std::sin(a), -0.6);
        cage.mesh.positions.col(k + 5) = V3(3 * std::cos(a), std::sin(a), 0.6);
    }
    cage.mesh.addFace({4, 3, 2, 1, 0});
    cage.mesh.addFace({5, 6, 7, 8, 9});
    for (int k = 0; k < 5; ++k) cage.mesh.addFace({k, (k + 1) % 5, (k + 1) % 5 + 5, k + 5});
    return cage;
}

double minX(const PolygonMesh& m) { return m.positions.row(0).minCoeff(); }

} // namespace

TEST_CASE("a tolerance per region: every cell within its own tolerance, far parts coarser", "[subdivision][tessellation]")
{
    struct Case {
        std::string name;
        SubdivisionCage cage;
        SubdivisionScheme scheme;
        bool closed;
        int level; // of the reference
    };
    SubdivisionCage octahedron = readCage(kCages + "octahedron.obj");
    octahedron.mesh.positions.row(0) *= 3;
    const std::vector<Case> cases = {
        {"long open grid (Catmull-Clark, regular cells)", longGrid(), SubdivisionScheme::Catmark, false, 6},
        {"long pentagonal prism (Catmull-Clark, valence-5 cells)", longPrism(), SubdivisionScheme::Catmark, true, 7},
        {"long octahedron (Loop)", octahedron, SubdivisionScheme::Loop, true, 7},
    };
    for (const Case& c : cases)
        DYNAMIC_SECTION(c.name)
        {
            const SubdivisionSurface surface(c.cage, c.scheme, c.cage.boundary.value_or(BoundaryInterpolation::EdgeOnly));
            const Region region{1e-3, minX(c.cage.mesh)};
            SubdivisionTessellationOptions o;
            o.tolerance = 1; // the region's tolerance is always the smaller here
            o.toleranceOf = region;
            SubdivisionTessellationReport report;
            const PolygonMesh mesh = surface.tessellate(o, &report);

            const Reference ref = reference(c.cage, c.scheme, c.level);
            const double slack = referenceError(reference(c.cage, c.scheme, c.level - 1), ref);
            const Ratios r = ratios(mesh, ref, region, slack, 0.03); // deviations stay under 0.013 here; none found within 0.03 reads as infinity and fails

            // The near tolerance everywhere, for comparison.
            SubdivisionTessellationOptions near;
            near.tolerance = region.t0;
            const PolygonMesh uniformMesh = surface.tessellate(near);

            const double mid = (mesh.positions.row(0).minCoeff() + mesh.positions.row(0).maxCoeff()) / 2;
            int nearHalf = 0, farHalf = 0;
            for (int f = 0; f < mesh.faceCount(); ++f) {
                const int* t = mesh.face(f);
                const double x = (mesh.positions(0, t[0]) + mesh.positions(0, t[1]) + mesh.positions(0, t[2])) / 3;
                (x < mid ? nearHalf : farHalf)++;
            }
            std::printf("%-55s %6d triangles (near half %d, far half %d; %d at the near tolerance everywhere), bound %.3g, "
                        "worst sampled/own tolerance: surface->mesh %.3f, mesh->surface %.3f (slack %.2g)\n",
                        c.name.c_str(), mesh.faceCount(), nearHalf, farHalf, uniformMesh.faceCount(), report.errorBound, r.surfaceToMesh,
                        r.meshToSurface, slack);
            CHECK(report.certifiedPath);
            CHECK(r.surfaceToMesh <= 1.0);
            CHECK(r.meshToSurface <= 1.0);
            int certified = 0;
            for (char f : report.faceCertified) certified += f;
            CHECK(certified == static_cast<int>(report.faceCertified.size()));
            // The report's per-face tolerance: at most the region's at the face's near side (the
            // cells' boxes hold the face's limit surface) and never above the tolerance.
            REQUIRE(report.faceTolerance.size() == static_cast<std::size_t>(c.cage.mesh.faceCount()));
            for (int f = 0; f < c.cage.mesh.faceCount(); ++f) {
                // A cell of the face holds its limit point at (0, 0), so its box reaches that x.
                REQUIRE(surface.inDomain(f, 0, 0));
                const V3 corner = surface.evaluate(f, 0, 0).position;
                CHECK(report.faceTolerance[static_cast<std::size_t>(f)] <= region.at(corner) * (1 + 1e-12));
                CHECK(report.faceTolerance[static_cast<std::size_t>(f)] >= region.t0 * (1 - 1e-12));
                CHECK(report.faceBounds[static_cast<std::size_t>(f)] <= o.tolerance);
            }
            CHECK(report.errorBound <= region(Eigen::AlignedBox3d(V3(1e9, 0, 0), V3(1e9, 0, 0))));
            // Fewer triangles far away than near, and fewer than the near tolerance everywhere.
            CHECK(farHalf < nearHalf);
            CHECK(mesh.faceCount() < uniformMesh.faceCount());
            if (c.closed) {
                const auto t = test::topology(mesh);
                CHECK(t.boundaryEdges == 0);
                CHECK(t.nonManifoldEdges == 0);
                CHECK(t.euler() == 2);
            }
            CHECK(tJunctions(mesh) == 0);
        }
}

TEST_CASE("a tolerance per region never below the tolerance changes nothing", "[subdivision][tessellation]")
{
    SubdivisionCage octahedron = readCage(kCages + "octahedron.obj");
    for (const auto& [cage, scheme] : {std::pair{longPrism(), SubdivisionScheme::Catmark}, std::pair{octahedron, SubdivisionScheme::Loop}}) {
        const SubdivisionSurface surface(cage, scheme);
        SubdivisionTessellationOptions o;
        o.tolerance = 3e-3;
        SubdivisionTessellationReport plainReport, regionReport;
        const PolygonMesh plain = surface.tessellate(o, &plainReport);
        int calls = 0;
        o.toleranceOf = [&](const Eigen::AlignedBox3d& box) {
            ++calls;
            return 3e-3 * (1 + box.min().x() * box.min().x());
        };
        const PolygonMesh region = surface.tessellate(o, &regionReport);
        CHECK(calls > 0);
        CHECK(plain.faceVertices == region.faceVertices);
        CHECK(plain.positions == region.positions);
        CHECK(plainReport.errorBound == regionReport.errorBound);
        for (double t : regionReport.faceTolerance) CHECK(t == 3e-3);
    }
}

TEST_CASE("a tolerance per region: a non-positive region tolerance is an Error", "[subdivision][tessellation]")
{
    const SubdivisionSurface surface(longPrism(), SubdivisionScheme::Catmark);
    SubdivisionTessellationOptions o;
    o.tolerance = 1e-2;
    o.toleranceOf = [](const Eigen::AlignedBox3d&) { return 0.0; };
    CHECK_THROWS_AS(surface.tessellate(o), Error);
}
