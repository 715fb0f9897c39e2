// A face grid's cells (brep/part_mesh.h, docs/cad.md "Tessellation"): each cell's sub-net, cut
// once and kept, and the bounds on the surface's derivatives over a cell or along a direction that
// the edge sampler and the face meshing read (FaceGrid::slopesOver, FaceGrid::slopeAlong).

#include <algorithm>
#include <cmath>

#include "part_mesh_internal.h"

namespace freeform::part_mesh {
namespace {

/// A rational patch's homogeneous points (h, w) moved so that the centre c of its control box is
/// the origin: (h - c w, w). With rho the box's half diagonal (|S - c| <= rho) and wmin the least
/// weight, a derivative of S is (h'_d - (S - c) w_d) / w, bounded by the differences of these.
struct CentredNet {
    explicit CentredNet(const RationalPatch& p) : h(p.homogeneous())
    {
        const Box<double, 3> box = p.controlBox();
        centre = box.center();
        rho = 0.5 * box.diagonal().norm();
        for (int i = 0; i <= p.degreeU(); ++i)
            for (int j = 0; j <= p.degreeV(); ++j) wmin = std::min(wmin, h.controlPoint(i, j)[3]);
    }
    Eigen::Vector4d operator()(int i, int j) const
    {
        const Eigen::Vector4d q = h.controlPoint(i, j);
        return {q[0] - q[3] * centre.x(), q[1] - q[3] * centre.y(), q[2] - q[3] * centre.z(), q[3]};
    }
    const RationalPatch::Homogeneous& h;
    Eigen::Vector3d centre;
    double rho = 0, wmin = kInf;
};

} // namespace

/// Bound on |S_u| and |S_v| of a rational patch over [0, 1]^2: S_u = (h'_u - (S - c) w_u) / w with
/// h' = h - c w, c the centre and rho the half diagonal of the control box.
std::pair<double, double> patchSlopes(const RationalPatch& patch)
{
    const int m = patch.degreeU(), n = patch.degreeV();
    const CentredNet net(patch);
    double hu = 0, wu = 0, hv = 0, wv = 0;
    for (int i = 0; i < m; ++i)
        for (int j = 0; j <= n; ++j) {
            const Eigen::Vector4d d = m * (net(i + 1, j) - net(i, j));
            hu = std::max(hu, d.head<3>().norm());
            wu = std::max(wu, std::abs(d[3]));
        }
    for (int i = 0; i <= m; ++i)
        for (int j = 0; j < n; ++j) {
            const Eigen::Vector4d d = n * (net(i, j + 1) - net(i, j));
            hv = std::max(hv, d.head<3>().norm());
            wv = std::max(wv, std::abs(d[3]));
        }
    return {(hu + net.rho * wu) / net.wmin, (hv + net.rho * wv) / net.wmin};
}

FaceGrid::Cell& FaceGrid::cell(std::size_t i, std::size_t j) const
{
    const long long key = static_cast<long long>(i) * static_cast<long long>(gv.size()) + static_cast<long long>(j);
    if (const auto it = cells_.find(key); it != cells_.end()) return it->second;
    // The knot span holding the cell (a cell across a merged knot, or of no width: the face's).
    Cell c;
    c.slopes = {slopeU, slopeV};
    const double u0 = gu[i], u1 = gu[i + 1], v0 = gv[j], v1 = gv[j + 1];
    const std::size_t a = static_cast<std::size_t>(
        std::clamp<std::ptrdiff_t>(std::upper_bound(bu.begin(), bu.end(), 0.5 * (u0 + u1)) - bu.begin() - 1, 0,
                                   static_cast<std::ptrdiff_t>(bu.size()) - 2));
    const std::size_t b = static_cast<std::size_t>(
        std::clamp<std::ptrdiff_t>(std::upper_bound(bv.begin(), bv.end(), 0.5 * (v0 + v1)) - bv.begin() - 1, 0,
                                   static_cast<std::ptrdiff_t>(bv.size()) - 2));
    const double du = bu[a + 1] - bu[a], dv = bv[b + 1] - bv[b];
    if (u1 > u0 && v1 > v0 && u0 >= bu[a] && u1 <= bu[a + 1] && v0 >= bv[b] && v1 <= bv[b + 1]) {
        const double a0 = (u0 - bu[a]) / du, a1 = (u1 - bu[a]) / du, b0 = (v0 - bv[b]) / dv, b1 = (v1 - bv[b]) / dv;
        RationalPatch q = patches[a * (bv.size() - 1) + b].pieceU(a0, a1).pieceV(b0, b1);
        const auto [su, sv] = patchSlopes(q);
        // The sub-net's slopes are per its own [0, 1]; the face's bound caps them (a split in
        // floating point is a hair off the exact sub-net).
        c.slopes = {std::min(slopeU, su / (u1 - u0)), std::min(slopeV, sv / (v1 - v0))};
        c.width = u1 - u0;
        c.height = v1 - v0;
        c.net = std::move(q);
    }
    return cells_.emplace(key, std::move(c)).first->second;
}

namespace {

/// What slopeAlong needs of a cell with its own net, computed once.
void prepareAlong(FaceGrid::Cell& c)
{
    if (!c.net || !c.alongU.empty()) return;
    // For slopeAlong: D_n S = (D_n h' - (S - c) D_n w) / w with h' = h - c w (c the control
    // box's centre, |S - c| <= rho), and D_n h' = n_u h'_u + n_v h'_v with both raised to
    // degree (m, n): its Bézier coefficients are n_u m [(i/m) (h'_ij - h'_i-1,j) + (1 - i/m)
    // (h'_i+1,j - h'_ij)] / width plus the same along v, and it lies in their hull.
    const RationalPatch& q = *c.net;
    const int m = q.degreeU(), k = q.degreeV();
    const CentredNet net(q);
    for (int a = 0; a <= m; ++a)
        for (int b = 0; b <= k; ++b) {
            Eigen::Vector4d du = Eigen::Vector4d::Zero(), dv = Eigen::Vector4d::Zero();
            if (a > 0) du += a * (net(a, b) - net(a - 1, b));
            if (a < m) du += (m - a) * (net(a + 1, b) - net(a, b));
            if (b > 0) dv += b * (net(a, b) - net(a, b - 1));
            if (b < k) dv += (k - b) * (net(a, b + 1) - net(a, b));
            c.alongU.push_back(du / c.width);
            c.alongV.push_back(dv / c.height);
        }
    c.overW = 1 / net.wmin;
    c.rhoOverW = net.rho / net.wmin;
}

} // namespace

bool FaceGrid::cellsOf(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, std::size_t& i0, std::size_t& i1, std::size_t& j0,
                       std::size_t& j1) const
{
    if (!(hi.x() >= lo.x()) || !(hi.y() >= lo.y())) return false;
    auto range = [](const std::vector<double>& l, double x0, double x1, std::size_t& first, std::size_t& end) {
        const std::ptrdiff_t last = static_cast<std::ptrdiff_t>(l.size()) - 2;
        const std::ptrdiff_t f = std::clamp<std::ptrdiff_t>(std::upper_bound(l.begin(), l.end(), x0) - l.begin() - 1, 0, last);
        first = static_cast<std::size_t>(f);
        end = static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(std::lower_bound(l.begin(), l.end(), x1) - l.begin() - 1, f, last));
    };
    range(gu, lo.x(), hi.x(), i0, i1);
    range(gv, lo.y(), hi.y(), j0, j1);
    return (i1 - i0 + 1) * (j1 - j0 + 1) <= 4;
}

