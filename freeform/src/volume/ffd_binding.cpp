// FfdBinding: cached lattice coordinates and the CPU-dispatched, multi-threaded FFD kernel
// (volume/deform.h; design in docs/ffd.md, "Performance").
//
// Layout: vertices in blocks of W = 64 bytes / sizeof(Scalar) lanes (8 doubles, 16 floats), each
// block x[W] y[W] z[W] s[W] t[W] u[W] (structure of arrays inside, blocks contiguous), so one
// block is six aligned vector loads and the kernel vectorises across vertices. Per block the
// kernel forms the Bernstein values (and derivatives) of every axis by the de Casteljau-style
// recursion (convex combinations), then sums the displacement coefficients as nested tensor sums
// (k innermost): about 250 fused multiply-adds per vertex for positions of a cubic lattice, 580
// with the Jacobian. Degrees 1, 2, 3 in all directions are compiled with constant bounds; other
// degrees use the same code with run-time bounds. Each kernel is cloned for x86-64-v4 (AVX-512),
// x86-64-v3 (AVX2 + FMA) and the baseline; the loader picks one for the running CPU.

#include "freeform/volume/deform.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>

#include "freeform/core/bernstein.h"
#include "freeform/core/parallel.h"

#include "cpu_dispatch.h" // FREEFORM_CPU_CLONES

