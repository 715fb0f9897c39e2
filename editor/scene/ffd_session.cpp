#include "scene/ffd_session.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "freeform/core/bernstein.h" // kMaxDegree
#include "freeform/core/parallel.h"

namespace freeform::editor {

FfdSession::FfdSession(const Lattice& lattice, PolygonMesh rest)
    : frame_(lattice), rest_(std::move(rest)), binding_(lattice, rest_.positions), restNormals_(rest_.normals.cast<float>())
{
}

bool FfdSession::matches(const Lattice& lattice) const
{
    return lattice.sameFrame(frame_) && lattice.outside() == frame_.outside();
}

DeformReport FfdSession::deform(const Lattice& lattice, double strength, PolygonMesh& out, std::vector<float>* detJ,
                                Eigen::AlignedBox3d* bounds, bool live)
{
    approximate_ = false;
    const Eigen::Index count = rest_.positions.cols();
    const bool normals = rest_.normals.cols() == count;
    positions_.resize(3, count);
    if (out.positions.cols() != count) out.positions.resize(3, count);
    FfdOutputs<float> o;
    o.positions = positions_.data();
    if (normals) {
        normals_.resize(3, count);
        if (out.normals.cols() != count) out.normals.resize(3, count);
        o.normalsIn = restNormals_.data();
        o.normalsOut = normals_.data();
    }
    if (detJ) {
        detJ->resize(static_cast<std::size_t>(count));
        o.determinants = detJ->data();
    }
    DeformOptions options;
    options.strength = strength;
    DeformReport report;
    if (lattice.isRest() || strength == 0) {
        // The identity: the file's own vertices, bit for bit (float would round them), det J 1.
        out.positions = rest_.positions;
        if (normals) out.normals = rest_.normals;
        if (detJ) std::fill(detJ->begin(), detJ->end(), 1.0f);
        drag_.reset();
        previous_ = lattice.controlPoints();
        // The base of the next grab: the identity (no copy: grabDrag reads the rest mesh).
        base_ = normals ? Base::Identity : Base::None;
        basePoints_ = lattice.controlPoints();
        baseStrength_ = strength;
        report.vertices = static_cast<std::size_t>(count);
        report.outside = binding_.outsideVertices().size();
        if (bounds) {
            bounds->setEmpty();
            for (Eigen::Index k = 0; k < count; ++k) bounds->extend(Eigen::Vector3d(out.positions.col(k)));
        }
        return report;
    }
    std::vector<float> scratch;
    if (!detJ) {
        scratch.resize(static_cast<std::size_t>(count));
        o.determinants = scratch.data();
    }
    if (!live) {
        drag_.reset();
    } else if (const auto delta = dragDelta(lattice, strength)) {
        // A drag frame that only translates the drag's points further: the linear update.
        dragFrame(*delta, normals, out, o.determinants, report, bounds);
        approximate_ = true;
        previous_ = lattice.controlPoints();
        return report;
    } else if (base_ != Base::None && normals && baseStrength_ == strength && basePoints_.cols() == lattice.controlPoints().cols() &&
               binding_.outsideVertices().empty()) {
        // The grab: when the points that moved since the last full evaluation (or the identity)
        // moved by one common vector, the drag starts from that evaluation without a new one.
        // Only for meshes inside the lattice box (the outside policies' handling in grabDrag is
        // not covered by a test yet; with vertices outside, the grab is today's full path).
        auto drag = std::make_unique<Drag>();
        drag->points = basePoints_;
        drag->strength = strength;
        for (Eigen::Index k = 0; k < basePoints_.cols(); ++k)
            if (basePoints_.col(k) != lattice.controlPoints().col(k)) drag->moved.push_back(static_cast<int>(k));
        if (!drag->moved.empty()) {
            drag_ = std::move(drag);
            if (const auto grabDelta = dragDelta(lattice, strength)) {
                grabDrag(lattice, strength, drag_->moved);
                dragFrame(*grabDelta, normals, out, o.determinants, report, bounds);
                approximate_ = true;
                previous_ = lattice.controlPoints();
                return report;
            }
            drag_.reset();
        }
    }
    // The full evaluation; its report, the double copy and the bounds come from one pass below.
    // In a drag, when the points that moved since the last evaluation are known, the Jacobians
    // are kept too: the next frames of the drag are linear updates from this one.
    std::vector<int> moved;
    if (live && previous_.cols() == lattice.controlPoints().cols())
        for (Eigen::Index k = 0; k < previous_.cols(); ++k)
            if (previous_.col(k) != lattice.controlPoints().col(k)) moved.push_back(static_cast<int>(k));
    drag_.reset();
    // The Jacobians A are kept with every full evaluation (with normals): the next grab starts
    // from them (grabDrag).
    if (normals) {
        jacobians_.resize(9 * static_cast<std::size_t>(count));
        o.jacobians = jacobians_.data();
    }
    binding_.deform(lattice, o, options, nullptr);
    finish(o.determinants, normals, out, report, bounds);
    base_ = normals ? Base::Evaluated : Base::None;
    if (normals) {
        baseDet_.assign(o.determinants, o.determinants + count);
        basePoints_ = lattice.controlPoints();
        baseStrength_ = strength;
    }
    if (o.jacobians && !moved.empty()) startDrag(lattice, strength, std::move(moved), jacobians_, o.determinants);
    previous_ = lattice.controlPoints();
    return report;
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

void FfdSession::startDrag(const Lattice& lattice, double strength, std::vector<int> moved, const std::vector<float>& jacobians,
                           const float* det)
{
    // Per vertex, from the evaluation just made (J = A there): with every point of the set moved
    // by the same delta, D changes by w B delta and J by u v^T, u = w delta, v = dual^T grad B,
    // B the sum of the set's Bernstein products (docs/architecture.md, "Lattice drag"). Then
    //   p = p0 + B u,   det J = det A + (cof(A) v) . u,   cof(J) n = cof(A) n + u x (A (n x v)),
    // the last because cof(M) has the columns m1 x m2, m2 x m0, m0 x m1. Normals are stored as
    // n0 = cof(A) n / |cof(A) n| and h = A (n x v) / |cof(A) n|, so n = normalise(n0 + u x h).
    constexpr int W = kLanes;
    const std::size_t count = static_cast<std::size_t>(positions_.cols());
    auto drag = std::make_unique<Drag>();
    drag->points = lattice.controlPoints();
    drag->strength = strength;
    drag->moved = std::move(moved);
    // (The scratch arrays stay allocated between drags: fresh pages cost more than the work.)
    dragData_.resize(((count + W - 1) / W) * kFields * W);
    // B and v of every vertex by the library's own kernel (so with its outside policy): by
    // linearity, the lattice whose set is displaced by 2^10 e_x (all else at rest), strength 1,
    // gives p + 2^10 B e_x and J = I + 2^10 e_x v^T (a power of two: the scaling is exact).
    constexpr float kScale = 1024.0f;
    Lattice unit = lattice;
    Lattice::Points points = lattice.restPoints();
    for (const int k : drag->moved) points(0, k) += double(kScale);
    unit.setControlPoints(points);
    unitPositions_.resize(3, static_cast<Eigen::Index>(count));
    unitJacobians_.resize(9 * count);
    const auto& unitPositions = unitPositions_;
    FfdOutputs<float> o;
    o.positions = unitPositions_.data();
    o.jacobians = unitJacobians_.data();
    binding_.deform(unit, o);
    const Eigen::Matrix<double, 3, Eigen::Dynamic>& restPositions = rest_.positions;
    parallelFor(0, count, 4096, 0, [&](int, std::size_t first, std::size_t last) {
        for (std::size_t v = first; v < last; ++v) {
            const auto col = static_cast<Eigen::Index>(v);
            // The x coordinate as the kernel holds it (float), then the displacement it added.
            const double b = (double(unitPositions(0, col)) - double(float(restPositions(0, col)))) / kScale;
            const float* uj = unitJacobians_.data() + 9 * v; // column-major: J(0, c) = uj[3 c]
            const Eigen::Vector3d gv((double(uj[0]) - 1) / kScale, double(uj[3]) / kScale, double(uj[6]) / kScale);
            const Eigen::Matrix3d a = Eigen::Map<const Eigen::Matrix<float, 3, 3>>(jacobians.data() + 9 * v).cast<double>();
            const Eigen::Vector3d k0 = a.col(1).cross(a.col(2)), k1 = a.col(2).cross(a.col(0)), k2 = a.col(0).cross(a.col(1));
            const Eigen::Vector3d nr = rest_.normals.col(static_cast<Eigen::Index>(v));
            const Eigen::Vector3d c0 = nr[0] * k0 + nr[1] * k1 + nr[2] * k2;
            const Eigen::Vector3d e = gv[0] * k0 + gv[1] * k1 + gv[2] * k2;
            Eigen::Vector3d h = a * nr.cross(gv);
            if (const double len = c0.norm(); len > 0) h /= len;
            float* blk = dragData_.data() + (v / W) * kFields * W + v % W;
            const float values[kFields] = {positions_(0, Eigen::Index(v)), positions_(1, Eigen::Index(v)), positions_(2, Eigen::Index(v)),
                                           normals_(0, Eigen::Index(v)),   normals_(1, Eigen::Index(v)),   normals_(2, Eigen::Index(v)),
                                           float(h[0]), float(h[1]), float(h[2]), float(e[0]), float(e[1]), float(e[2]), float(b), det[v]};
            for (int f = 0; f < kFields; ++f) blk[f * W] = values[f];
        }
    });
    drag_ = std::move(drag);
}

void FfdSession::grabDrag(const Lattice& lattice, double strength, std::vector<int> moved)
{
    // As startDrag, with A, p0, n0 and det A from the base, and B and v = dual^T grad B computed
    // here: B(s,t,u) = sum over the moved points (i,j,k) of B_i(s) B_j(t) B_k(u), at the bound
    // lattice coordinates with the outside policy as FfdBinding::deform applies it: inside the box
    // and under extrapolate the coordinates as bound; under clamp the clamped coordinates, and
    // no gradient along an axis whose coordinate lies outside [0, 1] (the library's Jacobian
    // there); under keep nothing moves outside (B = 0, v = 0, A = I). (deform() calls this only
    // when no vertex is outside, so the outside branches are not reached yet: no test covers them.)
    (void)strength;
    constexpr int W = kLanes;
    const std::size_t count = static_cast<std::size_t>(positions_.cols());
    const OutsidePolicy policy = lattice.outside();
    const int deg[3] = {lattice.degree(0), lattice.degree(1), lattice.degree(2)};
    std::vector<std::array<int, 3>> ijk;
    ijk.reserve(moved.size());
    for (const int k : moved) {
        const int nu = deg[2] + 1, nt = deg[1] + 1;
        ijk.push_back({k / (nt * nu), (k / nu) % nt, k % nu});
    }
    float dual[9]; // row-major
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) dual[3 * r + c] = float(lattice.dual()(r, c));
    const Eigen::Matrix3d toLattice = lattice.dual();
    const Eigen::Vector3d origin = lattice.origin();
    const std::vector<int>& outside = binding_.outsideVertices();
    const bool identity = base_ == Base::Identity;
    const std::size_t blocks = (count + W - 1) / W;
    dragData_.resize(blocks * kFields * W);
    // In float, W lanes at a time (loops over the lanes the compiler vectorises), as dragFrame.
    parallelFor(0, blocks, 256, 0, [&](int, std::size_t firstBlock, std::size_t lastBlock) {
        auto it = std::lower_bound(outside.begin(), outside.end(), static_cast<int>(firstBlock * W));
        float q[3][W], act[3][W], on[W], a[9][W], nr[3][W], p0[3][W], n0[3][W], det0[W];
        float b[3][kMaxDegree + 1][W], db[3][kMaxDegree + 1][W];
        for (std::size_t blk = firstBlock; blk < lastBlock; ++blk) {
            // Gather: coordinates with the policy, the base's A, p0, n0, det A, the rest normal.
            for (int w = 0; w < W; ++w) {
                const std::size_t v = std::min(blk * W + std::size_t(w), count - 1); // padding repeats the last vertex
                const auto col = static_cast<Eigen::Index>(v);
                const bool out = it != outside.end() && *it == static_cast<int>(v);
                if (out && blk * W + std::size_t(w) < count) ++it;
                on[w] = out && policy == OutsidePolicy::Keep ? 0.0f : 1.0f;
                // Inside the box the coordinates dual (p - X0) (as the binding's to float rounding, without
                // a library call per vertex); outside, the binding's own unclamped ones.
                const Eigen::Vector3d raw = out ? binding_.parameters(v) : Eigen::Vector3d(toLattice * (rest_.positions.col(col) - origin));
                for (int x = 0; x < 3; ++x) {
                    double t = raw[x];
                    act[x][w] = 1.0f;
                    if (out && policy == OutsidePolicy::Clamp && (t < 0 || t > 1)) {
                        act[x][w] = 0.0f;
                        t = std::clamp(t, 0.0, 1.0);
                    }
                    q[x][w] = float(t);
                    nr[x][w] = restNormals_(x, col);
                }
                if (identity) {
                    const float len = std::sqrt(nr[0][w] * nr[0][w] + nr[1][w] * nr[1][w] + nr[2][w] * nr[2][w]);
                    for (int x = 0; x < 3; ++x) {
                        p0[x][w] = float(rest_.positions(x, col));
                        n0[x][w] = len > 0 ? nr[x][w] / len : 0.0f;
                    }
                    for (int c = 0; c < 9; ++c) a[c][w] = c % 4 == 0 ? 1.0f : 0.0f;
                    det0[w] = 1.0f;
                } else {
                    for (int x = 0; x < 3; ++x) {
                        p0[x][w] = positions_(x, col);
                        n0[x][w] = normals_(x, col);
                    }
                    const float* j = jacobians_.data() + 9 * v; // column-major: A(r, c) = j[3 c + r]
                    for (int c = 0; c < 9; ++c) a[c][w] = j[c];
                    det0[w] = baseDet_[v];
                }
            }
            // Bernstein values and derivatives of each axis by the triangle (no binomials).
            for (int x = 0; x < 3; ++x) {
                const int n = deg[x];
                if (n == 3) { // the usual lattice, in closed form
                    for (int w = 0; w < W; ++w) {
                        const float t = q[x][w], r = 1.0f - t;
                        b[x][0][w] = r * r * r, b[x][1][w] = 3 * t * r * r, b[x][2][w] = 3 * t * t * r, b[x][3][w] = t * t * t;
                        db[x][0][w] = -3 * r * r, db[x][1][w] = 3 * (r * r - 2 * t * r), db[x][2][w] = 3 * (2 * t * r - t * t),
                        db[x][3][w] = 3 * t * t;
                    }
                    continue;
                }
                for (int w = 0; w < W; ++w) {
                    b[x][0][w] = 1.0f;
                    db[x][0][w] = 0.0f;
                }
                for (int d = 1; d <= n; ++d) {
                    if (d == n)
                        for (int i = 0; i <= n; ++i)
                            for (int w = 0; w < W; ++w)
                                db[x][i][w] = float(n) * ((i > 0 ? b[x][i - 1][w] : 0.0f) - (i < n ? b[x][i][w] : 0.0f));
                    for (int w = 0; w < W; ++w) {
                        const float t = q[x][w], r = 1.0f - t;
                        b[x][d][w] = t * b[x][d - 1][w];
                        for (int i = d - 1; i > 0; --i) b[x][i][w] = r * b[x][i][w] + t * b[x][i - 1][w];
                        b[x][0][w] *= r;
                    }
                }
            }
            float bs[W], g[3][W];
            for (int w = 0; w < W; ++w) bs[w] = g[0][w] = g[1][w] = g[2][w] = 0.0f;
            for (const auto& m : ijk)
                for (int w = 0; w < W; ++w) {
                    const float x = b[0][m[0]][w], y = b[1][m[1]][w], z = b[2][m[2]][w];
                    bs[w] += x * y * z;
                    g[0][w] += db[0][m[0]][w] * y * z;
                    g[1][w] += x * db[1][m[1]][w] * z;
                    g[2][w] += x * y * db[2][m[2]][w];
                }
            float* out = dragData_.data() + blk * kFields * W;
            float len2[W], inv[W];
            for (int w = 0; w < W; ++w) {
                const float g0 = g[0][w] * act[0][w] * on[w], g1 = g[1][w] * act[1][w] * on[w], g2 = g[2][w] * act[2][w] * on[w];
                // v = dual^T g
                const float v0 = dual[0] * g0 + dual[3] * g1 + dual[6] * g2;
                const float v1 = dual[1] * g0 + dual[4] * g1 + dual[7] * g2;
                const float v2 = dual[2] * g0 + dual[5] * g1 + dual[8] * g2;
                // A column-major (a[3 c + r]); its cofactor columns k0 = a1 x a2, k1 = a2 x a0, k2 = a0 x a1
                const float k0x = a[4][w] * a[8][w] - a[5][w] * a[7][w], k0y = a[5][w] * a[6][w] - a[3][w] * a[8][w],
                            k0z = a[3][w] * a[7][w] - a[4][w] * a[6][w];
                const float k1x = a[7][w] * a[2][w] - a[8][w] * a[1][w], k1y = a[8][w] * a[0][w] - a[6][w] * a[2][w],
                            k1z = a[6][w] * a[1][w] - a[7][w] * a[0][w];
                const float k2x = a[1][w] * a[5][w] - a[2][w] * a[4][w], k2y = a[2][w] * a[3][w] - a[0][w] * a[5][w],
                            k2z = a[0][w] * a[4][w] - a[1][w] * a[3][w];
                const float nx = nr[0][w], ny = nr[1][w], nz = nr[2][w];
                const float cx = nx * k0x + ny * k1x + nz * k2x, cy = nx * k0y + ny * k1y + nz * k2y, cz = nx * k0z + ny * k1z + nz * k2z;
                out[kE * W + w] = v0 * k0x + v1 * k1x + v2 * k2x;
                out[(kE + 1) * W + w] = v0 * k0y + v1 * k1y + v2 * k2y;
                out[(kE + 2) * W + w] = v0 * k0z + v1 * k1z + v2 * k2z;
                const float mx = ny * v2 - nz * v1, my = nz * v0 - nx * v2, mz = nx * v1 - ny * v0; // n x v
                out[kH * W + w] = a[0][w] * mx + a[3][w] * my + a[6][w] * mz; // A (n x v), scaled below
                out[(kH + 1) * W + w] = a[1][w] * mx + a[4][w] * my + a[7][w] * mz;
                out[(kH + 2) * W + w] = a[2][w] * mx + a[5][w] * my + a[8][w] * mz;
                len2[w] = cx * cx + cy * cy + cz * cz;
                for (int x = 0; x < 3; ++x) {
                    out[(kP + x) * W + w] = p0[x][w];
                    out[(kN + x) * W + w] = n0[x][w];
                }
                out[kB * W + w] = bs[w] * on[w];
                out[kD * W + w] = det0[w];
            }
#if defined(__SSE2__)
            for (int w = 0; w < W; w += 4) {
                const __m128 l2 = _mm_loadu_ps(len2 + w);
                const __m128 pos = _mm_cmpgt_ps(l2, _mm_setzero_ps());
                const __m128 r = _mm_div_ps(_mm_set1_ps(1.0f), _mm_sqrt_ps(_mm_or_ps(_mm_and_ps(pos, l2), _mm_andnot_ps(pos, _mm_set1_ps(1.0f)))));
                _mm_storeu_ps(inv + w, r); // 1 where |cof(A) n| = 0 (h unscaled, as startDrag)
            }
#else
            for (int w = 0; w < W; ++w) inv[w] = len2[w] > 0 ? 1.0f / std::sqrt(len2[w]) : 1.0f;
#endif
            for (int x = 0; x < 3; ++x)
                for (int w = 0; w < W; ++w) out[(kH + x) * W + w] *= inv[w];
        }
    });
}

void FfdSession::dragFrame(const Eigen::Vector3d& delta, bool normals, PolygonMesh& out, float* det, DeformReport& report,
                           Eigen::AlignedBox3d* bounds) const
{
    // One thread, one pass: every output (double mesh, det J, report, box) from the drag's data.
    constexpr int W = kLanes;
    const std::size_t count = static_cast<std::size_t>(positions_.cols());
    const Eigen::Vector3f u = (drag_->strength * delta).cast<float>();
    report = DeformReport{};
    report.vertices = count;
    report.outside = binding_.outsideVertices().size();
    double lo = count ? std::numeric_limits<double>::infinity() : 1, hi = count ? -lo : 1;
    float mn[3] = {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity()};
    float mx[3] = {-mn[0], -mn[1], -mn[2]};
    double* pos = out.positions.data();
    double* nor = normals ? out.normals.data() : nullptr;
    for (std::size_t base = 0; base < count; base += W) {
        const float* b = dragData_.data() + (base / W) * kFields * W;
        float p[3][W], q[3][W], d[W], len2[W], inv[W];
        for (int w = 0; w < W; ++w) {
            const float bw = b[kB * W + w];
            for (int x = 0; x < 3; ++x) p[x][w] = b[(kP + x) * W + w] + bw * u[x];
            const float hx = b[kH * W + w], hy = b[(kH + 1) * W + w], hz = b[(kH + 2) * W + w];
            q[0][w] = b[kN * W + w] + (u[1] * hz - u[2] * hy);
            q[1][w] = b[(kN + 1) * W + w] + (u[2] * hx - u[0] * hz);
            q[2][w] = b[(kN + 2) * W + w] + (u[0] * hy - u[1] * hx);
            d[w] = b[kD * W + w] + (b[kE * W + w] * u[0] + b[(kE + 1) * W + w] * u[1] + b[(kE + 2) * W + w] * u[2]);
            len2[w] = q[0][w] * q[0][w] + q[1][w] * q[1][w] + q[2][w] * q[2][w];
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
        const std::size_t lanes = std::min<std::size_t>(W, count - base);
        for (std::size_t w = 0; w < lanes; ++w) {
            for (int x = 0; x < 3; ++x) {
                pos[3 * (base + w) + std::size_t(x)] = double(p[x][w]);
                mn[x] = p[x][w] < mn[x] ? p[x][w] : mn[x];
                mx[x] = p[x][w] > mx[x] ? p[x][w] : mx[x];
            }
            if (nor)
                for (int x = 0; x < 3; ++x) nor[3 * (base + w) + std::size_t(x)] = double(q[x][w] * inv[w]);
            det[base + w] = d[w];
            const double dd = double(d[w]);
            lo = std::min(lo, dd);
            hi = std::max(hi, dd);
            if (!(dd > 0)) report.folds.push_back(static_cast<int>(base + w));
        }
    }
    report.minDetJ = lo;
    report.maxDetJ = hi;
    report.foldCount = report.folds.size();
    if (bounds) {
        bounds->setEmpty();
        if (count) bounds->extend(Eigen::AlignedBox3d(Eigen::Vector3d(mn[0], mn[1], mn[2]), Eigen::Vector3d(mx[0], mx[1], mx[2])));
    }
}

void FfdSession::finish(const float* det, bool normals, PolygonMesh& out, DeformReport& report, Eigen::AlignedBox3d* bounds) const
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
    std::vector<Part> parts(static_cast<std::size_t>(parallelChunkCount(0, static_cast<std::size_t>(count), kGrain, 0)));
    parallelFor(0, static_cast<std::size_t>(count), kGrain, 0, [&](int c, std::size_t first, std::size_t last) {
        const auto n = static_cast<Eigen::Index>(last - first), f = static_cast<Eigen::Index>(first);
        out.positions.middleCols(f, n) = positions_.middleCols(f, n).cast<double>();
        if (normals) out.normals.middleCols(f, n) = normals_.middleCols(f, n).cast<double>();
        Part& part = parts[static_cast<std::size_t>(c)];
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
