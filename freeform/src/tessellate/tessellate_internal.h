#pragma once
// What the pieces of the patch tessellation share (docs/surfaces.md, "Tessellation"): the
// tessellation's entry points, the grid and the verification (tessellate.cpp), the trees of
// sub-nets and their second-difference bounds (tessellate_tree.cpp), the geometric measure
// (tessellate_geometric.cpp) and the local mesher (tessellate_local.cpp). Private to
// src/tessellate/ (never installed).

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include "freeform/core/bernstein.h"
#include "freeform/tessellate/tessellate.h"

namespace freeform::tessellate_detail {

/// Union-find over the 2P segment counts (patch p: 2p is its u count, 2p+1 its v count).
struct Classes {
    std::vector<int> parent;
    explicit Classes(int n) : parent(static_cast<std::size_t>(n)) { std::iota(parent.begin(), parent.end(), 0); }
    int find(int x)
    {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    }
    void join(int a, int b) { parent[find(a)] = find(b); }
};

/// Exact key of a position (-0 and +0 alike).
struct PositionKey {
    double x, y, z;
    bool operator==(const PositionKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct PositionHash {
    std::size_t operator()(const PositionKey& k) const
    {
        std::size_t h = 1469598103934665603ull;
        for (double d : {k.x, k.y, k.z}) {
            std::uint64_t bits;
            std::memcpy(&bits, &d, sizeof bits);
            h = (h ^ bits) * 1099511628211ull;
        }
        return h;
    }
};

/// The side's curve in canonical orientation (the lexicographically smaller point sequence) and
/// whether that is the side's own order reversed. (tessellate.cpp)
std::pair<BezierCurve<double, 3>, bool> canonicalEdge(const Patch& p, PatchSide side);

/// The tolerance of patch p: its own (patchTolerance) or the one of every patch.
inline double toleranceOf(const TessellationOptions& options, int p)
{
    return options.patchTolerance.empty() ? options.tolerance : options.patchTolerance[static_cast<std::size_t>(p)];
}

/// Bernstein values b[0..n] and their derivatives db[0..n] at t. N > 0 fixes n = N at compile
/// time (the cubic case, unrolled by the compiler; the same operations, so the same numbers).
/// Always inlined, so that a caller's b and db can stay in registers (PatchRow::atOf).
template <int N = 0>
[[gnu::always_inline]] inline void basisWithDerivativeOf(int n, double t, double* b, double* db)
{
    if constexpr (N > 0) n = N;
    if (n == 0) {
        b[0] = 1;
        db[0] = 0;
        return;
    }
    double low[kMaxDegree + 1]; // degree n - 1 (core/bernstein.h), then its last level by hand
    bernsteinTriangle<(N > 1 ? N - 1 : 0)>(n - 1, t, low);
    const double s = 1 - t;
    for (int i = 0; i <= n; ++i) {
        const double a = i > 0 ? low[i - 1] : 0, c = i < n ? low[i] : 0;
        b[i] = t * a + s * c;
        db[i] = n * (a - c);
    }
}

inline void basisWithDerivative(int n, double t, double* b, double* db)
{
    if (n == 3) basisWithDerivativeOf<3>(n, t, b, db);
    else basisWithDerivativeOf(n, t, b, db);
}

/// A patch's position and first partial derivatives at a point.
struct Jet1 {
    Eigen::Vector3d p, fu, fv;
};

/// The largest value(D) over the second differences D of an (m+1) x (n+1) net (point (i, j) at
/// net[i*(n+1)+j]): {max over D_uu, max over D_uv, max over D_vv}. M, N > 0 fix the degrees at
/// compile time (the bicubic case, unrolled); M = N = 0 takes m, n.
template <int M, int N, class Point, class Value>
std::array<double, 3> maxSecondDifferencesOf(const Point* net, int m, int n, const Value& value)
{
    if constexpr (M > 0) {
        m = M;
        n = N;
    }
    const int w = n + 1;
    double uu = 0, uv = 0, vv = 0;
    for (int i = 0; i + 2 <= m; ++i)
        for (int j = 0; j <= n; ++j) uu = std::max(uu, value(net[(i + 2) * w + j] - 2 * net[(i + 1) * w + j] + net[i * w + j]));
    for (int i = 0; i < m; ++i)
        for (int j = 0; j < n; ++j)
            uv = std::max(uv, value(net[(i + 1) * w + j + 1] - net[(i + 1) * w + j] - net[i * w + j + 1] + net[i * w + j]));
    for (int i = 0; i <= m; ++i)
        for (int j = 0; j + 2 <= n; ++j) vv = std::max(vv, value(net[i * w + j + 2] - 2 * net[i * w + j + 1] + net[i * w + j]));
    return {uu, uv, vv};
}

template <class Point, class Value>
std::array<double, 3> maxSecondDifferences(const Point* net, int m, int n, const Value& value)
{
    if (m == 3 && n == 3) return maxSecondDifferencesOf<3, 3>(net, m, n, value);
    return maxSecondDifferencesOf<0, 0>(net, m, n, value);
}

/// The 25 second differences of a bicubic net: D_uu (i = 0..1, j = 0..3), D_uv (3 x 3), D_vv
/// (i = 0..3, j = 0..1), in the order of maxSecondDifferencesOf.
struct BicubicDifferences {
    Eigen::Vector3d uu[8], uv[9], vv[8];
};

/// A leaf of a patch's tree: [u0, u1] x [v0, v1] in units of 1/S of the patch's domain.
struct Leaf {
    std::int32_t u0, u1, v0, v1;
};

// ---- tessellate_tree.cpp

/// The three terms of the local bound of a net (m+1) x (n+1), point (i, j) at net[i*(n+1)+j]:
/// m(m-1) max|D_uu|, 2 m n max|D_uv|, n(n-1) max|D_vv| (their sum / 8 is the bound).
std::array<double, 3> netTerms(const Eigen::Vector3d* net, int m, int n);

/// The patch's control points as a net (point (i, j) at [i*(n+1)+j]).
std::vector<Eigen::Vector3d> netOf(const Patch& p);

/// De Casteljau split of an (m+1) x (n+1) net at t, in u or in v: lower gets [0, t], net (in
/// place) [t, 1].
void splitNet(Eigen::Vector3d* net, Eigen::Vector3d* lower, int m, int n, bool inU, double t);

/// Splits the patch's net until every leaf's bound is at most tolerance (or the leaves reach
/// minWidth), appending the leaves; returns the worst leaf bound (tessellate_tree.cpp says more).
double buildTree(const Patch& patch, double tolerance, bool geometric, std::int32_t minWidth, std::int32_t S,
                 std::vector<Leaf>& leaves, long long& leafCount, long long leafBudget, const std::string& budgetMessage);

// ---- tessellate_geometric.cpp

/// The leaf's bound b (its parametric bound, netTerms' sum / 8) lowered to its geometric bound
/// where that is smaller (docs/surfaces.md, "The geometric measure"): b as it is outside
/// (tolerance, 16 tolerance). net: the leaf's sub-net; terms: its netTerms; diff: its
/// second differences (bicubic nets only, else null); box: the leaf in units of 1/S.
double geometricLeafBound(double b, const Eigen::Vector3d* net, int m, int n, const BicubicDifferences* diff,
                          const std::array<double, 3>& terms, const Leaf& box, std::int32_t S, double tolerance);

// ---- tessellate_local.cpp

/// The adaptive mesh with local bounds (docs/surfaces.md, "Local refinement").
PolygonMesh tessellateLocal(const PatchComplex& complex, const TessellationOptions& options, TessellationReport* report);

} // namespace freeform::tessellate_detail
