#pragma once
// The independent reference of the subdivision tessellation tests (test_subdivision_tessellation*.cpp):
// OpenSubdiv Far's *uniform* refinement of the whole cage to level N, built here from the cage and
// its tags (not through the library), and its limit masks (PrimvarRefiner::Limit): exact limit
// points, joined as the level-N faces' triangles. The library's adaptive path (patch table, Bézier
// conversion, 1-ring hulls, welding; docs/subdivision.md) uses none of it. Also the measurements
// taken against it: the deviation both ways, the reference's own chord error, and the conformity
// checks (T-junctions, repeated positions, closedness, normals) of a tessellated mesh; and two
// cages more than one of those tests uses (a wavy open grid, a pentagonal prism).
// The tests that include this link OpenSubdiv's CPU library (tests/CMakeLists.txt).

#include <catch2/catch.hpp>

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <freeform/mesh/polygon_mesh.h>
#include <freeform/subdivision/subdivision_surface.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

#include "support/tessellation_checks.h"

namespace freeform::test {

namespace osd = OpenSubdiv::OPENSUBDIV_VERSION;

/// A point as Far's primvar refiner takes it (Clear, AddWithWeight), in double.
struct FarPoint {
    double p[3] = {0, 0, 0};
    void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0; }
    void AddWithWeight(const FarPoint& s, double w)
    {
        for (int k = 0; k < 3; ++k) p[k] += w * s.p[k];
    }
    V3 vec() const { return {p[0], p[1], p[2]}; }
};

/// The boundary rule a SubdivisionSurface of the cage uses by default: its tag, else edge_only.
inline BoundaryInterpolation boundaryOf(const SubdivisionCage& cage) { return cage.boundary.value_or(BoundaryInterpolation::EdgeOnly); }

/// An open nx x ny grid of quads (vertices 0.4 apart in x and y) with wavy heights
/// 0.3 sin(1.3 r + 0.7 c^2): boundary patches, and four corner vertices of one face each.
inline SubdivisionCage wavyGrid(int nx, int ny)
{
    SubdivisionCage cage;
    cage.mesh.positions.resize(3, nx * ny);
    for (int r = 0; r < nx; ++r)
        for (int c = 0; c < ny; ++c) cage.mesh.positions.col(r * ny + c) = V3(0.4 * r, 0.4 * c, 0.3 * std::sin(1.3 * r + 0.7 * c * c));
    for (int r = 0; r + 1 < nx; ++r)
        for (int c = 0; c + 1 < ny; ++c) cage.mesh.addFace({r * ny + c, (r + 1) * ny + c, (r + 1) * ny + c + 1, r * ny + c + 1});
    return cage;
}

/// A closed pentagonal prism (two pentagons, five quads; valence-5 extraordinary vertices at the
/// pentagons' centres after the first refinement), its x stretched by xScale.
inline SubdivisionCage pentagonalPrism(double xScale = 1)
{
    SubdivisionCage cage;
    cage.mesh.positions.resize(3, 10);
    for (int k = 0; k < 5; ++k) {
        const double a = 2 * M_PI * k / 5;
        cage.mesh.positions.col(k) = V3(xScale * std::cos(a), std::sin(a), -0.6);
        cage.mesh.positions.col(k + 5) = V3(xScale * std::cos(a), std::sin(a), 0.6);
    }
    cage.mesh.addFace({4, 3, 2, 1, 0});
    cage.mesh.addFace({5, 6, 7, 8, 9});
    for (int k = 0; k < 5; ++k) cage.mesh.addFace({k, (k + 1) % 5, (k + 1) % 5 + 5, k + 5});
    return cage;
}

