// Certified tessellation of rational Bézier patches and NURBS surfaces (tessellate_rational.h;
// the bound is derived in docs/surfaces.md, "Rational patches").

#include "freeform/tessellate/tessellate_rational.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <vector>

#include "freeform/core/error.h"

namespace freeform {
namespace {

/// The largest second differences of a polynomial patch's control values (a vector of any size,
/// in the Euclidean norm, or a scalar), scaled by the degrees: M_uu, M_uv and M_vv of the bound
/// M_uu/(8 nu^2) + M_uv/(4 nu nv) + M_vv/(8 nv^2) (docs/surfaces.md). They do not depend on the
/// segment counts, so a search over the counts computes them once.
struct SecondDifferences {
    double muu = 0, muv = 0, mvv = 0;
    double bound(int nu, int nv) const { return muu / (8.0 * nu * nu) + muv / (4.0 * nu * nv) + mvv / (8.0 * nv * nv); }
};

/// The rational patch's bound as a function of the segment counts (docs/surfaces.md, "Rational
/// patches"): (bound of w (P - c) + rho * bound of w) / min w, with c the centre and rho the
/// half-diagonal of the control points' box; and the same per axis of a frame that follows the
/// patch (its normal, its u direction and a third), combined as sqrt(sum over the axes of their
/// squares), where that is smaller: the error of a cell of a fillet is mostly along the normal
/// across the fillet and mostly along the fillet in the other direction, and the sum of the two
/// norms counted both in full.
class RationalBound {
public:
    /// `framed`: also the bound per axis of the frame (else the whole net's alone).
    explicit RationalBound(const RationalPatch& patch, bool framed = true)
    {
        const int m = patch.degreeU(), n = patch.degreeV();
        const auto& h = patch.homogeneous();
        const auto& points = h.controlPoints(); // homogeneous (w P, w), column h.index(i, j)
        Eigen::Vector3d lo = patch.controlPoint(0, 0), hi = lo;
        wmin_ = patch.weight(0, 0);
        for (int i = 0; i <= m; ++i)
            for (int j = 0; j <= n; ++j) {
                lo = lo.cwiseMin(patch.controlPoint(i, j));
                hi = hi.cwiseMax(patch.controlPoint(i, j));
                wmin_ = std::min(wmin_, patch.weight(i, j));
            }
        const Eigen::Vector3d c = (lo + hi) / 2;
        rho_ = (hi - lo).norm() / 2;
        // The frame: the normal of the corners' mean u and v directions, the u direction, and
        // their cross product (none where the corners are degenerate: a flat line, a pole).
        const Eigen::Vector3d p00 = patch.controlPoint(0, 0), pm0 = patch.controlPoint(m, 0), p0n = patch.controlPoint(0, n),
                              pmn = patch.controlPoint(m, n);
        const Eigen::Vector3d du = (pm0 - p00) + (pmn - p0n), dv = (p0n - p00) + (pmn - pm0), normal = du.cross(dv);
        Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
        Eigen::Vector3d fc = Eigen::Vector3d::Zero();
        framed_ = framed && normal.norm() > 1e-9 * du.norm() * dv.norm() && m + n >= 2;
        if (framed_) {
            frame.row(0) = normal.normalized();
            frame.row(1) = du.normalized();
            frame.row(2) = frame.row(0).cross(frame.row(1));
            // Per axis x: |(S - R)_x| <= (E_h,x + rho_x E_w) / w_min, with rho_x the half extent
            // of the control points' box along x (R lies in their hull) and E_h,x the scalar bound
            // of the numerator's component, centred on that box.
            Eigen::Vector3d flo = frame * p00, fhi = flo;
            for (int i = 0; i <= m; ++i)
                for (int j = 0; j <= n; ++j) {
                    const Eigen::Vector3d q = frame * patch.controlPoint(i, j);
                    flo = flo.cwiseMin(q);
                    fhi = fhi.cwiseMax(q);
                }
            fc = (flo + fhi) / 2;
            axisRho_ = (fhi - flo) / 2;
        }
        // One pass over the second differences d of the homogeneous net: the numerator
        // w (P - c) has d.head(3) - d.w c, the weight d.w, and the numerator in the frame,
        // centred on its box, frame d.head(3) - d.w fc.
        // (The numerator's largest norm is the root of its largest square: the same number, with
        // no root in the loop, whose latency each maximum would wait for.)
        Eigen::Vector3d axisUU = Eigen::Vector3d::Zero(), axisUV = axisUU, axisVV = axisUU;
        double squareUU = 0, squareUV = 0, squareVV = 0, weightUU = 0, weightUV = 0, weightVV = 0;
        auto take = [&](const Eigen::Vector4d& d, double& square, double& weight, Eigen::Vector3d& axis) {
            square = std::max(square, (d.head<3>() - d[3] * c).squaredNorm());
            weight = std::max(weight, std::abs(d[3]));
            if (framed_) axis = axis.cwiseMax((frame * d.head<3>() - d[3] * fc).cwiseAbs());
        };
        auto at = [&](int i, int j) { return points.col(h.index(i, j)); };
        for (int i = 0; i <= m; ++i)
            for (int j = 0; j <= n; ++j) {
                if (i + 2 <= m) take(at(i + 2, j) - 2 * at(i + 1, j) + at(i, j), squareUU, weightUU, axisUU);
                if (j + 2 <= n) take(at(i, j + 2) - 2 * at(i, j + 1) + at(i, j), squareVV, weightVV, axisVV);
                if (i + 1 <= m && j + 1 <= n) take(at(i + 1, j + 1) - at(i + 1, j) - at(i, j + 1) + at(i, j), squareUV, weightUV, axisUV);
            }
        numerator_ = {std::sqrt(squareUU), std::sqrt(squareUV), std::sqrt(squareVV)};
        weight_ = {weightUU, weightUV, weightVV};
        const double su = double(m) * (m - 1), sv = double(n) * (n - 1), suv = double(m) * n;
        numerator_.muu *= su, numerator_.mvv *= sv, numerator_.muv *= suv;
        weight_.muu *= su, weight_.mvv *= sv, weight_.muv *= suv;
        for (int x = 0; x < 3; ++x) axes_[static_cast<std::size_t>(x)] = {axisUU[x] * su, axisUV[x] * suv, axisVV[x] * sv};
    }
    /// The bound from the whole net alone (the same number whether framed or not).
    double wholeNet(int nu, int nv) const { return (numerator_.bound(nu, nv) + rho_ * weight_.bound(nu, nv)) / wmin_; }
    double operator()(int nu, int nv) const
    {
        const double whole = wholeNet(nu, nv);
        if (!framed_) return whole;
        const double ew = weight_.bound(nu, nv);
        double sum = 0;
        for (std::size_t x = 0; x < 3; ++x) {
            const double e = (axes_[x].bound(nu, nv) + axisRho_[static_cast<Eigen::Index>(x)] * ew) / wmin_;
            sum += e * e;
        }
        return std::min(whole, std::sqrt(sum));
    }

private:
    SecondDifferences numerator_, weight_;
    double rho_ = 0, wmin_ = 1;
    bool framed_ = false;
    std::array<SecondDifferences, 3> axes_;
    Eigen::Vector3d axisRho_ = Eigen::Vector3d::Zero();
};

void checkOptions(const TessellationOptions& o)
{
    if (!(o.tolerance >= 0) || !std::isfinite(o.tolerance)) throw Error("tessellate: the tolerance must be finite and >= 0");
    if (!o.patchTolerance.empty()) throw Error("tessellate: patchTolerance is for patch complexes only (tessellate())");
    if (o.tolerance == 0 && (o.segmentsU < 1 || o.segmentsV < 1))
        throw Error("tessellate: the segment counts must be at least 1");
    if (o.maxSegments < 1) throw Error("tessellate: maxSegments must be at least 1");
}

struct Sample {
    Eigen::Vector3d point, normal;
};

/// The shared grid: column a of patches gets countsU[a] cells in u, row b countsV[b] in v; every
/// vertex evaluated once by `at(a, b, localU, localV)`.
PolygonMesh gridMesh(int rows, int cols, const std::vector<int>& countsU, const std::vector<int>& countsV,
                     const std::vector<double>& breaksU, const std::vector<double>& breaksV,
                     const std::function<Sample(int, int, double, double)>& at, bool flip)
{
    // Global parameter lists: (patch, local) per vertex line.
    std::vector<std::pair<int, double>> us, vs;
    for (int a = 0; a < rows; ++a)
        for (int k = (a == 0 ? 0 : 1); k <= countsU[static_cast<std::size_t>(a)]; ++k)
            us.emplace_back(a, double(k) / countsU[static_cast<std::size_t>(a)]);
    for (int b = 0; b < cols; ++b)
        for (int k = (b == 0 ? 0 : 1); k <= countsV[static_cast<std::size_t>(b)]; ++k)
            vs.emplace_back(b, double(k) / countsV[static_cast<std::size_t>(b)]);
    const int nU = static_cast<int>(us.size()), nV = static_cast<int>(vs.size());
    PolygonMesh mesh;
    mesh.positions.resize(3, nU * nV);
    mesh.normals.resize(3, nU * nV);
    mesh.texcoords.resize(2, nU * nV);
    for (int i = 0; i < nU; ++i)
        for (int j = 0; j < nV; ++j) {
            const auto [a, lu] = us[static_cast<std::size_t>(i)];
            const auto [b, lv] = vs[static_cast<std::size_t>(j)];
            const Sample s = at(a, b, lu, lv);
            const int k = i * nV + j;
            mesh.positions.col(k) = s.point;
            mesh.normals.col(k) = flip ? Eigen::Vector3d(-s.normal) : s.normal;
            const double gu = breaksU[static_cast<std::size_t>(a)] + lu * (breaksU[static_cast<std::size_t>(a) + 1] - breaksU[static_cast<std::size_t>(a)]);
            const double gv = breaksV[static_cast<std::size_t>(b)] + lv * (breaksV[static_cast<std::size_t>(b) + 1] - breaksV[static_cast<std::size_t>(b)]);
            mesh.texcoords.col(k) = Eigen::Vector2d(gu, gv);
        }
    for (int i = 0; i + 1 < nU; ++i)
        for (int j = 0; j + 1 < nV; ++j) {
            const int v00 = i * nV + j, v10 = (i + 1) * nV + j, v01 = i * nV + j + 1, v11 = (i + 1) * nV + j + 1;
            if (flip) {
                mesh.addFace({v00, v01, v11});
                mesh.addFace({v00, v11, v10});
            } else {
                mesh.addFace({v00, v10, v11});
                mesh.addFace({v00, v11, v01});
            }
        }
    return mesh;
}

/// Per-column and per-row counts for the patch grid (maximum of what its patches ask for).
void gridCounts(const std::vector<RationalPatch>& patches, int rows, int cols, const TessellationOptions& options,
                std::vector<int>& countsU, std::vector<int>& countsV, TessellationReport* report)
{
    countsU.assign(static_cast<std::size_t>(rows), 1);
    countsV.assign(static_cast<std::size_t>(cols), 1);
    std::vector<std::array<int, 2>> required;
    for (int a = 0; a < rows; ++a)
        for (int b = 0; b < cols; ++b) {
            const RationalPatch& p = patches[static_cast<std::size_t>(a * cols + b)];
            const std::array<int, 2> r = options.tolerance > 0 ? rationalAdaptiveSegments(p, options.tolerance, options.maxSegments)
                                                               : std::array<int, 2>{options.segmentsU, options.segmentsV};
            required.push_back(r);
            countsU[static_cast<std::size_t>(a)] = std::max(countsU[static_cast<std::size_t>(a)], r[0]);
            countsV[static_cast<std::size_t>(b)] = std::max(countsV[static_cast<std::size_t>(b)], r[1]);
        }
    if (report) {
        report->required = required;
        report->segments.clear();
        report->errorBound = 0;
        for (int a = 0; a < rows; ++a)
            for (int b = 0; b < cols; ++b) {
                const int nu = countsU[static_cast<std::size_t>(a)], nv = countsV[static_cast<std::size_t>(b)];
                report->segments.push_back({nu, nv});
                report->errorBound = std::max(report->errorBound,
                                              rationalTessellationErrorBound(patches[static_cast<std::size_t>(a * cols + b)], nu, nv));
            }
    }
}

} // namespace

double rationalTessellationErrorBound(const RationalPatch& patch, int nu, int nv)
{
    if (nu < 1 || nv < 1) throw Error("rationalTessellationErrorBound: segment counts must be at least 1");
    return RationalBound(patch)(nu, nv);
}

double rationalWholeNetBound(const RationalPatch& patch, int nu, int nv)
{
    if (nu < 1 || nv < 1) throw Error("rationalWholeNetBound: segment counts must be at least 1");
    return RationalBound(patch, false)(nu, nv);
}

RationalBounds rationalBounds(const RationalPatch& patch, int nu, int nv)
{
    if (nu < 1 || nv < 1) throw Error("rationalBounds: segment counts must be at least 1");
    const RationalBound bound(patch);
    return {bound.wholeNet(nu, nv), bound(nu, nv)};
}

std::array<int, 2> rationalAdaptiveSegments(const RationalPatch& patch, double tolerance, int maxSegments)
{
    if (!(tolerance > 0)) throw Error("rationalAdaptiveSegments: the tolerance must be positive");
    // The bound is decreasing in each count: search the fewest cells nu * nv by trying every nu
    // (the patch's differences computed once, not once per trial).
    const RationalBound bound(patch);
    std::array<int, 2> best{maxSegments, maxSegments};
    long bestCells = static_cast<long>(maxSegments) * maxSegments + 1;
    // Only nv <= cap can beat the best so far (nu * nv < bestCells), and once nu alone reaches it
    // no larger nu can: the same result as trying every nu against every nv up to maxSegments.
    for (int nu = 1; nu <= maxSegments && nu < bestCells; ++nu) {
        const int cap = static_cast<int>(std::min<long>(maxSegments, (bestCells - 1) / nu));
        if (bound(nu, cap) > tolerance) continue;
        int lo = 1, hi = cap; // smallest nv with bound <= tolerance
        while (lo < hi) {
            const int mid = lo + (hi - lo) / 2;
            if (bound(nu, mid) <= tolerance) hi = mid;
            else lo = mid + 1;
        }
        const long cells = static_cast<long>(nu) * lo;
        if (cells < bestCells) {
            bestCells = cells;
            best = {nu, lo};
        }
        if (lo == 1) break; // larger nu only adds cells
    }
    return best;
}

PolygonMesh tessellateRational(const std::vector<RationalPatch>& patches, int rows, int cols,
                               const TessellationOptions& options, TessellationReport* report)
{
    checkOptions(options);
    if (rows < 1 || cols < 1 || static_cast<long>(patches.size()) != static_cast<long>(rows) * cols)
        throw Error("tessellateRational: " + std::to_string(patches.size()) + " patches do not form a " + std::to_string(rows) +
                    " x " + std::to_string(cols) + " grid");
    std::vector<int> countsU, countsV;
    gridCounts(patches, rows, cols, options, countsU, countsV, report);
    std::vector<double> breaksU, breaksV;
    for (int a = 0; a <= rows; ++a) breaksU.push_back(a);
    for (int b = 0; b <= cols; ++b) breaksV.push_back(b);
    return gridMesh(rows, cols, countsU, countsV, breaksU, breaksV,
                    [&](int a, int b, double u, double v) {
                        const RationalPatch& p = patches[static_cast<std::size_t>(a * cols + b)];
                        return Sample{p.evaluate(u, v), p.normal(u, v)};
                    },
                    options.flipNormals);
}

PolygonMesh tessellateNurbs(const NurbsSurface<double, 3>& surface, const TessellationOptions& options,
                            TessellationReport* report)
{
    checkOptions(options);
    const auto& ku = surface.knotsU();
    const auto& kv = surface.knotsV();
    std::vector<double> breaksU, breaksV;
    for (int i = surface.degreeU(); i < surface.countU(); ++i)
        if (ku[i] < ku[i + 1]) {
            if (breaksU.empty()) breaksU.push_back(ku[i]);
            breaksU.push_back(ku[i + 1]);
        }
    for (int j = surface.degreeV(); j < surface.countV(); ++j)
        if (kv[j] < kv[j + 1]) {
            if (breaksV.empty()) breaksV.push_back(kv[j]);
            breaksV.push_back(kv[j + 1]);
        }
    const int rows = static_cast<int>(breaksU.size()) - 1, cols = static_cast<int>(breaksV.size()) - 1;
    const std::vector<RationalPatch> patches = surface.bezierPatches();
    std::vector<int> countsU, countsV;
    gridCounts(patches, rows, cols, options, countsU, countsV, report);
    // Vertices from the surface itself at the global parameter (one evaluation per vertex).
    return gridMesh(rows, cols, countsU, countsV, breaksU, breaksV,
                    [&](int a, int b, double lu, double lv) {
                        const std::size_t ia = static_cast<std::size_t>(a), ib = static_cast<std::size_t>(b);
                        const double u = lu == 1 ? breaksU[ia + 1] : breaksU[ia] + lu * (breaksU[ia + 1] - breaksU[ia]);
                        const double v = lv == 1 ? breaksV[ib + 1] : breaksV[ib] + lv * (breaksV[ib + 1] - breaksV[ib]);
                        return Sample{surface.evaluate(u, v), surface.normal(u, v)};
                    },
                    options.flipNormals);
}

} // namespace freeform
