#include "scene/ffd_session.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "freeform/core/bernstein.h" // kMaxDegree
#include "freeform/core/parallel.h"

namespace freeform::editor {

namespace {

// The frame's per-vertex data (FfdSession: coords_ and base_): fields per block of lanes.
constexpr int FfdCoordFields = 6, FfdBaseFields = 13;

// The frame's pass is compiled for x86-64-v4, v3 and the baseline, chosen at run time (as the
// library's FFD kernel is: freeform/src/volume/ffd_binding.cpp); no -march in the build.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(FREEFORM_NO_CPU_DISPATCH)
#define FREEFORM_FRAME_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define FREEFORM_FRAME_CLONES
#endif
#define FREEFORM_INLINE inline __attribute__((always_inline))

// The lane vectors below never cross a call boundary (everything is inlined into the clones).
#pragma GCC diagnostic ignored "-Wpsabi"

/// Sixteen float lanes, one block (GCC's vector extension: one AVX-512 register, two AVX or four
/// SSE ones, whichever the clone has).
typedef float V16 __attribute__((vector_size(64)));
typedef int V16i __attribute__((vector_size(64)));
FREEFORM_INLINE V16 load16(const float* p)
{
    V16 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
FREEFORM_INLINE void store16(float* p, const V16& v) { std::memcpy(p, &v, sizeof v); } // (by reference: no -Wpsabi note where it is not inlined)

/// dst[0..n) = src[0..n) widened to double, and copy[0..n) = src when given. (Non-temporal
/// stores for the doubles, which nothing reads in the frame, were tried: the frame with its
/// upload took 10.2 ms of CPU against 9.2 ms with these plain stores.)
FREEFORM_INLINE void storeOut(double* dst, float* copy, const float* src, int n)
{
    if (copy) std::memcpy(copy, src, sizeof(float) * std::size_t(n));
    for (int i = 0; i < n; ++i) dst[i] = double(src[i]);
}

/// What one drag frame reads and writes (FfdSession::dragFrame), and what it finds.
struct FrameArgs {
    std::size_t count = 0;
    const float* coords = nullptr;        // blocks of W: s, t, u, rest normal x, y, z
    const unsigned char* masks = nullptr; // per vertex (Masked only)
    const float* base = nullptr;          // blocks of W: p0 (3), A (9, column-major), det A (Evaluated only)
    const double* rest = nullptr;         // 3 x V, the rest positions (Identity only)
    int deg[3] = {3, 3, 3};
    const std::array<int, 3>* ijk = nullptr;
    std::size_t moved = 0;
    float dual[9] = {}; // row-major
    float u[3] = {};
    double* pos = nullptr;
    double* nor = nullptr;
    float* fpos = nullptr; // the float copies (FloatVertices), or null
    float* fnor = nullptr;
    float* det = nullptr;
    // Found: det J's range and folds, the box in float.
    double lo = 1, hi = 1;
    std::vector<int>* folds = nullptr;
    float mn[3] = {}, mx[3] = {};
};

/// Bernstein values b[0..n] and derivatives db of degree n at the W lanes t, by the triangle
/// (no binomials); the cubic in closed form.
template <int W>
FREEFORM_INLINE void laneBernstein(int n, const float* t, float (*b)[W], float (*db)[W])
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

/// The frame's pass (FfdSession::dragFrame), a block of W = 16 lanes at a time in vectors of 16
/// and loops the compiler vectorises: Identity reads the rest mesh as the base (A = I, det A = 1),
/// Masked applies the per-vertex masks of the outside policy.
template <int W, bool Identity, bool Masked>
FREEFORM_INLINE void framePassBody(FrameArgs& f)
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
        const float* q = f.coords + (base / W) * FfdCoordFields * W;
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
        const float* cb = f.coords + (base / W) * FfdCoordFields * W;
        const float* bb = Identity ? nullptr : f.base + (base / W) * FfdBaseFields * W; // (no base blocks at the identity)
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
FREEFORM_FRAME_CLONES void framePassIdentity(FrameArgs& f) { framePassBody<16, true, false>(f); }
FREEFORM_FRAME_CLONES void framePassIdentityMasked(FrameArgs& f) { framePassBody<16, true, true>(f); }
FREEFORM_FRAME_CLONES void framePassEvaluated(FrameArgs& f) { framePassBody<16, false, false>(f); }
FREEFORM_FRAME_CLONES void framePassEvaluatedMasked(FrameArgs& f) { framePassBody<16, false, true>(f); }

} // namespace

FfdSession::FfdSession(const Lattice& lattice, PolygonMesh rest)
    : frame_(lattice), rest_(std::move(rest)), binding_(lattice, rest_.positions), restNormals_(rest_.normals.cast<float>())
{
    // The lattice coordinates of every vertex as the library's kernel uses them (float; the
    // policy's clamp applied), and the outside policy's masks (docs/ffd.md, "Outside the box").
    constexpr int W = kLanes;
    const std::size_t count = static_cast<std::size_t>(rest_.positions.cols());
    const std::vector<int>& outside = binding_.outsideVertices();
    const OutsidePolicy policy = lattice.outside();
    const bool masked = !outside.empty() && policy != OutsidePolicy::Extrapolate;
    const bool normals = rest_.normals.cols() == rest_.positions.cols();
    coords_.assign(((count + W - 1) / W) * kCoordFields * W, 0.5f);
    if (masked) masks_.assign(count, 0x0f);
    auto next = outside.begin();
    for (std::size_t v = 0; v < count; ++v) {
        const bool out = next != outside.end() && *next == static_cast<int>(v);
        if (out) ++next;
        Eigen::Vector3d q = binding_.parameters(v); // inside: the binding's own float coordinates
        if (out && policy != OutsidePolicy::Extrapolate) {
            const OutsideRule rule = outsideRule(q, policy); // the mask's bits are the rule's
            masks_[v] = static_cast<unsigned char>(rule.mask);
            q = rule.at;
        }
        float* b = coords_.data() + (v / W) * kCoordFields * W + v % W;
        for (int x = 0; x < 3; ++x) {
            b[x * W] = static_cast<float>(q[x]);
            b[(3 + x) * W] = normals ? restNormals_(x, static_cast<Eigen::Index>(v)) : 0.0f;
        }
    }
    static_assert(kCoordFields == FfdCoordFields && kBaseFields == FfdBaseFields);
    // Padding lanes repeat the last vertex (finite; never written out).
    for (std::size_t v = count; count > 0 && v % W != 0; ++v)
        for (int x = 0; x < kCoordFields; ++x)
            coords_[(v / W) * kCoordFields * W + std::size_t(x) * W + v % W] =
                coords_[((count - 1) / W) * kCoordFields * W + std::size_t(x) * W + (count - 1) % W];
}

FfdSession::~FfdSession()
{
    if (job_.joinable()) job_.join();
}

bool FfdSession::matches(const Lattice& lattice) const
{
    return lattice.sameFrame(frame_) && lattice.outside() == frame_.outside();
}

void FfdSession::settle()
{
    if (!job_.joinable()) return;
    job_.join();
    jobError_ = nullptr; // (a failed evaluation left no base: base_ is None)
}

DeformReport FfdSession::deform(const Lattice& lattice, double strength, PolygonMesh& out, std::vector<float>* detJ,
                                Eigen::AlignedBox3d* bounds, bool live, FloatVertices* drawn)
{
    settle(); // a background evaluation in flight becomes the base of this call
    approximate_ = false;
    const Eigen::Index count = rest_.positions.cols();
    const bool normals = rest_.normals.cols() == count;
    if (out.positions.cols() != count) out.positions.resize(3, count);
    if (normals && out.normals.cols() != count) out.normals.resize(3, count);
    if (!normals) drawn = nullptr;
    if (drawn && drawn->positions.cols() != count) drawn->positions.resize(3, count);
    if (drawn && drawn->normals.cols() != count) drawn->normals.resize(3, count);
    if (detJ) detJ->resize(static_cast<std::size_t>(count));
    DeformReport report;
    if (lattice.isRest() || strength == 0) {
        identity(lattice, strength, out, detJ, report, bounds, drawn);
        return report;
    }
    if (live && base_ != Base::None && normals) {
        // A frame of a drag: when the points that moved since the base (the last full evaluation,
        // or the identity) moved by one common vector, the frame is the base plus the linear
        // change, straight from the base (the grab, the first such frame, costs what any does).
        if (!dragDelta(lattice, strength)) {
            drag_.reset();
            const Lattice::Points& p = lattice.controlPoints();
            if (baseStrength_ == strength && basePoints_.cols() == p.cols()) {
                auto drag = std::make_unique<Drag>();
                drag->points = basePoints_;
                drag->strength = strength;
                const int nu = lattice.degree(2) + 1, nt = lattice.degree(1) + 1;
                for (Eigen::Index k = 0; k < p.cols(); ++k)
                    if (basePoints_.col(k) != p.col(k)) {
                        const int i = static_cast<int>(k);
                        drag->moved.push_back(i);
                        drag->ijk.push_back({i / (nt * nu), (i / nu) % nt, i % nu});
                    }
                if (!drag->moved.empty()) drag_ = std::move(drag);
            }
        }
        if (const auto delta = dragDelta(lattice, strength)) {
            dragFrame(lattice, *delta, out, drawn, detJ ? detJ->data() : nullptr, report, bounds);
            approximate_ = true;
            return report;
        }
        drag_.reset();
    }
    evaluate(lattice, strength, out, detJ, report, bounds, 0, drawn);
    return report;
}

void FfdSession::identity(const Lattice& lattice, double strength, PolygonMesh& out, std::vector<float>* detJ, DeformReport& report,
                          Eigen::AlignedBox3d* bounds, FloatVertices* drawn)
{
    // The identity: the file's own vertices, bit for bit (float would round them), det J 1.
    const Eigen::Index count = rest_.positions.cols();
    const bool normals = rest_.normals.cols() == count;
    out.positions = rest_.positions;
    if (normals) out.normals = rest_.normals;
    if (normals && drawn) {
        drawn->positions = rest_.positions.cast<float>();
        drawn->normals = restNormals_;
    }
    if (detJ) detJ->assign(static_cast<std::size_t>(count), 1.0f);
    drag_.reset();
    // The base of the next grab: the identity (no copy: the frames read the rest mesh).
    base_ = normals ? Base::Identity : Base::None;
    basePoints_ = lattice.controlPoints();
    baseStrength_ = strength;
    report = DeformReport{};
    report.vertices = static_cast<std::size_t>(count);
    report.outside = binding_.outsideVertices().size();
    if (bounds) {
        bounds->setEmpty();
        for (Eigen::Index k = 0; k < count; ++k) bounds->extend(Eigen::Vector3d(out.positions.col(k)));
    }
}

void FfdSession::evaluate(const Lattice& lattice, double strength, PolygonMesh& out, std::vector<float>* detJ, DeformReport& report,
                          Eigen::AlignedBox3d* bounds, int threads, FloatVertices* drawn)
{
    // The library's evaluation in float into the base (the Jacobians A kept with normals: the
    // next drag starts from them), then the report, the double copy and the bounds in one pass.
    const Eigen::Index count = rest_.positions.cols();
    const bool normals = rest_.normals.cols() == count;
    drag_.reset();
    base_ = Base::None;
    positions_.resize(3, count);
    baseDet_.resize(static_cast<std::size_t>(count));
    FfdOutputs<float> o;
    o.positions = positions_.data();
    o.determinants = baseDet_.data();
    if (normals) {
        normals_.resize(3, count);
        jacobians_.resize(9 * static_cast<std::size_t>(count));
        o.normalsIn = restNormals_.data();
        o.normalsOut = normals_.data();
        o.jacobians = jacobians_.data();
    }
    DeformOptions options;
    options.strength = strength;
    options.threads = threads;
    binding_.deform(lattice, o, options, nullptr);
    if (out.positions.cols() != count) out.positions.resize(3, count);
    if (normals && out.normals.cols() != count) out.normals.resize(3, count);
    finish(baseDet_.data(), normals, out, normals ? drawn : nullptr, report, bounds, threads);
    if (detJ) detJ->assign(baseDet_.begin(), baseDet_.end());
    base_ = normals ? Base::Evaluated : Base::None;
    basePoints_ = lattice.controlPoints();
    baseStrength_ = strength;
}

void FfdSession::deformInBackground(const Lattice& lattice, double strength)
{
    settle();
    approximate_ = false;
    jobDone_.store(false, std::memory_order_relaxed);
    // One thread fewer than the machine has: the frames keep a core.
    const int threads = std::max(1, resolveThreadCount(0) - 1);
    job_ = std::thread([this, lattice, strength, threads] {
        try {
            if (lattice.isRest() || strength == 0) {
                identity(lattice, strength, jobMesh_, &jobDet_, jobReport_, &jobBounds_, &jobDrawn_);
            } else {
                evaluate(lattice, strength, jobMesh_, &jobDet_, jobReport_, &jobBounds_, threads, &jobDrawn_);
            }
        } catch (...) {
            jobError_ = std::current_exception();
            base_ = Base::None;
        }
        jobDone_.store(true, std::memory_order_release);
    });
}

std::optional<DeformReport> FfdSession::takeBackground(PolygonMesh& out, std::vector<float>& detJ, Eigen::AlignedBox3d& bounds, bool wait,
                                                      FloatVertices* drawn)
{
    if (!job_.joinable()) return std::nullopt;
    if (!wait && !jobDone_.load(std::memory_order_acquire)) return std::nullopt;
    job_.join();
    if (jobError_) {
        const std::exception_ptr e = jobError_;
        jobError_ = nullptr;
        std::rethrow_exception(e);
    }
    // Swapped, not copied: the scene's buffers come back here for the next release.
    out.positions.swap(jobMesh_.positions);
    if (rest_.normals.cols() == rest_.positions.cols()) {
        out.normals.swap(jobMesh_.normals);
        if (drawn) {
            drawn->positions.swap(jobDrawn_.positions);
            drawn->normals.swap(jobDrawn_.normals);
        }
    }
    detJ.swap(jobDet_);
    bounds = jobBounds_;
    approximate_ = false;
    return jobReport_;
}

std::optional<Eigen::Vector3d> FfdSession::dragDelta(const Lattice& lattice, double strength) const
{
    if (!drag_ || drag_->strength != strength) return std::nullopt;
    const Lattice::Points& p = lattice.controlPoints();
    const Eigen::Matrix3Xd& base = drag_->points;
    if (p.cols() != base.cols()) return std::nullopt;
    // Every point outside the drag's set unchanged; those inside moved by one common vector
    // (a grab computes each as its own start + delta, so they agree to a few ulps of the points).
    std::size_t next = 0;
    Eigen::Vector3d delta = Eigen::Vector3d::Zero();
    for (Eigen::Index k = 0; k < p.cols(); ++k) {
        const bool inSet = next < drag_->moved.size() && drag_->moved[next] == k;
        if (!inSet) {
            if (p.col(k) != base.col(k)) return std::nullopt;
            continue;
        }
        const Eigen::Vector3d d = p.col(k) - base.col(k);
        if (next == 0) delta = d;
        else if ((d - delta).cwiseAbs().maxCoeff() > 8 * std::numeric_limits<double>::epsilon() * (1 + p.col(k).cwiseAbs().maxCoeff()))
            return std::nullopt;
        ++next;
    }
    return delta;
}

void FfdSession::dragFrame(const Lattice& lattice, const Eigen::Vector3d& delta, PolygonMesh& out, FloatVertices* drawn, float* det,
                           DeformReport& report, Eigen::AlignedBox3d* bounds) const
{
    // One thread, one pass from the base (docs/architecture.md, "A lattice drag"): with every
    // point of the set moved by the same delta since the base, D changes by w B delta and J by
    // u v^T, u = w delta, v = dual^T grad B, B the sum of the set's Bernstein products. Then
    //   p = p0 + B u,   det J = det A + (cof(A) v) . u,   cof(J) n = cof(A) n + u x (A (n x v)),
    // the last because cof(M) has the columns m1 x m2, m2 x m0, m0 x m1.
    constexpr int W = kLanes;
    FrameArgs f;
    f.count = static_cast<std::size_t>(rest_.positions.cols());
    f.coords = coords_.data();
    f.masks = masks_.empty() ? nullptr : masks_.data();
    f.base = baseBlocks_.data();
    f.rest = rest_.positions.data();
    for (int x = 0; x < 3; ++x) f.deg[x] = lattice.degree(x);
    f.ijk = drag_->ijk.data();
    f.moved = drag_->ijk.size();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) f.dual[3 * r + c] = float(lattice.dual()(r, c));
    const Eigen::Vector3f u = (drag_->strength * delta).cast<float>();
    for (int x = 0; x < 3; ++x) f.u[x] = u[x];
    f.pos = out.positions.data();
    f.nor = out.normals.data();
    f.fpos = drawn ? drawn->positions.data() : nullptr;
    f.fnor = drawn ? drawn->normals.data() : nullptr;
    f.det = det;
    report = DeformReport{};
    report.vertices = f.count;
    report.outside = binding_.outsideVertices().size();
    f.folds = &report.folds;
    const bool identity = base_ == Base::Identity;
    static_assert(W == 16);
    if (identity) {
        if (f.masks) framePassIdentityMasked(f);
        else framePassIdentity(f);
    } else {
        if (f.masks) framePassEvaluatedMasked(f);
        else framePassEvaluated(f);
    }
    report.minDetJ = f.lo;
    report.maxDetJ = f.hi;
    report.foldCount = report.folds.size();
    if (bounds) {
        bounds->setEmpty();
        if (f.count) bounds->extend(Eigen::AlignedBox3d(Eigen::Vector3d(f.mn[0], f.mn[1], f.mn[2]), Eigen::Vector3d(f.mx[0], f.mx[1], f.mx[2])));
    }
}

void FfdSession::finish(const float* det, bool normals, PolygonMesh& out, FloatVertices* drawn, DeformReport& report,
                        Eigen::AlignedBox3d* bounds, int threads)
{
    // One pass over the float results, on the same threads as before, in chunks combined in chunk
    // order: the scene's double mesh (exact widening), the report from det J as FfdBinding::deform
    // makes it (min, max, folds ascending) and the bounding box. Before, the library's report, the
    // widening and the scene's bounds were three passes (docs/performance.md, "lattice drag").
    const Eigen::Index count = positions_.cols();
    struct Part {
        double lo = 1, hi = 1;
        std::vector<int> folds;
        float min[3] = {0, 0, 0}, max[3] = {0, 0, 0};
    };
    constexpr std::size_t kGrain = 16384;
    constexpr int W = kLanes;
    static_assert(kGrain % W == 0);
    if (normals) baseBlocks_.resize(((static_cast<std::size_t>(count) + W - 1) / W) * kBaseFields * W);
    if (drawn) {
        if (drawn->positions.cols() != count) drawn->positions.resize(3, count);
        if (drawn->normals.cols() != count) drawn->normals.resize(3, count);
    }
    std::vector<Part> parts(static_cast<std::size_t>(parallelChunkCount(0, static_cast<std::size_t>(count), kGrain, threads)));
    parallelFor(0, static_cast<std::size_t>(count), kGrain, threads, [&](int c, std::size_t first, std::size_t last) {
        const auto n = static_cast<Eigen::Index>(last - first), f = static_cast<Eigen::Index>(first);
        out.positions.middleCols(f, n) = positions_.middleCols(f, n).cast<double>();
        if (normals) out.normals.middleCols(f, n) = normals_.middleCols(f, n).cast<double>();
        if (drawn) {
            drawn->positions.middleCols(f, n) = positions_.middleCols(f, n);
            drawn->normals.middleCols(f, n) = normals_.middleCols(f, n);
        }
        Part& part = parts[static_cast<std::size_t>(c)];
        // The base's blocks for the drag frames (chunks start at whole blocks: kGrain % W == 0).
        if (normals)
            for (std::size_t v = first; v < last; ++v) {
                float* b = baseBlocks_.data() + (v / W) * kBaseFields * W + v % W;
                const auto col = static_cast<Eigen::Index>(v);
                for (int x = 0; x < 3; ++x) b[x * W] = positions_(x, col);
                const float* j = jacobians_.data() + 9 * v;
                for (int k = 0; k < 9; ++k) b[(3 + k) * W] = j[k];
                b[12 * W] = det[v];
            }
        // det J: the same comparisons in double as the library's report.
        double lo = double(det[first]), hi = lo;
        for (std::size_t v = first; v < last; ++v) {
            const double d = double(det[v]);
            lo = std::min(lo, d);
            hi = std::max(hi, d);
            if (!(d > 0)) part.folds.push_back(static_cast<int>(v));
        }
        part.lo = lo;
        part.hi = hi;
        // The box in float (widening to double is exact and keeps the order, so the box is the one
        // of the double positions), in a loop the compiler vectorises.
        const float* p = positions_.data() + 3 * first;
        float mn[3] = {p[0], p[1], p[2]}, mx[3] = {p[0], p[1], p[2]};
        for (std::size_t v = 0; v < last - first; ++v)
            for (int x = 0; x < 3; ++x) {
                const float a = p[3 * v + std::size_t(x)];
                mn[x] = a < mn[x] ? a : mn[x];
                mx[x] = a > mx[x] ? a : mx[x];
            }
        for (int x = 0; x < 3; ++x) {
            part.min[x] = mn[x];
            part.max[x] = mx[x];
        }
    });
    report = DeformReport{};
    report.vertices = static_cast<std::size_t>(count);
    report.outside = binding_.outsideVertices().size();
    if (count > 0) {
        report.minDetJ = parts[0].lo;
        report.maxDetJ = parts[0].hi;
    }
    for (const Part& p : parts) {
        report.minDetJ = std::min(report.minDetJ, p.lo);
        report.maxDetJ = std::max(report.maxDetJ, p.hi);
        report.folds.insert(report.folds.end(), p.folds.begin(), p.folds.end());
    }
    report.foldCount = report.folds.size();
    if (bounds) {
        bounds->setEmpty();
        for (const Part& p : parts)
            bounds->extend(Eigen::AlignedBox3d(Eigen::Vector3d(p.min[0], p.min[1], p.min[2]), Eigen::Vector3d(p.max[0], p.max[1], p.max[2])));
    }
}

} // namespace freeform::editor
