// Certified tessellation of a Loop limit surface (docs/subdivision.md, "Certified tessellation",
// "Loop cages"): cells from OpenSubdiv's adaptive refinement and patch table; a regular cell (patch
// type LOOP, the quartic box spline of 12 points) becomes a quartic triangular Bézier patch (15
// points, a fixed matrix) split by triangular de Casteljau into four until its second-difference
// bound is within the tolerance; an irregular cell (a face next to an extraordinary vertex on the
// finest level) is bounded by the convex hull of its 1-ring; one still above the tolerance at
// OpenSubdiv's level 10 gets a local cage (its level-10 1-ring) cut into cells the same way, nested
// down to depth 30 ("Deeper than level 10"). A cell next to a boundary or an infinitely sharp
// crease (a LOOP patch with boundary bits: phantom points, not the limit) is a feature cell, bounded
// by its 1-ring hull and, above the tolerance, split through its own local cage refined once
// (splitFeature). Creases, corners, boundary rule and creasing method are the cage's; holes (and
// boundary none's faces) stay in the cage without a frame. Vertices are exact limit points under
// canonical keys (cage vertex, cage edge + dyadic parameter, face + dyadic (u, v)); each leaf is cut
// as the polygon of its corners and of the registered points inside its sides (ear clipping in
// (u, v)), so the mesh is conforming and closed cages give closed meshes. The operations on the
// Bézier nets (sub-nets, bounds, corner normals) are in loop_bezier.cpp (loop_bezier_net.h).

#include "freeform/subdivision/subdivision_surface.h"

#include <opensubdiv/far/error.h>
#include <opensubdiv/far/patchTable.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/primvarRefiner.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <unordered_map>

#include "certified_tessellation_common.h"
#include "freeform/core/error.h"
#include "freeform/subdivision/loop_bezier.h"
#include "loop_bezier_net.h"

namespace freeform {

using namespace detail;
using namespace detail::loop;

namespace {

Net bezierOfLoop(const std::vector<Point3>& all, osd::Far::ConstIndexArray cvs)
{
    Net b;
    int row = 0;
    for (int j = 0; j <= 4; ++j)
        for (int k = 0; k <= 4 - j; ++k, ++row) {
            Eigen::Vector3d x = Eigen::Vector3d::Zero();
            for (int c = 0; c < 12; ++c)
                if (kLoopToBezier[row][c] != 0) x += kLoopToBezier[row][c] * all[static_cast<std::size_t>(cvs[c])].vec();
            b[static_cast<std::size_t>(j)][static_cast<std::size_t>(k)] = x / 24.0;
        }
    return b;
}

/// Canonical keys and the lines leaf sides lie on, for a triangle cage (face (u, v): corner 0 at
/// (0, 0), corner 1 at (kR, 0), corner 2 at (0, kR)). Lines: {0, edge, 0} a cage edge (canonical
/// parameter), {1, f, v} horizontal (u along it), {2, f, u} vertical (v), {3, f, u + v} diagonal (u).
class TriangleKeys {
public:
    explicit TriangleKeys(const std::vector<int>& faceVerts) : fv_(faceVerts) {}

    /// The cage edge k of face f (0: corner 0 -> 1, 1: 1 -> 2, 2: 2 -> 0) and the local parameter
    /// t from its first corner of (iu, iv) on it.
    static bool onEdge(Int iu, Int iv, int& k, Int& t)
    {
        if (iv == 0) k = 0, t = iu;
        else if (iu + iv == kR) k = 1, t = iv;
        else if (iu == 0) k = 2, t = kR - iv;
        else return false;
        return true;
    }

    Key key(int f, Int iu, Int iv) const
    {
        int k;
        Int t;
        if (!onEdge(iu, iv, k, t)) return {2, f, 0, iu, iv};
        const int a = vert(f, k), b = vert(f, (k + 1) % 3);
        if (t == 0) return {0, a, 0, 0, 0};
        if (t == kR) return {0, b, 0, 0, 0};
        return a < b ? Key{1, a, b, t, 0} : Key{1, b, a, kR - t, 0};
    }

    void registerPoint(int f, Int iu, Int iv)
    {
        const Key k = key(f, iu, iv);
        if (k.kind == 2) {
            lines_.add({1, f, iv}, iu);
            lines_.add({2, f, iu}, iv);
            lines_.add({3, f, iu + iv}, iu);
        } else if (k.kind == 1) {
            lines_.add(edgeLine(k.a, k.b), k.x);
        }
    }

    void sortLines() { lines_.sort(); }

