// Certified tessellation of a Catmull-Clark limit surface (docs/subdivision.md, "Certified
// tessellation"): cells from OpenSubdiv's adaptive refinement and patch table; a regular cell is a
// bicubic Bézier patch split by de Casteljau until netErrorBound(patch) <= tolerance, an irregular
// cell (innermost level, next to an extraordinary vertex or an irregular sharp feature) is bounded
// by the convex hull of its 1-ring; one still above the tolerance at OpenSubdiv's deepest level 10
// gets a local cage (its level-10 1-ring) that is cut into cells the same way. Holes (and boundary
// `none`'s faces) get no cells; `smoothtriangles` acts in the quad base's one refinement only; a cell
// whose 1-ring holds an edge_only boundary vertex of one face is never OpenSubdiv's patch but a hull
// bounded cell refined apart (refineTainted; docs/subdivision.md, "Holes, boundary none, smooth
// triangles, smooth boundary corners"). Every mesh vertex is
// an exact limit point, computed once under a canonical key (cage vertex, cage edge + dyadic
// parameter, or face + dyadic (u, v)), so the mesh is conforming and watertight; every leaf is triangulated as a polygon of its corners and of the
// corners of the leaves touching its sides (ear clipping in (u, v)), so its bound holds.

#include "freeform/subdivision/subdivision_surface.h"

#include <opensubdiv/far/error.h>
#include <opensubdiv/far/patchTable.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/primvarRefiner.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <tuple>
#include <unordered_map>

#include "certified_tessellation_common.h"
#include "freeform/tessellate/tessellate.h"

namespace freeform {

using namespace detail;

namespace {

/// The all-quad base mesh the cells live on: the cage itself when every face is a quad, else the
/// cage refined once (every Catmark face then has quads; each base face records its cage face).
struct QuadBase {
    int vertices = 0;
    std::vector<int> faceVerts; // 4 per face
    std::vector<int> cageFace;  // per base face
    std::vector<Point3> positions;
    Sharpness sharp;
    std::vector<int> holes;  // faces without a limit surface (the cage's holes, boundary `none`'s faces)
    std::vector<char> taint; // per vertex (or empty): a boundary vertex of one face under edge_only
    int faces() const { return static_cast<int>(faceVerts.size() / 4); }
};

/// OpenSubdiv's Catmark refiner of a cage (a base, a local cage).
std::unique_ptr<osd::Far::TopologyRefiner> catmarkRefiner(int vertices, const std::vector<int>& counts, const std::vector<int>& faceVerts,
                                                          const Sharpness& sharp, const std::vector<int>& holes, const osd::Sdc::Options& sdc)
{
    return makeRefiner(topologyDescriptor(vertices, counts, faceVerts, sharp, &holes), osd::Sdc::SCHEME_CATMARK, sdc,
                       "subdivision tessellation: OpenSubdiv could not build the topology");
}

QuadBase quadBase(const SubdivisionCage& cage, const osd::Sdc::Options& sdc)
{
    const PolygonMesh& mesh = cage.mesh;
    QuadBase b;
    Sharpness sharp = cageSharpness(cage, false);
    bool quads = true;
    for (int f = 0; f < mesh.faceCount(); ++f) quads = quads && mesh.faceSize(f) == 4;
    // Under edge_only, a boundary vertex of one face (a smooth corner: its rule is the crease rule)
    // gets a regular corner patch from OpenSubdiv that is not the limit surface; the cells near it
    // are handled apart (refineTainted).
    std::vector<char> oneFace(static_cast<std::size_t>(mesh.vertexCount()), 0);
    bool anyOneFace = false;
    if (sdc.GetVtxBoundaryInterpolation() == osd::Sdc::Options::VTX_BOUNDARY_EDGE_ONLY) {
        std::vector<int> faceCount(static_cast<std::size_t>(mesh.vertexCount()), 0);
        for (int v : mesh.faceVertices) ++faceCount[static_cast<std::size_t>(v)];
        for (std::size_t v = 0; v < faceCount.size(); ++v) {
            oneFace[v] = faceCount[v] == 1;
            anyOneFace = anyOneFace || oneFace[v];
        }
    }
    b.positions = cagePoints(mesh);
    if (quads) {
        b.vertices = mesh.vertexCount();
        b.faceVerts = mesh.faceVertices;
        b.cageFace.resize(static_cast<std::size_t>(mesh.faceCount()));
        for (int f = 0; f < mesh.faceCount(); ++f) b.cageFace[static_cast<std::size_t>(f)] = f;
        b.sharp = std::move(sharp);
        b.holes = cage.holes;
        if (anyOneFace) b.taint = std::move(oneFace);
        return b;
    }
    // One uniform level: every face becomes quads; sharpness as OpenSubdiv carries it to level 1.
    std::vector<int> counts(static_cast<std::size_t>(mesh.faceCount()));
    for (int f = 0; f < mesh.faceCount(); ++f) counts[static_cast<std::size_t>(f)] = mesh.faceSize(f);
    auto refiner = catmarkRefiner(mesh.vertexCount(), counts, mesh.faceVertices, sharp, cage.holes, sdc);
    osd::Far::TopologyRefiner::UniformOptions uniform(1);
    uniform.fullTopologyInLastLevel = true;
    refiner->RefineUniform(uniform);
    const osd::Far::TopologyLevel& level = refiner->GetLevel(1);
    std::vector<Point3> fine(static_cast<std::size_t>(level.GetNumVertices()));
    const Point3* src = b.positions.data();
    Point3* dst = fine.data();
    osd::Far::PrimvarRefinerReal<double>(*refiner).Interpolate(1, src, dst);
    b.positions = std::move(fine);
    b.vertices = level.GetNumVertices();
    if (anyOneFace) {
        b.taint.assign(static_cast<std::size_t>(b.vertices), 0);
        for (std::size_t v = 0; v < oneFace.size(); ++v)
            if (oneFace[v]) b.taint[static_cast<std::size_t>(refiner->GetLevel(0).GetVertexChildVertex(static_cast<Index>(v)))] = 1;
    }
    for (int f = 0; f < level.GetNumFaces(); ++f) {
        const auto fv = level.GetFaceVertices(f);
        for (int k = 0; k < fv.size(); ++k) b.faceVerts.push_back(fv[k]);
        b.cageFace.push_back(level.GetFaceParentFace(f));
        // A hole's children are holes (so are boundary `none`'s faces: OpenSubdiv tags them so).
        if (level.IsFaceHole(f)) b.holes.push_back(f);
    }
    for (int e = 0; e < level.GetNumEdges(); ++e) {
        const float s = level.GetEdgeSharpness(e);
        if (s > 0 && level.GetEdgeFaces(e).size() == 2) {
            const auto ev = level.GetEdgeVertices(e);
            b.sharp.creasePairs.insert(b.sharp.creasePairs.end(), {ev[0], ev[1]});
            b.sharp.creaseWeights.push_back(s);
        }
    }
    for (int v = 0; v < level.GetNumVertices(); ++v) {
        const float s = level.GetVertexSharpness(v);
        if (s > 0) {
            b.sharp.cornerVerts.push_back(v);
            b.sharp.cornerWeights.push_back(s);
        }
    }
    return b;
}

struct Leaf {
    int face = 0;
    Int u0 = 0, v0 = 0, u1 = 0, v1 = 0;
    int patch = -1; // index into the regular leaf patches; -1: irregular
    double bound = 0;
    double tol = 0; // its own tolerance (SubdivisionTessellationOptions::toleranceOf)
};

class Builder {
public:
    explicit Builder(const QuadBase& base) : base_(base) {}

