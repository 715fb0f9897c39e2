// The trees of the local refinement (docs/surfaces.md, "Local refinement"): a patch's control net
// split by de Casteljau into dyadic sub-nets until the bound of every leaf from the second
// differences of its own sub-net (netTerms; for a bicubic net, with SSE2, the 25 differences and
// their norms in vector registers) is within the tolerance, or the geometric measure's bound
// (tessellate_geometric.cpp) is.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include "freeform/core/error.h"
#include "tessellate_internal.h"

namespace freeform::tessellate_detail {

/// The three terms of the local bound of a net (m+1) x (n+1), point (i, j) at net[i*(n+1)+j]:
/// m(m-1) max|D_uu|, 2 m n max|D_uv|, n(n-1) max|D_vv| (their sum / 8 is the bound).
std::array<double, 3> netTerms(const Eigen::Vector3d* net, int m, int n)
{
    const auto d = maxSecondDifferences(net, m, n, [](const Eigen::Vector3d& x) { return x.squaredNorm(); });
    return {m * (m - 1.0) * std::sqrt(d[0]), 2.0 * m * n * std::sqrt(d[1]), n * (n - 1.0) * std::sqrt(d[2])};
}

namespace {

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

} // namespace

std::vector<Eigen::Vector3d> netOf(const Patch& p)
{
    std::vector<Eigen::Vector3d> net(static_cast<std::size_t>(p.controlPoints().cols()));
    for (std::size_t k = 0; k < net.size(); ++k) net[k] = p.controlPoints().col(static_cast<Eigen::Index>(k));
    return net;
}

void splitNet(Eigen::Vector3d* net, Eigen::Vector3d* lower, int m, int n, bool inU, double t)
{
    if (m == 3 && n == 3) return inU ? splitBicubicU(net, lower, t) : splitBicubicV(net, lower, t);
    const int deg = inU ? m : n, outer = inU ? n : m;
    const int stride = inU ? n + 1 : 1, step = inU ? 1 : n + 1; // along the split direction, across it
    if (deg == 3) splitLines<3>(net, lower, deg, outer, stride, step, t);
    else splitLines<0>(net, lower, deg, outer, stride, step, t);
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
        if (geometric) b = geometricLeafBound(b, net, m, n, diff, t, box, S, tolerance);
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

} // namespace freeform::tessellate_detail