    /// The registered points strictly inside the side p -> q of face f (a segment along one of the
    /// three directions), in order from p to q.
    void sidePoints(int f, const UV& p, const UV& q, std::vector<UV>& out) const
    {
        out.clear();
        // The line of the side: a cage edge k (v = 0, u + v = 1, u = 0) or a line inside the face.
        int k = -1;
        LineKey line;
        Int cp, cq;
        if (p[1] == q[1]) k = p[1] == 0 ? 0 : -1, line = {1, f, p[1]}, cp = p[0], cq = q[0];
        else if (p[0] == q[0]) k = p[0] == 0 ? 2 : -1, line = {2, f, p[0]}, cp = p[1], cq = q[1];
        else k = p[0] + p[1] == kR ? 1 : -1, line = {3, f, p[0] + p[1]}, cp = p[0], cq = q[0];
        if (k >= 0) {
            const int a = vert(f, k), b = vert(f, (k + 1) % 3);
            const int lo = std::min(a, b);
            line = edgeLine(a, b);
            const Int tp = localOnEdge(p, k), tq = localOnEdge(q, k);
            cp = a == lo ? tp : kR - tp;
            cq = a == lo ? tq : kR - tq;
        }
        lines_.inside(line, cp, cq, [&](Int x) {
            if (k >= 0) {
                const Int t = vert(f, k) == std::min(vert(f, k), vert(f, (k + 1) % 3)) ? x : kR - x;
                out.push_back(k == 0 ? UV{t, 0} : k == 1 ? UV{kR - t, t} : UV{0, kR - t});
            } else if (line[0] == 1) out.push_back({x, line[2]});
            else if (line[0] == 2) out.push_back({line[2], x});
            else out.push_back({x, line[2] - x});
        });
        auto dist = [&](const UV& x) { return std::abs(x[0] - p[0]) + std::abs(x[1] - p[1]); };
        std::sort(out.begin(), out.end(), [&](const UV& x, const UV& y) { return dist(x) < dist(y); });
    }

private:
    int vert(int f, int k) const { return fv_[static_cast<std::size_t>(3 * f + k)]; }
    /// The local parameter of x on edge k (from its first corner).
    static Int localOnEdge(const UV& x, int k) { return k == 0 ? x[0] : k == 1 ? x[1] : kR - x[1]; }