    /// The canonical key of face f's dyadic point (iu, iv), and (for a point inside an edge) the
    /// edge's line with the canonical coordinate.
    Key key(int f, Int iu, Int iv) const
    {
        const int* fv = &base_.faceVerts[static_cast<std::size_t>(4 * f)];
        if (iu > 0 && iu < kR && iv > 0 && iv < kR) return {2, f, 0, iu, iv};
        int k;
        Int t;
        if (iv == 0 && iu < kR) k = 0, t = iu;
        else if (iu == kR && iv < kR) k = 1, t = iv;
        else if (iv == kR && iu > 0) k = 2, t = kR - iu;
        else k = 3, t = kR - iv;
        if (t == 0) return {0, fv[k], 0, 0, 0};
        const int a = fv[k], b = fv[(k + 1) % 4];
        return a < b ? Key{1, a, b, t, 0} : Key{1, b, a, kR - t, 0};
    }

    void registerCorner(int f, Int iu, Int iv)
    {
        const Key k = key(f, iu, iv);
        if (k.kind == 2) {
            lines_.add({1, f, iv}, iu);
            lines_.add({2, f, iu}, iv);
        } else if (k.kind == 1) {
            lines_.add(edgeLine(k.a, k.b), k.x);
        }
    }

    void sortLines() { lines_.sort(); }

