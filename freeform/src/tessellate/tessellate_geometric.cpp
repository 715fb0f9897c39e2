// The geometric measure of the local refinement (docs/surfaces.md, "The geometric measure", "At a
// patch's sides"): a bound on the distance from every triangle point of a leaf to the surface,
// from the leaf's sub-net (its second differences projected on the normal and the tangents at the
// leaf's centre, and the sub-net grown by the foot point's step), which leaves out the tangential
// part of the parametric bound. buildTree (tessellate_tree.cpp) asks for it through
// geometricLeafBound.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include "tessellate_internal.h"

namespace freeform::tessellate_detail {

namespace {

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

} // namespace

double geometricLeafBound(double b, const Eigen::Vector3d* net, int m, int n, const BicubicDifferences* diff,
                          const std::array<double, 3>& terms, const Leaf& box, std::int32_t S, double tolerance)
{
    // (Far above the tolerance the geometric bound cannot help either: its offset term grows with b.)
    if (!(b > tolerance && b < kGeometricRange * tolerance)) return b;
    Centre centre;
    const double full = geometricBound(net, m, n, diff, terms, box, S, tolerance, centre);
    b = std::min(b, full);
    if (!std::isfinite(full)) { // at a patch's side: the foot point along the side only
        const bool sideU = box.u0 == 0 || box.u1 == S, sideV = box.v0 == 0 || box.v1 == S;
        if (sideU && !sideV) b = std::min(b, geometricBoundAlong(net, m, n, diff, terms, box, S, 1, tolerance, centre));
        if (sideV && !sideU) b = std::min(b, geometricBoundAlong(net, m, n, diff, terms, box, S, 0, tolerance, centre));
    }
    return b;
}

} // namespace freeform::tessellate_detail