namespace freeform {

namespace detail {

template <typename Scalar>
struct FfdKernelArgs {
    const Scalar* blocks = nullptr;
    std::size_t count = 0; // vertices
    int l = 0, m = 0, n = 0;
    const Scalar* d = nullptr; // strength * (P - R), 3 x N column-major
    Scalar dual[9] = {};       // row-major: (s,t,u) = dual * (p - X0)
    Scalar* positions = nullptr;
    const Scalar* normalsIn = nullptr;
    Scalar* normalsOut = nullptr;
    Scalar* jacobians = nullptr;
    Scalar* determinants = nullptr;
};

/// One block of lanes as a GCC vector (lowered to zmm, 2 x ymm or 4 x xmm by each clone).
template <typename Scalar>
struct LanesOf;
template <>
struct LanesOf<double> {
    typedef double type __attribute__((vector_size(64)));
};
template <>
struct LanesOf<float> {
    typedef float type __attribute__((vector_size(64)));
};
template <typename Scalar>
using Lanes = typename LanesOf<Scalar>::type;

template <typename V>
FREEFORM_CPU_INLINE void loadLanes(V& v, const void* p)
{
    std::memcpy(&v, p, sizeof(V));
}

/// Bernstein values b[0..deg] (and derivatives db) of degree deg at s, lane-wise, by the
/// recursion B_i^r = (1-s) B_i^(r-1) + s B_(i-1)^(r-1); db_i = deg (B_(i-1)^(deg-1) - B_i^(deg-1)).
template <typename Scalar, typename V, bool Jac>
FREEFORM_CPU_INLINE void laneBasis(int deg, const Scalar* lanes, V* b, V* db)
{
    V s;
    loadLanes(s, lanes);
    const V one = V{} + Scalar(1), r1 = one - s;
    b[0] = one;
    for (int r = 1; r < deg; ++r) {
        b[r] = s * b[r - 1];
        for (int i = r - 1; i >= 1; --i) b[i] = r1 * b[i] + s * b[i - 1];
        b[0] = r1 * b[0];
    }
    if constexpr (Jac) {
        const V fd = V{} + Scalar(deg);
        db[0] = -fd * b[0];
        for (int i = 1; i < deg; ++i) db[i] = fd * (b[i - 1] - b[i]);
        db[deg] = fd * b[deg - 1];
    }
    b[deg] = s * b[deg - 1];
    for (int i = deg - 1; i >= 1; --i) b[i] = r1 * b[i] + s * b[i - 1];
    b[0] = r1 * b[0];
}

template <typename Scalar, int L, int M, int N, bool Jac>
FREEFORM_CPU_INLINE void ffdBlocks(const FfdKernelArgs<Scalar>& a, std::size_t firstBlock,
                                                     std::size_t lastBlock)
{
    using V = Lanes<Scalar>;
    constexpr int W = FfdBinding<Scalar>::kLanes;
    static_assert(sizeof(V) == W * sizeof(Scalar));
    constexpr bool kFixed = L > 0 && M > 0 && N > 0;
    constexpr int kCap = kFixed ? std::max(L, std::max(M, N)) + 1 : kMaxDegree + 1;
    const int l = kFixed ? L : a.l, m = kFixed ? M : a.m, n = kFixed ? N : a.n;
    V bs[kCap], bt[kCap], bu[kCap];
    V ds[Jac ? kCap : 1], dt[Jac ? kCap : 1], du[Jac ? kCap : 1];
    const Scalar* dual = a.dual;

    for (std::size_t blk = firstBlock; blk < lastBlock; ++blk) {
        const Scalar* in = a.blocks + blk * 6 * W;
        laneBasis<Scalar, V, Jac>(l, in + 3 * W, bs, ds);
        laneBasis<Scalar, V, Jac>(m, in + 4 * W, bt, dt);
        laneBasis<Scalar, V, Jac>(n, in + 5 * W, bu, du);

        V dv[3] = {}, dvs[3] = {}, dvt[3] = {}, dvu[3] = {};
        for (int i = 0; i <= l; ++i) {
            V ai[3] = {}, bi[3] = {}, ci[3] = {};
            for (int j = 0; j <= m; ++j) {
                V p[3] = {}, q[3] = {};
                const Scalar* c = a.d + 3 * ((i * (m + 1) + j) * (n + 1));
                for (int k = 0; k <= n; ++k, c += 3) {
                    for (int x = 0; x < 3; ++x) {
                        p[x] += bu[k] * c[x];
                        if constexpr (Jac) q[x] += du[k] * c[x];
                    }
                }
                for (int x = 0; x < 3; ++x) {
                    ai[x] += bt[j] * p[x];
                    if constexpr (Jac) {
                        bi[x] += dt[j] * p[x];
                        ci[x] += bt[j] * q[x];
                    }
                }
            }
            for (int x = 0; x < 3; ++x) {
                dv[x] += bs[i] * ai[x];
                if constexpr (Jac) {
                    dvs[x] += ds[i] * ai[x];
                    dvt[x] += bs[i] * bi[x];
                    dvu[x] += bs[i] * ci[x];
                }
            }
        }

        const std::size_t base = blk * std::size_t(W);
        const std::size_t lanes = std::min<std::size_t>(W, a.count - base);
        V out[3];
        for (int x = 0; x < 3; ++x) {
            // p + 0 would turn -0.0 into +0.0: where the displacement is zero, p is kept as it is.
            V p;
            loadLanes(p, in + x * W);
            out[x] = dv[x] == Scalar(0) ? p : p + dv[x];
        }
        if (lanes == std::size_t(W)) {
            Scalar* o = a.positions + 3 * base;
            for (int w = 0; w < W; ++w)
                for (int x = 0; x < 3; ++x) o[3 * w + x] = out[x][w];
        } else {
            for (std::size_t w = 0; w < lanes; ++w)
                for (int x = 0; x < 3; ++x) a.positions[3 * (base + w) + std::size_t(x)] = out[x][w];
        }

        if constexpr (Jac) {
            // J = I + [dvs dvt dvu] dual; jac[c][r] = J(r, c).
            V jac[3][3];
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c)
                    jac[c][r] = dvs[r] * dual[c] + dvt[r] * dual[3 + c] + dvu[r] * dual[6 + c] + (r == c ? Scalar(1) : Scalar(0));
            // Columns c0, c1, c2 of J and their cross products (the columns of cof(J)).
            const V* c0 = jac[0];
            const V* c1 = jac[1];
            const V* c2 = jac[2];
            const V k0[3] = {c1[1] * c2[2] - c1[2] * c2[1], c1[2] * c2[0] - c1[0] * c2[2], c1[0] * c2[1] - c1[1] * c2[0]};
            const V det = c0[0] * k0[0] + c0[1] * k0[1] + c0[2] * k0[2];
            if (a.determinants)
                for (std::size_t w = 0; w < lanes; ++w) a.determinants[base + w] = det[w];
            if (a.jacobians)
                for (std::size_t w = 0; w < lanes; ++w)
                    for (int c = 0; c < 3; ++c)
                        for (int r = 0; r < 3; ++r) a.jacobians[9 * (base + w) + std::size_t(3 * c + r)] = jac[c][r][w];
            if (a.normalsOut) {
                V nin[3] = {};
                if (lanes == std::size_t(W)) {
                    const Scalar* src = a.normalsIn + 3 * base;
                    for (int w = 0; w < W; ++w)
                        for (int x = 0; x < 3; ++x) nin[x][w] = src[3 * w + x];
                } else {
                    for (std::size_t w = 0; w < lanes; ++w)
                        for (int x = 0; x < 3; ++x) nin[x][w] = a.normalsIn[3 * (base + w) + std::size_t(x)];
                }
                const V k1[3] = {c2[1] * c0[2] - c2[2] * c0[1], c2[2] * c0[0] - c2[0] * c0[2], c2[0] * c0[1] - c2[1] * c0[0]};
                const V k2[3] = {c0[1] * c1[2] - c0[2] * c1[1], c0[2] * c1[0] - c0[0] * c1[2], c0[0] * c1[1] - c0[1] * c1[0]};
                V nout[3];
                for (int x = 0; x < 3; ++x) nout[x] = nin[0] * k0[x] + nin[1] * k1[x] + nin[2] * k2[x];
                const V len2 = nout[0] * nout[0] + nout[1] * nout[1] + nout[2] * nout[2];
                V inv;
                for (int w = 0; w < W; ++w) inv[w] = len2[w] > Scalar(0) ? Scalar(1) / std::sqrt(len2[w]) : Scalar(0);
                for (int x = 0; x < 3; ++x) nout[x] *= inv;
                if (lanes == std::size_t(W)) {
                    Scalar* o = a.normalsOut + 3 * base;
                    for (int w = 0; w < W; ++w)
                        for (int x = 0; x < 3; ++x) o[3 * w + x] = nout[x][w];
                } else {
                    for (std::size_t w = 0; w < lanes; ++w)
                        for (int x = 0; x < 3; ++x) a.normalsOut[3 * (base + w) + std::size_t(x)] = nout[x][w];
                }
            }
        }
    }
}

namespace {

#define FREEFORM_FFD_KERNEL(Scalar, L, M, N, Jac, name)                                                     \
    FREEFORM_CPU_CLONES void name(const FfdKernelArgs<Scalar>& a, std::size_t first, std::size_t last)       \
    {                                                                                                        \
        ffdBlocks<Scalar, L, M, N, Jac>(a, first, last);                                                     \
    }
FREEFORM_FFD_KERNEL(double, 1, 1, 1, false, ffd_d111)
FREEFORM_FFD_KERNEL(double, 2, 2, 2, false, ffd_d222)
FREEFORM_FFD_KERNEL(double, 3, 3, 3, false, ffd_d333)
FREEFORM_FFD_KERNEL(double, 0, 0, 0, false, ffd_dany)
FREEFORM_FFD_KERNEL(double, 1, 1, 1, true, ffd_d111j)
FREEFORM_FFD_KERNEL(double, 2, 2, 2, true, ffd_d222j)
FREEFORM_FFD_KERNEL(double, 3, 3, 3, true, ffd_d333j)
FREEFORM_FFD_KERNEL(double, 0, 0, 0, true, ffd_danyj)
FREEFORM_FFD_KERNEL(float, 1, 1, 1, false, ffd_f111)
FREEFORM_FFD_KERNEL(float, 2, 2, 2, false, ffd_f222)
FREEFORM_FFD_KERNEL(float, 3, 3, 3, false, ffd_f333)
FREEFORM_FFD_KERNEL(float, 0, 0, 0, false, ffd_fany)
FREEFORM_FFD_KERNEL(float, 1, 1, 1, true, ffd_f111j)
FREEFORM_FFD_KERNEL(float, 2, 2, 2, true, ffd_f222j)
FREEFORM_FFD_KERNEL(float, 3, 3, 3, true, ffd_f333j)
FREEFORM_FFD_KERNEL(float, 0, 0, 0, true, ffd_fanyj)
#undef FREEFORM_FFD_KERNEL

template <typename Scalar>
using KernelFn = void (*)(const FfdKernelArgs<Scalar>&, std::size_t, std::size_t);

template <typename Scalar>
KernelFn<Scalar> pickKernel(int l, int m, int n, bool jac)
{
    const int equal = (l == m && m == n && l <= 3) ? l : 0;
    if constexpr (std::is_same_v<Scalar, double>) {
        static const KernelFn<double> table[2][4] = {{ffd_dany, ffd_d111, ffd_d222, ffd_d333},
                                                     {ffd_danyj, ffd_d111j, ffd_d222j, ffd_d333j}};
        return table[jac][equal];
    } else {
        static const KernelFn<float> table[2][4] = {{ffd_fany, ffd_f111, ffd_f222, ffd_f333},
                                                    {ffd_fanyj, ffd_f111j, ffd_f222j, ffd_f333j}};
        return table[jac][equal];
    }
}

/// Displacement D and its partials at lattice coordinates q (double, from the lattice directly).
void displacementJet(const Lattice& lattice, const Eigen::Vector3d& q, Eigen::Vector3d& dv, Eigen::Vector3d (&dd)[3])
{
    const int l = lattice.degree(0), m = lattice.degree(1), n = lattice.degree(2);
    double bs[kMaxDegree + 1], bt[kMaxDegree + 1], bu[kMaxDegree + 1];
    double ds[kMaxDegree + 1], dt[kMaxDegree + 1], du[kMaxDegree + 1], scratch[kMaxDegree + 1];
    bernsteinAll(l, q[0], bs);
    bernsteinAll(m, q[1], bt);
    bernsteinAll(n, q[2], bu);
    bernsteinDerivativeAll(l, 1, q[0], ds, scratch);
    bernsteinDerivativeAll(m, 1, q[1], dt, scratch);
    bernsteinDerivativeAll(n, 1, q[2], du, scratch);
    const auto& d = lattice.displacements();
    dv.setZero();
    for (auto& v : dd) v.setZero();
    for (int i = 0; i <= l; ++i)
        for (int j = 0; j <= m; ++j)
            for (int k = 0; k <= n; ++k) {
                const Eigen::Vector3d c = d.col(lattice.index(i, j, k));
                dv += bs[i] * bt[j] * bu[k] * c;
                dd[0] += ds[i] * bt[j] * bu[k] * c;
                dd[1] += bs[i] * dt[j] * bu[k] * c;
                dd[2] += bs[i] * bt[j] * du[k] * c;
            }
}

/// The frame as Lattice::toLattice uses it: rows of the numerator (T x U, S x U, S x T) and the
/// denominators, formed by the same Eigen expressions as Lattice's constructor (so the same bits).
struct BindFrame {
    double origin[3];
    double num[3][3];
    double den[3];
    bool clamp;
};

/// Binds blocks [firstBlock, lastBlock): positions and lattice coordinates (toLattice's arithmetic,
/// the same operations in the same order: (n0 q0 + (n1 q1 + n2 q2)) / den, as Eigen's unrolled dot
/// product of 3 sums them), lane by lane so that the divisions vectorise. Vertices outside the box
/// are appended to `outside` in order; returns the first vertex that is not finite, or count.
template <typename Scalar, typename In>
FREEFORM_CPU_INLINE std::size_t bindBlocks(const BindFrame& f, const In* positions, std::size_t count,
                                                              Scalar* data, std::size_t firstBlock, std::size_t lastBlock,
                                                              std::vector<int>& outside)
{
    constexpr int W = FfdBinding<Scalar>::kLanes;
    for (std::size_t blk = firstBlock; blk < lastBlock; ++blk) {
        Scalar* b = data + blk * 6 * W;
        alignas(64) double q[3][W];
        alignas(64) double stu[3][W];
        if ((blk + 1) * W <= count) {
            const In* p = positions + 3 * blk * W;
            for (int w = 0; w < W; ++w)
                for (int x = 0; x < 3; ++x) {
                    const In c = p[3 * w + x];
                    b[x * W + w] = static_cast<Scalar>(c);
                    q[x][w] = double(c) - f.origin[x];
                }
        } else {
            for (int w = 0; w < W; ++w) {
                // Padding lanes repeat the last vertex (finite numbers; never written out).
                const std::size_t v = std::min(blk * W + std::size_t(w), count - 1);
                for (int x = 0; x < 3; ++x) {
                    const In c = positions[3 * v + std::size_t(x)];
                    b[x * W + w] = static_cast<Scalar>(c);
                    q[x][w] = double(c) - f.origin[x];
                }
            }
        }
        for (int a = 0; a < 3; ++a)
            for (int w = 0; w < W; ++w)
                stu[a][w] = (f.num[a][0] * q[0][w] + (f.num[a][1] * q[1][w] + f.num[a][2] * q[2][w])) / f.den[a];
        unsigned bad = 0, out = 0;
        for (int w = 0; w < W; ++w) {
            for (int x = 0; x < 3; ++x)
                bad |= static_cast<unsigned>(!(std::abs(q[x][w]) <= std::numeric_limits<double>::max()));
            out |= static_cast<unsigned>(!(stu[0][w] >= 0.0 && stu[0][w] <= 1.0 && stu[1][w] >= 0.0 &&
                                           stu[1][w] <= 1.0 && stu[2][w] >= 0.0 && stu[2][w] <= 1.0));
        }
        if (bad) {
            for (int w = 0; w < W; ++w) {
                const std::size_t v = std::min(blk * W + std::size_t(w), count - 1);
                for (int x = 0; x < 3; ++x)
                    if (!std::isfinite(double(positions[3 * v + std::size_t(x)]))) return v;
            }
        }
        if (out) {
            for (int w = 0; w < W; ++w) {
                const bool o = !(stu[0][w] >= 0.0 && stu[0][w] <= 1.0 && stu[1][w] >= 0.0 && stu[1][w] <= 1.0 &&
                                 stu[2][w] >= 0.0 && stu[2][w] <= 1.0);
                if (!o) continue;
                if (blk * W + std::size_t(w) < count) outside.push_back(static_cast<int>(blk * W + std::size_t(w)));
                if (f.clamp)
                    for (int a = 0; a < 3; ++a) stu[a][w] = std::min(std::max(stu[a][w], 0.0), 1.0); // as cwiseMax/Min
            }
        }
        for (int a = 0; a < 3; ++a)
            for (int w = 0; w < W; ++w) b[(3 + a) * W + w] = static_cast<Scalar>(stu[a][w]);
    }
    return count;
}

// Cloned like the kernels, without contraction into fused multiply-adds (which would change the
// bits of the lattice coordinates against Lattice::toLattice): GCC's optimize attribute, clang's
// fp pragma (clang contracts within an expression by default where the target has FMA).
#if defined(__clang__)
#define FREEFORM_NO_CONTRACT
#define FREEFORM_NO_CONTRACT_BODY _Pragma("clang fp contract(off)")
#elif defined(__GNUC__)
#define FREEFORM_NO_CONTRACT __attribute__((optimize("fp-contract=off")))
#define FREEFORM_NO_CONTRACT_BODY
#else
#define FREEFORM_NO_CONTRACT
#define FREEFORM_NO_CONTRACT_BODY
#endif
#define FREEFORM_BIND_KERNEL(Scalar, In, name)                                                                        \
    FREEFORM_CPU_CLONES FREEFORM_NO_CONTRACT std::size_t name(const BindFrame& f, const In* positions,                  \
                                                              std::size_t count, Scalar* data, std::size_t first,       \
                                                              std::size_t last, std::vector<int>& outside)              \
    {                                                                                                                  \
        FREEFORM_NO_CONTRACT_BODY                                                                                      \
        return bindBlocks<Scalar, In>(f, positions, count, data, first, last, outside);                                \
    }
FREEFORM_BIND_KERNEL(double, double, bind_dd)
FREEFORM_BIND_KERNEL(double, float, bind_df)
FREEFORM_BIND_KERNEL(float, double, bind_fd)
FREEFORM_BIND_KERNEL(float, float, bind_ff)
#undef FREEFORM_BIND_KERNEL

inline std::size_t bindKernel(const BindFrame& f, const double* p, std::size_t n, double* d, std::size_t a, std::size_t b,
                              std::vector<int>& o) { return bind_dd(f, p, n, d, a, b, o); }
inline std::size_t bindKernel(const BindFrame& f, const float* p, std::size_t n, double* d, std::size_t a, std::size_t b,
                              std::vector<int>& o) { return bind_df(f, p, n, d, a, b, o); }
inline std::size_t bindKernel(const BindFrame& f, const double* p, std::size_t n, float* d, std::size_t a, std::size_t b,
                              std::vector<int>& o) { return bind_fd(f, p, n, d, a, b, o); }
inline std::size_t bindKernel(const BindFrame& f, const float* p, std::size_t n, float* d, std::size_t a, std::size_t b,
                              std::vector<int>& o) { return bind_ff(f, p, n, d, a, b, o); }

/// The BindFrame of a lattice, or nullopt when it does not reproduce the lattice's own dual() and
/// toLattice() bit for bit at the probe points (then bind() takes the point-by-point path through
/// toLattice). Only on x86-64, where Lattice::toLattice (baseline code, no FMA) and the lanes
/// compute the same operations; elsewhere always the point-by-point path.
FREEFORM_NO_CONTRACT std::optional<BindFrame> bindFrame(const Lattice& lattice, const std::vector<Eigen::Vector3d>& probes)
{
    FREEFORM_NO_CONTRACT_BODY
#if !defined(__x86_64__)
    (void)lattice;
    (void)probes;
    return std::nullopt;
#else
    const Eigen::Matrix3d& axes = lattice.axes();
    const Eigen::Vector3d s = axes.col(0), t = axes.col(1), u = axes.col(2);
    Eigen::Matrix3d num;
    num.row(0) = t.cross(u).transpose();
    num.row(1) = s.cross(u).transpose();
    num.row(2) = s.cross(t).transpose();
    const Eigen::Vector3d den(num.row(0).dot(s), num.row(1).dot(t), num.row(2).dot(u));
    BindFrame f{};
    for (int a = 0; a < 3; ++a) {
        if (num.row(a) / den[a] != lattice.dual().row(a)) return std::nullopt;
        f.origin[a] = lattice.origin()[a];
        f.den[a] = den[a];
        for (int c = 0; c < 3; ++c) f.num[a][c] = num(a, c);
    }
    f.clamp = clampsOutside(lattice.outside()); // outsideRule's clamp, lane by lane in bindBlocks
    for (const Eigen::Vector3d& probe : probes) {
        const Eigen::Vector3d q = probe - lattice.origin();
        const Eigen::Vector3d expected = lattice.toLattice(probe);
        for (int a = 0; a < 3; ++a) {
            const double mine = (f.num[a][0] * q[0] + (f.num[a][1] * q[1] + f.num[a][2] * q[2])) / f.den[a];
            if (std::memcmp(&mine, &expected[a], sizeof mine) != 0) return std::nullopt;
        }
    }
    return f;
#endif
}

template <typename Scalar>
Scalar* alignedArray(std::size_t count)
{
    const std::size_t bytes = std::max<std::size_t>(64, (count * sizeof(Scalar) + 63) / 64 * 64);
    void* p = std::aligned_alloc(64, bytes);
    if (!p) throw std::bad_alloc();
    return static_cast<Scalar*>(p);
}

} // namespace
} // namespace detail