    /// The registered points strictly inside the side from (pu, pv) to (qu, qv) of face f (an
    /// axis-parallel segment), in order from p to q, as face coordinates.
    void sidePoints(int f, Int pu, Int pv, Int qu, Int qv, std::vector<std::array<Int, 2>>& out) const
    {
        out.clear();
        const bool horizontal = pv == qv;
        const Int c = horizontal ? pv : pu;
        if (c == 0 || c == kR) {
            const Key kp = key(f, pu, pv), kq = key(f, qu, qv);
            // The edge of face f the side lies on.
            int k = horizontal ? (c == 0 ? 0 : 2) : (c == 0 ? 3 : 1);
            const int* fv = &base_.faceVerts[static_cast<std::size_t>(4 * f)];
            const int a = fv[k], b = fv[(k + 1) % 4];
            const int lo = std::min(a, b), hi = std::max(a, b);
            auto canonical = [&](const Key& kk) -> Int {
                if (kk.kind == 1) return kk.x;
                return kk.a == lo ? 0 : kR; // a vertex: the edge's end
            };
            const Int tp = canonical(kp), tq = canonical(kq);
            lines_.inside(edgeLine(lo, hi), tp, tq, [&](Int x) {
                const Int tLocal = a < b ? x : kR - x; // from a along edge k
                std::array<Int, 2> uv{};
                switch (k) {
                case 0: uv = {tLocal, 0}; break;
                case 1: uv = {kR, tLocal}; break;
                case 2: uv = {kR - tLocal, kR}; break;
                default: uv = {0, kR - tLocal}; break;
                }
                out.push_back(uv);
            });
        } else {
            lines_.inside({horizontal ? 1 : 2, f, c}, horizontal ? pu : pv, horizontal ? qu : qv,
                          [&](Int x) { out.push_back(horizontal ? UV{x, c} : UV{c, x}); });
        }
        const Int p = horizontal ? pu : pv, q = horizontal ? qu : qv;
        const bool forward = q > p;
        auto coord = [&](const std::array<Int, 2>& x) { return horizontal ? x[0] : x[1]; };
        std::sort(out.begin(), out.end(), [&](const auto& x, const auto& y) { return forward ? coord(x) < coord(y) : coord(x) > coord(y); });
    }

private:
    const QuadBase& base_;
    SideLines lines_;
};

/// max |second differences| terms of a bicubic net: (u, uv, v) parts of netErrorBound.
std::array<double, 3> boundTerms(const Patch& p)
{
    const int m = p.degreeU(), n = p.degreeV();
    const auto& b = p.controlPoints();
    auto at = [&](int i, int j) { return Eigen::Vector3d(b.col(i * (n + 1) + j)); };
    double uu = 0, uv = 0, vv = 0;
    for (int i = 0; i <= m; ++i)
        for (int j = 0; j <= n; ++j) {
            if (i + 2 <= m) uu = std::max(uu, (at(i + 2, j) - 2 * at(i + 1, j) + at(i, j)).norm());
            if (j + 2 <= n) vv = std::max(vv, (at(i, j + 2) - 2 * at(i, j + 1) + at(i, j)).norm());
            if (i + 1 <= m && j + 1 <= n) uv = std::max(uv, (at(i + 1, j + 1) - at(i + 1, j) - at(i, j + 1) + at(i, j)).norm());
        }
    return {m * (m - 1) * uu / 8, 2.0 * m * n * uv / 8, n * (n - 1) * vv / 8};
}

/// The Bézier patch of a regular B-spline patch of the patch table (16 points, OpenSubdiv's order:
/// index 4 i + j, j along u, i along v; boundary bits extrapolate the missing row or column).
Patch bezierOfRegular(const std::vector<Point3>& all, osd::Far::ConstIndexArray cvs, unsigned boundary)
{
    Eigen::Vector3d P[4][4]; // [i along v][j along u]
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) P[i][j] = all[static_cast<std::size_t>(cvs[4 * i + j])].vec();
    if (boundary & 8u)
        for (int i = 0; i < 4; ++i) P[i][0] = 2 * P[i][1] - P[i][2];
    if (boundary & 2u)
        for (int i = 0; i < 4; ++i) P[i][3] = 2 * P[i][2] - P[i][1];
    if (boundary & 1u)
        for (int j = 0; j < 4; ++j) P[0][j] = 2 * P[1][j] - P[2][j];
    if (boundary & 4u)
        for (int j = 0; j < 4; ++j) P[3][j] = 2 * P[2][j] - P[1][j];
    PointMatrix<double, 3> deBoor(3, 16);
    for (int r = 0; r < 4; ++r)     // along u
        for (int c = 0; c < 4; ++c) // along v
            deBoor.col(r * 4 + c) = P[c][r];
    return deboorSurfacePatches(deBoor, 4, 4, EndCondition::Open, EndCondition::Open).patches.front();
}

Eigen::Vector3d unitNormal(const Patch& p, double u, double v)
{
    auto at = [&](double a, double b) {
        const auto jet = p.jet(a, b, 1);
        return Eigen::Vector3d(Eigen::Vector3d(jet.col(1)).cross(Eigen::Vector3d(jet.col(2))));
    };
    Eigen::Vector3d n = at(u, v);
    if (!(n.norm() > 1e-300)) {
        // f_u x f_v vanishes here (a collapsed corner): the normal approached from the leaf's centre.
        const double w = 1e-7;
        n = at((1 - w) * u + w * 0.5, (1 - w) * v + w * 0.5);
    }
    const double len = n.norm();
    return len > 0 && std::isfinite(len) ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}


/// An irregular cell (an end cap of the patch table) with its hull bound, in base-face coordinates.
struct Irregular {
    int face = 0;
    Int u0 = 0, v0 = 0, size = 0;
    std::array<Eigen::Vector3d, 4> corner, normal; // at (u0, v0), (u1, v0), (u1, v1), (u0, v1)
    double bound = 0;
    double tol = 0; // its own tolerance (SubdivisionTessellationOptions::toleranceOf)
};
/// A regular cell: its exact bicubic Bézier patch, in base-face coordinates.
struct Regular {
    int face = 0;
    Int u0 = 0, v0 = 0, size = 0;
    Patch patch;
};

/// Where a face of the quad mesh handed to OpenSubdiv lies on the base: the base face and the dyadic
/// square of it (face < 0: a face whose cells are not wanted, the ring of a local cage).
struct Frame {
    int face = -1;
    Int u0 = 0, v0 = 0, size = kR;
};

/// Semi-sharp features must be refined past their sharpness before their cells are regular
/// patches or their limit masks are exact: the first isolation level.
int firstDepthOf(const QuadBase& m, int maxDepth)
{
    double semiSharp = 0;
    for (float s : m.sharp.creaseWeights)
        if (s < kInfiniteSharpness) semiSharp = std::max(semiSharp, static_cast<double>(s));
    for (float s : m.sharp.cornerWeights)
        if (s < kInfiniteSharpness) semiSharp = std::max(semiSharp, static_cast<double>(s));
    return std::clamp(static_cast<int>(std::ceil(semiSharp)) + 1, 1, maxDepth);
}

using CatmarkSearch = CellSearch<Irregular, Regular>;

/// The child of face `current` on level l in quadrant (qa, qb) of its (u, v), and the vertices at
/// its corners on level l + 1 (slot 2 b + a at corner (a, b); `corner` holds the parent's so).
std::pair<Index, std::array<Index, 4>> childFace(const osd::Far::TopologyRefiner& refiner, int l, Index current,
                                                 const std::array<Index, 4>& corner, int qa, int qb)
{
    const osd::Far::TopologyLevel& level = refiner.GetLevel(l);
    const auto faceVerts = level.GetFaceVertices(current);
    const auto faceEdges = level.GetFaceEdges(current);
    auto edgeBetween = [&](Index x, Index y) {
        for (int k = 0; k < 4; ++k)
            if ((faceVerts[k] == x && faceVerts[(k + 1) % 4] == y) || (faceVerts[k] == y && faceVerts[(k + 1) % 4] == x))
                return level.GetEdgeChildVertex(faceEdges[k]);
        throw Error("subdivision tessellation: a cell's corners are not an edge (internal)");
    };
    std::array<Index, 4> next{};
    next[static_cast<std::size_t>(2 * qb + qa)] = level.GetVertexChildVertex(corner[static_cast<std::size_t>(2 * qb + qa)]);
    next[static_cast<std::size_t>(2 * qb + (1 - qa))] =
        edgeBetween(corner[static_cast<std::size_t>(2 * qb + qa)], corner[static_cast<std::size_t>(2 * qb + (1 - qa))]);
    next[static_cast<std::size_t>(2 * (1 - qb) + qa)] =
        edgeBetween(corner[static_cast<std::size_t>(2 * qb + qa)], corner[static_cast<std::size_t>(2 * (1 - qb) + qa)]);
    next[static_cast<std::size_t>(2 * (1 - qb) + (1 - qa))] = level.GetFaceChildVertex(current);
    Index child = -1;
    for (Index c : level.GetFaceChildFaces(current)) {
        if (c < 0) continue;
        const auto cv = refiner.GetLevel(l + 1).GetFaceVertices(c);
        int found = 0;
        for (int k = 0; k < cv.size(); ++k) found += std::count(next.begin(), next.end(), cv[k]) > 0 ? 1 : 0;
        if (found == 4) child = c;
    }
    if (child < 0) throw Error("subdivision tessellation: a cell's face was not refined (internal)");
    return {child, next};
}

/// The local cage of a cell (docs/subdivision.md, "Deeper than level 10"): every face of the level
/// at a corner of the cell (its 1-ring), the cell first with its corners in (u, v) order, edge and
/// vertex sharpness and holes as on that level; `taint` (or null) marks the level's one-face
/// boundary vertices under edge_only, carried to the local vertices.
QuadBase localCage(const osd::Far::TopologyLevel& level, const std::array<Index, 4>& corner, const Point3* positions,
                   const std::vector<char>* taint)
{
    const std::vector<Index> faces = facesAround(level, corner);
    QuadBase local;
    std::unordered_map<Index, int> localOf;
    bool tainted = false;
    auto localVertex = [&](Index v) {
        const auto [it, added] = localOf.emplace(v, static_cast<int>(local.positions.size()));
        if (added) {
            local.positions.push_back(positions[v]);
            const char t = taint && static_cast<std::size_t>(v) < taint->size() ? (*taint)[static_cast<std::size_t>(v)] : 0;
            local.taint.push_back(t);
            tainted = tainted || t;
        }
        return it->second;
    };
    for (int k : {0, 1, 3, 2}) local.faceVerts.push_back(localVertex(corner[static_cast<std::size_t>(k)]));
    std::vector<Index> edges;
    for (Index f : faces) {
        const auto fv = level.GetFaceVertices(f);
        if (fv.size() != 4) throw Error("subdivision tessellation: a refined face is not a quad (internal)");
        const auto fe = level.GetFaceEdges(f);
        edges.insert(edges.end(), fe.begin(), fe.end());
        int shared = 0;
        for (int k = 0; k < 4; ++k) shared += std::count(corner.begin(), corner.end(), fv[k]) > 0 ? 1 : 0;
        if (shared == 4) continue; // the cell itself, already first
        if (level.IsFaceHole(f)) local.holes.push_back(local.faces());
        for (int k = 0; k < 4; ++k) local.faceVerts.push_back(localVertex(fv[k]));
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    for (Index e : edges) {
        const float sharp = level.GetEdgeSharpness(e);
        if (sharp > 0 && level.GetEdgeFaces(e).size() == 2) {
            const auto ev = level.GetEdgeVertices(e);
            local.sharp.creasePairs.insert(local.sharp.creasePairs.end(), {localVertex(ev[0]), localVertex(ev[1])});
            local.sharp.creaseWeights.push_back(sharp);
        }
    }
    for (const auto& [v, lv] : localOf) {
        const float sharp = level.GetVertexSharpness(v);
        if (sharp > 0) {
            local.sharp.cornerVerts.push_back(lv);
            local.sharp.cornerWeights.push_back(sharp);
        }
    }
    local.vertices = static_cast<int>(local.positions.size());
    if (!tainted) local.taint.clear();
    return local;
}

int collectCells(CatmarkSearch& s, const QuadBase& m, const std::vector<Frame>& frames, int firstDepth);

/// A cell whose 1-ring holds a boundary vertex of one face under edge_only (docs/subdivision.md,
/// "Smooth boundary corners"): OpenSubdiv's patch there is not the limit surface, so the cell is
/// never a patch. Its local cage (face 0 the cell, in `frame` of the base) is refined uniformly
/// by one level; the cell is an irregular leaf with its 1-ring hull bound when that is within the
/// tolerance, else each of its four children is handled again: as such a cell when its 1-ring
/// still holds such a vertex, else as an ordinary local cage (collectCells).
void refineTainted(CatmarkSearch& s, const QuadBase& local, const Frame& frame)
{
    const std::vector<int> counts(static_cast<std::size_t>(local.faces()), 4);
    auto refiner = catmarkRefiner(local.vertices, counts, local.faceVerts, local.sharp, local.holes, s.sdc);
    osd::Far::TopologyRefiner::UniformOptions uniform(1);
    uniform.fullTopologyInLastLevel = true;
    refiner->RefineUniform(uniform);
    const osd::Far::TopologyLevel& level0 = refiner->GetLevel(0);
    const osd::Far::TopologyLevel& level1 = refiner->GetLevel(1);
    std::vector<Point3> fine(static_cast<std::size_t>(level1.GetNumVertices()));
    const osd::Far::PrimvarRefinerReal<double> primvar(*refiner);
    const Point3* src = local.positions.data();
    Point3* dst = fine.data();
    primvar.Interpolate(1, src, dst);
    std::vector<Point3> limit(fine.size()), tan1(fine.size()), tan2(fine.size());
    clearOsdError();
    primvar.Limit(fine, limit, tan1, tan2);
    takeOsdError();

    // The cell's bound from its 1-ring (every local vertex) and its corners' limit points (those
    // of their children on level 1, the same points).
    Irregular cell;
    cell.face = frame.face;
    cell.u0 = frame.u0;
    cell.v0 = frame.v0;
    cell.size = frame.size;
    for (int k = 0; k < 4; ++k) {
        const Index v = level0.GetVertexChildVertex(local.faceVerts[static_cast<std::size_t>(k)]);
        cell.corner[static_cast<std::size_t>(k)] = limit[static_cast<std::size_t>(v)].vec();
        cell.normal[static_cast<std::size_t>(k)] = limitNormal(tan1, tan2, static_cast<std::size_t>(v));
    }
    auto ringPoint = [&](std::size_t i) { return local.positions[i].vec(); };
    cell.bound = hullBound(cell.corner, local.positions.size(), ringPoint);
    cell.tol = s.of(local.positions.size(), ringPoint);
    // Room for the children and their own cells (10 levels and 10 halvings) in the 2^40 keys.
    if (cell.bound <= cell.tol || (frame.size >> 1 >> kOsdMaxDepth) < (Int(1) << 10)) {
        s.irregular.push_back(cell);
        return;
    }
    std::vector<char> taint1(static_cast<std::size_t>(level1.GetNumVertices()), 0);
    for (int v = 0; v < local.vertices; ++v)
        if (local.taint[static_cast<std::size_t>(v)]) {
            const Index c = level0.GetVertexChildVertex(v);
            if (c >= 0) taint1[static_cast<std::size_t>(c)] = 1;
        }
    const std::array<Index, 4> corner{local.faceVerts[0], local.faceVerts[1], local.faceVerts[3], local.faceVerts[2]};
    const Int half = frame.size / 2;
    for (int qb = 0; qb < 2; ++qb)
        for (int qa = 0; qa < 2; ++qa) {
            const auto [child, next] = childFace(*refiner, 0, 0, corner, qa, qb);
            (void)child;
            const QuadBase sub = localCage(level1, next, fine.data(), &taint1);
            const Frame subFrame{frame.face, frame.u0 + qa * half, frame.v0 + qb * half, half};
            if (!sub.taint.empty()) {
                refineTainted(s, sub, subFrame);
                continue;
            }
            std::vector<Frame> subFrames(static_cast<std::size_t>(sub.faces()));
            subFrames[0] = subFrame;
            collectCells(s, sub, subFrames, firstDepthOf(sub, s.maxDepth));
        }
}

/// The cells of the faces of m that have a frame: OpenSubdiv's adaptive refinement and patch table
/// at isolation levels firstDepth, firstDepth + 1, ... until every irregular cell's hull bound is at
/// most the tolerance or maxDepth is reached. There, with `deeper`, an irregular cell still above
/// the tolerance is replaced by the cells of its own local cage (the faces around its corners on
/// that level, docs/subdivision.md "Deeper than level 10"), found the same way. A cell whose 1-ring
/// holds a one-face boundary vertex under edge_only (m.taint) goes to refineTainted instead.
/// Returns the level reached on m.
int collectCells(CatmarkSearch& s, const QuadBase& m, const std::vector<Frame>& frames, int firstDepth)
{
    const std::vector<int> counts(static_cast<std::size_t>(m.faces()), 4);
    const bool hasTaint = std::find(m.taint.begin(), m.taint.end(), char(1)) != m.taint.end();
    std::vector<Irregular> irregular;
    std::vector<std::array<Index, 4>> irregularCorners; // the level-d vertices at each cell's corners
    std::vector<Regular> regular;
    struct Tainted {
        Frame frame;
        int depth = 0;
        std::array<Index, 4> corner{};
    };
    std::vector<Tainted> tainted;
    for (int depth = firstDepth;; ++depth) {
        irregular.clear();
        irregularCorners.clear();
        regular.clear();
        tainted.clear();
        auto refiner = catmarkRefiner(m.vertices, counts, m.faceVerts, m.sharp, m.holes, s.sdc);
        osd::Far::TopologyRefiner::AdaptiveOptions adaptive(depth);
        adaptive.SetSecondaryLevel(depth);
        adaptive.useInfSharpPatch = true;
        refiner->RefineAdaptive(adaptive);
        osd::Far::PatchTableFactory::Options po(static_cast<unsigned>(depth));
        po.SetEndCapType(osd::Far::PatchTableFactory::Options::ENDCAP_BILINEAR_BASIS);
        po.useInfSharpPatch = true;
        clearOsdError();
        std::unique_ptr<osd::Far::PatchTable> table(osd::Far::PatchTableFactory::Create(*refiner, po));
        takeOsdError();
        if (!table) throw Error("subdivision tessellation: OpenSubdiv could not build the patch table");

        // Positions on every level.
        const osd::Far::PrimvarRefinerReal<double> primvar(*refiner);
        std::vector<Point3> all;
        std::vector<std::size_t> offset;
        interpolateLevels(*refiner, primvar, m.positions, all, offset);
        // The one-face boundary vertices on every level: the vertex children of the base's (no
        // other vertex has one face: edge and face children have two or more).
        std::vector<std::vector<char>> taintAt;
        if (hasTaint) {
            taintAt.push_back(m.taint);
            for (int l = 1; l <= refiner->GetMaxLevel(); ++l) {
                std::vector<char> next(static_cast<std::size_t>(refiner->GetLevel(l).GetNumVertices()), 0);
                const std::vector<char>& prev = taintAt.back();
                for (std::size_t v = 0; v < prev.size(); ++v)
                    if (prev[v]) {
                        const Index c = refiner->GetLevel(l - 1).GetVertexChildVertex(static_cast<Index>(v));
                        if (c >= 0) next[static_cast<std::size_t>(c)] = 1;
                    }
                taintAt.push_back(std::move(next));
            }
        }
        // Limit positions and tangents of the finest level.
        const int finest = refiner->GetMaxLevel();
        const std::size_t nFine = static_cast<std::size_t>(refiner->GetLevel(finest).GetNumVertices());
        std::vector<Point3> limit(nFine), tan1(nFine), tan2(nFine);
        const Point3* fineSrc = all.data() + offset[static_cast<std::size_t>(finest)];
        clearOsdError();
        primvar.Limit(fineSrc, limit, tan1, tan2);
        takeOsdError();

        bool over = false; // an irregular cell above its own tolerance
        for (int array = 0; array < table->GetNumPatchArrays(); ++array) {
            const auto type = table->GetPatchArrayDescriptor(array).GetType();
            for (int patch = 0; patch < table->GetNumPatches(array); ++patch) {
                const osd::Far::PatchParam param = table->GetPatchParam(array, patch);
                const int face = param.GetFaceId();
                const Frame& frame = frames[static_cast<std::size_t>(face)];
                if (frame.face < 0) continue;
                const int d = param.GetDepth();
                const Int size = frame.size >> d;
                const Int u0 = frame.u0 + static_cast<Int>(param.GetU()) * size, v0 = frame.v0 + static_cast<Int>(param.GetV()) * size;
                const bool isRegular = type == osd::Far::PatchDescriptor::REGULAR;
                if (isRegular && !hasTaint) {
                    regular.push_back({frame.face, u0, v0, size,
                                       bezierOfRegular(all, table->GetPatchVertices(array, patch), param.GetBoundary())});
                    continue;
                }
                // The cell's face on level d, found by descending from the base face, keeping which
                // vertex sits at each corner.
                const int* fv = &m.faceVerts[static_cast<std::size_t>(4 * face)];
                std::array<Index, 4> corner{fv[0], fv[1], fv[3], fv[2]}; // slot 2 * b + a at corner (a, b)
                Index current = face;
                for (int l = 0; l < d; ++l) {
                    const int shift = d - 1 - l;
                    const int qa = static_cast<int>((param.GetU() >> shift) & 1), qb = static_cast<int>((param.GetV() >> shift) & 1);
                    std::tie(current, corner) = childFace(*refiner, l, current, corner, qa, qb);
                }
                const osd::Far::TopologyLevel& level = refiner->GetLevel(d);
                const std::vector<Index> ring = ringOf(level, corner);
                if (hasTaint) {
                    const std::vector<char>& t = taintAt[static_cast<std::size_t>(d)];
                    bool near = false;
                    for (Index w : ring) near = near || t[static_cast<std::size_t>(w)];
                    if (near) {
                        tainted.push_back({{frame.face, u0, v0, size}, d, corner});
                        continue;
                    }
                }
                if (isRegular) {
                    regular.push_back({frame.face, u0, v0, size,
                                       bezierOfRegular(all, table->GetPatchVertices(array, patch), param.GetBoundary())});
                    continue;
                }
                if (d != finest) throw Error("subdivision tessellation: an irregular cell above the finest level (internal)");
                Irregular cell;
                cell.face = frame.face;
                cell.u0 = u0;
                cell.v0 = v0;
                cell.size = size;
                const std::array<int, 4> order{0, 1, 3, 2}; // slots at (0,0), (1,0), (1,1), (0,1)
                for (int k = 0; k < 4; ++k) {
                    const Index v = corner[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])];
                    cell.corner[static_cast<std::size_t>(k)] = limit[static_cast<std::size_t>(v)].vec();
                    cell.normal[static_cast<std::size_t>(k)] = limitNormal(tan1, tan2, static_cast<std::size_t>(v));
                }
                auto ringPoint = [&](std::size_t i) { return all[offset[static_cast<std::size_t>(d)] + static_cast<std::size_t>(ring[i])].vec(); };
                cell.bound = hullBound(cell.corner, ring.size(), ringPoint);
                cell.tol = s.of(ring.size(), ringPoint);
                over = over || cell.bound > cell.tol;
                irregular.push_back(cell);
                irregularCorners.push_back(corner);
            }
        }
        if (over && depth < s.maxDepth) continue;

        s.regular.insert(s.regular.end(), std::make_move_iterator(regular.begin()), std::make_move_iterator(regular.end()));
        for (std::size_t i = 0; i < irregular.size(); ++i) {
            const Irregular& cell = irregular[i];
            // Past the deepest level: a local cage (CellSearch::localCageFor).
            if (!s.localCageFor(depth, cell, cell.size)) {
                s.irregular.push_back(cell);
                continue;
            }
            const QuadBase local = localCage(refiner->GetLevel(depth), irregularCorners[i],
                                             all.data() + offset[static_cast<std::size_t>(depth)], nullptr);
            std::vector<Frame> localFrames(static_cast<std::size_t>(local.faces()));
            localFrames[0] = {cell.face, cell.u0, cell.v0, cell.size};
            collectCells(s, local, localFrames, firstDepthOf(local, kOsdMaxDepth));
        }
        for (const Tainted& t : tainted) {
            const QuadBase local = localCage(refiner->GetLevel(t.depth), t.corner, all.data() + offset[static_cast<std::size_t>(t.depth)],
                                             &taintAt[static_cast<std::size_t>(t.depth)]);
            refineTainted(s, local, t.frame);
        }
        return depth;
    }
}

} // namespace

