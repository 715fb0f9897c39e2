#pragma once
// What the certified tessellations of Catmull-Clark cages (certified_tessellation.cpp) and of Loop
// cages (certified_tessellation_loop.cpp) share, and the cage adapter they share with
// subdivision_surface.cpp (docs/subdivision.md, "Certified tessellation", "Loop cages"). Private to
// src/subdivision/ (never installed); everything is inline so that the hot loops stay inlined.

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "freeform/core/error.h"
#include "freeform/subdivision/subdivision_surface.h"
#include "../mesh/convex_ring.h"
#include "osd_errors.h"

namespace freeform {

namespace osd = OpenSubdiv::OPENSUBDIV_VERSION;

namespace detail {

using Index = osd::Far::Index;
using Int = std::int64_t;
using UV = std::array<Int, 2>; // a dyadic point (u, v) of a face: integers over kR

constexpr int kResolutionBits = 40;           // dyadic parameters are integers over 2^40
constexpr Int kR = Int(1) << kResolutionBits; // the face's side
constexpr int kOsdMaxDepth = 10;              // OpenSubdiv's PatchParam holds no deeper level

/// A point of a primvar buffer for OpenSubdiv's refiners.
struct Point3 {
    double p[3] = {0, 0, 0};
    void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0; }
    void AddWithWeight(const Point3& s, double w)
    {
        p[0] += w * s.p[0];
        p[1] += w * s.p[1];
        p[2] += w * s.p[2];
    }
    Eigen::Vector3d vec() const { return {p[0], p[1], p[2]}; }
};

/// The options of a certified tessellation that both schemes check (Error outside their ranges).
inline void checkCertifiedOptions(const SubdivisionTessellationOptions& options)
{
    if (options.maxDepth < 1 || options.maxDepth > 10)
        throw Error("subdivision tessellation: maxDepth " + std::to_string(options.maxDepth) + " is outside 1..10");
    if (options.maxSplits < 0 || options.maxSplits > 28)
        throw Error("subdivision tessellation: maxSplits " + std::to_string(options.maxSplits) + " is outside 0..28");
}

/// The level at which a dyadic cell has the given side: the least d with kR >> d <= size.
inline int levelOfSize(Int size)
{
    int d = 0;
    while ((kR >> d) > size) ++d;
    return d;
}

// ---- The cage handed to OpenSubdiv ----------------------------------------------------------

/// The mesh's vertex positions as a primvar buffer.
inline std::vector<Point3> cagePoints(const PolygonMesh& mesh)
{
    std::vector<Point3> points(static_cast<std::size_t>(mesh.vertexCount()));
    for (int v = 0; v < mesh.vertexCount(); ++v)
        for (int k = 0; k < 3; ++k) points[static_cast<std::size_t>(v)].p[k] = mesh.positions(k, v);
    return points;
}

/// Edge and vertex sharpness as OpenSubdiv's TopologyDescriptor takes them.
struct Sharpness {
    std::vector<int> creasePairs;     // the sharp edges, vertex pairs
    std::vector<float> creaseWeights; // their sharpness
    std::vector<int> cornerVerts;     // the sharp vertices
    std::vector<float> cornerWeights; // their sharpness
};

/// The cage's creases and corners; with positiveOnly, those of sharpness 0 are left out.
inline Sharpness cageSharpness(const SubdivisionCage& cage, bool positiveOnly)
{
    Sharpness s;
    for (const EdgeCrease& c : cage.creases) {
        if (positiveOnly && !(c.sharpness > 0)) continue;
        s.creasePairs.insert(s.creasePairs.end(), {c.v0, c.v1});
        s.creaseWeights.push_back(static_cast<float>(c.sharpness));
    }
    for (const VertexCorner& c : cage.corners) {
        if (positiveOnly && !(c.sharpness > 0)) continue;
        s.cornerVerts.push_back(c.vertex);
        s.cornerWeights.push_back(static_cast<float>(c.sharpness));
    }
    return s;
}

/// OpenSubdiv's rules for a Catmark cage: its creasing method and triangle rule, the boundary.
inline osd::Sdc::Options sdcOptions(const SubdivisionCage& cage, BoundaryInterpolation boundary)
{
    osd::Sdc::Options sdc;
    sdc.SetCreasingMethod(cage.chaikin ? osd::Sdc::Options::CREASE_CHAIKIN : osd::Sdc::Options::CREASE_UNIFORM);
    sdc.SetTriangleSubdivision(cage.smoothTriangles ? osd::Sdc::Options::TRI_SUB_SMOOTH : osd::Sdc::Options::TRI_SUB_CATMARK);
    sdc.SetVtxBoundaryInterpolation(boundary == BoundaryInterpolation::None        ? osd::Sdc::Options::VTX_BOUNDARY_NONE
                                    : boundary == BoundaryInterpolation::EdgeOnly ? osd::Sdc::Options::VTX_BOUNDARY_EDGE_ONLY
                                                                                   : osd::Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
    return sdc;
}

/// The descriptor of a cage for OpenSubdiv (pointing into the arguments, which must outlive it);
/// holes may be null (none).
inline osd::Far::TopologyDescriptor topologyDescriptor(int vertices, const std::vector<int>& counts, const std::vector<int>& faceVerts,
                                                       const Sharpness& sharp, const std::vector<int>* holes)
{
    osd::Far::TopologyDescriptor desc;
    desc.numVertices = vertices;
    desc.numFaces = static_cast<int>(counts.size());
    desc.numVertsPerFace = counts.data();
    desc.vertIndicesPerFace = faceVerts.data();
    desc.numCreases = static_cast<int>(sharp.creaseWeights.size());
    desc.creaseVertexIndexPairs = sharp.creasePairs.data();
    desc.creaseWeights = sharp.creaseWeights.data();
    desc.numCorners = static_cast<int>(sharp.cornerWeights.size());
    desc.cornerVertexIndices = sharp.cornerVerts.data();
    desc.cornerWeights = sharp.cornerWeights.data();
    if (holes) {
        desc.numHoles = static_cast<int>(holes->size());
        desc.holeIndices = holes->data();
    }
    return desc;
}

/// OpenSubdiv's refiner of a descriptor; OpenSubdiv's error is thrown as an Error (osd_errors.h),
/// and `failure` where it builds none.
inline std::unique_ptr<osd::Far::TopologyRefiner> makeRefiner(const osd::Far::TopologyDescriptor& desc, osd::Sdc::SchemeType scheme,
                                                              const osd::Sdc::Options& sdc, const char* failure)
{
    using Factory = osd::Far::TopologyRefinerFactory<osd::Far::TopologyDescriptor>;
    clearOsdError();
    std::unique_ptr<osd::Far::TopologyRefiner> r(Factory::Create(desc, Factory::Options(scheme, sdc)));
    takeOsdError(); // after the refiner is owned, so nothing leaks
    if (!r) throw Error(failure);
    return r;
}

/// The points of every level of the refiner, the base's (level 0) first: vertex v of level l is
/// all[offset[l] + v] (offset: GetMaxLevel() + 2 entries, the last the total).
inline void interpolateLevels(const osd::Far::TopologyRefiner& refiner, const osd::Far::PrimvarRefinerReal<double>& primvar,
                              const std::vector<Point3>& base, std::vector<Point3>& all, std::vector<std::size_t>& offset)
{
    all.assign(static_cast<std::size_t>(refiner.GetNumVerticesTotal()), Point3{});
    std::copy(base.begin(), base.end(), all.begin());
    const int maxLevel = refiner.GetMaxLevel();
    offset.assign(static_cast<std::size_t>(maxLevel) + 2, 0);
    for (int l = 0; l <= maxLevel; ++l)
        offset[static_cast<std::size_t>(l) + 1] = offset[static_cast<std::size_t>(l)] + static_cast<std::size_t>(refiner.GetLevel(l).GetNumVertices());
    for (int l = 1; l <= maxLevel; ++l) {
        const Point3* src = all.data() + offset[static_cast<std::size_t>(l) - 1];
        Point3* dst = all.data() + offset[static_cast<std::size_t>(l)];
        primvar.Interpolate(l, src, dst);
    }
}

/// The faces of a level at the given vertices (a cell's corners), ascending.
template <class Vertices>
std::vector<Index> facesAround(const osd::Far::TopologyLevel& level, const Vertices& corner)
{
    std::vector<Index> faces;
    for (Index v : corner)
        for (Index f : level.GetVertexFaces(v)) faces.push_back(f);
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    return faces;
}

/// The 1-ring of a cell on a level: every vertex of every face at one of its corners, ascending.
template <class Vertices>
std::vector<Index> ringOf(const osd::Far::TopologyLevel& level, const Vertices& corner)
{
    std::vector<Index> ring;
    for (Index v : corner)
        for (Index f : level.GetVertexFaces(v))
            for (Index w : level.GetFaceVertices(f)) ring.push_back(w);
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
    return ring;
}

/// The unit normal of OpenSubdiv's limit tangents at vertex v (zero where their cross product is).
inline Eigen::Vector3d limitNormal(const std::vector<Point3>& tan1, const std::vector<Point3>& tan2, std::size_t v)
{
    const Eigen::Vector3d n = tan1[v].vec().cross(tan2[v].vec());
    return n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::Zero();
}

// ---- Cells -------------------------------------------------------------------------------------

/// The 1-ring hull bound of a cell (docs/subdivision.md, "Certified tessellation"): over its
/// corners' limit points c, the least largest distance from c to the points at(0), ..., at(n - 1)
/// whose convex hull holds the cell's limit surface.
template <std::size_t N, class At>
double hullBound(const std::array<Eigen::Vector3d, N>& corners, std::size_t n, At at)
{
    double bound = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& c : corners) {
        double far = 0;
        for (std::size_t i = 0; i < n; ++i) far = std::max(far, (at(i) - c).norm());
        bound = std::min(bound, far);
    }
    return bound;
}

/// A cell's own tolerance: min(tol, toleranceOf(box)) of the points whose hull bounds it, or tol
/// without toleranceOf (SubdivisionTessellationOptions::toleranceOf).
struct CellTolerance {
    double tol = 0;
    std::function<double(const Eigen::AlignedBox3d&)> toleranceOf;
    /// Of the points at(0), ..., at(n - 1).
    template <class At>
    double of(std::size_t n, At at) const
    {
        if (!toleranceOf) return tol;
        Eigen::AlignedBox3d box;
        box.setEmpty();
        for (std::size_t i = 0; i < n; ++i) box.extend(Eigen::Vector3d(at(i)));
        const double t = toleranceOf(box);
        if (!(t > 0) || !std::isfinite(t))
            throw Error("subdivision tessellation: toleranceOf gave " + std::to_string(t) + " (must be finite and > 0)");
        return std::min(tol, t);
    }
};

/// The cells of a cage as the search for them goes (Irregular and Regular: each scheme's cells).
template <class Irregular, class Regular>
struct CellSearch : CellTolerance {
    osd::Sdc::Options sdc;
    int maxDepth = kOsdMaxDepth;
    bool deeper = false; // past OpenSubdiv's deepest level by local cages (maxDepth at that maximum)
    std::vector<Irregular> irregular;
    std::vector<Regular> regular;