template <typename Scalar>
FfdBinding<Scalar>::FfdBinding(const Lattice& lattice, const double* positions, std::size_t count) : lattice_(lattice)
{
    bind(lattice, positions, count);
}

template <typename Scalar>
FfdBinding<Scalar>::FfdBinding(const Lattice& lattice, const float* positions, std::size_t count) : lattice_(lattice)
{
    bind(lattice, positions, count);
}

template <typename Scalar>
template <typename In>
void FfdBinding<Scalar>::bind(const Lattice& lattice, const In* positions, std::size_t count)
{
    constexpr int W = kLanes;
    count_ = count;
    blocks_ = (count + W - 1) / W;
    data_ = std::shared_ptr<Scalar>(detail::alignedArray<Scalar>(blocks_ * 6 * W), std::free);
    Scalar* data = data_.get();
    const OutsidePolicy policy = lattice.outside();
    std::vector<std::vector<int>> outsideChunks(static_cast<std::size_t>(parallelChunkCount(0, blocks_, 256, 0)));
    // Probes: the first, middle and last points (when finite) and three points of the box.
    std::vector<Eigen::Vector3d> probes;
    for (const std::size_t v : {std::size_t(0), count / 2, count ? count - 1 : 0}) {
        if (v >= count) continue;
        const Eigen::Vector3d p{double(positions[3 * v]), double(positions[3 * v + 1]), double(positions[3 * v + 2])};
        if (p.allFinite()) probes.push_back(p);
    }
    for (const Eigen::Vector3d& stu : {Eigen::Vector3d(0.3, 0.7, 0.1), Eigen::Vector3d(1.7, -0.2, 0.6),
                                      Eigen::Vector3d(0.123, 0.456, 0.789)})
        probes.push_back(lattice.toWorld(stu));
    const std::optional<detail::BindFrame> frame = detail::bindFrame(lattice, probes);
    if (frame && count) {
        std::vector<std::size_t> bad(outsideChunks.size(), count);
        parallelFor(0, blocks_, 256, 0, [&](int chunk, std::size_t first, std::size_t last) {
            bad[static_cast<std::size_t>(chunk)] =
                detail::bindKernel(*frame, positions, count, data, first, last, outsideChunks[static_cast<std::size_t>(chunk)]);
        });
        for (const std::size_t v : bad)
            if (v < count) throw Error("ffd: vertex " + std::to_string(v) + " is not finite");
    } else
    parallelFor(0, blocks_, 256, 0, [&](int chunk, std::size_t first, std::size_t last) {
        auto& outside = outsideChunks[static_cast<std::size_t>(chunk)];
        for (std::size_t blk = first; blk < last; ++blk) {
            Scalar* b = data + blk * 6 * W;
            for (int w = 0; w < W; ++w) {
                // Padding lanes repeat the last vertex (finite numbers; never written out).
                const std::size_t v = std::min(blk * W + std::size_t(w), count - 1);
                const Eigen::Vector3d p{double(positions[3 * v]), double(positions[3 * v + 1]), double(positions[3 * v + 2])};
                if (!p.allFinite()) throw Error("ffd: vertex " + std::to_string(v) + " is not finite");
                // Keep's outside points are evaluated clamped too, then put back (below).
                const OutsideRule rule = outsideRule(lattice.toLattice(p), policy);
                if (rule.outside && blk * W + std::size_t(w) < count) outside.push_back(static_cast<int>(v));
                for (int x = 0; x < 3; ++x) {
                    b[x * W + w] = static_cast<Scalar>(positions[3 * v + std::size_t(x)]);
                    b[(3 + x) * W + w] = static_cast<Scalar>(rule.at[x]);
                }
            }
        }
    });
    for (const auto& c : outsideChunks) outside_.insert(outside_.end(), c.begin(), c.end());
    raw_.resize(3 * outside_.size());
    for (std::size_t o = 0; o < outside_.size(); ++o) {
        const std::size_t v = static_cast<std::size_t>(outside_[o]);
        const Eigen::Vector3d p{double(positions[3 * v]), double(positions[3 * v + 1]), double(positions[3 * v + 2])};
        Eigen::Map<Eigen::Vector3d>(raw_.data() + 3 * o) = lattice.toLattice(p);
    }
}

