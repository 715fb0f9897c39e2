// Patch complexes: shared edges, continuity across them, and the bicubic de Boor
// surface by the tensor-product A-frame (docs/surfaces.md).

#include "freeform/surface/patch_complex.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <tuple>

#include "freeform/core/error.h"

namespace freeform {

namespace {

using Curve3 = BezierCurve<double, 3>;

/// Control points of a side, in its parameter order.
PointMatrix<double, 3> sidePoints(const Patch& p, PatchSide side)
{
    const int m = p.degreeU(), n = p.degreeV();
    const bool alongV = side == PatchSide::U0 || side == PatchSide::U1;
    const int count = alongV ? n + 1 : m + 1;
    PointMatrix<double, 3> out(3, count);
    for (int k = 0; k < count; ++k) {
        switch (side) {
        case PatchSide::U0: out.col(k) = p.controlPoint(0, k); break;
        case PatchSide::U1: out.col(k) = p.controlPoint(m, k); break;
        case PatchSide::V0: out.col(k) = p.controlPoint(k, 0); break;
        case PatchSide::V1: out.col(k) = p.controlPoint(k, n); break;
        }
    }
    return out;
}

/// Inward cross-boundary derivative control points along a side (degree of the side).
PointMatrix<double, 3> inwardDerivative(const Patch& p, PatchSide side)
{
    const int m = p.degreeU(), n = p.degreeV();
    const bool alongV = side == PatchSide::U0 || side == PatchSide::U1;
    const int count = alongV ? n + 1 : m + 1;
    PointMatrix<double, 3> out(3, count);
    for (int k = 0; k < count; ++k) {
        switch (side) {
        case PatchSide::U0: out.col(k) = m * (p.controlPoint(std::min(1, m), k) - p.controlPoint(0, k)); break;
        case PatchSide::U1: out.col(k) = m * (p.controlPoint(std::max(m - 1, 0), k) - p.controlPoint(m, k)); break;
        case PatchSide::V0: out.col(k) = n * (p.controlPoint(k, std::min(1, n)) - p.controlPoint(k, 0)); break;
        case PatchSide::V1: out.col(k) = n * (p.controlPoint(k, std::max(n - 1, 0)) - p.controlPoint(k, n)); break;
        }
    }
    return out;
}

/// (u, v) of parameter t along a side.
std::array<double, 2> sideParameter(PatchSide side, double t)
{
    switch (side) {
    case PatchSide::U0: return {0.0, t};
    case PatchSide::U1: return {1.0, t};
    case PatchSide::V0: return {t, 0.0};
    case PatchSide::V1: return {t, 1.0};
    }
    return {0.0, 0.0};
}

double maxGap(const PointMatrix<double, 3>& a, const PointMatrix<double, 3>& b, bool reversed)
{
    double gap = 0;
    const Eigen::Index count = a.cols();
    for (Eigen::Index k = 0; k < count; ++k) gap = std::max(gap, (a.col(k) - b.col(reversed ? count - 1 - k : k)).norm());
    return gap;
}

} // namespace

BezierCurve<double, 3> edgeCurve(const Patch& patch, PatchSide side)
{
    return Curve3(sidePoints(patch, side));
}

bool isCollapsedEdge(const Patch& patch, PatchSide side, double tolerance)
{
    const PointMatrix<double, 3> pts = sidePoints(patch, side);
    for (Eigen::Index k = 1; k < pts.cols(); ++k)
        if ((pts.col(k) - pts.col(0)).norm() > tolerance) return false;
    return true;
}

std::vector<SharedEdge> sharedEdges(const PatchComplex& complex, double tolerance)
{
    struct Side {
        PatchEdge edge;
        PointMatrix<double, 3> points;
        double key; // smaller x of the two end points: sorted, then swept with the tolerance
    };
    std::vector<Side> sides;
    for (int p = 0; p < static_cast<int>(complex.patches.size()); ++p) {
        for (int s = 0; s < 4; ++s) {
            const PatchSide side = static_cast<PatchSide>(s);
            if (isCollapsedEdge(complex.patches[p], side, tolerance)) continue;
            PointMatrix<double, 3> pts = sidePoints(complex.patches[p], side);
            const double key = std::min(pts(0, 0), pts(0, pts.cols() - 1));
            sides.push_back({{p, side}, std::move(pts), key});
        }
    }
    std::sort(sides.begin(), sides.end(), [](const Side& a, const Side& b) { return a.key < b.key; });
    std::vector<SharedEdge> out;
    for (std::size_t i = 0; i < sides.size(); ++i) {
        for (std::size_t j = i + 1; j < sides.size() && sides[j].key - sides[i].key <= tolerance; ++j) {
            const Side& a = sides[i];
            const Side& b = sides[j];
            if (a.points.cols() != b.points.cols()) continue;
            const double forward = maxGap(a.points, b.points, false);
            const double backward = maxGap(a.points, b.points, true);
            const bool reversed = backward < forward;
            const double gap = std::min(forward, backward);
            if (gap > tolerance) continue;
            SharedEdge e{a.edge, b.edge, reversed, gap};
            if (std::tie(e.b.patch, e.b.side) < std::tie(e.a.patch, e.a.side)) std::swap(e.a, e.b);
            out.push_back(e);
        }
    }
    std::sort(out.begin(), out.end(), [](const SharedEdge& x, const SharedEdge& y) {
        return std::tie(x.a.patch, x.a.side, x.b.patch, x.b.side) < std::tie(y.a.patch, y.a.side, y.b.patch, y.b.side);
    });
    return out;
}

std::vector<EdgeContinuity> edgeContinuity(const PatchComplex& complex, double tolerance, double angleTolerance)
{
    std::vector<EdgeContinuity> out;
    for (const SharedEdge& e : sharedEdges(complex, tolerance)) {
        const Patch& pa = complex.patches[e.a.patch];
        const Patch& pb = complex.patches[e.b.patch];
        EdgeContinuity c;
        c.a = e.a;
        c.b = e.b;
        c.reversed = e.reversed;
        c.gap = e.gap;
        c.c0 = true;
        // C1: inward derivatives opposite, control point by control point.
        const PointMatrix<double, 3> da = inwardDerivative(pa, e.a.side), db = inwardDerivative(pb, e.b.side);
        const double scale = std::max(da.colwise().norm().maxCoeff(), db.colwise().norm().maxCoeff());
        PointMatrix<double, 3> negB = -db;
        c.c1 = maxGap(da, negB, e.reversed) <= tolerance * std::max(scale, 1.0);
        // G1: unit normals along the edge agree up to sign, and no fold.
        const Curve3 edge = edgeCurve(pa, e.a.side);
        const Curve3 dA(da), dB(db);
        const int samples = 4 * edge.degree() + 1;
        bool fold = false;
        double angle = 0;
        for (int k = 0; k < samples; ++k) {
            const double t = static_cast<double>(k) / (samples - 1);
            const double tb = e.reversed ? 1.0 - t : t;
            const auto ua = sideParameter(e.a.side, t), ub = sideParameter(e.b.side, tb);
            const Eigen::Vector3d na = pa.normal(ua[0], ua[1]), nb = pb.normal(ub[0], ub[1]);
            if (na.squaredNorm() == 0 || nb.squaredNorm() == 0) {
                angle = std::numbers::pi / 2;
                continue;
            }
            const double cosine = std::min(1.0, std::abs(na.dot(nb)));
            angle = std::max(angle, std::acos(cosine));
            // Fold: the inward directions, with the edge tangent removed, point the same way.
            const Eigen::Vector3d tangent = edge.tangent(t);
            Eigen::Vector3d wa = dA.evaluate(t), wb = dB.evaluate(tb);
            wa -= wa.dot(tangent) * tangent;
            wb -= wb.dot(tangent) * tangent;
            if (wa.norm() > 1e-12 * scale && wb.norm() > 1e-12 * scale && wa.dot(wb) > 0.5 * wa.norm() * wb.norm())
                fold = true;
        }
        c.angle = angle;
        c.g1 = !fold && angle <= angleTolerance;
        out.push_back(c);
    }
    return out;
}

// ------------------------------------------------------------------------------- de Boor surface

std::array<int, 2> deboorSurfaceSegments(int rows, int cols, EndCondition endU, EndCondition endV)
{
    return {aframeSegmentCount(rows, endU), aframeSegmentCount(cols, endV)};
}

PatchComplex deboorSurfacePatches(const PointMatrix<double, 3>& points, int rows, int cols, EndCondition endU,
                                  EndCondition endV)
{
    if (rows < 1 || cols < 1 || points.cols() != static_cast<Eigen::Index>(rows) * cols)
        throw Error("deboorSurfacePatches: " + std::to_string(points.cols()) + " points do not form a " +
                    std::to_string(rows) + " x " + std::to_string(cols) + " grid");
    if (rows < aframeMinimumPoints(endU))
        throw Error("deboorSurfacePatches: " + std::to_string(rows) + " rows of de Boor points are too few for end condition \"" +
                    toString(endU) + "\" in u (needs at least " + std::to_string(aframeMinimumPoints(endU)) + ")");
    if (cols < aframeMinimumPoints(endV))
        throw Error("deboorSurfacePatches: " + std::to_string(cols) + " columns of de Boor points are too few for end condition \"" +
                    toString(endV) + "\" in v (needs at least " + std::to_string(aframeMinimumPoints(endV)) + ")");
    requireFinite(points, "deboorSurfacePatches");
    const auto [lu, lv] = deboorSurfaceSegments(rows, cols, endU, endV);
    // Along v: every row of de Boor points becomes a row of Bézier points.
    const int bv = endV == EndCondition::Closed ? 3 * lv : 3 * lv + 1;
    const int bu = endU == EndCondition::Closed ? 3 * lu : 3 * lu + 1;
    PointMatrix<double, 3> half(3, static_cast<Eigen::Index>(rows) * bv);
    for (int r = 0; r < rows; ++r)
        half.middleCols(static_cast<Eigen::Index>(r) * bv, bv) =
            aframeBezierPoints<double, 3>(PointMatrix<double, 3>(points.middleCols(static_cast<Eigen::Index>(r) * cols, cols)), endV);
    // Along u: every column of the result.
    PointMatrix<double, 3> net(3, static_cast<Eigen::Index>(bu) * bv);
    PointMatrix<double, 3> column(3, rows);
    for (int c = 0; c < bv; ++c) {
        for (int r = 0; r < rows; ++r) column.col(r) = half.col(static_cast<Eigen::Index>(r) * bv + c);
        const PointMatrix<double, 3> b = aframeBezierPoints<double, 3>(column, endU);
        for (int r = 0; r < bu; ++r) net.col(static_cast<Eigen::Index>(r) * bv + c) = b.col(r);
    }
    PatchComplex complex;
    complex.patches.reserve(static_cast<std::size_t>(lu) * lv);
    for (int a = 0; a < lu; ++a) {
        for (int b = 0; b < lv; ++b) {
            PointMatrix<double, 3> pts(3, 16);
            for (int i = 0; i <= 3; ++i)
                for (int j = 0; j <= 3; ++j) {
                    const int r = (3 * a + i) % bu, c = (3 * b + j) % bv; // wraps onto column 0 when closed
                    pts.col(i * 4 + j) = net.col(static_cast<Eigen::Index>(r) * bv + c);
                }
            complex.patches.emplace_back(3, 3, std::move(pts));
        }
    }
    return complex;
}

} // namespace freeform
