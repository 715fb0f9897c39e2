// The drag pass (volume/drag_pass.h): one frame of a lattice drag from its base, sixteen float
// lanes at a time, compiled per CPU level (cpu_dispatch.h, as FfdBinding's kernel).

#include "freeform/volume/drag_pass.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "freeform/core/bernstein.h" // kMaxDegree
#include "cpu_dispatch.h"            // FREEFORM_CPU_CLONES

namespace freeform {

namespace {

/// Sixteen float lanes, one block (GCC's vector extension: one AVX-512 register, two AVX or four
/// SSE ones, whichever the clone has).
typedef float V16 __attribute__((vector_size(64)));
typedef int V16i __attribute__((vector_size(64)));
FREEFORM_CPU_INLINE V16 load16(const float* p)
{
    V16 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
FREEFORM_CPU_INLINE void store16(float* p, const V16& v) { std::memcpy(p, &v, sizeof v); } // (by reference: no -Wpsabi note where it is not inlined)

/// dst[0..n) = src[0..n) widened to double, and copy[0..n) = src when given. (Non-temporal
/// stores for the doubles, which nothing reads in the frame, were tried: the frame with its
/// upload took 10.2 ms of CPU against 9.2 ms with these plain stores.)
FREEFORM_CPU_INLINE void storeOut(double* dst, float* copy, const float* src, int n)
{
    if (copy) std::memcpy(copy, src, sizeof(float) * std::size_t(n));
    for (int i = 0; i < n; ++i) dst[i] = double(src[i]);
}

/// Bernstein values b[0..n] and derivatives db of degree n at the W lanes t, by the triangle
/// (no binomials); the cubic in closed form.
template <int W>
FREEFORM_CPU_INLINE void laneBernstein(int n, const float* t, float (*b)[W], float (*db)[W])
{
    if (n == 3) {
        for (int w = 0; w < W; ++w) {
            const float s = t[w], r = 1.0f - s;
            b[0][w] = r * r * r, b[1][w] = 3 * s * r * r, b[2][w] = 3 * s * s * r, b[3][w] = s * s * s;
            db[0][w] = -3 * r * r, db[1][w] = 3 * (r * r - 2 * s * r), db[2][w] = 3 * (2 * s * r - s * s), db[3][w] = 3 * s * s;
        }
        return;
    }
    for (int w = 0; w < W; ++w) {
        b[0][w] = 1.0f;
        db[0][w] = 0.0f;
    }
    for (int d = 1; d <= n; ++d) {
        if (d == n)
            for (int i = 0; i <= n; ++i)
                for (int w = 0; w < W; ++w) db[i][w] = float(n) * ((i > 0 ? b[i - 1][w] : 0.0f) - (i < n ? b[i][w] : 0.0f));
        for (int w = 0; w < W; ++w) {
            const float s = t[w], r = 1.0f - s;
            b[d][w] = s * b[d - 1][w];
            for (int i = d - 1; i > 0; --i) b[i][w] = r * b[i][w] + s * b[i - 1][w];
            b[0][w] *= r;
        }
    }
}

/// The frame's pass (runDragPass), a block of W = 16 lanes at a time in vectors of 16
/// and loops the compiler vectorises: Identity reads the rest mesh as the base (A = I, det A = 1),
/// Masked applies the per-vertex masks of the outside policy.
template <int W, bool Identity, bool Masked>
FREEFORM_CPU_INLINE void framePassBody(DragPass& f)
{
    static_assert(W == 16, "a block is one V16");
    const std::size_t count = f.count;
    float mn[3] = {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity()};
    float mx[3] = {-mn[0], -mn[1], -mn[2]};
    double lo = count ? std::numeric_limits<double>::infinity() : 1, hi = count ? -lo : 1;
    const float u0 = f.u[0], u1 = f.u[1], u2 = f.u[2];
    const float* dual = f.dual;
    float b[3][kMaxDegree + 1][W], db[3][kMaxDegree + 1][W];
    const V16 inf = V16{} + std::numeric_limits<float>::infinity();
    V16 vmn[3] = {inf, inf, inf}, vmx[3] = {-inf, -inf, -inf}, vlo = inf, vhi = -inf;
    for (std::size_t base = 0; base < count; base += W) {
        const std::size_t lanes = std::min<std::size_t>(W, count - base);
        const float* q = f.coords + (base / W) * kDragCoordFields * W;
        for (int x = 0; x < 3; ++x) laneBernstein<W>(f.deg[x], q + x * W, b[x], db[x]);
        // B and grad B (lattice coordinates) of the moved points.
        float bs[W], g[3][W];
        for (int w = 0; w < W; ++w) bs[w] = g[0][w] = g[1][w] = g[2][w] = 0.0f;
        for (std::size_t m = 0; m < f.moved; ++m) {
            const int i = f.ijk[m][0], j = f.ijk[m][1], k = f.ijk[m][2];
            for (int w = 0; w < W; ++w) {
                const float x = b[0][i][w], y = b[1][j][w], z = b[2][k][w];
                bs[w] += x * y * z;
                g[0][w] += db[0][i][w] * y * z;
                g[1][w] += x * db[1][j][w] * z;
                g[2][w] += x * y * db[2][k][w];
            }
        }
        if constexpr (Masked) {
            // Outside the box: under keep nothing moves (bit 3 off), under clamp an axis whose
            // coordinate lies beyond the box adds no gradient (its bit off).
            for (std::size_t w = 0; w < lanes; ++w) {
                const unsigned m = f.masks[base + w];
                bs[w] = m & 8u ? bs[w] : 0.0f;
                for (int x = 0; x < 3; ++x) g[x][w] = (m & 8u) && (m >> x & 1u) ? g[x][w] : 0.0f;
            }
        }
        alignas(64) float p[3][W], n[3][W], d[W], len2[W], inv[W];
        const float* cb = f.coords + (base / W) * kDragCoordFields * W;
        const float* bb = Identity ? nullptr : f.base + (base / W) * kDragBaseFields * W; // (no base blocks at the identity)
        alignas(64) float rp[3][W]; // Identity: the rest positions in float
        if constexpr (Identity)
            for (int w = 0; w < W; ++w) {
                const std::size_t v = std::min(base + std::size_t(w), count - 1); // padding repeats the last vertex
                for (int x = 0; x < 3; ++x) rp[x][w] = float(f.rest[3 * v + std::size_t(x)]);
            }
        // The block at once (the base and the coordinates are structures of arrays).
        {
            const V16 g0 = load16(g[0]), g1 = load16(g[1]), g2 = load16(g[2]), b4 = load16(bs);
            const V16 nx = load16(cb + 3 * W), ny = load16(cb + 4 * W), nz = load16(cb + 5 * W);
            // v = dual^T g
            const V16 v0 = dual[0] * g0 + dual[3] * g1 + dual[6] * g2;
            const V16 v1 = dual[1] * g0 + dual[4] * g1 + dual[7] * g2;
            const V16 v2 = dual[2] * g0 + dual[5] * g1 + dual[8] * g2;
            const V16 mxv = ny * v2 - nz * v1, myv = nz * v0 - nx * v2, mzv = nx * v1 - ny * v0; // n x v
            V16 px, py, pz, cx, cy, cz, ex, ey, ez, hx, hy, hz, d0;
            if constexpr (Identity) {
                px = load16(rp[0]), py = load16(rp[1]), pz = load16(rp[2]);
                cx = nx, cy = ny, cz = nz;           // cof(I) n
                ex = v0, ey = v1, ez = v2;           // cof(I) v
                hx = mxv, hy = myv, hz = mzv;        // I (n x v)
                d0 = V16{} + 1.0f;
            } else {
                px = load16(bb), py = load16(bb + W), pz = load16(bb + 2 * W);
                V16 a[9];
                for (int c = 0; c < 9; ++c) a[c] = load16(bb + (3 + c) * W);
                d0 = load16(bb + 12 * W);
                // cof(A)'s columns k0 = a1 x a2, k1 = a2 x a0, k2 = a0 x a1 (A column-major, a[3 c + r]).
                const V16 k0x = a[4] * a[8] - a[5] * a[7], k0y = a[5] * a[6] - a[3] * a[8], k0z = a[3] * a[7] - a[4] * a[6];
                const V16 k1x = a[7] * a[2] - a[8] * a[1], k1y = a[8] * a[0] - a[6] * a[2], k1z = a[6] * a[1] - a[7] * a[0];
                const V16 k2x = a[1] * a[5] - a[2] * a[4], k2y = a[2] * a[3] - a[0] * a[5], k2z = a[0] * a[4] - a[1] * a[3];
                cx = nx * k0x + ny * k1x + nz * k2x, cy = nx * k0y + ny * k1y + nz * k2y, cz = nx * k0z + ny * k1z + nz * k2z;
                ex = v0 * k0x + v1 * k1x + v2 * k2x, ey = v0 * k0y + v1 * k1y + v2 * k2y, ez = v0 * k0z + v1 * k1z + v2 * k2z;
                hx = a[0] * mxv + a[3] * myv + a[6] * mzv;
                hy = a[1] * mxv + a[4] * myv + a[7] * mzv;
                hz = a[2] * mxv + a[5] * myv + a[8] * mzv;
            }
            // det J = det A + (cof(A) v) . u;  cof(J) n = cof(A) n + u x (A (n x v));  p = p0 + B u
            store16(d, d0 + (ex * u0 + ey * u1 + ez * u2));
            const V16 qx = cx + (u1 * hz - u2 * hy), qy = cy + (u2 * hx - u0 * hz), qz = cz + (u0 * hy - u1 * hx);
            store16(n[0], qx);
            store16(n[1], qy);
            store16(n[2], qz);
            store16(len2, qx * qx + qy * qy + qz * qz);
            store16(p[0], px + b4 * u0);
            store16(p[1], py + b4 * u1);
            store16(p[2], pz + b4 * u2);
        }
#if defined(__SSE2__)
        for (int w = 0; w < W; w += 4) {
            const __m128 l2 = _mm_loadu_ps(len2 + w);
            const __m128 r = _mm_div_ps(_mm_set1_ps(1.0f), _mm_sqrt_ps(l2));
            _mm_storeu_ps(inv + w, _mm_and_ps(r, _mm_cmpgt_ps(l2, _mm_setzero_ps()))); // 0 where |n| = 0
        }
#else
        for (int w = 0; w < W; ++w) inv[w] = len2[w] > 0 ? 1.0f / std::sqrt(len2[w]) : 0.0f;
#endif
        if (lanes == std::size_t(W)) {
            // A whole block: the box and det J's range in vectors (min and max in float, then
            // widened: the same values as in double), folds looked for only where a lane has one.
            {
                for (int x = 0; x < 3; ++x) {
                    const V16 px = load16(p[x]);
                    vmn[x] = px < vmn[x] ? px : vmn[x];
                    vmx[x] = vmx[x] < px ? px : vmx[x];
                    store16(n[x], load16(n[x]) * load16(inv));
                }
                const V16 dv = load16(d);
                vlo = dv < vlo ? dv : vlo;
                vhi = vhi < dv ? dv : vhi;
                const V16i positive = dv > 0.0f;
                int all = -1;
                for (int k = 0; k < W; ++k) all &= positive[k];
                if (all == 0)
                    for (int k = 0; k < W; ++k)
                        if (!(d[k] > 0)) f.folds->push_back(static_cast<int>(base + std::size_t(k)));
            }
            // Interleaved (x y z per vertex), then out: double, float copies, det J.
            alignas(16) float pi[3 * W], ni[3 * W];
            for (int w = 0; w < W; ++w)
                for (int x = 0; x < 3; ++x) {
                    pi[3 * w + x] = p[x][w];
                    ni[3 * w + x] = n[x][w];
                }
            storeOut(f.pos + 3 * base, f.fpos ? f.fpos + 3 * base : nullptr, pi, 3 * W);
            storeOut(f.nor + 3 * base, f.fnor ? f.fnor + 3 * base : nullptr, ni, 3 * W);
            if (f.det) std::memcpy(f.det + base, d, sizeof d); // (read by the upload: cached)
            continue;
        }
        for (std::size_t w = 0; w < lanes; ++w) {
            for (int x = 0; x < 3; ++x) {
                f.pos[3 * (base + w) + std::size_t(x)] = double(p[x][w]);
                mn[x] = p[x][w] < mn[x] ? p[x][w] : mn[x];
                mx[x] = p[x][w] > mx[x] ? p[x][w] : mx[x];
            }
            for (int x = 0; x < 3; ++x) {
                const float nx = n[x][w] * inv[w];
                f.nor[3 * (base + w) + std::size_t(x)] = double(nx);
                if (f.fpos) f.fpos[3 * (base + w) + std::size_t(x)] = p[x][w];
                if (f.fnor) f.fnor[3 * (base + w) + std::size_t(x)] = nx;
            }
            if (f.det) f.det[base + w] = d[w];
            const double dd = double(d[w]);
            lo = std::min(lo, dd);
            hi = std::max(hi, dd);
            if (!(dd > 0)) f.folds->push_back(static_cast<int>(base + w));
        }
    }
    for (int k = 0; k < W; ++k) {
        for (int x = 0; x < 3; ++x) {
            mn[x] = vmn[x][k] < mn[x] ? vmn[x][k] : mn[x];
            mx[x] = vmx[x][k] > mx[x] ? vmx[x][k] : mx[x];
        }
        lo = std::min(lo, double(vlo[k]));
        hi = std::max(hi, double(vhi[k]));
    }
    f.lo = lo;
    f.hi = hi;
    for (int x = 0; x < 3; ++x) {
        f.mn[x] = mn[x];
        f.mx[x] = mx[x];
    }
}

// The four variants, each compiled for every clone target.
FREEFORM_CPU_CLONES void framePassIdentity(DragPass& f) { framePassBody<16, true, false>(f); }
FREEFORM_CPU_CLONES void framePassIdentityMasked(DragPass& f) { framePassBody<16, true, true>(f); }
FREEFORM_CPU_CLONES void framePassEvaluated(DragPass& f) { framePassBody<16, false, false>(f); }
FREEFORM_CPU_CLONES void framePassEvaluatedMasked(DragPass& f) { framePassBody<16, false, true>(f); }

} // namespace

void runDragPass(DragPass& f, bool identityBase)
{
    static_assert(kDragLanes == 16, "a block is one V16");
    if (identityBase) {
        if (f.masks) framePassIdentityMasked(f);
        else framePassIdentity(f);
    } else {
        if (f.masks) framePassEvaluatedMasked(f);
        else framePassEvaluated(f);
    }
}

} // namespace freeform