template <typename Scalar>
Eigen::Vector3d FfdBinding<Scalar>::parameters(std::size_t v) const
{
    const auto it = std::lower_bound(outside_.begin(), outside_.end(), static_cast<int>(v));
    if (it != outside_.end() && *it == static_cast<int>(v))
        return Eigen::Map<const Eigen::Vector3d>(raw_.data() + 3 * static_cast<std::size_t>(it - outside_.begin()));
    const Scalar* b = data_.get() + (v / kLanes) * 6 * kLanes + v % kLanes;
    return Eigen::Vector3d(double(b[3 * kLanes]), double(b[4 * kLanes]), double(b[5 * kLanes]));
}

template <typename Scalar>
void FfdBinding<Scalar>::copyPositions(Scalar* out) const
{
    constexpr int W = kLanes;
    for (std::size_t v = 0; v < count_; ++v) {
        const Scalar* b = data_.get() + (v / W) * 6 * W + v % W;
        for (int x = 0; x < 3; ++x) out[3 * v + std::size_t(x)] = b[x * W];
    }
}

template <typename Scalar>
void FfdBinding<Scalar>::deform(const Lattice& lattice, const FfdOutputs<Scalar>& out, const DeformOptions& options,
                                DeformReport* report) const
{
    if (!lattice.sameFrame(lattice_) || lattice.outside() != lattice_.outside())
        throw Error("ffd: the lattice's degrees, frame or outside policy differ from the ones the points were bound to");
    if (!out.positions) throw Error("ffd: no output array for the positions");
    if (out.normalsOut && !out.normalsIn) throw Error("ffd: normals requested without input normals");
    if (!std::isfinite(options.strength)) throw Error("ffd: strength is not finite");
    if (count_ == 0) {
        if (report) *report = DeformReport{};
        return;
    }
    constexpr int W = kLanes;
    const double w = options.strength;

    // Scaled displacement coefficients in Scalar.
    const auto& disp = lattice.displacements();
    std::vector<Scalar> d(static_cast<std::size_t>(disp.size()));
    for (Eigen::Index i = 0; i < disp.size(); ++i) d[static_cast<std::size_t>(i)] = static_cast<Scalar>(w * disp.data()[i]);

    std::unique_ptr<Scalar, decltype(&std::free)> detScratch(nullptr, std::free);
    Scalar* determinants = out.determinants;
    if (report && !determinants) {
        detScratch.reset(detail::alignedArray<Scalar>(count_));
        determinants = detScratch.get();
    }
    const bool jac = out.normalsOut || out.jacobians || determinants;

    detail::FfdKernelArgs<Scalar> args;
    args.blocks = data_.get();
    args.count = count_;
    args.l = lattice.degree(0);
    args.m = lattice.degree(1);
    args.n = lattice.degree(2);
    args.d = d.data();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) args.dual[3 * r + c] = static_cast<Scalar>(lattice.dual()(r, c));
    args.positions = out.positions;
    args.normalsIn = out.normalsIn;
    args.normalsOut = out.normalsOut;
    args.jacobians = out.jacobians;
    args.determinants = determinants;
    const auto kernel = detail::pickKernel<Scalar>(args.l, args.m, args.n, jac);
    parallelFor(0, blocks_, 64, options.threads,
                [&](int, std::size_t first, std::size_t last) { kernel(args, first, last); });

    // Outside vertices under keep (unchanged) and, for the Jacobian, under clamp (no change of the
    // displacement across the box faces they lie beyond).
    const OutsidePolicy policy = lattice.outside();
    if (policy == OutsidePolicy::Keep || (policy == OutsidePolicy::Clamp && jac)) {
        parallelFor(0, outside_.size(), 1024, options.threads, [&](int, std::size_t first, std::size_t last) {
            for (std::size_t o = first; o < last; ++o) {
                const std::size_t v = static_cast<std::size_t>(outside_[o]);
                const Scalar* b = data_.get() + (v / W) * 6 * W + v % W;
                Eigen::Matrix3d j = Eigen::Matrix3d::Identity();
                if (policy == OutsidePolicy::Keep) {
                    for (int x = 0; x < 3; ++x) out.positions[3 * v + std::size_t(x)] = b[x * W];
                } else {
                    const OutsideRule rule = outsideRule(Eigen::Map<const Eigen::Vector3d>(raw_.data() + 3 * o), policy);
                    Eigen::Vector3d dv, dd[3];
                    detail::displacementJet(lattice, rule.at, dv, dd);
                    for (int a = 0; a < 3; ++a)
                        if (rule.follows(a)) j += w * dd[a] * lattice.dual().row(a);
                }
                if (determinants) determinants[v] = static_cast<Scalar>(j.determinant());
                if (out.jacobians)
                    for (int c = 0; c < 9; ++c) out.jacobians[9 * v + std::size_t(c)] = static_cast<Scalar>(j.data()[c]);
                if (out.normalsOut) {
                    const Eigen::Vector3d n{double(out.normalsIn[3 * v]), double(out.normalsIn[3 * v + 1]),
                                            double(out.normalsIn[3 * v + 2])};
                    const Eigen::Vector3d m = transformNormal(j, n);
                    for (int x = 0; x < 3; ++x) out.normalsOut[3 * v + std::size_t(x)] = static_cast<Scalar>(m[x]);
                }
            }
        });
    }

    if (report) {
        const int chunks = parallelChunkCount(0, count_, 4096, options.threads);
        struct Part {
            double lo = 1, hi = 1;
            std::vector<int> folds;
        };
        std::vector<Part> parts(static_cast<std::size_t>(chunks));
        parallelFor(0, count_, 4096, options.threads, [&](int c, std::size_t first, std::size_t last) {
            Part& part = parts[static_cast<std::size_t>(c)];
            double lo = double(determinants[first]), hi = lo;
            for (std::size_t v = first; v < last; ++v) {
                const double det = double(determinants[v]);
                lo = std::min(lo, det);
                hi = std::max(hi, det);
                if (!(det > 0)) part.folds.push_back(static_cast<int>(v));
            }
            part.lo = lo;
            part.hi = hi;
        });
        DeformReport r;
        r.vertices = count_;
        r.outside = outside_.size();
        r.minDetJ = parts[0].lo;
        r.maxDetJ = parts[0].hi;
        for (const Part& p : parts) {
            r.minDetJ = std::min(r.minDetJ, p.lo);
            r.maxDetJ = std::max(r.maxDetJ, p.hi);
            r.folds.insert(r.folds.end(), p.folds.begin(), p.folds.end());
        }
        r.foldCount = r.folds.size();
        *report = std::move(r);
    }
}

template class FfdBinding<float>;
template class FfdBinding<double>;

} // namespace freeform
