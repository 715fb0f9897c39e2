#include "scene/ffd_session.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>

#include "freeform/core/parallel.h"
#include "freeform/volume/drag_pass.h"

namespace freeform::editor {

FfdSession::FfdSession(const Lattice& lattice, PolygonMesh rest)
    : frame_(lattice), rest_(std::move(rest)), binding_(lattice, rest_.positions), restNormals_(rest_.normals.cast<float>())
{
    // The lattice coordinates of every vertex as the library's kernel uses them (float; the
    // policy's clamp applied), and the outside policy's masks (docs/ffd.md, "Outside the box").
    constexpr int W = kLanes;
    const std::size_t count = static_cast<std::size_t>(rest_.positions.cols());
    const std::vector<int>& outside = binding_.outsideVertices();
    const OutsidePolicy policy = lattice.outside();
    const bool masked = !outside.empty() && clampsOutside(policy);
    const bool normals = rest_.normals.cols() == rest_.positions.cols();
    coords_.assign(((count + W - 1) / W) * kCoordFields * W, 0.5f);
    if (masked) masks_.assign(count, 0x0f);
    auto next = outside.begin();
    for (std::size_t v = 0; v < count; ++v) {
        const bool out = next != outside.end() && *next == static_cast<int>(v);
        if (out) ++next;
        Eigen::Vector3d q = binding_.parameters(v); // inside: the binding's own float coordinates
        if (out && masked) {
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
    // One thread, one pass from the base (docs/architecture.md, "A lattice drag"): the library's
    // drag pass (volume/drag_pass.h, which derives it) with this session's blocks.
    DragPass f;
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
    runDragPass(f, base_ == Base::Identity); // the library's kernel (volume/drag_pass.h)
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