std::pair<double, double> FaceGrid::slopesOver(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) const
{
    std::size_t i0, i1, j0, j1;
    if (!cellsOf(lo, hi, i0, i1, j0, j1)) return {slopeU, slopeV};
    std::pair<double, double> s{0, 0};
    for (std::size_t i = i0; i <= i1; ++i)
        for (std::size_t j = j0; j <= j1; ++j) {
            const auto [su, sv] = cell(i, j).slopes;
            s = {std::max(s.first, su), std::max(s.second, sv)};
        }
    return s;
}

double FaceGrid::slopeAlong(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, const Eigen::Vector2d& n) const
{
    std::size_t i0, i1, j0, j1;
    const double plain = std::abs(n.x()) * slopeU + std::abs(n.y()) * slopeV;
    if (!cellsOf(lo, hi, i0, i1, j0, j1)) return plain;
    double worst = 0;
    for (std::size_t i = i0; i <= i1; ++i)
        for (std::size_t j = j0; j <= j1; ++j) {
            Cell& c = cell(i, j);
            prepareAlong(c);
            const double fromSlopes = std::abs(n.x()) * c.slopes.first + std::abs(n.y()) * c.slopes.second;
            if (!c.net) {
                worst = std::max(worst, fromSlopes);
                continue;
            }
            double dh = 0, dw = 0;
            for (std::size_t x = 0; x < c.alongU.size(); ++x) {
                const Eigen::Vector4d d = n.x() * c.alongU[x] + n.y() * c.alongV[x];
                dh = std::max(dh, d.head<3>().squaredNorm());
                dw = std::max(dw, std::abs(d[3]));
            }
            worst = std::max(worst, std::min(fromSlopes, std::sqrt(dh) * c.overW + dw * c.rhoOverW));
        }
    return worst;
}

} // namespace freeform::part_mesh
