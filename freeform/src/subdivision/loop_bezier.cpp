// The quartic triangular Bézier nets of Loop cages (docs/subdivision.md, "Loop cages"): the regular
// Loop patch in Bézier form (loopPatchToBezier), evaluation by blossoming, the nets of
// sub-triangles, the certified bound of a net and the normals at its corners. The public part is
// freeform/subdivision/loop_bezier.h; the certified tessellation of Loop cages
// (certified_tessellation_loop.cpp) uses the rest through loop_bezier_net.h.

#include "freeform/subdivision/loop_bezier.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

#include "loop_bezier_net.h"

namespace freeform {

namespace detail::loop {

namespace {

/// The blossom of the net at four points given in barycentric coordinates (weights of corners 0, 1, 2).
Eigen::Vector3d blossom(const Net& net, const std::array<Eigen::Vector3d, 4>& args)
{
    Net p = net;
    for (int n = 4; n >= 1; --n) {
        const Eigen::Vector3d& a = args[static_cast<std::size_t>(4 - n)];
        for (int j = 0; j <= n - 1; ++j)
            for (int k = 0; k <= n - 1 - j; ++k) {
                const auto J = static_cast<std::size_t>(j), K = static_cast<std::size_t>(k);
                p[J][K] = a[0] * p[J][K] + a[1] * p[J + 1][K] + a[2] * p[J][K + 1];
            }
    }
    return p[0][0];
}

Net toNet(const QuarticTriangleNet& flat)
{
    Net n;
    for (int j = 0; j <= 4; ++j)
        for (int k = 0; k <= 4 - j; ++k) n[static_cast<std::size_t>(j)][static_cast<std::size_t>(k)] = flat[static_cast<std::size_t>(bezierIndex(j, k))];
    return n;
}

} // namespace

/// The net of the sub-triangle with corners q0, q1, q2 (barycentric in the parent).
Net subNet(const Net& net, const Eigen::Vector3d& q0, const Eigen::Vector3d& q1, const Eigen::Vector3d& q2)
{
    Net out;
    for (int j = 0; j <= 4; ++j)
        for (int k = 0; k <= 4 - j; ++k) {
            std::array<Eigen::Vector3d, 4> args;
            std::size_t m = 0;
            for (int r = 0; r < 4 - j - k; ++r) args[m++] = q0;
            for (int r = 0; r < j; ++r) args[m++] = q1;
            for (int r = 0; r < k; ++r) args[m++] = q2;
            out[static_cast<std::size_t>(j)][static_cast<std::size_t>(k)] = blossom(net, args);
        }
    return out;
}

/// The certified bound of the net's triangle (docs/subdivision.md, "Loop cages"): for any triangle
/// whose vertices are surface points of the cell, every point of it is within this of the surface
/// point at the same parameter (and back). min over the corner taken as origin a of
/// n(n-1)/8 (max|D_bb| + 2 max|D_bc| + max|D_cc|), n = 4, the second differences of the net along the
/// cell's sides from a.
double netBound(const Net& net)
{
    auto at = [&](const std::array<int, 3>& m) -> const Eigen::Vector3d& {
        return net[static_cast<std::size_t>(m[1])][static_cast<std::size_t>(m[2])];
    };
    double best = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        const int b = (a + 1) % 3, c = (a + 2) % 3;
        double bb = 0, bc = 0, cc = 0;
        for (int m1 = 0; m1 <= 2; ++m1)
            for (int m2 = 0; m2 <= 2 - m1; ++m2) {
                const std::array<int, 3> m{2 - m1 - m2, m1, m2};
                auto plus = [&](int x, int y) {
                    std::array<int, 3> r = m;
                    ++r[static_cast<std::size_t>(x)];
                    ++r[static_cast<std::size_t>(y)];
                    return r;
                };
                const Eigen::Vector3d& aa = at(plus(a, a));
                bb = std::max(bb, (at(plus(b, b)) - 2 * at(plus(a, b)) + aa).norm());
                cc = std::max(cc, (at(plus(c, c)) - 2 * at(plus(a, c)) + aa).norm());
                bc = std::max(bc, (at(plus(b, c)) - at(plus(a, c)) - at(plus(a, b)) + aa).norm());
            }
        best = std::min(best, 12.0 / 8.0 * (bb + 2 * bc + cc));
    }
    return best;
}

/// The unit normal of the net at corner k (tangents along its two sides, counter-clockwise).
Eigen::Vector3d cornerNormal(const Net& b, int k)
{
    Eigen::Vector3d n;
    if (k == 0) n = (b[1][0] - b[0][0]).cross(b[0][1] - b[0][0]);
    else if (k == 1) n = (b[3][1] - b[4][0]).cross(b[3][0] - b[4][0]);
    else n = (b[0][3] - b[0][4]).cross(b[1][3] - b[0][4]);
    const double len = n.norm();
    return len > 1e-300 && std::isfinite(len) ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

} // namespace detail::loop

QuarticTriangleNet loopPatchToBezier(const std::array<Eigen::Vector3d, 12>& points)
{
    using detail::loop::kLoopToBezier;
    QuarticTriangleNet out;
    for (int row = 0; row < 15; ++row) {
        Eigen::Vector3d x = Eigen::Vector3d::Zero();
        for (int c = 0; c < 12; ++c) x += kLoopToBezier[row][c] * points[static_cast<std::size_t>(c)];
        out[static_cast<std::size_t>(row)] = x / 24.0;
    }
    return out;
}

Eigen::Vector3d evaluateTriangleNet(const QuarticTriangleNet& net, double s, double t)
{
    const Eigen::Vector3d a(1 - s - t, s, t);
    return detail::loop::blossom(detail::loop::toNet(net), {a, a, a, a});
}

double triangleNetErrorBound(const QuarticTriangleNet& net) { return detail::loop::netBound(detail::loop::toNet(net)); }

} // namespace freeform