    CellSearch(const SubdivisionTessellationOptions& options, const osd::Sdc::Options& rules)
        : CellTolerance{options.tolerance, options.toleranceOf}, sdc(rules), maxDepth(options.maxDepth),
          deeper(options.maxDepth == kOsdMaxDepth)
    {
    }

    /// Whether an irregular cell found at `depth` gets its own local cage (docs/subdivision.md,
    /// "Deeper than level 10"): at OpenSubdiv's deepest level, with `deeper`, above its own
    /// tolerance, while the cell (of side `size`) leaves room for 10 more levels and 10 halvings of
    /// its regular cells in the 2^40 resolution of the keys.
    bool localCageFor(int depth, const Irregular& cell, Int size) const
    {
        return deeper && depth == kOsdMaxDepth && cell.bound > cell.tol && (size >> kOsdMaxDepth) >= (Int(1) << 10);
    }
};

// ---- Mesh vertices and leaf polygons -----------------------------------------------------------

/// A canonical point, the key of its one mesh vertex: kind 0 a vertex (a), 1 a point inside an
/// edge (a < b, x the dyadic parameter from a), 2 a point inside a face (a, x = u, y = v); of the
/// base (Catmull-Clark) or of the cage (Loop).
struct Key {
    int kind = 0, a = 0, b = 0;
    Int x = 0, y = 0;
    bool operator==(const Key& o) const { return kind == o.kind && a == o.a && b == o.b && x == o.x && y == o.y; }
};
struct KeyHash {
    std::size_t operator()(const Key& k) const
    {
        std::uint64_t h = static_cast<std::uint64_t>(k.kind) * 0x9E3779B97F4A7C15ull;
        for (std::uint64_t v : {static_cast<std::uint64_t>(k.a), static_cast<std::uint64_t>(k.b), static_cast<std::uint64_t>(k.x),
                                static_cast<std::uint64_t>(k.y)})
            h = (h ^ v) * 0x100000001B3ull + (h >> 29);
        return static_cast<std::size_t>(h);
    }
};

/// A line that leaf sides lie on: {0, edgeLine(a, b), 0} an edge (its points by their parameter
/// from the lower vertex), or {kind > 0, face, c} a line inside a face (each scheme its own kinds).
using LineKey = std::array<Int, 3>;

/// The line of the edge between vertices a and b.
inline LineKey edgeLine(int a, int b)
{
    const int lo = std::min(a, b), hi = std::max(a, b);
    return {0, Int(lo) * (Int(1) << 31) + hi, 0};
}

/// The registered points of the lines leaf sides lie on, as their coordinates along each line.
class SideLines {
public:
    void add(const LineKey& line, Int x) { lines_[line].push_back(x); }

