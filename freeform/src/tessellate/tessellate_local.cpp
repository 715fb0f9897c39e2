// The local mesher (docs/surfaces.md, "Local refinement"): every patch's tree of leaves
// (buildTree, tessellate_tree.cpp), the samples on shared sides merged so that neighbours meet
// vertex for vertex, the vertices evaluated line by line (PatchRow) and welded on the sides, and
// each leaf cut into triangles: two, a fan from a corner, or by ear clipping where its sides hold
// the corners of finer neighbours.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "../mesh/convex_ring.h"
#include "tessellate_internal.h"

namespace freeform::tessellate_detail {

namespace {

/// The local mesher's vertices written straight into the mesh's matrices (no second copy of
/// every vertex, so about half the fresh memory a call touches): columns reserved from an
/// estimate (uninitialised, so untouched pages cost nothing), grown by doubling if it was short,
/// cut to the count at the end (realloc of the trailing columns, no copy). The normals are sums of
/// unit normals until finish() normalises them as finishMesh does.
struct MeshVertices {
    PolygonMesh& mesh;
    int size = 0;
    MeshVertices(PolygonMesh& m, Eigen::Index estimate) : mesh(m)
    {
        mesh.positions.resize(3, estimate);
        mesh.normals.resize(3, estimate);
        mesh.texcoords.resize(2, estimate);
    }
    int add(const Eigen::Vector3d& q, const Eigen::Vector3d& n, double u, double v)
    {
        if (size == mesh.positions.cols()) {
            const Eigen::Index grown = 2 * mesh.positions.cols() + 64;
            mesh.positions.conservativeResize(3, grown);
            mesh.normals.conservativeResize(3, grown);
            mesh.texcoords.conservativeResize(2, grown);
        }
        // Plain stores (Eigen's column assignment of a dynamic matrix is an out-of-line loop).
        double* P = mesh.positions.data() + 3 * static_cast<std::size_t>(size);
        double* N = mesh.normals.data() + 3 * static_cast<std::size_t>(size);
        double* T = mesh.texcoords.data() + 2 * static_cast<std::size_t>(size);
        P[0] = q.x(), P[1] = q.y(), P[2] = q.z();
        N[0] = n.x(), N[1] = n.y(), N[2] = n.z();
        T[0] = u, T[1] = v;
        return size++;
    }
    void addNormal(int k, const Eigen::Vector3d& n)
    {
        double* N = mesh.normals.data() + 3 * static_cast<std::size_t>(k);
        N[0] += n.x(), N[1] += n.y(), N[2] += n.z();
    }
    /// The same arithmetic as finishMesh.
    void finish(bool flip)
    {
        mesh.positions.conservativeResize(3, size);
        mesh.normals.conservativeResize(3, size);
        mesh.texcoords.conservativeResize(2, size);
        double* N = mesh.normals.data();
        for (int k = 0; k < size; ++k, N += 3) {
            Eigen::Vector3d n(N[0], N[1], N[2]);
            const double len = n.norm();
            n = len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
            if (flip) n = -n;
            N[0] = n.x(), N[1] = n.y(), N[2] = n.z();
        }
    }
};

/// f, f_u, f_v along a line u = const: the sums over i done once (the curves c(v) = f(u, v) and
/// d(v) = f_u(u, v)), then per v only the sums over j.
struct PatchRow {
    int n = 0;
    Eigen::Vector3d c[kMaxDegree + 1], d[kMaxDegree + 1];
    void set(const Patch& patch, double u)
    {
        const int m = patch.degreeU();
        n = patch.degreeV();
        double bu[kMaxDegree + 1], dbu[kMaxDegree + 1];
        basisWithDerivative(m, u, bu, dbu);
        const double* P = patch.controlPoints().data();
        for (int j = 0; j <= n; ++j) {
            c[j].setZero();
            d[j].setZero();
        }
        for (int i = 0; i <= m; ++i)
            for (int j = 0; j <= n; ++j) {
                const Eigen::Map<const Eigen::Vector3d> q(P + 3 * (i * (n + 1) + j));
                c[j] += bu[i] * q;
                d[j] += dbu[i] * q;
            }
    }
    Jet1 at(double v) const
    {
        double bv[kMaxDegree + 1], dbv[kMaxDegree + 1];
        basisWithDerivative(n, v, bv, dbv);
        // Per coordinate, the same sums in the same order as r.p += bv[j] * c[j] from zero (plain
        // scalars: GCC left Eigen's fixed-size loops out of line here).
        double p[3] = {0, 0, 0}, fu[3] = {0, 0, 0}, fv[3] = {0, 0, 0};
        for (int j = 0; j <= n; ++j)
            for (int e = 0; e < 3; ++e) {
                p[e] += bv[j] * c[j][e];
                fu[e] += bv[j] * d[j][e];
                fv[e] += dbv[j] * c[j][e];
            }
        return {Eigen::Vector3d(p[0], p[1], p[2]), Eigen::Vector3d(fu[0], fu[1], fu[2]), Eigen::Vector3d(fv[0], fv[1], fv[2])};
    }
    /// The numbers of at(v) into plain arrays (the same sums in the same order). For n = 3 the
    /// basis and the sums are unrolled with the degree known, so the basis stays in registers: a
    /// basis written as scalars and read back as 16-byte packets (what GCC made of at()) stalls on
    /// the store-to-load forwarding, on every vertex.
    void at(double v, double* p, double* fu, double* fv) const
    {
        if (n == 3) return atOf<3>(v, p, fu, fv);
        const Jet1 j = at(v);
        for (int e = 0; e < 3; ++e) p[e] = j.p[e], fu[e] = j.fu[e], fv[e] = j.fv[e];
    }
    template <int N>
    void atOf(double v, double* p, double* fu, double* fv) const
    {
        double bv[N + 1], dbv[N + 1];
        basisWithDerivativeOf<N>(N, v, bv, dbv);
        for (int e = 0; e < 3; ++e) p[e] = 0, fu[e] = 0, fv[e] = 0;
        for (int j = 0; j <= N; ++j)
            for (int e = 0; e < 3; ++e) {
                p[e] += bv[j] * c[j][e];
                fu[e] += bv[j] * d[j][e];
                fv[e] += dbv[j] * c[j][e];
            }
    }
};

/// Sorts (key, payload) pairs by key, key = a << 32 | b: two stable counting passes (b, then a) on
/// the coordinates divided by their largest common power of two when that leaves at most 2^16 + 1
/// buckets (always for the default maxSegments), std::sort otherwise.
void sortPairs(std::vector<std::pair<std::uint64_t, int>>& v, std::vector<std::pair<std::uint64_t, int>>& tmp,
               std::vector<int>& counts)
{
    std::uint64_t bitsA = 0, bitsB = 0, maxA = 0, maxB = 0;
    for (const auto& e : v) {
        const std::uint64_t a = e.first >> 32, b = e.first & 0xffffffffu;
        bitsA |= a;
        bitsB |= b;
        maxA = std::max(maxA, a);
        maxB = std::max(maxB, b);
    }
    const int shiftA = bitsA ? std::countr_zero(bitsA) : 0, shiftB = bitsB ? std::countr_zero(bitsB) : 0;
    const std::uint64_t bucketsA = (maxA >> shiftA) + 1, bucketsB = (maxB >> shiftB) + 1;
    if (bucketsA > 65537 || bucketsB > 65537) {
        std::sort(v.begin(), v.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
        return;
    }
    tmp.resize(v.size());
    // Each pass counts and places the two halves [0, half) and [half, size) of its input with their
    // own counters, interleaved: neighbours often fall in one bucket (a leaf's corners share their
    // coordinates), and one counter bumped by both would chain every increment through memory.
    // The second half's elements of a bucket go after the first half's: the same stable order.
    auto pass = [&](std::vector<std::pair<std::uint64_t, int>>& from, std::vector<std::pair<std::uint64_t, int>>& to,
                    std::uint64_t buckets, auto bucketOf) {
        const std::size_t size = from.size(), half = size / 2;
        counts.assign(2 * buckets, 0);
        int* first = counts.data();
        int* second = first + buckets;
        const auto* f = from.data();
        for (std::size_t k = 0; k < half; ++k) {
            ++first[bucketOf(f[k].first)];
            ++second[bucketOf(f[half + k].first)];
        }
        if (size % 2) ++second[bucketOf(f[size - 1].first)];
        int start = 0;
        for (std::size_t b = 0; b < buckets; ++b) {
            const int n1 = first[b], n2 = second[b];
            first[b] = start;
            second[b] = start + n1;
            start += n1 + n2;
        }
        auto* t = to.data();
        for (std::size_t k = 0; k < half; ++k) {
            const auto& x = f[k];
            const auto& y = f[half + k];
            t[first[bucketOf(x.first)]++] = x;
            t[second[bucketOf(y.first)]++] = y;
        }
        if (size % 2) t[second[bucketOf(f[size - 1].first)]++] = f[size - 1];
    };
    pass(v, tmp, bucketsB, [&](std::uint64_t key) { return static_cast<std::size_t>((key & 0xffffffffu) >> shiftB); });
    pass(tmp, v, bucketsA, [&](std::uint64_t key) { return static_cast<std::size_t>((key >> 32) >> shiftA); });
}

std::uint64_t packKey(std::int64_t a, std::int64_t b) { return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint64_t>(b); }

/// Twice the signed area of (p, q, r) in the integer parameters of keys (u << 32 | v); exact.
std::int64_t cross2(std::uint64_t p, std::uint64_t q, std::uint64_t r)
{
    const auto u = [](std::uint64_t k) { return static_cast<std::int64_t>(k >> 32); };
    const auto v = [](std::uint64_t k) { return static_cast<std::int64_t>(k & 0xffffffffu); };
    return (u(q) - u(p)) * (v(r) - v(p)) - (v(q) - v(p)) * (u(r) - u(p));
}

/// c.evaluate(t) (BezierCurve::deCasteljau: w_i = (1 - t) w_i + t w_(i+1), level by level) without
/// its copy of the control points on the heap (a malloc and a free per side vertex): the same
/// operations on each coordinate, so the same point.
Eigen::Vector3d curvePoint(const BezierCurve<double, 3>& c, double t)
{
    const int n = c.degree();
    double w[3 * (kMaxDegree + 1)];
    const double* P = c.controlPoints().data();
    std::copy(P, P + 3 * (n + 1), w);
    const double s = 1.0 - t;
    for (int k = 1; k <= n; ++k)
        for (int i = 0; i <= n - k; ++i)
            for (int e = 0; e < 3; ++e) w[3 * i + e] = s * w[3 * i + e] + t * w[3 * (i + 1) + e];
    return {w[0], w[1], w[2]};
}

} // namespace

/// The adaptive mesh with local bounds (docs/surfaces.md, "Local refinement").
PolygonMesh tessellateLocal(const PatchComplex& complex, const TessellationOptions& options, TessellationReport* report)
{
    const int count = static_cast<int>(complex.patches.size());
    const std::int32_t S = std::int32_t(1) << 30; // parameters in units of 2^-30
    const std::int32_t minWidth = std::max<std::int32_t>(1, S / options.maxSegments);
    TessellationReport rep;

    // 1. Trees, with a budget on the number of leaves (two triangles each at least).
    // Every patch's leaves in one array (patch p's at [treeStart[p], treeStart[p + 1])), reserved
    // from the one-grid estimate below so that it is written once, not copied as it grows
    // (untouched reserved pages cost nothing).
    std::vector<Leaf> allLeaves;
    std::vector<std::size_t> treeStart(static_cast<std::size_t>(count + 1), 0);
    long long leafCount = 0;
    const long long leafBudget = options.maxTriangles > 0 ? options.maxTriangles / 2 : 0;
    std::string budgetMessage;
    if (leafBudget > 0) {
        double grid = 0; // what one grid per patch would need (an estimate from above)
        for (int q = 0; q < count; ++q) {
            const Patch& p = complex.patches[q];
            const double tol = toleranceOf(options, q);
            const auto t = netTerms(netOf(p).data(), p.degreeU(), p.degreeV());
            const double nu = std::max(1.0, std::ceil(std::sqrt((t[0] + t[1] / 2) / 8 / (tol / 2))));
            const double nv = std::max(1.0, std::ceil(std::sqrt((t[2] + t[1] / 2) / 8 / (tol / 2))));
            grid += 2 * std::min(nu, double(options.maxSegments)) * std::min(nv, double(options.maxSegments));
        }
        char buffer[160];
        double smallest = options.tolerance;
        for (double t : options.patchTolerance) smallest = smallest > 0 ? std::min(smallest, t) : t;
        std::snprintf(buffer, sizeof buffer, "tolerance %g needs more than maxTriangles = %lld triangles (estimate: ", smallest,
                      options.maxTriangles);
        budgetMessage = std::string("tessellate: ") + buffer;
        std::snprintf(buffer, sizeof buffer, "more than %lld counted before stopping, about %.3g with one grid per patch", 2 * leafBudget,
                      grid);
        budgetMessage += std::string(buffer) + "); raise the limit (--max-triangles) or the tolerance";
        // (At most 2^20 leaves, 16 MB: a huge estimate or maxTriangles must not make the reserve fail.)
        allLeaves.reserve(static_cast<std::size_t>(std::min({grid / 2, static_cast<double>(leafBudget), 1048576.0}) + 64));
    }
    struct Tree {
        const Leaf *first, *last;
        const Leaf* begin() const { return first; }
        const Leaf* end() const { return last; }
        std::size_t size() const { return static_cast<std::size_t>(last - first); }
        const Leaf& operator[](std::size_t k) const { return first[k]; }
    };
    auto treeOf = [&](int p) {
        return Tree{allLeaves.data() + treeStart[static_cast<std::size_t>(p)], allLeaves.data() + treeStart[static_cast<std::size_t>(p) + 1]};
    };
    for (int p = 0; p < count; ++p) {
        const double tol = toleranceOf(options, p);
        const double b = buildTree(complex.patches[p], tol, options.measure == TessellationMeasure::Geometric, minWidth, S, allLeaves,
                                   leafCount, leafBudget, budgetMessage);
        treeStart[static_cast<std::size_t>(p) + 1] = allLeaves.size();
        rep.errorBound = std::max(rep.errorBound, b);
        rep.patchBound.push_back(b);
        rep.worstRatio = std::max(rep.worstRatio, b / tol);
        std::int32_t finestU = S, finestV = S;
        for (const Leaf& l : treeOf(p)) {
            finestU = std::min(finestU, l.u1 - l.u0);
            finestV = std::min(finestV, l.v1 - l.v0);
        }
        rep.required.push_back({S / finestU, S / finestV});
        rep.segments.push_back({S / finestU, S / finestV});
    }
    rep.leaves = leafCount;

    // 2. Samples on the sides: per side the leaf corners on it (canonical parameters), merged over
    //    every class of shared sides.
    struct Side {
        BezierCurve<double, 3> curve;
        bool reversed, collapsed;
    };
    std::vector<Side> sides;
    sides.reserve(static_cast<std::size_t>(4 * count));
    std::vector<std::vector<std::int32_t>> sidePoints(static_cast<std::size_t>(4 * count));
    for (int p = 0; p < count; ++p) {
        for (int s = 0; s < 4; ++s) {
            auto [curve, reversed] = canonicalEdge(complex.patches[p], static_cast<PatchSide>(s));
            sides.push_back({std::move(curve), reversed, isCollapsedEdge(complex.patches[p], static_cast<PatchSide>(s))});
        }
        for (const Leaf& l : treeOf(p)) {
            if (l.u0 == 0) sidePoints[4 * p + 0].insert(sidePoints[4 * p + 0].end(), {l.v0, l.v1});
            if (l.u1 == S) sidePoints[4 * p + 1].insert(sidePoints[4 * p + 1].end(), {l.v0, l.v1});
            if (l.v0 == 0) sidePoints[4 * p + 2].insert(sidePoints[4 * p + 2].end(), {l.u0, l.u1});
            if (l.v1 == S) sidePoints[4 * p + 3].insert(sidePoints[4 * p + 3].end(), {l.u0, l.u1});
        }
        for (int s = 0; s < 4; ++s)
            if (sides[4 * p + s].reversed)
                for (std::int32_t& t : sidePoints[4 * p + s]) t = S - t;
    }
    Classes classes(4 * count);
    for (const SharedEdge& e : sharedEdges(complex, 0))
        classes.join(4 * e.a.patch + static_cast<int>(e.a.side), 4 * e.b.patch + static_cast<int>(e.b.side));
    {
        std::vector<std::vector<std::int32_t>> merged(static_cast<std::size_t>(4 * count));
        for (int k = 0; k < 4 * count; ++k) {
            auto& into = merged[classes.find(k)];
            into.insert(into.end(), sidePoints[k].begin(), sidePoints[k].end());
        }
        for (auto& v : merged) {
            std::sort(v.begin(), v.end());
            v.erase(std::unique(v.begin(), v.end()), v.end());
        }
        for (int k = 0; k < 4 * count; ++k) {
            if (classes.find(k) != k) sidePoints[k] = merged[classes.find(k)];
        }
        for (int k = 0; k < 4 * count; ++k)
            if (classes.find(k) == k) sidePoints[k] = std::move(merged[k]);
        for (int k = 0; k < 4 * count; ++k)
            if (sides[k].reversed)
                for (std::int32_t& t : sidePoints[k]) t = S - t;
    }

    // 3. Vertices and triangles, patch by patch.
    PolygonMesh mesh;
    // (An open-addressing table in one array instead was no fewer instructions and raised the
    // page faults per call in a loop of calls from 270 to 656: without the map's small blocks
    // glibc trims the heap when the mesh is freed, so every call faults its pages in afresh;
    // docs/performance.md.)
    std::unordered_map<PositionKey, int, PositionHash> welded;
    std::vector<int> faces;
    // About 2.05 triangles and 1.05 vertices per leaf on the teapot: reserved, so that the arrays
    // are written once instead of being copied as they grow (fresh pages cost, docs/performance.md).
    faces.reserve(static_cast<std::size_t>(3 * (2.2 * leafCount + 64)));
    MeshVertices vertices(mesh, static_cast<Eigen::Index>(1.2 * leafCount + 64));
    const double inv = 1.0 / S;
    std::vector<std::uint64_t> keys;                         // (u << 32 | v), sorted: the lines u = const
    std::vector<std::pair<std::uint64_t, int>> byV;          // (v << 32 | u, index into keys)
    std::vector<int> ids;                                    // mesh vertex of each key
    std::vector<Eigen::Vector3d> keyPos;                     // its position
    std::vector<int> ring;                                   // ring of a leaf: indices into keys, or -1 (centre)
    std::vector<std::pair<std::uint64_t, int>> items, scratch; // (key, corner slot)
    std::vector<int> counts;
    std::vector<int> cornerIndex, positionV;                 // slot -> key index; key index -> place in byV
    PatchRow row;
    for (int p = 0; p < count; ++p) {
        const Patch& patch = complex.patches[p];
        const Tree leaves = treeOf(p);
        // Keys sorted with the leaf corner (slot 4 leaf + corner, -1 for side samples) they came
        // from, so that every corner knows its index without a search.
        // (Written in place: an insert of an initializer list built the four pairs on the stack
        // with 8- and 4-byte stores and copied them with 16-byte loads, which stall on the
        // store-to-load forwarding.)
        items.clear();
        items.reserve(leaves.size() * 4 + 16);
        items.resize(leaves.size() * 4);
        for (std::size_t l = 0; l < leaves.size(); ++l) {
            const Leaf& f = leaves[l];
            const int slot = static_cast<int>(4 * l);
            std::pair<std::uint64_t, int>* out = items.data() + slot;
            out[0].first = packKey(f.u0, f.v0), out[0].second = slot;
            out[1].first = packKey(f.u1, f.v0), out[1].second = slot + 1;
            out[2].first = packKey(f.u1, f.v1), out[2].second = slot + 2;
            out[3].first = packKey(f.u0, f.v1), out[3].second = slot + 3;
        }
        for (std::int32_t t : sidePoints[4 * p + 0]) items.push_back({packKey(0, t), -1});
        for (std::int32_t t : sidePoints[4 * p + 1]) items.push_back({packKey(S, t), -1});
        for (std::int32_t t : sidePoints[4 * p + 2]) items.push_back({packKey(t, 0), -1});
        for (std::int32_t t : sidePoints[4 * p + 3]) items.push_back({packKey(t, S), -1});
        sortPairs(items, scratch, counts);
        keys.clear();
        cornerIndex.resize(leaves.size() * 4);
        for (const auto& [key, slot] : items) {
            if (keys.empty() || keys.back() != key) keys.push_back(key);
            if (slot >= 0) cornerIndex[static_cast<std::size_t>(slot)] = static_cast<int>(keys.size()) - 1;
        }
        const int nk = static_cast<int>(keys.size());
        byV.resize(static_cast<std::size_t>(nk));
        ids.resize(static_cast<std::size_t>(nk));
        keyPos.resize(static_cast<std::size_t>(nk));
        std::int32_t rowU = -1;
        for (int k = 0; k < nk; ++k) {
            const std::int32_t u = static_cast<std::int32_t>(keys[k] >> 32), v = static_cast<std::int32_t>(keys[k] & 0xffffffffu);
            byV[k] = {packKey(v, u), k};
            if (u != rowU) { // keys run along lines u = const: the u sums once per line
                row.set(patch, u * inv);
                rowU = u;
            }
            // Position: on a side from its canonical curve (bit-identical in every patch that shares it).
            int side = -1;
            std::int32_t t = 0;
            if (u == 0) side = 0, t = v;
            else if (u == S) side = 1, t = v;
            else if (v == 0) side = 2, t = u;
            else if (v == S) side = 3, t = u;
            double jp[3], ju[3], jv[3]; // f, f_u, f_v as plain numbers (see PatchRow::at)
            row.at(v * inv, jp, ju, jv);
            Eigen::Vector3d q(jp[0], jp[1], jp[2]);
            bool onCollapsed = false;
            if (side >= 0) {
                const Side& sd = sides[4 * p + side];
                const std::int32_t tc = sd.reversed ? S - t : t;
                q = sd.curve.controlPoint(0);
                if (!sd.collapsed) q = curvePoint(sd.curve, tc * inv);
                for (int s = 0; s < 4; ++s) {
                    const bool on = (s == 0 && u == 0) || (s == 1 && u == S) || (s == 2 && v == 0) || (s == 3 && v == S);
                    if (on && sides[4 * p + s].collapsed) onCollapsed = true;
                }
            }
            // f_u x f_v, its squared norm and |f_u|^2, |f_v|^2 in plain numbers, formed as Eigen's
            // cross, squaredNorm and norm form them ((x^2 + y^2) + z^2; norm = sqrt(squaredNorm)).
            const double cx = ju[1] * jv[2] - ju[2] * jv[1], cy = ju[2] * jv[0] - ju[0] * jv[2], cz = ju[0] * jv[1] - ju[1] * jv[0];
            const double len2 = cx * cx + cy * cy + cz * cz, len = std::sqrt(len2);
            // len > 1e-10 |f_u| |f_v| without the two square roots where it clearly holds: len^2 >
            // 1e-19 |f_u|^2 |f_v|^2 (ten times the margin of the few roundings), all in the normal range.
            const double fu2 = ju[0] * ju[0] + ju[1] * ju[1] + ju[2] * ju[2], fv2 = jv[0] * jv[0] + jv[1] * jv[1] + jv[2] * jv[2];
            const double product = fu2 * fv2;
            const bool clearlyRegular = product > 1e-250 && product < 1e250 && len2 > 1e-19 * product;
            Eigen::Vector3d nrm;
            if (onCollapsed || (!clearlyRegular && (!(len > 1e-10 * std::sqrt(fu2) * std::sqrt(fv2)) || len == 0)))
                nrm = patch.normal(u * inv, v * inv);
            else
                nrm = Eigen::Vector3d(cx / len, cy / len, cz / len);
            keyPos[k] = q;
            if (side >= 0) {
                const PositionKey key{q.x() + 0.0, q.y() + 0.0, q.z() + 0.0};
                const auto [it, inserted] = welded.try_emplace(key, vertices.size);
                ids[k] = it->second;
                if (!inserted) {
                    vertices.addNormal(it->second, nrm);
                    continue;
                }
            }
            ids[k] = vertices.add(q, nrm, u * inv, v * inv);
        }
        sortPairs(byV, scratch, counts);
        positionV.resize(static_cast<std::size_t>(nk));
        for (int k = 0; k < nk; ++k) positionV[static_cast<std::size_t>(byV[k].second)] = k;
        auto uvOf = [&](int k) {
            return Eigen::Vector2d(static_cast<double>(keys[k] >> 32) * inv, static_cast<double>(keys[k] & 0xffffffffu) * inv);
        };
        for (std::size_t li = 0; li < leaves.size(); ++li) {
            const int i00 = cornerIndex[4 * li], i10 = cornerIndex[4 * li + 1], i11 = cornerIndex[4 * li + 2],
                      i01 = cornerIndex[4 * li + 3];
            int corner[4], hanging[4];
            // p00, then v = v0 rising in u, p10, u = u1 rising in v, p11, v = v1 falling, p01, u = u0 falling.
            // (The ring's size known first, so it is written without push_back's checks.)
            hanging[0] = std::max(0, positionV[i10] - positionV[i00] - 1);
            hanging[1] = i11 - i10 - 1;
            hanging[2] = positionV[i11] - positionV[i01] - 1;
            hanging[3] = i01 - i00 - 1;
            corner[0] = 0;
            corner[1] = corner[0] + 1 + hanging[0];
            corner[2] = corner[1] + 1 + std::max(0, hanging[1]);
            corner[3] = corner[2] + 1 + std::max(0, hanging[2]);
            ring.resize(static_cast<std::size_t>(corner[3] + 1 + std::max(0, hanging[3])));
            int* out = ring.data();
            *out++ = i00;
            for (int k = positionV[i00] + 1; k < positionV[i10]; ++k) *out++ = byV[k].second;
            *out++ = i10;
            for (int k = i10 + 1; k < i11; ++k) *out++ = k;
            *out++ = i11;
            for (int k = positionV[i11] - 1; k > positionV[i01]; --k) *out++ = byV[k].second;
            *out++ = i01;
            for (int k = i01 - 1; k > i00; --k) *out++ = k;

            auto emit = [&](int a, int b, int c) {
                const int ia = ids[a], ib = ids[b], ic = ids[c];
                if (ia == ib || ib == ic || ia == ic) return; // at a collapsed side
                faces.push_back(ia);
                faces.push_back(options.flipNormals ? ic : ib);
                faces.push_back(options.flipNormals ? ib : ic);
                if (options.sampleDeviation) {
                    const TriangleDeviation d =
                        sampleTriangleDeviation(patch, {uvOf(a), uvOf(b), uvOf(c)}, {keyPos[a], keyPos[b], keyPos[c]});
                    rep.measuredParametric = std::max(rep.measuredParametric, d.parametric);
                    rep.measuredGeometric = std::max(rep.measuredGeometric, d.geometric);
                }
            };
            const int n = static_cast<int>(ring.size());
            if (n == 4) {
                // The shorter diagonal (the bound holds for either).
                const int a = ring[0], b = ring[1], c = ring[2], d = ring[3];
                if ((keyPos[a] - keyPos[c]).squaredNorm() <= (keyPos[b] - keyPos[d]).squaredNorm()) {
                    emit(a, b, c);
                    emit(a, c, d);
                } else {
                    emit(a, b, d);
                    emit(b, c, d);
                }
                continue;
            }
            // A corner whose two sides have no extra points: fan from it over the two far sides.
            // Otherwise clip ears. Every triangle has its corners in the leaf, so it has the leaf's
            // bound (docs/surfaces.md, "The error bound of one triangle", Lemma 2).
            int from = -1;
            for (int c = 0; c < 4 && from < 0; ++c)
                if (hanging[c] == 0 && hanging[(c + 3) % 4] == 0) from = c;
            if (from >= 0) {
                const int o = corner[from];
                for (int k = 1; k + 1 < n; ++k) emit(ring[o], ring[(o + k) % n], ring[(o + k + 1) % n]);
            } else {
                // The ear whose new edge is shortest in space (mesh/convex_ring.h).
                detail::clipConvexRing(
                    ring, [&](int a, int b, int c) { return cross2(keys[a], keys[b], keys[c]); },
                    [&](int a, int b, int c) { emit(a, b, c); },
                    [&](int a, int c) { return (keyPos[a] - keyPos[c]).squaredNorm(); });
            }
        }
    }
    vertices.finish(options.flipNormals);
    mesh.faceVertices = std::move(faces);
    mesh.faceStart.resize(mesh.faceVertices.size() / 3 + 1);
    for (std::size_t f = 0; f < mesh.faceStart.size(); ++f) mesh.faceStart[f] = static_cast<int>(3 * f);
    if (report) *report = std::move(rep);
    return mesh;
}

} // namespace freeform::tessellate_detail