/// OpenSubdiv's own refiner of the cage, with every tag the library passes: creases, corners,
/// holes, the boundary rule, the crease method (Chaikin) and the triangle rule (smoothtriangles,
/// Catmark only).
inline std::unique_ptr<osd::Far::TopologyRefiner> farRefiner(const SubdivisionCage& cage, SubdivisionScheme scheme,
                                                            BoundaryInterpolation boundary)
{
    std::vector<int> counts, pairs, corners;
    std::vector<float> creaseW, cornerW;
    for (int f = 0; f < cage.mesh.faceCount(); ++f) counts.push_back(cage.mesh.faceSize(f));
    for (const EdgeCrease& c : cage.creases) {
        pairs.insert(pairs.end(), {c.v0, c.v1});
        creaseW.push_back(static_cast<float>(c.sharpness));
    }
    for (const VertexCorner& c : cage.corners) {
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
    desc.numHoles = static_cast<int>(cage.holes.size());
    desc.holeIndices = cage.holes.data();
    osd::Sdc::Options sdc;
    sdc.SetVtxBoundaryInterpolation(boundary == BoundaryInterpolation::EdgeAndCorner ? osd::Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER
                                    : boundary == BoundaryInterpolation::None        ? osd::Sdc::Options::VTX_BOUNDARY_NONE
                                                                                     : osd::Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
    sdc.SetCreasingMethod(cage.chaikin ? osd::Sdc::Options::CREASE_CHAIKIN : osd::Sdc::Options::CREASE_UNIFORM);
    sdc.SetTriangleSubdivision(cage.smoothTriangles ? osd::Sdc::Options::TRI_SUB_SMOOTH : osd::Sdc::Options::TRI_SUB_CATMARK);
    using Factory = osd::Far::TopologyRefinerFactory<osd::Far::TopologyDescriptor>;
    std::unique_ptr<osd::Far::TopologyRefiner> refiner(Factory::Create(
        desc, Factory::Options(scheme == SubdivisionScheme::Loop ? osd::Sdc::SCHEME_LOOP : osd::Sdc::SCHEME_CATMARK, sdc)));
    REQUIRE(refiner);
    return refiner;
}

/// The points of every level of a refined refiner (level 0 the mesh's positions, then each level's
/// vertices in order), by Far's PrimvarRefiner in double.
inline std::vector<FarPoint> refinedPoints(const osd::Far::TopologyRefiner& refiner, const PolygonMesh& mesh)
{
    std::vector<FarPoint> all(static_cast<std::size_t>(refiner.GetNumVerticesTotal()));
    for (int v = 0; v < mesh.vertexCount(); ++v)
        for (int k = 0; k < 3; ++k) all[static_cast<std::size_t>(v)].p[k] = mesh.positions(k, v);
    const osd::Far::PrimvarRefinerReal<double> primvar(refiner);
    FarPoint* src = all.data();
    for (int l = 1; l <= refiner.GetMaxLevel(); ++l) {
        FarPoint* dst = src + refiner.GetLevel(l - 1).GetNumVertices();
        primvar.Interpolate(l, src, dst);
        src = dst;
    }
    return all;
}

/// The reference: the exact limit points of the uniform level-N refinement of the faces that have
/// a limit surface (not holes), and all level-N limit points joined as those faces' triangles
/// (each level-N face cut as a fan from its first vertex: quads in two, triangles kept).
struct Reference {
    std::vector<V3> points;
    PolygonMesh mesh;
};

inline Reference reference(const SubdivisionCage& cage, SubdivisionScheme scheme, BoundaryInterpolation boundary, int level)
{
    auto refiner = farRefiner(cage, scheme, boundary);
    osd::Far::TopologyRefiner::UniformOptions uniform(level);
    uniform.fullTopologyInLastLevel = true;
    refiner->RefineUniform(uniform);
    const std::vector<FarPoint> all = refinedPoints(*refiner, cage.mesh);
    const osd::Far::TopologyLevel& last = refiner->GetLevel(level);
    const FarPoint* src = all.data() + (all.size() - static_cast<std::size_t>(last.GetNumVertices()));
    std::vector<FarPoint> limit(static_cast<std::size_t>(last.GetNumVertices()));
    osd::Far::PrimvarRefinerReal<double>(*refiner).Limit(src, limit);
    Reference r;
    r.mesh.positions.resize(3, last.GetNumVertices());
    std::vector<char> used(static_cast<std::size_t>(last.GetNumVertices()), 0);
    for (int v = 0; v < last.GetNumVertices(); ++v) r.mesh.positions.col(v) = limit[static_cast<std::size_t>(v)].vec();
    for (int f = 0; f < last.GetNumFaces(); ++f) {
        if (last.IsFaceHole(f)) continue; // no limit surface
        const auto fv = last.GetFaceVertices(f);
        for (int k = 1; k + 1 < fv.size(); ++k) r.mesh.addFace({fv[0], fv[k], fv[k + 1]});
        for (int k = 0; k < fv.size(); ++k) used[static_cast<std::size_t>(fv[k])] = 1;
    }
    for (int v = 0; v < last.GetNumVertices(); ++v)
        if (used[static_cast<std::size_t>(v)]) r.points.push_back(r.mesh.positions.col(v));
    return r;
}

/// The grid's distance from p to its nearest triangle within radius (infinity, or a distance past
/// radius, when none is that near): first searched within `near` (a triangle nearer than that
/// meets the searched box, so a hit there is the nearest), then, only when nothing is that near,
/// within the whole radius. Equal to grid.distance(p, radius); faster when most points are near
/// and the grid holds many triangles per searched cell.
inline double nearest(const TriangleGrid& grid, const V3& p, double near, double radius)
{
    const double small = std::min(near, radius);
    const double d = grid.distance(p, small);
    return d <= small ? d : grid.distance(p, radius);
}

/// The reference triangles' own distance to the limit surface, estimated at the centroids of a
/// coarser reference's triangles against a finer one's (fineGrid, a TriangleGrid of its mesh): the
/// slack of the mesh-to-surface and vertex checks (chords shrink with the level). Searched within
/// radius, first within near (see nearest).
inline double referenceError(const Reference& coarse, const TriangleGrid& fineGrid, double near, double radius)
{
    double worst = 0;
    for (int f = 0; f < coarse.mesh.faceCount(); ++f) {
        const int* t = coarse.mesh.face(f);
        const V3 c = (V3(coarse.mesh.positions.col(t[0])) + V3(coarse.mesh.positions.col(t[1])) + V3(coarse.mesh.positions.col(t[2]))) / 3;
        worst = std::max(worst, nearest(fineGrid, c, near, radius));
    }
    return worst;
}

/// A level-N reference kept for several measurements: a grid of its triangles (cell: the grid's
/// cell) and its own chord error, `slack`, measured from level N - 1 (referenceError within
/// slackRadius, first within slackNear). The grid refers to the reference's mesh: built in place,
/// never copied or moved.
struct MeasuredReference {
    Reference ref;
    TriangleGrid grid;
    double slack;
    MeasuredReference(const SubdivisionCage& cage, SubdivisionScheme scheme, BoundaryInterpolation boundary, int level, double cell,
                      double slackNear, double slackRadius)
        : ref(reference(cage, scheme, boundary, level)),
          grid(ref.mesh, cell),
          slack(referenceError(reference(cage, scheme, boundary, level - 1), grid, slackNear, slackRadius))
    {
    }
    MeasuredReference(const MeasuredReference&) = delete;
    MeasuredReference& operator=(const MeasuredReference&) = delete;
};

/// A tessellated mesh's deviation from the reference:
///   - surfaceToMesh: from every reference limit point to the mesh (exact points: no slack);
///   - meshToSurface: from the points (i, j, k) / 4 of every triangle but its corners to the
///     reference's triangles;
///   - vertexOff: from every mesh vertex to the reference's triangles.
/// Distances past radius come back as infinity (or past radius) and fail every bound below it.
/// refGrid: a TriangleGrid of ref.mesh; near: the first search's radius (nearest); meshCell: the
/// cell of the mesh's grid. The cells and near change the time taken, never a distance within radius.
struct Deviation {
    double surfaceToMesh = 0, meshToSurface = 0, vertexOff = 0;
};

inline Deviation deviation(const PolygonMesh& mesh, const Reference& ref, const TriangleGrid& refGrid, double near, double radius,
                           double meshCell)
{
    Deviation d;
    const TriangleGrid meshGrid(mesh, meshCell);
    for (const V3& p : ref.points) d.surfaceToMesh = std::max(d.surfaceToMesh, nearest(meshGrid, p, near, radius));
    for (int v = 0; v < mesh.vertexCount(); ++v) d.vertexOff = std::max(d.vertexOff, nearest(refGrid, mesh.positions.col(v), near, radius));
    for (int f = 0; f < mesh.faceCount(); ++f) {
        const int* t = mesh.face(f);
        const V3 a = mesh.positions.col(t[0]), b = mesh.positions.col(t[1]), c = mesh.positions.col(t[2]);
        for (int i = 0; i <= 4; ++i)
            for (int j = 0; i + j <= 4; ++j) {
                if (i == 4 || j == 4 || i + j == 0) continue; // the corners are vertices
                const double x = i / 4.0, y = j / 4.0;
                d.meshToSurface = std::max(d.meshToSurface, nearest(refGrid, x * a + y * b + (1 - x - y) * c, near, radius));
            }
    }
    return d;
}

/// The number of (edge, vertex) pairs with the vertex strictly inside the edge (within
/// 1e-12 max(1, length) of it): every edge checked. The vertices are bucketed in cubes of about the
/// mean edge length; each edge looks at the buckets its bounding box (grown by that tolerance)
/// meets, which hold every vertex that near it.
inline long tJunctions(const PolygonMesh& mesh)
{
    std::vector<std::pair<int, int>> edges;
    for (int f = 0; f < mesh.faceCount(); ++f)
        for (int k = 0; k < mesh.faceSize(f); ++k) {
            const int a = mesh.face(f)[k], b = mesh.face(f)[(k + 1) % mesh.faceSize(f)];
            edges.emplace_back(std::min(a, b), std::max(a, b));
        }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    if (edges.empty()) return 0;
    Eigen::AlignedBox3d bounds;
    for (int v = 0; v < mesh.vertexCount(); ++v) bounds.extend(V3(mesh.positions.col(v)));
    double total = 0;
    for (const auto& [a, b] : edges) total += (V3(mesh.positions.col(a)) - V3(mesh.positions.col(b))).norm();
    // At most 2^20 cubes a side: the packed key below never collides.
    const double cell = std::max({total / static_cast<double>(edges.size()), bounds.diagonal().maxCoeff() / 1e6, 1e-300});
    const V3 origin = bounds.min() - V3::Constant(cell);
    auto index = [&](const V3& p) {
        const V3 q = ((p - origin) / cell).array().floor().matrix();
        return std::array<std::int64_t, 3>{static_cast<std::int64_t>(q.x()), static_cast<std::int64_t>(q.y()), static_cast<std::int64_t>(q.z())};
    };
    auto key = [](std::int64_t x, std::int64_t y, std::int64_t z) { return (x << 42) | (y << 21) | z; };
    std::unordered_map<std::int64_t, std::vector<int>> buckets;
    for (int v = 0; v < mesh.vertexCount(); ++v) {
        const auto i = index(mesh.positions.col(v));
        buckets[key(i[0], i[1], i[2])].push_back(v);
    }
    long found = 0;
    for (const auto& [ia, ib] : edges) {
        const V3 a = mesh.positions.col(ia), b = mesh.positions.col(ib);
        const double len = (b - a).norm(), eps = 1e-12 * std::max(1.0, len);
        const auto lo = index(a.cwiseMin(b) - V3::Constant(eps)), hi = index(a.cwiseMax(b) + V3::Constant(eps));
        for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
            for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
                for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
                    const auto it = buckets.find(key(x, y, z));
                    if (it == buckets.end()) continue;
                    for (int v : it->second) {
                        if (v == ia || v == ib) continue;
                        const V3 p = mesh.positions.col(v);
                        const double t = (p - a).dot(b - a) / (len * len);
                        if (t > 0 && t < 1 && (a + t * (b - a) - p).norm() <= eps) ++found;
                    }
                }
    }
    return found;
}

/// The number of distinct vertex positions (equal to the vertex count when no two vertices are at
/// one place).
inline long distinctPositions(const PolygonMesh& mesh)
{
    std::map<std::array<double, 3>, int> at;
    for (int v = 0; v < mesh.vertexCount(); ++v) at[{mesh.positions(0, v), mesh.positions(1, v), mesh.positions(2, v)}]++;
    return static_cast<long>(at.size());
}

/// Closed and genus 0: no boundary or non-manifold edge, Euler characteristic 2, every vertex used.
inline void checkClosed(const PolygonMesh& mesh)
{
    const auto t = topology(mesh);
    CHECK(t.boundaryEdges == 0);
    CHECK(t.nonManifoldEdges == 0);
    CHECK(t.euler() == 2);
    CHECK(t.vertices == mesh.vertexCount()); // no unused vertex
}

/// One unit normal per vertex.
inline void checkUnitNormals(const PolygonMesh& mesh)
{
    CHECK(mesh.normals.cols() == mesh.vertexCount());
    for (int v = 0; v < mesh.normals.cols(); ++v) CHECK(std::abs(mesh.normals.col(v).norm() - 1) < 1e-9);
}

/// Unit normals, on the side of the triangles' own normals (counter-clockwise from outside): every
/// triangle's at the vertex for a smooth surface; on a sharp crease a vertex has one normal, the
/// limit normal of one side, so there it must agree with at least one of its triangles (creased).
inline void checkNormals(const PolygonMesh& mesh, bool creased)
{
    checkUnitNormals(mesh);
    if (mesh.normals.cols() != mesh.vertexCount()) return; // failed above
    std::vector<double> best(static_cast<std::size_t>(mesh.vertexCount()), -2.0), worst(best.size(), 2.0);
    for (int f = 0; f < mesh.faceCount(); ++f) {
        const int* t = mesh.face(f);
        const V3 a = mesh.positions.col(t[0]), b = mesh.positions.col(t[1]), c = mesh.positions.col(t[2]);
        const V3 n = (b - a).cross(c - a).normalized();
        for (int k = 0; k < 3; ++k) {
            const double d = n.dot(V3(mesh.normals.col(t[k])));
            best[static_cast<std::size_t>(t[k])] = std::max(best[static_cast<std::size_t>(t[k])], d);
            worst[static_cast<std::size_t>(t[k])] = std::min(worst[static_cast<std::size_t>(t[k])], d);
        }
    }
    int against = 0;
    for (std::size_t v = 0; v < best.size(); ++v)
        if ((creased ? best[v] : worst[v]) <= 0) ++against;
    CHECK(against == 0);
}

} // namespace freeform::test