    /// Sorts every line's coordinates, once all are added (before inside()).
    void sort()
    {
        for (auto& [line, xs] : lines_) {
            std::sort(xs.begin(), xs.end());
            xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
        }
    }

    /// Calls f(x) for every registered x of the line strictly between a and b (either order), ascending.
    template <class F>
    void inside(const LineKey& line, Int a, Int b, F&& f) const
    {
        const auto it = lines_.find(line);
        if (it == lines_.end()) return;
        const auto first = std::upper_bound(it->second.begin(), it->second.end(), std::min(a, b));
        const auto last = std::lower_bound(it->second.begin(), it->second.end(), std::max(a, b));
        for (auto i = first; i != last; ++i) f(*i);
    }

private:
    std::map<LineKey, std::vector<Int>> lines_;
};

/// Twice the signed area of (a, b, c) in (u, v) (integers as long double: exact enough at 2^40).
inline long double cross2(const UV& a, const UV& b, const UV& c)
{
    return static_cast<long double>(b[0] - a[0]) * static_cast<long double>(c[1] - a[1]) -
           static_cast<long double>(b[1] - a[1]) * static_cast<long double>(c[0] - a[0]);
}

/// The polygon buffers of triangulateLeaf, kept across leaves.
struct LeafPolygon {
    std::vector<UV> poly, side;
    std::vector<int> ring;
};

/// Appends the triangles of a leaf with the given corners (counter-clockwise in (u, v)) to
/// `triangles` as mesh vertices: the polygon of its corners and of the registered points inside its
/// sides, ear clipped. sidePoints(p, q, out) lists the points strictly inside the side p -> q in
/// order from p; vertexOf(uv) is the mesh vertex of a polygon point.
template <std::size_t N, class SidePoints, class VertexOf>
void triangulateLeaf(const std::array<UV, N>& corners, SidePoints&& sidePoints, VertexOf&& vertexOf, LeafPolygon& buf,
                     std::vector<int>& triangles)
{
    buf.poly.clear();
    for (std::size_t k = 0; k < N; ++k) {
        buf.poly.push_back(corners[k]);
        sidePoints(corners[k], corners[(k + 1) % N], buf.side);
        buf.poly.insert(buf.poly.end(), buf.side.begin(), buf.side.end());
    }
    // The next ear from where the last was cut (mesh/convex_ring.h).
    buf.ring.resize(buf.poly.size());
    for (std::size_t i = 0; i < buf.ring.size(); ++i) buf.ring[i] = static_cast<int>(i);
    const auto P = [&](int i) -> const UV& { return buf.poly[static_cast<std::size_t>(i)]; };
    if (!detail::clipConvexRing(
            buf.ring, [&](int a, int b, int c) { return cross2(P(a), P(b), P(c)); },
            [&](int a, int b, int c) {
                for (int k : {a, b, c}) triangles.push_back(vertexOf(P(k)));
            },
            detail::FirstEarInTurn{}))
        throw Error("subdivision tessellation: a leaf polygon could not be triangulated (internal)");
}

// ---- The mesh and the report -------------------------------------------------------------------

/// Per cage face, what its leaves certify.
struct LeafTally {
    std::vector<double> bound; // its largest leaf bound
    std::vector<double> tol;   // the smallest own tolerance of its leaves
    std::vector<char> within;  // every leaf's bound within the leaf's own tolerance
    std::vector<int> rate;     // kR over its narrowest leaf side (at most 2^30)
    double worst = 0;          // the largest leaf bound of all