    const std::vector<int>& fv_;
    SideLines lines_;
};

struct Leaf {
    int face = 0;
    std::array<UV, 3> c; // counter-clockwise in (u, v); the net's corners 0, 1, 2
    int net = -1;        // index into the leaf nets; -1 - i: irregular cell i
    double bound = 0;
    double tol = 0;      // its own tolerance (SubdivisionTessellationOptions::toleranceOf)
};

/// A cell's corners in the face's integer (u, v) from OpenSubdiv's PatchParam (local (0,0), (1,0),
/// (0,1); a rotated triangle runs backwards from (2^d - U, 2^d - V), osd::Far::PatchParam::NormalizeTriangle).
std::array<UV, 3> cellCorners(const osd::Far::PatchParam& param)
{
    const Int size = kR >> param.GetDepth();
    const Int U = static_cast<Int>(param.GetU()) * size, V = static_cast<Int>(param.GetV()) * size;
    if (param.IsTriangleRotated()) return {UV{kR - U, kR - V}, UV{kR - U - size, kR - V}, UV{kR - U, kR - V - size}};
    return {UV{U, V}, UV{U + size, V}, UV{U, V + size}};
}

/// The level-d face of the cell with the given corners inside base face f, by descending the
/// adaptive refinement: at each level the child triangle (the three corner children and the middle
/// one, as in the four-way split) that holds the cell's centroid, found among the face's children
/// by its vertices (the corners' and the edges' child vertices). Returns the level-d vertex at each
/// of the cell's corners.
std::array<Index, 3> descend(const osd::Far::TopologyRefiner& refiner, const std::vector<int>& faceVerts, int f,
                             const std::array<UV, 3>& cell, int d)
{
    std::array<UV, 3> c{UV{0, 0}, UV{kR, 0}, UV{0, kR}};
    std::array<Index, 3> v{faceVerts[static_cast<std::size_t>(3 * f)], faceVerts[static_cast<std::size_t>(3 * f + 1)],
                           faceVerts[static_cast<std::size_t>(3 * f + 2)]};
    Index face = f;
    // The cell's centroid, times 3 (exact in integers).
    const UV centroid{cell[0][0] + cell[1][0] + cell[2][0], cell[0][1] + cell[1][1] + cell[2][1]};
    auto inside = [&](const std::array<UV, 3>& t) {
        const std::array<UV, 3> t3{UV{3 * t[0][0], 3 * t[0][1]}, UV{3 * t[1][0], 3 * t[1][1]}, UV{3 * t[2][0], 3 * t[2][1]}};
        return cross2(t3[0], t3[1], centroid) > 0 && cross2(t3[1], t3[2], centroid) > 0 && cross2(t3[2], t3[0], centroid) > 0;
    };
    auto mid = [](const UV& a, const UV& b) { return UV{(a[0] + b[0]) / 2, (a[1] + b[1]) / 2}; };
    for (int l = 0; l < d; ++l) {
        const osd::Far::TopologyLevel& level = refiner.GetLevel(l);
        const auto fv = level.GetFaceVertices(face);
        const auto fe = level.GetFaceEdges(face);
        auto edgeChild = [&](Index x, Index y) {
            for (int k = 0; k < 3; ++k)
                if ((fv[k] == x && fv[(k + 1) % 3] == y) || (fv[k] == y && fv[(k + 1) % 3] == x)) return level.GetEdgeChildVertex(fe[k]);
            throw Error("subdivision tessellation: a Loop cell's corners are not an edge (internal)");
        };
        const UV m01 = mid(c[0], c[1]), m12 = mid(c[1], c[2]), m20 = mid(c[2], c[0]);
        const Index w0 = level.GetVertexChildVertex(v[0]), w1 = level.GetVertexChildVertex(v[1]), w2 = level.GetVertexChildVertex(v[2]);
        const Index e01 = edgeChild(v[0], v[1]), e12 = edgeChild(v[1], v[2]), e20 = edgeChild(v[2], v[0]);
        const std::array<std::array<UV, 3>, 4> parts{std::array<UV, 3>{c[0], m01, m20}, std::array<UV, 3>{m01, c[1], m12},
                                                     std::array<UV, 3>{m20, m12, c[2]}, std::array<UV, 3>{m12, m20, m01}};
        const std::array<std::array<Index, 3>, 4> partVerts{std::array<Index, 3>{w0, e01, e20}, std::array<Index, 3>{e01, w1, e12},
                                                            std::array<Index, 3>{e20, e12, w2}, std::array<Index, 3>{e12, e20, e01}};
        int which = -1;
        for (int k = 0; k < 4 && which < 0; ++k)
            if (inside(parts[static_cast<std::size_t>(k)])) which = k;
        if (which < 0) throw Error("subdivision tessellation: a Loop cell outside its face (internal)");
        const auto& target = partVerts[static_cast<std::size_t>(which)];
        Index child = -1;
        for (Index ch : level.GetFaceChildFaces(face)) {
            if (ch < 0) continue;
            const auto cv = refiner.GetLevel(l + 1).GetFaceVertices(ch);
            int found = 0;
            for (int k = 0; k < cv.size(); ++k) found += std::count(target.begin(), target.end(), cv[k]) > 0 ? 1 : 0;
            if (found == 3) child = ch;
        }
        if (child < 0) throw Error("subdivision tessellation: a Loop cell's face was not refined (internal)");
        face = child;
        c = parts[static_cast<std::size_t>(which)];
        v = target;
    }
    // The corners of the level-d face, matched to the cell's corners by (u, v).
    std::array<Index, 3> out{};
    for (std::size_t k = 0; k < 3; ++k) {
        int match = -1;
        for (int i = 0; i < 3; ++i)
            if (c[static_cast<std::size_t>(i)] == cell[k]) match = i;
        if (match < 0) throw Error("subdivision tessellation: a Loop cell's corners do not match its face (internal)");
        out[k] = v[static_cast<std::size_t>(match)];
    }
    return out;
}

/// An irregular cell (an end cap on the finest level): its corners' limit points and normals and
/// its 1-ring hull bound, in base-face coordinates.
struct LoopIrregular {
    int face = 0;
    std::array<UV, 3> c;
    std::array<Eigen::Vector3d, 3> corner, normal;
    double bound = 0;
    double tol = 0; // its own tolerance (SubdivisionTessellationOptions::toleranceOf)
};
/// A regular cell: its quartic Bézier net, in base-face coordinates.
struct LoopRegular {
    int face = 0;
    std::array<UV, 3> c;
    Net net;
};

/// A triangle cage handed to OpenSubdiv: the base cage, or a local cage (docs/subdivision.md,
/// "Deeper than level 10").
struct TriCage {
    std::vector<Point3> points;
    std::vector<int> faceVerts;
    Sharpness sharp; // the sharp edges and vertices
};

/// OpenSubdiv's Loop refiner of a TriCage; `failure` where it builds none.
std::unique_ptr<osd::Far::TopologyRefiner> loopRefiner(const TriCage& m, const osd::Sdc::Options& sdc, const char* failure)
{
    const std::vector<int> counts(m.faceVerts.size() / 3, 3);
    return makeRefiner(topologyDescriptor(static_cast<int>(m.points.size()), counts, m.faceVerts, m.sharp, nullptr), osd::Sdc::SCHEME_LOOP, sdc,
                       failure);
}

/// The local cage of a cell (docs/subdivision.md, "Deeper than level 10", "Loop cages"): every face
/// of `level` at one of the cell's corners (its 1-ring), the cell first with its corners in the
/// cell's order (counter-clockwise, as the level's faces), with the level's points (`points`,
/// indexed by the level's vertices) and its edge and vertex sharpness.
TriCage localCage(const osd::Far::TopologyLevel& level, const Point3* points, const std::array<Index, 3>& corner)
{
    const std::vector<Index> ringFaces = facesAround(level, corner);
    TriCage out;
    std::unordered_map<Index, int> localOf;
    auto localVertex = [&](Index v) {
        const auto [it, added] = localOf.emplace(v, static_cast<int>(out.points.size()));
        if (added) {
            out.points.push_back(points[static_cast<std::size_t>(v)]);
            const float sharp = level.GetVertexSharpness(v);
            if (sharp > 0) {
                out.sharp.cornerVerts.push_back(it->second);
                out.sharp.cornerWeights.push_back(sharp);
            }
        }
        return it->second;
    };
    for (Index v : corner) out.faceVerts.push_back(localVertex(v));
    bool own = false;
    std::unordered_map<Index, char> edgeSeen;
    for (Index f : ringFaces) {
        const auto fv = level.GetFaceVertices(f);
        int shared = 0, first = -1;
        for (int k = 0; k < 3; ++k) {
            shared += std::count(corner.begin(), corner.end(), fv[k]) > 0 ? 1 : 0;
            if (fv[k] == corner[0]) first = k;
        }
        if (shared == 3) { // the cell itself, already first: the same turning
            if (first < 0 || fv[(first + 1) % 3] != corner[1])
                throw Error("subdivision tessellation: a Loop cell turns against its face (internal)");
            own = true;
        } else {
            for (int k = 0; k < 3; ++k) out.faceVerts.push_back(localVertex(fv[k]));
        }
        const auto fe = level.GetFaceEdges(f);
        for (int k = 0; k < 3; ++k) {
            const float sharp = level.GetEdgeSharpness(fe[k]);
            if (!(sharp > 0) || !edgeSeen.emplace(fe[k], 1).second) continue;
            out.sharp.creasePairs.insert(out.sharp.creasePairs.end(), {localOf.at(fv[k]), localOf.at(fv[(k + 1) % 3])});
            out.sharp.creaseWeights.push_back(sharp);
        }
    }
    if (!own) throw Error("subdivision tessellation: a Loop cell's face is not around its corners (internal)");
    return out;
}

/// Where a face of a TriCage lies on the base: the base face and the base (u, v) of the face's
/// corners 0, 1, 2 (face < 0: a face whose cells are not wanted, the ring of a local cage).
struct TriFrame {
    int face = -1;
    std::array<UV, 3> c{};
};

/// A point (u, v) of a cage face (corner 0 at (0, 0), 1 at (kR, 0), 2 at (0, kR)) in base-face
/// coordinates. The frame's triangle has sides along the three directions, of a power-of-two size,
/// so the map is exact in integers for every point on that size's dyadic grid.
UV toBase(const TriFrame& frame, const UV& x)
{
    const UV& c0 = frame.c[0];
    const Int size = std::max(std::abs(frame.c[1][0] - c0[0]), std::abs(frame.c[1][1] - c0[1]));
    const Int step = kR / size;
    if (x[0] % step != 0 || x[1] % step != 0) throw Error("subdivision tessellation: a Loop cell finer than its keys (internal)");
    const Int a = x[0] / step, b = x[1] / step;
    return {c0[0] + (frame.c[1][0] - c0[0]) / size * a + (frame.c[2][0] - c0[0]) / size * b,
            c0[1] + (frame.c[1][1] - c0[1]) / size * a + (frame.c[2][1] - c0[1]) / size * b};
}

using LoopSearch = CellSearch<LoopIrregular, LoopRegular>;

int collectLoopCells(LoopSearch& s, const TriCage& m, const std::vector<TriFrame>& frames);

/// A feature cell (docs/subdivision.md, "Loop cages", "Boundaries, holes, creases and corners"):
/// face 0 of its local cage m, at base face and corners `cell`. Refined once uniformly: its
/// corners' limit points (OpenSubdiv's limit masks on the refined level) and the 1-ring hull bound
/// (every point of m); within the tolerance (or at the finest allowed size) it is an irregular
/// leaf, else its four children are cut into cells by collectLoopCells on the refined local cage's
/// faces around the children (their 1-rings).
void splitFeature(LoopSearch& s, const TriCage& m, const TriFrame& cell)
{
    const auto refiner = loopRefiner(m, s.sdc, "subdivision tessellation: OpenSubdiv could not build a Loop local cage");
    osd::Far::TopologyRefiner::UniformOptions uniform(1);
    uniform.fullTopologyInLastLevel = true;
    refiner->RefineUniform(uniform);
    const osd::Far::TopologyLevel& l0 = refiner->GetLevel(0);
    const osd::Far::TopologyLevel& l1 = refiner->GetLevel(1);
    const auto n1 = static_cast<std::size_t>(l1.GetNumVertices());
    std::vector<Point3> fine(n1), limit(n1), tan1(n1), tan2(n1);
    const osd::Far::PrimvarRefinerReal<double> primvar(*refiner);
    clearOsdError();
    const Point3* src = m.points.data();
    Point3* dst = fine.data();
    primvar.Interpolate(1, src, dst);
    primvar.Limit(fine, limit, tan1, tan2);
    takeOsdError();

    const auto fv = l0.GetFaceVertices(0);
    const auto fe = l0.GetFaceEdges(0);
    LoopIrregular leaf;
    leaf.face = cell.face;
    leaf.c = cell.c;
    for (std::size_t k = 0; k < 3; ++k) {
        const auto v = static_cast<std::size_t>(l0.GetVertexChildVertex(fv[static_cast<int>(k)]));
        leaf.corner[k] = limit[v].vec();
        leaf.normal[k] = limitNormal(tan1, tan2, v);
    }
    auto ringPoint = [&](std::size_t i) { return m.points[i].vec(); };
    leaf.bound = hullBound(leaf.corner, m.points.size(), ringPoint);
    leaf.tol = s.of(m.points.size(), ringPoint);
    const Int size = std::max(std::abs(cell.c[1][0] - cell.c[0][0]), std::abs(cell.c[1][1] - cell.c[0][1]));
    const int level = levelOfSize(size);
    // Split while the children leave room for 10 levels of OpenSubdiv and 10 halvings of their
    // regular cells in the 2^40 resolution of the keys; below maxDepth 10, no deeper than maxDepth.
    const int finest = s.deeper ? 40 - 21 : s.maxDepth;
    if (leaf.bound <= leaf.tol || level >= finest) {
        s.irregular.push_back(leaf);
        return;
    }

    // The children's 1-rings on the refined level: every level-1 face at a vertex of face 0's children.
    auto mid = [](const UV& a, const UV& b) { return UV{(a[0] + b[0]) / 2, (a[1] + b[1]) / 2}; };
    std::unordered_map<Index, UV> uvOf;
    for (int k = 0; k < 3; ++k) {
        uvOf[l0.GetVertexChildVertex(fv[k])] = cell.c[static_cast<std::size_t>(k)];
        uvOf[l0.GetEdgeChildVertex(fe[k])] = mid(cell.c[static_cast<std::size_t>(k)], cell.c[static_cast<std::size_t>((k + 1) % 3)]);
    }
    std::vector<Index> ringFaces;
    for (const auto& [v, uv] : uvOf)
        for (Index f : l1.GetVertexFaces(v)) ringFaces.push_back(f);
    std::sort(ringFaces.begin(), ringFaces.end());
    ringFaces.erase(std::unique(ringFaces.begin(), ringFaces.end()), ringFaces.end());
    const auto children = l0.GetFaceChildFaces(0);
    TriCage next;
    std::vector<TriFrame> frames;
    std::unordered_map<Index, int> localOf;
    auto localVertex = [&](Index v) {
        const auto [it, added] = localOf.emplace(v, static_cast<int>(next.points.size()));
        if (added) {
            next.points.push_back(fine[static_cast<std::size_t>(v)]);
            const float sharp = l1.GetVertexSharpness(v);
            if (sharp > 0) {
                next.sharp.cornerVerts.push_back(it->second);
                next.sharp.cornerWeights.push_back(sharp);
            }
        }
        return it->second;
    };
    auto onFeature = [&](Index f) {
        for (Index v : l1.GetFaceVertices(f)) {
            if (l1.IsVertexBoundary(v) || l1.GetVertexSharpness(v) >= osd::Sdc::Crease::SHARPNESS_INFINITE) return true;
            for (Index e : l1.GetVertexEdges(v))
                if (l1.GetEdgeSharpness(e) >= osd::Sdc::Crease::SHARPNESS_INFINITE) return true;
        }
        return false;
    };
    bool wanted = false;
    std::unordered_map<Index, char> edgeSeen;
    for (Index f : ringFaces) {
        const auto v = l1.GetFaceVertices(f);
        const auto e = l1.GetFaceEdges(f);
        for (int k = 0; k < 3; ++k) next.faceVerts.push_back(localVertex(v[k]));
        for (int k = 0; k < 3; ++k) {
            const float sharp = l1.GetEdgeSharpness(e[k]);
            if (!(sharp > 0) || !edgeSeen.emplace(e[k], 1).second) continue;
            next.sharp.creasePairs.insert(next.sharp.creasePairs.end(), {localOf.at(v[k]), localOf.at(v[(k + 1) % 3])});
            next.sharp.creaseWeights.push_back(sharp);
        }
        TriFrame frame;
        if (std::find(children.begin(), children.end(), f) != children.end() && !onFeature(f))
            frame = {cell.face, {uvOf.at(v[0]), uvOf.at(v[1]), uvOf.at(v[2])}};
        wanted = wanted || frame.face >= 0;
        frames.push_back(frame);
    }
    // A child with a corner on a boundary or an infinitely sharp feature is never a regular patch
    // without boundary bits: a feature cell again, split here without a patch table. The others are
    // cut into cells by OpenSubdiv (regular ones become Bézier cells).
    for (Index ch : children)
        if (onFeature(ch)) {
            const auto v = l1.GetFaceVertices(ch);
            splitFeature(s, localCage(l1, fine.data(), {v[0], v[1], v[2]}), {cell.face, {uvOf.at(v[0]), uvOf.at(v[1]), uvOf.at(v[2])}});
        }
    if (wanted) collectLoopCells(s, next, frames);
}

/// The cells of the faces of m that have a frame: OpenSubdiv's adaptive Loop refinement and patch
/// table at isolation levels 1, 2, ... until every irregular cell's hull bound is at most the
/// tolerance or maxDepth is reached. There, with `deeper`, an irregular cell still above the
/// tolerance is replaced by the cells of its own local cage (the faces around its corners on that
/// level, docs/subdivision.md "Deeper than level 10"), found the same way. Returns the level
/// reached on m.
int collectLoopCells(LoopSearch& s, const TriCage& m, const std::vector<TriFrame>& frames)
{
    for (int depth = 1;; ++depth) {
        std::vector<LoopIrregular> irregular;
        std::vector<LoopRegular> regular;
        std::vector<std::array<Index, 3>> irregularCorners; // the level-d vertex at each corner
        struct Feature {
            int face;
            std::array<UV, 3> c;
            std::array<Index, 3> corner; // its level-d vertices
            int d;
        };
        std::vector<Feature> features;
        const auto refiner = loopRefiner(m, s.sdc, "subdivision tessellation: OpenSubdiv could not build the Loop topology");
        // Infinitely sharp creases as boundaries: their cells are regular patches with a boundary
        // mask (feature cells, split by splitFeature where needed) rather than isolated to the
        // finest level all along the crease.
        osd::Far::TopologyRefiner::AdaptiveOptions adaptive(depth);
        adaptive.useInfSharpPatch = true;
        refiner->RefineAdaptive(adaptive);
        osd::Far::PatchTableFactory::Options po(static_cast<unsigned>(depth));
        po.SetEndCapType(osd::Far::PatchTableFactory::Options::ENDCAP_BILINEAR_BASIS);
        po.useInfSharpPatch = true; // as the refinement: an infinitely sharp edge bounds a patch (its mask)
        clearOsdError();
        std::unique_ptr<osd::Far::PatchTable> table(osd::Far::PatchTableFactory::Create(*refiner, po));
        takeOsdError();
        if (!table) throw Error("subdivision tessellation: OpenSubdiv could not build the Loop patch table");

        // Positions on every level, and the limit points and tangents of every level's vertices.
        const int maxLevel = refiner->GetMaxLevel();
        const osd::Far::PrimvarRefinerReal<double> primvar(*refiner);
        std::vector<Point3> all;
        std::vector<std::size_t> offset;
        interpolateLevels(*refiner, primvar, m.points, all, offset);
        std::vector<Point3> limit, tan1, tan2; // of the finest level's vertices, computed when needed

        bool over = false; // an irregular cell above its own tolerance
        for (int array = 0; array < table->GetNumPatchArrays(); ++array) {
            const auto type = table->GetPatchArrayDescriptor(array).GetType();
            for (int patch = 0; patch < table->GetNumPatches(array); ++patch) {
                const osd::Far::PatchParam param = table->GetPatchParam(array, patch);
                const TriFrame& frame = frames[static_cast<std::size_t>(param.GetFaceId())];
                if (frame.face < 0) continue;
                const auto cvs = table->GetPatchVertices(array, patch);
                const std::array<UV, 3> corners = cellCorners(param);
                const std::array<UV, 3> baseCorners{toBase(frame, corners[0]), toBase(frame, corners[1]), toBase(frame, corners[2])};
                if (type == osd::Far::PatchDescriptor::LOOP && param.GetBoundary() == 0) {
                    regular.push_back({frame.face, baseCorners, bezierOfLoop(all, cvs)});
                    continue;
                }
                if (type == osd::Far::PatchDescriptor::LOOP) {
                    // A regular patch with a boundary mask (phantom points by extrapolation, negative
                    // weights): not the limit, so a feature cell, split by its own local cages
                    // (splitFeature) once the depth here is final.
                    const int d = param.GetDepth();
                    features.push_back({frame.face, baseCorners, descend(*refiner, m.faceVerts, param.GetFaceId(), corners, d), d});
                    continue;
                }
                if (type != osd::Far::PatchDescriptor::TRIANGLES)
                    throw Error("subdivision tessellation: an unexpected Loop patch type (internal)");
                // An irregular cell (an end cap on the finest level d): find its face on level d by
                // descending from the base face, keeping which vertex sits at each corner.
                const int d = param.GetDepth();
                if (d != maxLevel) throw Error("subdivision tessellation: a Loop end cap above the finest level (internal)");
                const auto D = static_cast<std::size_t>(d);
                if (limit.empty()) {
                    const std::size_t n = static_cast<std::size_t>(refiner->GetLevel(d).GetNumVertices());
                    limit.resize(n);
                    tan1.resize(n);
                    tan2.resize(n);
                    clearOsdError();
                    const Point3* src = all.data() + offset[D];
                    primvar.Limit(src, limit, tan1, tan2);
                    takeOsdError();
                }
                const std::array<Index, 3> local = descend(*refiner, m.faceVerts, param.GetFaceId(), corners, d);
                const osd::Far::TopologyLevel& level = refiner->GetLevel(d);
                const std::vector<Index> ring = ringOf(level, local);
                LoopIrregular cell;
                cell.face = frame.face;
                cell.c = baseCorners;
                for (std::size_t k = 0; k < 3; ++k) {
                    const auto v = static_cast<std::size_t>(local[k]);
                    cell.corner[k] = limit[v].vec();
                    cell.normal[k] = limitNormal(tan1, tan2, v);
                }
                auto ringPoint = [&](std::size_t i) { return all[offset[D] + static_cast<std::size_t>(ring[i])].vec(); };
                cell.bound = hullBound(cell.corner, ring.size(), ringPoint);
                cell.tol = s.of(ring.size(), ringPoint);
                over = over || cell.bound > cell.tol;
                irregular.push_back(cell);
                irregularCorners.push_back(local);
            }
        }
        if (over && depth < s.maxDepth) continue;

        s.regular.insert(s.regular.end(), std::make_move_iterator(regular.begin()), std::make_move_iterator(regular.end()));
        for (std::size_t i = 0; i < irregular.size(); ++i) {
            const LoopIrregular& cell = irregular[i];
            const Int size = std::max(std::abs(cell.c[1][0] - cell.c[0][0]), std::abs(cell.c[1][1] - cell.c[0][1]));
            // Past the deepest level: a local cage (CellSearch::localCageFor).
            if (!s.localCageFor(depth, cell, size)) {
                s.irregular.push_back(cell);
                continue;
            }
            const osd::Far::TopologyLevel& level = refiner->GetLevel(depth);
            const TriCage local = localCage(level, all.data() + offset[static_cast<std::size_t>(depth)], irregularCorners[i]);
            std::vector<TriFrame> localFrames(local.faceVerts.size() / 3);
            localFrames[0] = {cell.face, cell.c};
            collectLoopCells(s, local, localFrames);
        }
        for (const Feature& f : features)
            splitFeature(s, localCage(refiner->GetLevel(f.d), all.data() + offset[static_cast<std::size_t>(f.d)], f.corner), {f.face, f.c});
        return depth;
    }
}

} // namespace

PolygonMesh SubdivisionSurface::tessellateCertifiedLoop(const SubdivisionTessellationOptions& options,
                                                        SubdivisionTessellationReport* report) const
{
    checkCertifiedOptions(options);
    const double tol = options.tolerance;
    const PolygonMesh& mesh = cage_.mesh;
    const int faces = mesh.faceCount();

    // The cage's own rules (boundary none: the faces without a limit surface are left out below,
    // and the rest refine as under edge_only, docs/subdivision.md "Loop cages").
    osd::Sdc::Options sdc;
    sdc.SetVtxBoundaryInterpolation(boundary() == BoundaryInterpolation::EdgeAndCorner ? osd::Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER
                                                                                     : osd::Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
    sdc.SetCreasingMethod(cage_.chaikin ? osd::Sdc::Options::CREASE_CHAIKIN : osd::Sdc::Options::CREASE_UNIFORM);
    LoopSearch search(options, sdc);
    const TriCage base{cagePoints(mesh), mesh.faceVertices, cageSharpness(cage_, true)};
    // Holes, and under boundary none the faces touching the boundary, have no limit surface: they
    // stay in the cage (their points shape their neighbours) without a frame.
    std::vector<TriFrame> frames(static_cast<std::size_t>(faces));
    for (int f = 0; f < faces; ++f)
        if (hasLimitSurface(f)) frames[static_cast<std::size_t>(f)] = {f, {UV{0, 0}, UV{kR, 0}, UV{0, kR}}};
    int depth = collectLoopCells(search, base, frames);
    const std::vector<LoopIrregular>& irregular = search.irregular;
    const std::vector<LoopRegular>& regular = search.regular;
    for (const LoopIrregular& c : irregular) {
        const Int size = std::max(std::abs(c.c[1][0] - c.c[0][0]), std::abs(c.c[1][1] - c.c[0][1]));
        depth = std::max(depth, levelOfSize(size));
    }

    // Leaves: irregular cells as they are, regular cells split into four by de Casteljau.
    std::vector<Leaf> leaves;
    std::vector<Net> leafNet;
    for (std::size_t i = 0; i < irregular.size(); ++i)
        leaves.push_back({irregular[i].face, irregular[i].c, -1 - static_cast<int>(i), irregular[i].bound, irregular[i].tol});
    struct Task {
        int face;
        std::array<UV, 3> c;
        Net net;
        int splits;
    };
    std::vector<Task> stack;
    for (const LoopRegular& r : regular) stack.push_back({r.face, r.c, r.net, 0});
    const Eigen::Vector3d e0(1, 0, 0), e1(0, 1, 0), e2(0, 0, 1), m01(0.5, 0.5, 0), m12(0, 0.5, 0.5), m20(0.5, 0, 0.5);
    while (!stack.empty()) {
        Task t = std::move(stack.back());
        stack.pop_back();
        const double bound = netBound(t.net);
        const double own = search.of(15, [&](std::size_t i) {
            int j = 0, k = static_cast<int>(i);
            while (k > 4 - j) k -= 5 - j++; // i runs over (j, k), k = 0..4 - j, j = 0..4
            return t.net[static_cast<std::size_t>(j)][static_cast<std::size_t>(k)];
        });
        const Int side = std::max(std::abs(t.c[1][0] - t.c[0][0]), std::abs(t.c[1][1] - t.c[0][1]));
        if (bound <= own || t.splits >= options.maxSplits || side < 2) {
            leaves.push_back({t.face, t.c, static_cast<int>(leafNet.size()), bound, own});
            leafNet.push_back(t.net);
            continue;
        }
        auto mid = [](const UV& a, const UV& b) { return UV{(a[0] + b[0]) / 2, (a[1] + b[1]) / 2}; };
        const UV M01 = mid(t.c[0], t.c[1]), M12 = mid(t.c[1], t.c[2]), M20 = mid(t.c[2], t.c[0]);
        stack.push_back({t.face, {t.c[0], M01, M20}, subNet(t.net, e0, m01, m20), t.splits + 1});
        stack.push_back({t.face, {M01, t.c[1], M12}, subNet(t.net, m01, e1, m12), t.splits + 1});
        stack.push_back({t.face, {M20, M12, t.c[2]}, subNet(t.net, m20, m12, e2), t.splits + 1});
        stack.push_back({t.face, {M12, M20, M01}, subNet(t.net, m12, m20, m01), t.splits + 1});
    }

    // Every leaf corner once: irregular cells first (limit masks), then regular leaves (a corner of
    // the Bézier net is its surface point).
    TriangleKeys keys(mesh.faceVertices);
    std::unordered_map<Key, int, KeyHash> vertexOf;
    std::vector<Eigen::Vector3d> positions, normals;
    for (int pass = 0; pass < 2; ++pass)
        for (const Leaf& l : leaves) {
            if ((l.net < 0) != (pass == 0)) continue;
            for (int k = 0; k < 3; ++k) {
                const UV& uv = l.c[static_cast<std::size_t>(k)];
                const Key key = keys.key(l.face, uv[0], uv[1]);
                if (vertexOf.count(key)) continue;
                keys.registerPoint(l.face, uv[0], uv[1]);
                vertexOf.emplace(key, static_cast<int>(positions.size()));
                if (l.net < 0) {
                    const LoopIrregular& c = irregular[static_cast<std::size_t>(-1 - l.net)];
                    positions.push_back(c.corner[static_cast<std::size_t>(k)]);
                    normals.push_back(c.normal[static_cast<std::size_t>(k)]);
                } else {
                    const Net& b = leafNet[static_cast<std::size_t>(l.net)];
                    positions.push_back(k == 0 ? b[0][0] : k == 1 ? b[4][0] : b[0][4]);
                    normals.push_back(cornerNormal(b, k));
                }
            }
        }
    keys.sortLines();

    // OpenSubdiv's limit tangents have the vertex's own orientation: turn irregular corners' normals
    // to the side of their cell's triangle (counter-clockwise in (u, v), outward for a cage whose
    // faces run counter-clockwise); a missing normal becomes the cell's.
    for (const Leaf& l : leaves) {
        if (l.net >= 0) continue;
        const LoopIrregular& c = irregular[static_cast<std::size_t>(-1 - l.net)];
        const Eigen::Vector3d cellNormal = (c.corner[1] - c.corner[0]).cross(c.corner[2] - c.corner[0]).normalized();
        for (int k = 0; k < 3; ++k) {
            const UV& uv = l.c[static_cast<std::size_t>(k)];
            Eigen::Vector3d& n = normals[static_cast<std::size_t>(vertexOf.at(keys.key(l.face, uv[0], uv[1])))];
            if (n.isZero(0.0)) n = cellNormal;
            else if (n.dot(cellNormal) < 0) n = -n;
        }
    }

    // Triangulate every leaf as the polygon of its corners and side points.
    std::vector<int> triangles;
    LeafPolygon polygon;
    LeafTally tally(faces, tol);
    for (const Leaf& l : leaves) {
        triangulateLeaf(
            l.c, [&](const UV& p, const UV& q, std::vector<UV>& out) { keys.sidePoints(l.face, p, q, out); },
            [&](const UV& uv) { return vertexOf.at(keys.key(l.face, uv[0], uv[1])); }, polygon, triangles);
        tally.add(l.face, l.bound, l.tol, std::max(std::abs(l.c[1][0] - l.c[0][0]), std::abs(l.c[1][1] - l.c[0][1])));
    }

    PolygonMesh out = triangleMesh(positions, normals, std::move(triangles));
    if (report) certifiedReport(*report, *this, tally, regular.size(), irregular.size(), leaves.size(), depth);
    return out;
}

} // namespace freeform