PolygonMesh SubdivisionSurface::tessellateCertified(const SubdivisionTessellationOptions& options,
                                                    SubdivisionTessellationReport* report) const
{
    checkCertifiedOptions(options);
    const double tol = options.tolerance;
    const osd::Sdc::Options sdc = sdcOptions(cage_, boundary());
    const QuadBase base = quadBase(cage_, sdc);

    // Cells: the base's faces at increasing isolation levels, past OpenSubdiv's deepest by local
    // cages where maxDepth is at that maximum.
    CatmarkSearch search(options, sdc);
    std::vector<Frame> frames(static_cast<std::size_t>(base.faces()));
    for (int f = 0; f < base.faces(); ++f) frames[static_cast<std::size_t>(f)] = {f, 0, 0, kR};
    int depth = collectCells(search, base, frames, firstDepthOf(base, options.maxDepth));
    const std::vector<Irregular>& irregular = search.irregular;
    const std::vector<Regular>& regular = search.regular;
    for (const Irregular& c : irregular) depth = std::max(depth, levelOfSize(c.size));

    // Leaves: irregular cells as they are, regular cells split by de Casteljau.
    std::vector<Leaf> leaves;
    std::vector<Patch> leafPatch;
    for (std::size_t i = 0; i < irregular.size(); ++i) {
        const auto& c = irregular[i];
        leaves.push_back({c.face, c.u0, c.v0, c.u0 + c.size, c.v0 + c.size, -1 - static_cast<int>(i), c.bound, c.tol});
    }
    struct Task {
        Patch patch;
        int face;
        Int u0, v0, su, sv;
        int su_splits, sv_splits;
    };
    std::vector<Task> stack;
    for (const auto& r : regular) stack.push_back({r.patch, r.face, r.u0, r.v0, r.size, r.size, 0, 0});
    while (!stack.empty()) {
        Task t = std::move(stack.back());
        stack.pop_back();
        const double bound = netErrorBound(t.patch);
        const auto& net = t.patch.controlPoints();
        const double own = search.of(static_cast<std::size_t>(net.cols()), [&](std::size_t k) { return net.col(static_cast<Eigen::Index>(k)); });
        const bool canU = t.su_splits < options.maxSplits && t.su > 1, canV = t.sv_splits < options.maxSplits && t.sv > 1;
        if (bound <= own || (!canU && !canV)) {
            leaves.push_back({t.face, t.u0, t.v0, t.u0 + t.su, t.v0 + t.sv, static_cast<int>(leafPatch.size()), bound, own});
            leafPatch.push_back(std::move(t.patch));
            continue;
        }
        const auto terms = boundTerms(t.patch);
        bool splitU = canU, splitV = canV;
        if (canU && canV) {
            if (terms[0] > 2 * terms[2]) splitV = false;
            else if (terms[2] > 2 * terms[0]) splitU = false;
        }
        if (splitU && splitV) {
            // The last split: where halving one direction is expected to bring the bound within the
            // tolerance (a halving in u quarters the u term and halves the mixed one), halve only
            // that one. The halves' bounds are computed again, so this choice never weakens the
            // bound; it saves the overshoot of halving both.
            const double afterU = terms[0] / 4 + terms[1] / 2 + terms[2], afterV = terms[0] + terms[1] / 2 + terms[2] / 4;
            if (std::min(afterU, afterV) <= own) (afterU <= afterV ? splitV : splitU) = false;
        }
        std::vector<Task> parts{t};
        if (splitU) {
            std::vector<Task> next;
            for (const Task& p : parts) {
                auto [a, b] = p.patch.splitU(0.5);
                const Int h = p.su / 2;
                next.push_back({std::move(a), p.face, p.u0, p.v0, h, p.sv, p.su_splits + 1, p.sv_splits});
                next.push_back({std::move(b), p.face, p.u0 + h, p.v0, h, p.sv, p.su_splits + 1, p.sv_splits});
            }
            parts = std::move(next);
        }
        if (splitV) {
            std::vector<Task> next;
            for (const Task& p : parts) {
                auto [a, b] = p.patch.splitV(0.5);
                const Int h = p.sv / 2;
                next.push_back({std::move(a), p.face, p.u0, p.v0, p.su, h, p.su_splits, p.sv_splits + 1});
                next.push_back({std::move(b), p.face, p.u0, p.v0 + h, p.su, h, p.su_splits, p.sv_splits + 1});
            }
            parts = std::move(next);
        }
        for (Task& p : parts) stack.push_back(std::move(p));
    }

    // Every leaf corner once: irregular cells first (OpenSubdiv's limit masks), then regular
    // leaves (their own Bézier patch; the corner point is a control point).
    Builder builder(base);
    std::unordered_map<Key, int, KeyHash> vertexOf;
    std::vector<Eigen::Vector3d> positions, normals;
    auto cornerUV = [](const Leaf& l, int k) -> std::array<Int, 2> {
        switch (k) {
        case 0: return {l.u0, l.v0};
        case 1: return {l.u1, l.v0};
        case 2: return {l.u1, l.v1};
        default: return {l.u0, l.v1};
        }
    };
    for (int pass = 0; pass < 2; ++pass)
        for (const Leaf& l : leaves) {
            if ((l.patch < 0) != (pass == 0)) continue;
            for (int k = 0; k < 4; ++k) {
                const auto uv = cornerUV(l, k);
                const Key key = builder.key(l.face, uv[0], uv[1]);
                if (vertexOf.count(key)) continue;
                builder.registerCorner(l.face, uv[0], uv[1]);
                vertexOf.emplace(key, static_cast<int>(positions.size()));
                if (l.patch < 0) {
                    const Irregular& c = irregular[static_cast<std::size_t>(-1 - l.patch)];
                    positions.push_back(c.corner[static_cast<std::size_t>(k)]);
                    normals.push_back(c.normal[static_cast<std::size_t>(k)]);
                } else {
                    const Patch& p = leafPatch[static_cast<std::size_t>(l.patch)];
                    const double a = (k == 1 || k == 2) ? 1.0 : 0.0, b = (k >= 2) ? 1.0 : 0.0;
                    positions.push_back(p.evaluate(a, b));
                    normals.push_back(unitNormal(p, a, b));
                }
            }
        }
    builder.sortLines();

    // Irregular cells' normals from OpenSubdiv's tangents have the vertex's own orientation: turn
    // them to the side of the cell's corners' normal (counter-clockwise in (u, v)).
    for (const Leaf& l : leaves) {
        if (l.patch >= 0) continue;
        const Irregular& c = irregular[static_cast<std::size_t>(-1 - l.patch)];
        const Eigen::Vector3d poly = (c.corner[2] - c.corner[0]).cross(c.corner[3] - c.corner[1]);
        for (int k = 0; k < 4; ++k) {
            const auto uv = cornerUV(l, k);
            Eigen::Vector3d& n = normals[static_cast<std::size_t>(vertexOf.at(builder.key(l.face, uv[0], uv[1])))];
            // On a crease the limit normal is one side's: where OpenSubdiv's tangents give a normal
            // more than 60 degrees from the cell's own plane (the other side of the crease), or none,
            // the cell's normal (of its corner quad) is used instead.
            const Eigen::Vector3d cellNormal = poly.normalized();
            if (n.isZero(0.0) || std::abs(n.dot(cellNormal)) < 0.5) n = cellNormal;
            else if (n.dot(cellNormal) < 0) n = -n;
        }
    }

    // Triangulate every leaf as the polygon of its corners and side points.
    std::vector<int> triangles;
    LeafPolygon polygon;
    LeafTally tally(faceCount(), tol);
    auto sidePoints = [&](int face) {
        return [&builder, face](const UV& p, const UV& q, std::vector<UV>& out) { builder.sidePoints(face, p[0], p[1], q[0], q[1], out); };
    };
    auto vertexAt = [&](int face) { return [&, face](const UV& uv) { return vertexOf.at(builder.key(face, uv[0], uv[1])); }; };
    for (const Leaf& l : leaves) {
        triangulateLeaf(std::array<UV, 4>{cornerUV(l, 0), cornerUV(l, 1), cornerUV(l, 2), cornerUV(l, 3)}, sidePoints(l.face),
                        vertexAt(l.face), polygon, triangles);
        tally.add(base.cageFace[static_cast<std::size_t>(l.face)], l.bound, l.tol, std::min(l.u1 - l.u0, l.v1 - l.v0));
    }

    PolygonMesh out = triangleMesh(positions, normals, std::move(triangles));
    if (report) certifiedReport(*report, *this, tally, regular.size(), irregular.size(), leaves.size(), depth);
    return out;
}

} // namespace freeform