    LeafTally(int faces, double tolerance)
        : bound(static_cast<std::size_t>(faces), 0.0), tol(static_cast<std::size_t>(faces), tolerance),
          within(static_cast<std::size_t>(faces), 1), rate(static_cast<std::size_t>(faces), 0)
    {
    }

    /// A leaf of cage face `face` with its bound, its own tolerance and its narrowest side.
    void add(int face, double leafBound, double leafTol, Int narrowest)
    {
        const auto f = static_cast<std::size_t>(face);
        bound[f] = std::max(bound[f], leafBound);
        tol[f] = std::min(tol[f], leafTol);
        if (!(leafBound <= leafTol)) within[f] = 0;
        rate[f] = std::max(rate[f], static_cast<int>(std::min<Int>(kR / std::max<Int>(narrowest, 1), Int(1) << 30)));
        worst = std::max(worst, leafBound);
    }
};

/// The triangle mesh of the vertices (positions, unit normals) and triangles (3 vertices each).
inline PolygonMesh triangleMesh(const std::vector<Eigen::Vector3d>& positions, const std::vector<Eigen::Vector3d>& normals,
                                std::vector<int> triangles)
{
    PolygonMesh out;
    out.positions.resize(3, static_cast<Eigen::Index>(positions.size()));
    out.normals.resize(3, static_cast<Eigen::Index>(normals.size()));
    for (std::size_t i = 0; i < positions.size(); ++i) {
        out.positions.col(static_cast<Eigen::Index>(i)) = positions[i];
        out.normals.col(static_cast<Eigen::Index>(i)) = normals[i];
    }
    // The starts are built apart and moved in: resizing PolygonMesh's default faceStart ({0}) in
    // place draws a false -Warray-bounds from GCC 12 where this is inlined.
    std::vector<int> starts(triangles.size() / 3 + 1);
    for (std::size_t i = 0; i < starts.size(); ++i) starts[i] = static_cast<int>(3 * i);
    out.faceVertices = std::move(triangles);
    out.faceStart = std::move(starts);
    return out;
}

/// The certified path's report of a surface: cell and leaf counts, the depth reached and the tally.
inline void certifiedReport(SubdivisionTessellationReport& report, const SubdivisionSurface& surface, const LeafTally& tally,
                            std::size_t regularCells, std::size_t irregularCells, std::size_t leaves, int depth)
{
    report.certifiedPath = true;
    report.rates = tally.rate;
    report.regularFaces = 0;
    report.errorBound = tally.worst;
    report.cells = static_cast<long long>(regularCells + irregularCells);
    report.irregularCells = static_cast<long long>(irregularCells);
    report.leaves = static_cast<long long>(leaves);
    report.depth = depth;
    report.faceBounds = tally.bound;
    report.faceTolerance = tally.tol;
    report.faceCertified.assign(static_cast<std::size_t>(surface.faceCount()), 0);
    for (int f = 0; f < surface.faceCount(); ++f)
        // A face without a limit surface (a hole, a boundary face under `none`) has nothing to
        // approximate and no triangle: certified (vacuously), with bound 0.
        report.faceCertified[static_cast<std::size_t>(f)] = !surface.hasLimitSurface(f) || tally.within[static_cast<std::size_t>(f)];
}

} // namespace detail

} // namespace freeform
