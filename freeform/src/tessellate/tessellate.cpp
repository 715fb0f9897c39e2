// Patch complexes to triangle meshes: certified counts per patch, matched across shared sides,
// vertices welded on shared sides (docs/surfaces.md, "Tessellation").

#include "freeform/tessellate/tessellate.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <numeric>
#include <string>
#include <type_traits>
#include <unordered_map>

#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include "freeform/core/bernstein.h"
#include "freeform/core/error.h"

namespace freeform {

namespace {

struct DerivativeBounds {
    double uu = 0, uv = 0, vv = 0;
};

/// Bounds of |f_uu|, |f_uv|, |f_vv| over the patch from the control net (convex hull property of
/// the second-derivative patches).
DerivativeBounds derivativeBounds(const Patch& p)
{
    const int m = p.degreeU(), n = p.degreeV();
    DerivativeBounds b;
    for (int i = 0; i <= m; ++i) {
        for (int j = 0; j <= n; ++j) {
            if (i + 2 <= m)
                b.uu = std::max(b.uu, (p.controlPoint(i + 2, j) - 2 * p.controlPoint(i + 1, j) + p.controlPoint(i, j)).norm());
            if (j + 2 <= n)
                b.vv = std::max(b.vv, (p.controlPoint(i, j + 2) - 2 * p.controlPoint(i, j + 1) + p.controlPoint(i, j)).norm());
            if (i + 1 <= m && j + 1 <= n)
                b.uv = std::max(b.uv, (p.controlPoint(i + 1, j + 1) - p.controlPoint(i + 1, j) - p.controlPoint(i, j + 1) +
                                       p.controlPoint(i, j)).norm());
        }
    }
    b.uu *= m * (m - 1.0);
    b.vv *= n * (n - 1.0);
    b.uv *= static_cast<double>(m) * n;
    return b;
}

double bound(const DerivativeBounds& b, int nu, int nv)
{
    const double x = 1.0 / nu, y = 1.0 / nv;
    return b.uu * x * x / 8 + b.uv * x * y / 4 + b.vv * y * y / 8;
}

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

/// Which count governs a side: sides U0/U1 run along v (count nv), V0/V1 along u (count nu).
int countOf(const PatchEdge& e)
{
    return 2 * e.patch + ((e.side == PatchSide::U0 || e.side == PatchSide::U1) ? 1 : 0);
}

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
/// whether that is the side's own order reversed.
std::pair<BezierCurve<double, 3>, bool> canonicalEdge(const Patch& p, PatchSide side)
{
    const BezierCurve<double, 3> c = edgeCurve(p, side);
    const auto& pts = c.controlPoints();
    const Eigen::Index count = pts.cols();
    for (Eigen::Index k = 0; k < count; ++k) {
        for (int d = 0; d < 3; ++d) {
            const double a = pts(d, k) + 0.0, b = pts(d, count - 1 - k) + 0.0;
            if (a < b) return {c, false};
            if (a > b) return {c.reversed(), true};
        }
    }
    return {c, false};
}

} // namespace

double tessellationErrorBound(const Patch& patch, int segmentsU, int segmentsV)
{
    if (segmentsU < 1 || segmentsV < 1) throw Error("tessellationErrorBound: segment counts must be at least 1");
    return bound(derivativeBounds(patch), segmentsU, segmentsV);
}

std::array<int, 2> adaptiveSegments(const Patch& patch, double tolerance, int maxSegments)
{
    if (!(tolerance > 0) || !std::isfinite(tolerance)) throw Error("adaptiveSegments: tolerance must be positive and finite");
    if (maxSegments < 1) throw Error("adaptiveSegments: maxSegments must be at least 1");
    const DerivativeBounds b = derivativeBounds(patch);
    // Every nu with the smallest nv that meets the tolerance; then the fewest cells, preferring
    // (within 25 % more cells) the grid whose cells are closest to square in the parameters.
    std::vector<std::array<int, 2>> candidates;
    for (int nu = 1; nu <= maxSegments; ++nu) {
        const double x = 1.0 / nu;
        const double rest = tolerance - b.uu * x * x / 8;
        if (rest <= 0) continue;
        // Largest y with (M_vv/8) y^2 + (M_uv/4) x y <= rest.
        const double qa = b.vv / 8, qb = b.uv * x / 4;
        double y;
        if (qa > 0) y = (-qb + std::sqrt(qb * qb + 4 * qa * rest)) / (2 * qa);
        else if (qb > 0) y = rest / qb;
        else y = 1;
        int nv = std::max(1, static_cast<int>(std::ceil(1.0 / std::min(y, 1.0) - 1e-9)));
        while (nv <= maxSegments && bound(b, nu, nv) > tolerance) ++nv;
        if (nv > maxSegments) continue;
        candidates.push_back({nu, nv});
        if (nv == 1) break; // more u segments cannot help
    }
    if (candidates.empty()) return {maxSegments, maxSegments};
    long fewest = -1;
    for (const auto& c : candidates) {
        const long cells = static_cast<long>(c[0]) * c[1];
        if (fewest < 0 || cells < fewest) fewest = cells;
    }
    std::array<int, 2> best = candidates.front();
    double bestShape = std::numeric_limits<double>::infinity();
    for (const auto& c : candidates) {
        const long cells = static_cast<long>(c[0]) * c[1];
        if (cells * 4 > fewest * 5) continue;
        const double shape = std::abs(std::log(static_cast<double>(c[0]) / c[1]));
        if (shape < bestShape || (shape == bestShape && cells < static_cast<long>(best[0]) * best[1])) {
            bestShape = shape;
            best = c;
        }
    }
    return best;
}

namespace {

/// The tolerance of patch p: its own (patchTolerance) or the one of every patch.
double toleranceOf(const TessellationOptions& options, int p)
{
    return options.patchTolerance.empty() ? options.tolerance : options.patchTolerance[static_cast<std::size_t>(p)];
}

/// The mesh from the collected arrays (normals normalised, flipped on request); the report out.
PolygonMesh finishMesh(std::vector<Eigen::Vector3d>&& positions, std::vector<Eigen::Vector3d>&& normals,
                       std::vector<Eigen::Vector2d>&& texcoords, std::vector<int>&& faces, const TessellationOptions& options,
                       TessellationReport& rep, TessellationReport* report)
{
    PolygonMesh mesh;
    const int v = static_cast<int>(positions.size());
    mesh.positions.resize(3, v);
    mesh.normals.resize(3, v);
    mesh.texcoords.resize(2, v);
    for (int k = 0; k < v; ++k) {
        mesh.positions.col(k) = positions[k];
        Eigen::Vector3d n = normals[k];
        const double len = n.norm();
        n = len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
        mesh.normals.col(k) = options.flipNormals ? Eigen::Vector3d(-n) : n;
        mesh.texcoords.col(k) = texcoords[k];
    }
    mesh.faceVertices = std::move(faces);
    mesh.faceStart.resize(mesh.faceVertices.size() / 3 + 1);
    for (std::size_t f = 0; f < mesh.faceStart.size(); ++f) mesh.faceStart[f] = static_cast<int>(3 * f);
    if (report) *report = std::move(rep);
    return mesh;
}

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

// ------------------------------------------------------------------ local (tree) refinement

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
    double low[kMaxDegree + 1]; // degree n - 1
    low[0] = 1;
    const double s = 1 - t;
    for (int k = 1; k < n; ++k) {
        double carry = 0;
        for (int i = 0; i < k; ++i) {
            const double x = low[i];
            low[i] = carry + s * x;
            carry = t * x;
        }
        low[k] = carry;
    }
    for (int i = 0; i <= n; ++i) {
        const double a = i > 0 ? low[i - 1] : 0, c = i < n ? low[i] : 0;
        b[i] = t * a + s * c;
        db[i] = n * (a - c);
    }
}

void basisWithDerivative(int n, double t, double* b, double* db)
{
    if (n == 3) basisWithDerivativeOf<3>(n, t, b, db);
    else basisWithDerivativeOf(n, t, b, db);
}

struct Jet1 {
    Eigen::Vector3d p, fu, fv;
};

/// Position and first partial derivatives (tensor-product Bernstein sums).
Jet1 jet1(const Patch& patch, double u, double v)
{
    const int m = patch.degreeU(), n = patch.degreeV();
    double bu[kMaxDegree + 1], dbu[kMaxDegree + 1], bv[kMaxDegree + 1], dbv[kMaxDegree + 1];
    basisWithDerivative(m, u, bu, dbu);
    basisWithDerivative(n, v, bv, dbv);
    const double* P = patch.controlPoints().data();
    Jet1 r{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    for (int i = 0; i <= m; ++i) {
        Eigen::Vector3d row = Eigen::Vector3d::Zero(), rowV = Eigen::Vector3d::Zero();
        for (int j = 0; j <= n; ++j) {
            const Eigen::Map<const Eigen::Vector3d> q(P + 3 * (i * (n + 1) + j));
            row += bv[j] * q;
            rowV += dbv[j] * q;
        }
        r.p += bu[i] * row;
        r.fu += dbu[i] * row;
        r.fv += bu[i] * rowV;
    }
    return r;
}

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

/// The three terms of the local bound of a net (m+1) x (n+1), point (i, j) at net[i*(n+1)+j]:
/// m(m-1) max|D_uu|, 2 m n max|D_uv|, n(n-1) max|D_vv| (their sum / 8 is the bound).
std::array<double, 3> netTerms(const Eigen::Vector3d* net, int m, int n)
{
    const auto d = maxSecondDifferences(net, m, n, [](const Eigen::Vector3d& x) { return x.squaredNorm(); });
    return {m * (m - 1.0) * std::sqrt(d[0]), 2.0 * m * n * std::sqrt(d[1]), n * (n - 1.0) * std::sqrt(d[2])};
}

/// The 25 second differences of a bicubic net: D_uu (i = 0..1, j = 0..3), D_uv (3 x 3), D_vv
/// (i = 0..3, j = 0..1), in the order of maxSecondDifferencesOf.
struct BicubicDifferences {
    Eigen::Vector3d uu[8], uv[9], vv[8];
};

#ifndef __SSE2__
void bicubicDifferences(const Eigen::Vector3d* net, BicubicDifferences& d)
{
    // Each row of the net (points 4 i .. 4 i + 3) is 12 contiguous numbers, and so is each row of
    // every difference net (uu: 12, uv: 9, vv: 6 numbers): whole rows at once, the same operations
    // on each number as point by point (uu(i, j) = x(i + 2, j) - 2 x(i + 1, j) + x(i, j), uv(i, j) =
    // x(i + 1, j + 1) - x(i + 1, j) - x(i, j + 1) + x(i, j), vv(i, j) = x(i, j + 2) - 2 x(i, j + 1) +
    // x(i, j)), so the same values, in vector registers.
    const double* x = net[0].data();
    auto at = [x]<int N>(std::integral_constant<int, N>, int i, int offset) {
        return Eigen::Map<const Eigen::Matrix<double, N, 1>>(x + 12 * i + offset);
    };
    constexpr std::integral_constant<int, 12> n12;
    constexpr std::integral_constant<int, 9> n9;
    constexpr std::integral_constant<int, 6> n6;
    for (int i = 0; i < 2; ++i)
        Eigen::Map<Eigen::Matrix<double, 12, 1>>(d.uu[4 * i].data()) = at(n12, i + 2, 0) - 2 * at(n12, i + 1, 0) + at(n12, i, 0);
    for (int i = 0; i < 3; ++i)
        Eigen::Map<Eigen::Matrix<double, 9, 1>>(d.uv[3 * i].data()) = at(n9, i + 1, 3) - at(n9, i + 1, 0) - at(n9, i, 3) + at(n9, i, 0);
    for (int i = 0; i < 4; ++i)
        Eigen::Map<Eigen::Matrix<double, 6, 1>>(d.vv[2 * i].data()) = at(n6, i, 6) - 2 * at(n6, i, 3) + at(n6, i, 0);
}

/// netTerms of a bicubic net from its differences (the same values). (Without SSE2 only: with it,
/// bicubicDifferencesAndTerms below does both in one pass.)
std::array<double, 3> bicubicTerms(const BicubicDifferences& d)
{
    double uu = 0, uv = 0, vv = 0;
    for (const auto& x : d.uu) uu = std::max(uu, x.squaredNorm());
    for (const auto& x : d.uv) uv = std::max(uv, x.squaredNorm());
    for (const auto& x : d.vv) vv = std::max(vv, x.squaredNorm());
    return {3 * (3 - 1.0) * std::sqrt(uu), 2.0 * 3 * 3 * std::sqrt(uv), 3 * (3 - 1.0) * std::sqrt(vv)};
}
#endif

#ifdef __SSE2__
/// The squared norms of two points whose six numbers are the packets (x0, y0), (z0, x1), (y1, z1),
/// each summed as Eigen sums a Vector3d's squaredNorm, (x^2 + y^2) + z^2: the same values.
inline __m128d squaredNormsOfPair(__m128d p0, __m128d p1, __m128d p2)
{
    const __m128d q0 = _mm_mul_pd(p0, p0), q1 = _mm_mul_pd(p1, p1), q2 = _mm_mul_pd(p2, p2);
    const __m128d xs = _mm_move_sd(q1, q0);       // (x0^2, x1^2)
    const __m128d ys = _mm_shuffle_pd(q0, q2, 1); // (y0^2, y1^2)
    const __m128d zs = _mm_move_sd(q2, q1);       // (z0^2, z1^2)
    return _mm_add_pd(_mm_add_pd(xs, ys), zs);
}
#endif

/// bicubicDifferences and bicubicTerms in one pass (the same values): with SSE2 the net's 16
/// points are 24 packets held in registers, each difference is formed packet by packet with the
/// same operations on each number, stored in the layout of bicubicDifferences, and its squared
/// norm taken from the registers instead of being read back.
std::array<double, 3> bicubicDifferencesAndTerms(const Eigen::Vector3d* net, BicubicDifferences& d)
{
#ifdef __SSE2__
    const double* x = net[0].data();
    __m128d P[4][6], S[4][4]; // row i's numbers (2k, 2k + 1), and (2k + 3, 2k + 4)
    for (int i = 0; i < 4; ++i) {
        for (int k = 0; k < 6; ++k) P[i][k] = _mm_loadu_pd(x + 12 * i + 2 * k);
        for (int k = 0; k < 4; ++k) S[i][k] = _mm_shuffle_pd(P[i][k + 1], P[i][k + 2], 1);
    }
    const __m128d two = _mm_set1_pd(2.0);
    // D_uu(i, j) = x(i + 2, j) - 2 x(i + 1, j) + x(i, j): rows of 12 numbers.
    __m128d bestUu = _mm_setzero_pd();
    double* uu = d.uu[0].data();
    for (int i = 0; i < 2; ++i) {
        __m128d r[6];
        for (int k = 0; k < 6; ++k) {
            r[k] = _mm_add_pd(_mm_sub_pd(P[i + 2][k], _mm_mul_pd(two, P[i + 1][k])), P[i][k]);
            _mm_storeu_pd(uu + 12 * i + 2 * k, r[k]);
        }
        // maxpd gives its second operand where either is NaN: a NaN is passed over, as by std::max.
        bestUu = _mm_max_pd(squaredNormsOfPair(r[0], r[1], r[2]), bestUu);
        bestUu = _mm_max_pd(squaredNormsOfPair(r[3], r[4], r[5]), bestUu);
    }
    // D_uv(i, j) = x(i + 1, j + 1) - x(i + 1, j) - x(i, j + 1) + x(i, j): rows of 9 numbers, the
    // first 8 as packets, the ninth (x(., 3) and x(., 2)'s last coordinates) as a scalar.
    __m128d bestUv = _mm_setzero_pd();
    double* uv = d.uv[0].data();
    __m128d third[3][2]; // each row's third point: (its x, y), (its z, z)
    for (int i = 0; i < 3; ++i) {
        __m128d r[4];
        for (int k = 0; k < 4; ++k) {
            r[k] = _mm_add_pd(_mm_sub_pd(_mm_sub_pd(S[i + 1][k], P[i + 1][k]), S[i][k]), P[i][k]);
            _mm_storeu_pd(uv + 9 * i + 2 * k, r[k]);
        }
        const double* a = x + 12 * (i + 1);
        const double* c = x + 12 * i;
        const double last = ((a[11] - a[8]) - c[11]) + c[8];
        uv[9 * i + 8] = last;
        bestUv = _mm_max_pd(squaredNormsOfPair(r[0], r[1], r[2]), bestUv);
        third[i][0] = r[3];
        third[i][1] = _mm_set1_pd(last);
    }
    for (int i = 0; i < 3; i += 2) { // rows (0, 1), then row 2 with itself
        const int j = std::min(i + 1, 2);
        const __m128d xs = _mm_unpacklo_pd(third[i][0], third[j][0]), ys = _mm_unpackhi_pd(third[i][0], third[j][0]);
        const __m128d zs = _mm_unpacklo_pd(third[i][1], third[j][1]);
        const __m128d sq = _mm_add_pd(_mm_add_pd(_mm_mul_pd(xs, xs), _mm_mul_pd(ys, ys)), _mm_mul_pd(zs, zs));
        bestUv = _mm_max_pd(sq, bestUv);
    }
    // D_vv(i, j) = x(i, j + 2) - 2 x(i, j + 1) + x(i, j): rows of 6 numbers.
    __m128d bestVv = _mm_setzero_pd();
    double* vv = d.vv[0].data();
    for (int i = 0; i < 4; ++i) {
        __m128d r[3];
        for (int k = 0; k < 3; ++k) {
            r[k] = _mm_add_pd(_mm_sub_pd(P[i][k + 3], _mm_mul_pd(two, S[i][k])), P[i][k]);
            _mm_storeu_pd(vv + 6 * i + 2 * k, r[k]);
        }
        bestVv = _mm_max_pd(squaredNormsOfPair(r[0], r[1], r[2]), bestVv);
    }
    double lanes[3][2];
    _mm_storeu_pd(lanes[0], bestUu);
    _mm_storeu_pd(lanes[1], bestUv);
    _mm_storeu_pd(lanes[2], bestVv);
    const double mu = std::max(lanes[0][0], lanes[0][1]), mc = std::max(lanes[1][0], lanes[1][1]),
                 mv = std::max(lanes[2][0], lanes[2][1]);
    return {3 * (3 - 1.0) * std::sqrt(mu), 2.0 * 3 * 3 * std::sqrt(mc), 3 * (3 - 1.0) * std::sqrt(mv)};
#else
    bicubicDifferences(net, d);
    return bicubicTerms(d);
#endif
}

std::vector<Eigen::Vector3d> netOf(const Patch& p)
{
    std::vector<Eigen::Vector3d> net(static_cast<std::size_t>(p.controlPoints().cols()));
    for (std::size_t k = 0; k < net.size(); ++k) net[k] = p.controlPoints().col(static_cast<Eigen::Index>(k));
    return net;
}

/// A leaf of a patch's tree: [u0, u1] x [v0, v1] in units of 1/S of the patch's domain.
struct Leaf {
    std::int32_t u0, u1, v0, v1;
};

/// De Casteljau split of net at t, in u or in v: lower gets [0, t], net (in place) [t, 1].
/// De Casteljau along `outer + 1` lines of a net (stride between the points of a line, step between
/// lines); Deg > 0 fixes the degree at compile time, Deg = 0 takes deg.
template <int Deg>
void splitLines(Eigen::Vector3d* net, Eigen::Vector3d* lower, int deg, int outer, int stride, int step, double t)
{
    if constexpr (Deg > 0) deg = Deg;
    Eigen::Vector3d w[(Deg > 0 ? Deg : kMaxDegree) + 1];
    const double s = 1 - t;
    for (int o = 0; o <= outer; ++o) {
        Eigen::Vector3d* line = net + o * step;
        Eigen::Vector3d* low = lower + o * step;
        for (int k = 0; k <= deg; ++k) w[k] = line[k * stride];
        low[0] = w[0];
        for (int r = 1; r <= deg; ++r) {
            for (int k = 0; k <= deg - r; ++k) w[k] = s * w[k] + t * w[k + 1];
            low[r * stride] = w[0];
            line[(deg - r) * stride] = w[deg - r];
        }
    }
}

/// The bicubic split in u: the four lines' points k are one row of 12 contiguous numbers, so the
/// rows are combined whole (the same operations on each number as splitLines, so the same results,
/// in vector registers).
void splitBicubicU(Eigen::Vector3d* net, Eigen::Vector3d* lower, double t)
{
    using Row = Eigen::Matrix<double, 12, 1>;
    auto row = [](Eigen::Vector3d* p, int k) { return Eigen::Map<Row>(p[4 * k].data()); };
    const double s = 1 - t;
    const Row w0 = row(net, 0), w1 = row(net, 1), w2 = row(net, 2), w3 = row(net, 3);
    const Row a0 = s * w0 + t * w1, a1 = s * w1 + t * w2, a2 = s * w2 + t * w3;
    const Row b0 = s * a0 + t * a1, b1 = s * a1 + t * a2;
    const Row c0 = s * b0 + t * b1;
    row(lower, 0) = w0;
    row(lower, 1) = a0;
    row(lower, 2) = b0;
    row(lower, 3) = c0;
    row(net, 0) = c0;
    row(net, 1) = b1;
    row(net, 2) = a2;
}

/// The bicubic split in v: each line is a row of the net (points 4 o .. 4 o + 3).
void splitBicubicV(Eigen::Vector3d* net, Eigen::Vector3d* lower, double t)
{
    const double s = 1 - t;
    for (int o = 0; o < 4; ++o) {
        Eigen::Vector3d* line = net + 4 * o;
        Eigen::Vector3d* low = lower + 4 * o;
        const Eigen::Vector3d w0 = line[0], w1 = line[1], w2 = line[2], w3 = line[3];
        const Eigen::Vector3d a0 = s * w0 + t * w1, a1 = s * w1 + t * w2, a2 = s * w2 + t * w3;
        const Eigen::Vector3d b0 = s * a0 + t * a1, b1 = s * a1 + t * a2;
        const Eigen::Vector3d c0 = s * b0 + t * b1;
        low[0] = w0;
        low[1] = a0;
        low[2] = b0;
        low[3] = c0;
        line[0] = c0;
        line[1] = b1;
        line[2] = a2;
    }
}

void splitNet(Eigen::Vector3d* net, Eigen::Vector3d* lower, int m, int n, bool inU, double t)
{
    if (m == 3 && n == 3) return inU ? splitBicubicU(net, lower, t) : splitBicubicV(net, lower, t);
    const int deg = inU ? m : n, outer = inU ? n : m;
    const int stride = inU ? n + 1 : 1, step = inU ? 1 : n + 1; // along the split direction, across it
    if (deg == 3) splitLines<3>(net, lower, deg, outer, stride, step, t);
    else splitLines<0>(net, lower, deg, outer, stride, step, t);
}

// ---- The geometric measure (docs/surfaces.md, "The geometric measure"). A leaf has local
// parameters x = (s, t) in [0, 1]^2, centre c = (1/2, 1/2); a point x is described by (a, b) =
// (|s - 1/2|, |t - 1/2|) in [0, 1/2]^2.

/// sqrt(x^2 + y^2) (no overflow concerns at these magnitudes; std::hypot is several times slower).
double norm2(double x, double y) { return std::sqrt(x * x + y * y); }

/// Bounds of |g_ss|, |g_st|, |g_tt| over a leaf (or of |d . g_ss|, ... for a projected net).
struct Second {
    double ss = 0, st = 0, tt = 0;
};

Second secondOf(const std::array<double, 3>& terms) { return {terms[0], terms[1] / 2, terms[2]}; }

/// max over k of |d . x[k]|, from 0, NaNs passed over (as the loop of std::max did; the maximum
/// does not depend on the order of the k). With SSE2 two vectors at once: their six numbers are three 16-byte loads, multiplied by
/// (d_x, d_y), (d_z, d_x), (d_y, d_z) and regrouped by coordinate, so each dot product is summed
/// as Eigen sums a Vector3d's, (d_x x_x + d_y x_y) + d_z x_z: the same values.
template <int Count>
double largestProjection(const Eigen::Vector3d* x, const Eigen::Vector3d& d)
{
    int k = 0;
    double m = 0;
#ifdef __SSE2__
    const double* p = x[0].data();
    const __m128d dxy = _mm_set_pd(d.y(), d.x()), dzx = _mm_set_pd(d.x(), d.z()), dyz = _mm_set_pd(d.z(), d.y());
    const __m128d sign = _mm_set1_pd(-0.0);
    __m128d best = _mm_setzero_pd();
    for (; k + 2 <= Count; k += 2, p += 6) {
        const __m128d m0 = _mm_mul_pd(_mm_loadu_pd(p), dxy);     // (d_x x0, d_y y0)
        const __m128d m1 = _mm_mul_pd(_mm_loadu_pd(p + 2), dzx); // (d_z z0, d_x x1)
        const __m128d m2 = _mm_mul_pd(_mm_loadu_pd(p + 4), dyz); // (d_y y1, d_z z1)
        const __m128d xs = _mm_move_sd(m1, m0);                  // (d_x x0, d_x x1)
        const __m128d ys = _mm_shuffle_pd(m0, m2, 1);            // (d_y y0, d_y y1)
        const __m128d zs = _mm_move_sd(m2, m1);                  // (d_z z0, d_z z1)
        // maxpd gives its second operand where either is NaN: a NaN is passed over, as by std::max.
        best = _mm_max_pd(_mm_andnot_pd(sign, _mm_add_pd(_mm_add_pd(xs, ys), zs)), best);
    }
    double lanes[2];
    _mm_storeu_pd(lanes, best);
    m = std::max(lanes[0], lanes[1]);
#endif
    for (; k < Count; ++k) m = std::max(m, std::abs(d.dot(x[k])));
    return m;
}

/// The bounds of |d . g_ss|, |d . g_st|, |d . g_tt| over the leaf for a unit vector d: the scalar
/// patch d . g has the sub-net projected on d, and its second derivatives lie in the convex hulls
/// of that net's differences.
Second projectedBounds(const Eigen::Vector3d* net, int m, int n, const Eigen::Vector3d& d, const BicubicDifferences* diff)
{
    if (diff) {
        // d . D for the net's differences D (the differences of the projected net, up to rounding).
        const double uu = largestProjection<8>(diff->uu, d), uv = largestProjection<9>(diff->uv, d),
                     vv = largestProjection<8>(diff->vv, d);
        return {6 * uu, 9 * uv, 6 * vv};
    }
    // The net projected first: scalar differences.
    thread_local std::vector<double> projected;
    const int size = (m + 1) * (n + 1);
    if (projected.size() < static_cast<std::size_t>(size)) projected.resize(static_cast<std::size_t>(size));
    for (int k = 0; k < size; ++k) projected[k] = d.dot(net[k]);
    const auto p = maxSecondDifferences(projected.data(), m, n, [](double x) { return std::abs(x); });
    return {m * (m - 1.0) * p[0], double(m) * n * p[1], n * (n - 1.0) * p[2]};
}

/// g_s(c) and g_t(c) at the leaf's centre.
void centreDerivatives(const Eigen::Vector3d* net, int m, int n, Eigen::Vector3d& gs, Eigen::Vector3d& gt)
{
    if (m == 3 && n == 3) {
        // Bernstein values at 1/2 (1, 3, 3, 1)/8 and derivatives (-3, -3, 3, 3)/4.
        constexpr double b[4] = {0.125, 0.375, 0.375, 0.125}, db[4] = {-0.75, -0.75, 0.75, 0.75};
        Eigen::Vector3d rows[4], rowsV[4];
        for (int i = 0; i < 4; ++i) {
            rows[i] = b[0] * net[4 * i] + b[1] * net[4 * i + 1] + b[2] * net[4 * i + 2] + b[3] * net[4 * i + 3];
            rowsV[i] = db[0] * net[4 * i] + db[1] * net[4 * i + 1] + db[2] * net[4 * i + 2] + db[3] * net[4 * i + 3];
        }
        gs = db[0] * rows[0] + db[1] * rows[1] + db[2] * rows[2] + db[3] * rows[3];
        gt = b[0] * rowsV[0] + b[1] * rowsV[1] + b[2] * rowsV[2] + b[3] * rowsV[3];
        return;
    }
    const int w = n + 1;
    struct Basis {
        int m = -1, n = -1;
        double bu[kMaxDegree + 1], dbu[kMaxDegree + 1], bv[kMaxDegree + 1], dbv[kMaxDegree + 1];
    };
    thread_local Basis basis; // the Bernstein values at 1/2 of the last degrees asked for
    if (basis.m != m || basis.n != n) {
        basisWithDerivative(m, 0.5, basis.bu, basis.dbu);
        basisWithDerivative(n, 0.5, basis.bv, basis.dbv);
        basis.m = m;
        basis.n = n;
    }
    const double *bu = basis.bu, *dbu = basis.dbu, *bv = basis.bv, *dbv = basis.dbv;
    gs.setZero();
    gt.setZero();
    for (int i = 0; i <= m; ++i)
        for (int j = 0; j <= n; ++j) {
            gs += dbu[i] * bv[j] * net[i * w + j];
            gt += bu[i] * dbv[j] * net[i * w + j];
        }
}

/// Bounds of |g_ss|, |g_st|, |g_tt| (in the leaf's s, t) over the leaf grown by deltaS on both
/// sides in s and deltaT in t: the net of that rectangle by de Casteljau at 1 + delta and then
/// -delta / (1 + delta) (the same polynomial, parametrised over the larger interval).
/// The matrices E_k (k = 1, 2, 3) with sum_j E_k(i, j) c_j the Bernstein coefficients over
/// [-delta, 1 + delta] of the degree-k polynomial with coefficients c_j over [0, 1]: its blossom at
/// k - i arguments -delta and i arguments 1 + delta, with A = 1 + delta, B = -delta (each row sums
/// to (A + B)^k = 1; delta = 0 gives the identity).
struct Extensions {
    double e1[2][2], e2[3][3], e3[4][4];
    explicit Extensions(double delta)
    {
        const double A = 1 + delta, B = -delta, A2 = A * A, B2 = B * B, AB = A * B;
        const double r1[2][2] = {{A, B}, {B, A}};
        const double r2[3][3] = {{A2, 2 * AB, B2}, {AB, A2 + B2, AB}, {B2, 2 * AB, A2}};
        const double r3[4][4] = {{A2 * A, 3 * A2 * B, 3 * A * B2, B2 * B},
                                 {A2 * B, A2 * A + 2 * A * B2, 2 * A2 * B + B2 * B, A * B2},
                                 {A * B2, 2 * A2 * B + B2 * B, A2 * A + 2 * A * B2, A2 * B},
                                 {B2 * B, 3 * A * B2, 3 * A2 * B, A2 * A}};
        std::memcpy(e1, r1, sizeof e1);
        std::memcpy(e2, r2, sizeof e2);
        std::memcpy(e3, r3, sizeof e3);
    }
};

/// max |x| over the net (Rows x Cols, x(i, j) at d[i * Cols + j]) extended by Es (along i) and Et
/// (along j).
template <int Rows, int Cols>
double largestExtended(const Eigen::Vector3d* d, const double (&Es)[Rows][Rows], const double (&Et)[Cols][Cols])
{
#ifdef __SSE2__
    // Two outputs j, j + 1 at once, one coordinate per register (an odd last j paired with itself,
    // which does not change the maximum). Every number is the sum the loops below form, in the
    // same order (products Et[j][0] d_0 + Et[j][1] d_1 + ..., then Es[i][0] along_0j + ..., then
    // (x^2 + y^2) + z^2 as Eigen sums a squaredNorm): the same values, fewer instructions.
    constexpr int Pairs = (Cols + 1) / 2;
    __m128d c[Pairs][Cols];
    for (int q = 0; q < Pairs; ++q)
        for (int l = 0; l < Cols; ++l) c[q][l] = _mm_set_pd(Et[std::min(2 * q + 1, Cols - 1)][l], Et[2 * q][l]);
    __m128d alongs[Rows][Pairs][3];
    for (int i = 0; i < Rows; ++i)
        for (int e = 0; e < 3; ++e) {
            __m128d b[Cols];
            for (int l = 0; l < Cols; ++l) b[l] = _mm_set1_pd(d[i * Cols + l][e]);
            for (int q = 0; q < Pairs; ++q) {
                __m128d x = _mm_mul_pd(c[q][0], b[0]);
                for (int l = 1; l < Cols; ++l) x = _mm_add_pd(x, _mm_mul_pd(c[q][l], b[l]));
                alongs[i][q][e] = x;
            }
        }
    __m128d best = _mm_setzero_pd();
    for (int i = 0; i < Rows; ++i) {
        __m128d es[Rows];
        for (int l = 0; l < Rows; ++l) es[l] = _mm_set1_pd(Es[i][l]);
        for (int q = 0; q < Pairs; ++q) {
            __m128d x[3];
            for (int e = 0; e < 3; ++e) {
                x[e] = _mm_mul_pd(es[0], alongs[0][q][e]);
                for (int l = 1; l < Rows; ++l) x[e] = _mm_add_pd(x[e], _mm_mul_pd(es[l], alongs[l][q][e]));
            }
            const __m128d sq = _mm_add_pd(_mm_add_pd(_mm_mul_pd(x[0], x[0]), _mm_mul_pd(x[1], x[1])), _mm_mul_pd(x[2], x[2]));
            best = _mm_max_pd(sq, best); // a NaN passed over, as by std::max below
        }
    }
    double lanes[2];
    _mm_storeu_pd(lanes, best);
    return std::sqrt(std::max(lanes[0], lanes[1]));
#else
    Eigen::Vector3d along[Rows * Cols]; // extended along j first
    for (int i = 0; i < Rows; ++i)
        for (int j = 0; j < Cols; ++j) {
            Eigen::Vector3d x = Et[j][0] * d[i * Cols];
            for (int l = 1; l < Cols; ++l) x += Et[j][l] * d[i * Cols + l];
            along[i * Cols + j] = x;
        }
    double largest = 0;
    for (int i = 0; i < Rows; ++i)
        for (int j = 0; j < Cols; ++j) {
            Eigen::Vector3d x = Es[i][0] * along[j];
            for (int l = 1; l < Rows; ++l) x += Es[i][l] * along[l * Cols + j];
            largest = std::max(largest, x.squaredNorm());
        }
    return std::sqrt(largest);
#endif
}

/// grownBounds of a bicubic net from its second differences: the second-difference nets of the
/// grown net are those of the leaf extended to the grown rectangle (de Casteljau commutes with
/// differencing; the factors (1 + 2 delta)^2 of the longer interval cancel against fs, ft), so
/// only 25 differences are extended instead of the net being split four times.
Second grownBicubicBounds(const BicubicDifferences& d, double deltaS, double deltaT)
{
    const Extensions s(deltaS), t(deltaT);
    return {6 * largestExtended<2, 4>(d.uu, s.e1, t.e3), 9 * largestExtended<3, 3>(d.uv, s.e2, t.e2),
            6 * largestExtended<4, 2>(d.vv, s.e3, t.e1)};
}

Second grownBounds(const Eigen::Vector3d* net, int m, int n, double deltaS, double deltaT, const BicubicDifferences* diff)
{
    if (diff) return grownBicubicBounds(*diff, std::max(deltaS, 0.0), std::max(deltaT, 0.0));
    const int size = (m + 1) * (n + 1);
    thread_local std::vector<Eigen::Vector3d> buffer;
    if (buffer.size() < static_cast<std::size_t>(2 * size)) buffer.resize(static_cast<std::size_t>(2 * size));
    Eigen::Vector3d* grown = buffer.data();
    Eigen::Vector3d* spare = grown + size;
    std::copy(net, net + size, grown);
    for (int dir = 0; dir < 2; ++dir) {
        const double delta = dir == 0 ? deltaS : deltaT;
        if (!(delta > 0)) continue;
        splitNet(grown, spare, m, n, dir == 0, 1 + delta);           // spare: [0, 1 + delta]
        splitNet(spare, grown, m, n, dir == 0, -delta / (1 + delta)); // spare: [-delta, 1 + delta]
        std::copy(spare, spare + size, grown);
    }
    const Second g = secondOf(netTerms(grown, m, n));
    const double fs = 1 / (1 + 2 * deltaS), ft = 1 / (1 + 2 * deltaT);
    return {g.ss * fs * fs, g.st * fs * ft, g.tt * ft * ft};
}

/// The interpolation error bound at a point (a, b) of the leaf for every triangle with its vertices
/// in the leaf (docs/surfaces.md, Lemma 2): (M_ss (1/4 - a^2) + 2 M_st sqrt((1/4 - a^2)(1/4 - b^2)) +
/// M_tt (1/4 - b^2)) / 2, falling in a and in b.
double pointError(const Second& M, double a, double b)
{
    const double vs = 0.25 - a * a, vt = 0.25 - b * b;
    return 0.5 * (M.ss * vs + 2 * M.st * std::sqrt(vs * vt) + M.tt * vt);
}

/// The same from the factors (1/4 - a^2, 1/4 - b^2, their geometric mean), shared by several bounds.
struct PointFactors {
    double vs, vt, cov;
    PointFactors(double a, double b) : vs(0.25 - a * a), vt(0.25 - b * b), cov(std::sqrt(vs * vt)) {}
    double error(const Second& M) const { return 0.5 * (M.ss * vs + 2 * M.st * cov + M.tt * vt); }
};

/// An upper bound of sup f over [0, 1/2]^2 from cellBound(a0, a1, b0, b1) (an upper bound of f on
/// that cell): cells of a 2 x 2 grid, each split in four while its bound exceeds target, down to
/// cells 2^-(depth + 1) wide; once a cell of the finest size exceeds target, the rest is only
/// evaluated (the result then exceeds target anyway). The result is the largest final cell bound.
template <class CellBound>
double refineCells(const CellBound& cellBound, double target, int depth)
{
    struct Cell {
        double a0, b0, w;
        int level;
    };
    Cell stack[4 + 3 * 16];
    int top = 0;
    for (int k = 0; k < 4; ++k) stack[top++] = {(k & 1) * 0.25, (k >> 1) * 0.25, 0.25, 1};
    double worst = 0;
    bool failed = false;
    while (top > 0) {
        const Cell c = stack[--top];
        const double v = cellBound(c.a0, c.a0 + c.w, c.b0, c.b0 + c.w);
        if (v <= target || failed || c.level >= depth) {
            worst = std::max(worst, v);
            if (v > target) failed = true;
            continue;
        }
        const double h = c.w / 2;
        for (int k = 0; k < 4; ++k) stack[top++] = {c.a0 + (k & 1) * h, c.b0 + (k >> 1) * h, h, c.level + 1};
    }
    return worst;
}

// refineCells down to cells 1/32 wide in (a, b) (depth 3: 1.3 % more triangles on the teapot at 1e-3).
constexpr int kCellDepth = 4;
// The steps' maxima from 2 x 2 cells (4 x 4: 4 triangles fewer on the teapot at 1e-3, more time).
constexpr int kStepGrid = 2;
// Leaves whose parametric bound exceeds 16 tolerances do not try the geometric one.
constexpr double kGeometricRange = 16;

/// Bounds of the two components of the foot point's step delta(x) on the cell [a0, a1] x [b0, b1]
/// (docs/surfaces.md, "The geometric measure", step 1): with delta_c = A_c^+ E(x), whose components
/// r1 . E and r2 . E are bounded by the nets projected on the rows r1, r2 of A_c^+, |delta -
/// delta_c| <= rho(x) |E(x)| / (sigma_c sigma(x)), rho(x) the bound of |A(x) - A_c|; and |delta| <=
/// |E(x)| / sigma(x). Infinite where sigma(x) may vanish.
struct StepBounds {
    const Second &M, &R1, &R2;
    double sigmaC;
    std::array<double, 2> operator()(double a0, double a1, double b0, double b1) const { return at(PointFactors(a0, b0), a1, b1); }
    /// The same with the factors of (a0, b0) given (the cell bound needs them too).
    std::array<double, 2> at(const PointFactors& f, double a1, double b1) const
    {
        const double rho = norm2(M.ss * a1 + M.st * b1, M.st * a1 + M.tt * b1);
        const double sig = sigmaC - rho;
        if (!(sig > 0)) return {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
        const double e = f.error(M), whole = e / sig, extra = rho * whole / sigmaC;
        return {std::min(whole, f.error(R1) + extra), std::min(whole, f.error(R2) + extra)};
    }
};

/// The largest bounds of the step's components over the leaf, on a grid of cells.
template <class Steps>
std::array<double, 2> largestStep(const Steps& steps, std::array<std::array<double, 2>, kStepGrid * kStepGrid>& cells)
{
    std::array<double, 2> worst{0, 0};
    for (int ia = 0; ia < kStepGrid; ++ia)
        for (int ib = 0; ib < kStepGrid; ++ib) {
            const double w = 0.5 / kStepGrid;
            const auto d = steps(ia * w, (ia + 1) * w, ib * w, (ib + 1) * w);
            cells[static_cast<std::size_t>(ia + kStepGrid * ib)] = d;
            worst = {std::max(worst[0], d[0]), std::max(worst[1], d[1])};
        }
    return worst;
}

/// What geometricBound finds at the leaf's centre, reused by geometricBoundAlong on the same leaf
/// (the same numbers it would compute again): g_s(c), g_t(c), |g_s x g_t|, the unit normal n0 and
/// N = projectedBounds on n0 (set only where len > 0).
struct Centre {
    Eigen::Vector3d gs, gt, n0;
    double len = 0;
    Second N;
};

/// The geometric bound of a leaf (docs/surfaces.md, "The geometric measure"): every triangle point
/// T(x) of the leaf lies within the returned distance of a surface point g(y), y = x + delta(x) in
/// the patch's domain, chosen so that T(x) - g(x + delta) runs along the normal n0 at the leaf's
/// centre up to second-order terms. Infinity where the argument does not apply (a near-singular
/// leaf, delta could leave the patch's domain, or the bound cannot reach the tolerance). net: the
/// leaf's sub-net; terms: its netTerms; box: the leaf in units of 1/S.
double geometricBound(const Eigen::Vector3d* net, int m, int n, const BicubicDifferences* diff, const std::array<double, 3>& terms, const Leaf& box,
                      std::int32_t S, double tolerance, Centre& centre)
{
    constexpr double inf = std::numeric_limits<double>::infinity();
    Eigen::Vector3d& gs = centre.gs;
    Eigen::Vector3d& gt = centre.gt;
    centreDerivatives(net, m, n, gs, gt);
    const Eigen::Vector3d cross = gs.cross(gt);
    const double len = centre.len = cross.norm();
    if (!(len > 0)) return inf;
    const Eigen::Vector3d n0 = centre.n0 = cross / len;
    centre.N = projectedBounds(net, m, n, n0, diff);
    const Second M = secondOf(terms), N = centre.N;
    if (pointError(N, 0, 0) > tolerance) return inf; // |n0 . E(c)| alone
    const double a11 = gs.squaredNorm(), a12 = gs.dot(gt), a22 = gt.squaredNorm(), det = a11 * a22 - a12 * a12;
    if (!(det > 0)) return inf;
    const double sigmaC = std::sqrt(std::max(0.0, 0.5 * (a11 + a22 - std::sqrt((a11 - a22) * (a11 - a22) + 4 * a12 * a12))));
    const double hu = static_cast<double>(box.u1 - box.u0) / S, hv = static_cast<double>(box.v1 - box.v0) / S;
    if (box.u0 == 0 || box.u1 == S || box.v0 == 0 || box.v1 == S) {
        // A leaf at a patch's side fails the domain test below whenever the step bound across
        // that side is positive, and it is at least min(whole, extra) of the first cell (the cell
        // (0, 1/4) x (0, 1/4) as StepBounds::at computes it, whose other term only adds a bound
        // >= 0). Where that times the leaf's width exceeds 1e-15 (so that 1 + it > 1 too), the
        // answer is infinity without the projections on the rows of A_c^+.
        const double rho = norm2(M.ss * 0.25 + M.st * 0.25, M.st * 0.25 + M.tt * 0.25);
        const double sig = sigmaC - rho;
        if (sig > 0) {
            const double whole = PointFactors(0, 0).error(M) / sig, extra = rho * whole / sigmaC, lower = std::min(whole, extra);
            if (std::isfinite(lower) && (((box.u0 == 0 || box.u1 == S) && lower * hu > 1e-15) ||
                                         ((box.v0 == 0 || box.v1 == S) && lower * hv > 1e-15)))
                return inf;
        }
    }
    // Rows of A_c^+ = (A_c^T A_c)^-1 A_c^T, A_c = [g_s(c), g_t(c)].
    const Eigen::Vector3d r1 = (a22 * gs - a12 * gt) / det, r2 = (a11 * gt - a12 * gs) / det;
    const Second R1 = projectedBounds(net, m, n, r1, diff), R2 = projectedBounds(net, m, n, r2, diff);
    const StepBounds steps{M, R1, R2, sigmaC};
    std::array<std::array<double, 2>, kStepGrid * kStepGrid> firstCells; // refineCells starts on these cells
    const auto Delta = largestStep(steps, firstCells);
    if (!std::isfinite(Delta[0]) || !std::isfinite(Delta[1])) return inf;
    if (static_cast<double>(box.u0) / S - Delta[0] * hu < 0 || static_cast<double>(box.u1) / S + Delta[0] * hu > 1 ||
        static_cast<double>(box.v0) / S - Delta[1] * hv < 0 || static_cast<double>(box.v1) / S + Delta[1] * hv > 1)
        return inf;
    // The remainder of g(x + delta) over the segment, inside the leaf grown by Delta.
    const Second G = grownBounds(net, m, n, Delta[0], Delta[1], diff);
    auto cell = [&](double a0, double a1, double b0, double b1) {
        const PointFactors f(a0, b0);
        // The first 2 x 2 cells are largestStep's (the same numbers): their steps are known.
        const bool first = kStepGrid == 2 && a1 - a0 == 0.25;
        const auto d = first ? firstCells[static_cast<std::size_t>((a0 == 0 ? 0 : 1) + 2 * (b0 == 0 ? 0 : 1))] : steps.at(f, a1, b1);
        if (!std::isfinite(d[0]) || !std::isfinite(d[1])) return inf;
        // |n0 . g_s(x)| <= N_ss a + N_st b, |n0 . g_t(x)| <= N_st a + N_tt b (zero at the centre).
        const double tiltS = N.ss * a1 + N.st * b1, tiltT = N.st * a1 + N.tt * b1;
        const double remainder = 0.5 * (G.ss * d[0] * d[0] + 2 * G.st * d[0] * d[1] + G.tt * d[1] * d[1]);
        return f.error(N) + tiltS * d[0] + tiltT * d[1] + remainder;
    };
    return refineCells(cell, tolerance, kCellDepth);
}

/// The geometric bound of a leaf at a patch's side (docs/surfaces.md, "At a patch's sides"): the
/// foot point is sought along one parameter only (along = 1: t, y = x + (0, delta); along = 0: s),
/// so the leaf only needs room in that direction. With the unit tangent a = g_t(c)/|g_t(c)| (g_s for
/// along = 0) and c1 = n0 x a, delta cancels a . E, and the rest of E - g_t(x) delta lies along n0
/// and c1, each bounded from the projected sub-nets.
/// centre: what geometricBound found on the same leaf.
double geometricBoundAlong(const Eigen::Vector3d* net, int m, int n, const BicubicDifferences* diff, const std::array<double, 3>& terms, const Leaf& box,
                           std::int32_t S, int along, double tolerance, const Centre& centre)
{
    const Eigen::Vector3d &gs = centre.gs, &gt = centre.gt;
    const double len = centre.len;
    const Eigen::Vector3d& g = along == 1 ? gt : gs;
    const double gLen = g.norm();
    if (!(len > 0) || !(gLen > 0)) return std::numeric_limits<double>::infinity();
    const Second& N = centre.N;
    // The test below fails whenever |n0 . E(c)| alone exceeds the tolerance (geometricBound's
    // centre test): sqrt(x * x + y * y) >= sqrt(fl(x * x)) = x in round-to-nearest binary
    // arithmetic while x * x neither overflows nor underflows; then C need not be projected.
    const double centreN = pointError(N, 0, 0);
    if (centreN > tolerance && centreN > 1e-150 && centreN < 1e150) return std::numeric_limits<double>::infinity();
    const Eigen::Vector3d &n0 = centre.n0, a = g / gLen, c1 = n0.cross(a);
    const Second M = secondOf(terms), C = projectedBounds(net, m, n, c1, diff);
    if (norm2(centreN, pointError(C, 0, 0)) > tolerance) return std::numeric_limits<double>::infinity();
    // a . g_t(x) >= |g_t(c)| - |g_t(x) - g_t(c)| >= |g_t(c)| - (M_st a + M_tt b) (s: M_ss a + M_st b).
    // |a . E(x)| from the net projected on a; a . g_t(x) >= |g_t(c)| - |g_t(x) - g_t(c)| >= |g_t(c)| -
    // (M_st a + M_tt b) (s: M_ss a + M_st b).
    const Second A = projectedBounds(net, m, n, a, diff);
    auto stepAt = [&](const PointFactors& f, double a1, double b1) {
        const double sig = along == 1 ? gLen - (M.st * a1 + M.tt * b1) : gLen - (M.ss * a1 + M.st * b1);
        if (!(sig > 0)) return std::numeric_limits<double>::infinity();
        return f.error(A) / sig;
    };
    auto step = [&](double a0, double a1, double b0, double b1) { return stepAt(PointFactors(a0, b0), a1, b1); };
    double Delta = 0;
    for (int ia = 0; ia < 4; ++ia)
        for (int ib = 0; ib < 4; ++ib) Delta = std::max(Delta, step(ia * 0.125, (ia + 1) * 0.125, ib * 0.125, (ib + 1) * 0.125));
    if (!std::isfinite(Delta)) return Delta;
    const double h = static_cast<double>(along == 1 ? box.v1 - box.v0 : box.u1 - box.u0) / S;
    const double lo = static_cast<double>(along == 1 ? box.v0 : box.u0) / S, hi = static_cast<double>(along == 1 ? box.v1 : box.u1) / S;
    if (lo - Delta * h < 0 || hi + Delta * h > 1) return std::numeric_limits<double>::infinity();
    // Only the second derivative along the step is needed: for a bicubic net just that one of
    // grownBicubicBounds' three extended nets (the same value; the other two were unused work).
    double quad;
    if (diff) {
        const Extensions s(along == 0 ? Delta : 0.0), t(along == 1 ? Delta : 0.0);
        quad = 0.5 * (along == 1 ? 6 * largestExtended<4, 2>(diff->vv, s.e3, t.e1) : 6 * largestExtended<2, 4>(diff->uu, s.e1, t.e3));
    } else {
        const Second G = grownBounds(net, m, n, along == 0 ? Delta : 0, along == 1 ? Delta : 0, diff);
        quad = 0.5 * (along == 1 ? G.tt : G.ss);
    }
    auto cell = [&](double a0, double a1, double b0, double b1) {
        const PointFactors f(a0, b0);
        const double d = stepAt(f, a1, b1);
        if (!std::isfinite(d)) return d;
        // |d . g_t(x)| <= D_st a + D_tt b for d orthogonal to g_t(c) (s: D_ss a + D_st b).
        const double slopeN = along == 1 ? N.st * a1 + N.tt * b1 : N.ss * a1 + N.st * b1;
        const double slopeC = along == 1 ? C.st * a1 + C.tt * b1 : C.ss * a1 + C.st * b1;
        return norm2(f.error(N) + slopeN * d, f.error(C) + slopeC * d) + quad * d * d;
    };
    return refineCells(cell, tolerance, kCellDepth);
}

/// Splits the patch's net until every leaf's bound is at most tolerance (or the leaves reach
/// minWidth), halving each node in one direction (cuts are integers in units of 1/S, S = 2^30, so
/// the parameters are exact dyadic numbers), appending the leaves; returns the worst leaf bound.
/// Throws when the running total of leaves passes leafBudget (> 0). (Cutting near the tolerance at
/// 1/k instead of 1/2, so that leaves end just under it, gave 18 % fewer leaves on the teapot at
/// 1e-3 but 3 % more triangles: neighbours no longer line up and need fans.)
double buildTree(const Patch& patch, double tolerance, bool geometric, std::int32_t minWidth, std::int32_t S,
                 std::vector<Leaf>& leaves, long long& leafCount, long long leafBudget, const std::string& budgetMessage)
{
    const int m = patch.degreeU(), n = patch.degreeV();
    const int size = (m + 1) * (n + 1);
    std::vector<Eigen::Vector3d> pool(static_cast<std::size_t>(8 * size));
    std::vector<Leaf> stack;
    for (int k = 0; k < size; ++k) pool[k] = patch.controlPoints().col(k);
    stack.push_back({0, S, 0, S});
    double worst = 0;
    while (!stack.empty()) {
        const int k = static_cast<int>(stack.size()) - 1;
        const Leaf box = stack.back();
        if (pool.size() < static_cast<std::size_t>((k + 2) * size)) pool.resize(static_cast<std::size_t>(2 * (k + 2) * size));
        Eigen::Vector3d* net = pool.data() + static_cast<std::size_t>(k) * size;
        BicubicDifferences differences;
        const BicubicDifferences* diff = nullptr;
        std::array<double, 3> t;
        if (m == 3 && n == 3) {
            t = bicubicDifferencesAndTerms(net, differences);
            diff = &differences;
        } else {
            t = netTerms(net, m, n);
        }
        double b = (t[0] + t[1] + t[2]) / 8;
        // (Far above the tolerance the geometric bound cannot help either: its offset term grows with b.)
        if (geometric && b > tolerance && b < kGeometricRange * tolerance) {
            Centre centre;
            const double full = geometricBound(net, m, n, diff, t, box, S, tolerance, centre);
            b = std::min(b, full);
            if (!std::isfinite(full)) { // at a patch's side: the foot point along the side only
                const bool sideU = box.u0 == 0 || box.u1 == S, sideV = box.v0 == 0 || box.v1 == S;
                if (sideU && !sideV) b = std::min(b, geometricBoundAlong(net, m, n, diff, t, box, S, 1, tolerance, centre));
                if (sideV && !sideU) b = std::min(b, geometricBoundAlong(net, m, n, diff, t, box, S, 0, tolerance, centre));
            }
        }
        const std::int32_t wu = box.u1 - box.u0, wv = box.v1 - box.v0;
        const bool canU = wu >= 2 * minWidth && (t[0] > 0 || t[1] > 0);
        const bool canV = wv >= 2 * minWidth && (t[2] > 0 || t[1] > 0);
        if (b <= tolerance || (!canU && !canV)) {
            worst = std::max(worst, b);
            leaves.push_back(box);
            stack.pop_back();
            if (++leafCount > leafBudget && leafBudget > 0) throw Error(budgetMessage);
            continue;
        }
        // Halve in the direction that lowers the bound more: after a cut in u the terms are
        // t0/4 + t1/2 + t2, in v t0 + t1/2 + t2/4.
        const bool inU = canU && (!canV || t[0] >= t[2]);
        const std::int32_t w = inU ? wu : wv;
        const std::int32_t cut = w / 2;
        splitNet(net, net + size, m, n, inU, static_cast<double>(cut) / w);
        Leaf upper = box, lower = box;
        if (inU) lower.u1 = upper.u0 = box.u0 + cut;
        else lower.v1 = upper.v0 = box.v0 + cut;
        stack.back() = upper;
        stack.push_back(lower);
    }
    return worst;
}

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

/// Triangulates a convex ring (counter-clockwise in (u, v), indices into keys, points on a straight
/// side allowed) without a new vertex: n - 2 triangles, each time the ear whose new edge is shortest
/// in space, never an ear of three points of one side, nor one that leaves the rest on one line.
template <class Emit>
void clipEars(const std::vector<int>& ring, const std::vector<std::uint64_t>& keys, const std::vector<Eigen::Vector3d>& pos,
              const Emit& emit)
{
    thread_local std::vector<int> poly;
    poly.assign(ring.begin(), ring.end());
    while (poly.size() > 3) {
        const int size = static_cast<int>(poly.size());
        int best = -1;
        double bestLength = std::numeric_limits<double>::infinity();
        for (int k = 0; k < size; ++k) {
            const int p = poly[(k + size - 1) % size], c = poly[k], q = poly[(k + 1) % size];
            if (cross2(keys[p], keys[c], keys[q]) <= 0) continue; // a point inside a side
            const double length = (pos[p] - pos[q]).squaredNorm();
            if (length >= bestLength) continue;
            bool flat = true; // the rest, from q round to p, on the line pq?
            for (int r = (k + 2) % size; r != k && flat; r = (r + 1) % size)
                if (cross2(keys[p], keys[q], keys[poly[r]]) != 0) flat = false;
            if (flat) continue;
            best = k;
            bestLength = length;
        }
        if (best < 0) break; // cannot happen for a convex ring with a positive area
        emit(poly[(best + size - 1) % size], poly[best], poly[(best + 1) % size]);
        poly.erase(poly.begin() + best);
    }
    if (poly.size() == 3 && cross2(keys[poly[0]], keys[poly[1]], keys[poly[2]]) > 0) emit(poly[0], poly[1], poly[2]);
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
                clipEars(ring, keys, keyPos, [&](int a, int b, int c) { emit(a, b, c); });
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

} // namespace

TriangleDeviation sampleTriangleDeviation(const Patch& patch, const std::array<Eigen::Vector2d, 3>& uv,
                                          const std::array<Eigen::Vector3d, 3>& xyz, int samples)
{
    if (samples < 1) throw Error("sampleTriangleDeviation: samples must be at least 1");
    TriangleDeviation d;
    for (int i = 0; i <= samples; ++i)
        for (int j = 0; i + j <= samples; ++j) {
            const int k = samples - i - j;
            if (i == samples || j == samples || k == samples) continue;
            const double a = double(i) / samples, b = double(j) / samples, c = double(k) / samples;
            const Eigen::Vector2d x = a * uv[0] + b * uv[1] + c * uv[2];
            const Eigen::Vector3d target = a * xyz[0] + b * xyz[1] + c * xyz[2];
            Jet1 f = jet1(patch, x.x(), x.y());
            const double parametric = (f.p - target).norm();
            double best = parametric;
            // Gauss-Newton towards the foot point, kept in the domain.
            Eigen::Vector2d y = x;
            for (int it = 0; it < 12; ++it) {
                const Eigen::Vector3d r = f.p - target;
                Eigen::Matrix2d h;
                h << f.fu.dot(f.fu), f.fu.dot(f.fv), f.fu.dot(f.fv), f.fv.dot(f.fv);
                const Eigen::Vector2d g(f.fu.dot(r), f.fv.dot(r));
                const double det = h.determinant();
                if (!(std::abs(det) > 0)) break;
                const Eigen::Vector2d step = h.inverse() * g;
                y = (y - step).cwiseMax(0.0).cwiseMin(1.0);
                f = jet1(patch, y.x(), y.y());
                best = std::min(best, (f.p - target).norm());
                if (step.norm() < 1e-15) break;
            }
            d.parametric = std::max(d.parametric, parametric);
            d.geometric = std::max(d.geometric, best);
        }
    return d;
}

double netErrorBound(const Patch& patch)
{
    const auto t = netTerms(netOf(patch).data(), patch.degreeU(),
                            patch.degreeV());
    return (t[0] + t[1] + t[2]) / 8;
}

namespace {

/// One grid per patch (uniform mode, and adaptive mode with Refinement::PatchGrid).
PolygonMesh tessellateGrid(const PatchComplex& complex, const TessellationOptions& options, TessellationReport* report)
{
    const int count = static_cast<int>(complex.patches.size());

    // 1. Counts each patch asks for, then the maximum over every chain of shared sides.
    std::vector<int> counts(static_cast<std::size_t>(2 * count));
    TessellationReport rep;
    for (int p = 0; p < count; ++p) {
        const bool adaptive = options.tolerance > 0 || !options.patchTolerance.empty();
        const std::array<int, 2> want = adaptive ? adaptiveSegments(complex.patches[p], toleranceOf(options, p), options.maxSegments)
                                                 : std::array<int, 2>{options.segmentsU, options.segmentsV};
        rep.required.push_back(want);
        counts[2 * p] = want[0];
        counts[2 * p + 1] = want[1];
    }
    Classes classes(2 * count);
    for (const SharedEdge& e : sharedEdges(complex, 0)) classes.join(countOf(e.a), countOf(e.b));
    std::vector<int> classMax(counts.size(), 0);
    for (int k = 0; k < 2 * count; ++k) classMax[classes.find(k)] = std::max(classMax[classes.find(k)], counts[k]);
    for (int k = 0; k < 2 * count; ++k) counts[k] = classMax[classes.find(k)];
    long long triangles = 0;
    for (int p = 0; p < count; ++p) triangles += 2LL * counts[2 * p] * counts[2 * p + 1];
    if (options.maxTriangles > 0 && triangles > options.maxTriangles)
        throw Error("tessellate: the mesh would have " + std::to_string(triangles) + " triangles, more than maxTriangles = " +
                    std::to_string(options.maxTriangles) + " (raise the limit, --max-triangles, or the tolerance)");

    // 2. Vertices and triangles, patch by patch; boundary vertices welded by exact position.
    std::vector<Eigen::Vector3d> positions, normals;
    std::vector<Eigen::Vector2d> texcoords;
    std::unordered_map<PositionKey, int, PositionHash> welded;
    std::vector<int> faces;
    for (int p = 0; p < count; ++p) {
        const Patch& patch = complex.patches[p];
        const int nu = counts[2 * p], nv = counts[2 * p + 1];
        rep.segments.push_back({nu, nv});
        const double patchBound = tessellationErrorBound(patch, nu, nv);
        rep.errorBound = std::max(rep.errorBound, patchBound);
        if (options.tolerance > 0 || !options.patchTolerance.empty()) {
            rep.patchBound.push_back(patchBound);
            rep.worstRatio = std::max(rep.worstRatio, patchBound / toleranceOf(options, p));
        }
        std::vector<double> us(static_cast<std::size_t>(nu + 1)), vs(static_cast<std::size_t>(nv + 1));
        for (int i = 0; i <= nu; ++i) us[i] = static_cast<double>(i) / nu;
        for (int j = 0; j <= nv; ++j) vs[j] = static_cast<double>(j) / nv;
        PointMatrix<double, 3> gridPos, gridNrm;
        patch.evaluateGrid(us, vs, gridPos, &gridNrm);
        const int rowLength = nv + 1;
        // Boundary positions from the canonical side curves (identical in every patch sharing it).
        for (int s = 0; s < 4; ++s) {
            const PatchSide side = static_cast<PatchSide>(s);
            const bool alongV = side == PatchSide::U0 || side == PatchSide::U1;
            const int segs = alongV ? nv : nu;
            const auto [curve, reversed] = canonicalEdge(patch, side);
            // A collapsed side is its one point exactly ((1-t) p + t p need not round to p).
            const bool collapsed = isCollapsedEdge(patch, side);
            for (int k = 0; k <= segs; ++k) {
                const int kc = reversed ? segs - k : k;
                const Eigen::Vector3d q = collapsed ? Eigen::Vector3d(curve.controlPoint(0))
                                                    : curve.evaluate(static_cast<double>(kc) / segs);
                int i = 0, j = 0;
                switch (side) {
                case PatchSide::U0: i = 0; j = k; break;
                case PatchSide::U1: i = nu; j = k; break;
                case PatchSide::V0: i = k; j = 0; break;
                case PatchSide::V1: i = k; j = nv; break;
                }
                gridPos.col(i * rowLength + j) = q;
            }
        }
        std::vector<int> ids(static_cast<std::size_t>((nu + 1) * (nv + 1)));
        for (int i = 0; i <= nu; ++i) {
            for (int j = 0; j <= nv; ++j) {
                const int g = i * rowLength + j;
                const Eigen::Vector3d q = gridPos.col(g);
                const Eigen::Vector3d nrm = gridNrm.col(g);
                const bool boundary = i == 0 || j == 0 || i == nu || j == nv;
                if (boundary) {
                    const PositionKey key{q.x() + 0.0, q.y() + 0.0, q.z() + 0.0};
                    const auto [it, inserted] = welded.try_emplace(key, static_cast<int>(positions.size()));
                    ids[g] = it->second;
                    if (!inserted) {
                        normals[static_cast<std::size_t>(it->second)] += nrm;
                        continue;
                    }
                } else {
                    ids[g] = static_cast<int>(positions.size());
                }
                positions.push_back(q);
                normals.push_back(nrm);
                texcoords.emplace_back(us[i], vs[j]);
            }
        }
        for (int i = 0; i < nu; ++i) {
            for (int j = 0; j < nv; ++j) {
                const int g00 = i * rowLength + j, g10 = g00 + rowLength, g01 = g00 + 1, g11 = g10 + 1;
                const int a = ids[g00], b = ids[g10], c = ids[g11], d = ids[g01];
                // The shorter diagonal (the error bound holds for either).
                const double d1 = (gridPos.col(g00) - gridPos.col(g11)).squaredNorm();
                const double d2 = (gridPos.col(g10) - gridPos.col(g01)).squaredNorm();
                const int tri[2][3] = {{a, b, c}, {a, c, d}};
                const int alt[2][3] = {{a, b, d}, {b, c, d}};
                const auto& use = d1 <= d2 ? tri : alt;
                const int gtri[2][3] = {{g00, g10, g11}, {g00, g11, g01}}, galt[2][3] = {{g00, g10, g01}, {g10, g11, g01}};
                const auto& guse = d1 <= d2 ? gtri : galt;
                for (int h = 0; h < 2; ++h) {
                    const auto& t = use[h];
                    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue; // at a collapsed side
                    if (options.flipNormals) faces.insert(faces.end(), {t[0], t[2], t[1]});
                    else faces.insert(faces.end(), {t[0], t[1], t[2]});
                    if (options.sampleDeviation) {
                        std::array<Eigen::Vector2d, 3> uv;
                        std::array<Eigen::Vector3d, 3> xyz;
                        for (int c = 0; c < 3; ++c) {
                            const int g = guse[h][c];
                            uv[c] = Eigen::Vector2d(us[g / rowLength], vs[g % rowLength]);
                            xyz[c] = gridPos.col(g);
                        }
                        const TriangleDeviation dev = sampleTriangleDeviation(patch, uv, xyz);
                        rep.measuredParametric = std::max(rep.measuredParametric, dev.parametric);
                        rep.measuredGeometric = std::max(rep.measuredGeometric, dev.geometric);
                    }
                }
            }
        }
    }
    return finishMesh(std::move(positions), std::move(normals), std::move(texcoords), std::move(faces), options, rep, report);
}

} // namespace

PolygonMesh tessellate(const PatchComplex& complex, const TessellationOptions& options, TessellationReport* report)
{
    if (options.tolerance < 0 || !std::isfinite(options.tolerance))
        throw Error("tessellate: tolerance must be positive and finite");
    if (options.tolerance == 0 && options.patchTolerance.empty() && (options.segmentsU < 1 || options.segmentsV < 1))
        throw Error("tessellate: segment counts must be at least 1");
    if (options.maxSegments < 1) throw Error("tessellate: maxSegments must be at least 1");
    if (options.maxTriangles < 0) throw Error("tessellate: maxTriangles must be 0 (no limit) or positive");
    if (!options.patchTolerance.empty()) {
        if (options.patchTolerance.size() != complex.patches.size())
            throw Error("tessellate: patchTolerance has " + std::to_string(options.patchTolerance.size()) + " entries for " +
                        std::to_string(complex.patches.size()) + " patches");
        for (std::size_t p = 0; p < options.patchTolerance.size(); ++p)
            if (!(options.patchTolerance[p] > 0) || !std::isfinite(options.patchTolerance[p]))
                throw Error("tessellate: patchTolerance[" + std::to_string(p) + "] must be positive and finite");
    }
    const bool adaptive = options.tolerance > 0 || !options.patchTolerance.empty();
    if (adaptive && options.refinement == TessellationRefinement::Local)
        return tessellateLocal(complex, options, report);
    return tessellateGrid(complex, options, report);
}

PolygonMesh tessellateUniform(const PatchComplex& complex, int segmentsU, int segmentsV)
{
    TessellationOptions o;
    o.segmentsU = segmentsU;
    o.segmentsV = segmentsV;
    return tessellate(complex, o);
}

PolygonMesh tessellateAdaptive(const PatchComplex& complex, double tolerance)
{
    if (!(tolerance > 0)) throw Error("tessellateAdaptive: tolerance must be positive");
    TessellationOptions o;
    o.tolerance = tolerance;
    return tessellate(complex, o);
}

} // namespace freeform
