#include "tools/curve_tools.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "freeform/core/error.h"

namespace freeform::editor {

namespace {

using Curve3 = BezierCurve<double, 3>;
using Spline3 = BezierSpline<double, 3>;

/// All-1 intervals are written as none (the format's default), so that a file keeps its form.
std::vector<double> tidyIntervals(const std::vector<double>& h)
{
    return std::all_of(h.begin(), h.end(), [](double x) { return x == 1.0; }) ? std::vector<double>{} : h;
}

int segmentCountOf(const BezierSplineData& s)
{
    const auto cols = static_cast<int>(s.points.cols());
    return s.closed ? cols / s.degree : (cols - 1) / s.degree;
}

} // namespace

Points3 toPoints3(const PointColumns& points)
{
    Points3 out = Points3::Zero(3, points.cols());
    out.topRows(std::min<Eigen::Index>(3, points.rows())) = points.topRows(std::min<Eigen::Index>(3, points.rows()));
    return out;
}

PointColumns fromPoints3(const Points3& points, Eigen::Index rows)
{
    return PointColumns(points.topRows(rows));
}

// ---------------------------------------------------------------- Bézier curves

BezierCurveData elevateCurve(const BezierCurveData& curve)
{
    const Curve3 c(toPoints3(curve.points));
    return {fromPoints3(c.elevated().controlPoints(), curve.points.rows())};
}

std::pair<BezierCurveData, BezierCurveData> splitCurve(const BezierCurveData& curve, double t)
{
    if (!(t > 0 && t < 1)) throw Error("split: t must lie strictly inside (0, 1)");
    const auto halves = Curve3(toPoints3(curve.points)).split(t);
    return {{fromPoints3(halves.first.controlPoints(), curve.points.rows())},
            {fromPoints3(halves.second.controlPoints(), curve.points.rows())}};
}

BezierCurveData insertCurvePoint(const BezierCurveData& curve, int at, const Eigen::Vector3d& p)
{
    const auto n = static_cast<int>(curve.points.cols());
    if (at < 0 || at > n) throw Error("insert: position " + std::to_string(at) + " is outside 0.." + std::to_string(n));
    PointColumns out(curve.points.rows(), n + 1);
    out.leftCols(at) = curve.points.leftCols(at);
    out.col(at) = p.head(curve.points.rows());
    out.rightCols(n - at) = curve.points.rightCols(n - at);
    return {out};
}

BezierCurveData deleteCurvePoint(const BezierCurveData& curve, int k)
{
    const auto n = static_cast<int>(curve.points.cols());
    if (k < 0 || k >= n) throw Error("delete: the curve has no control point " + std::to_string(k));
    if (n <= 2) throw Error("delete: a curve keeps at least two control points");
    PointColumns out(curve.points.rows(), n - 1);
    out.leftCols(k) = curve.points.leftCols(k);
    out.rightCols(n - 1 - k) = curve.points.rightCols(n - 1 - k);
    return {out};
}

std::vector<Points3> deCasteljauLevels(const Points3& points, double t)
{
    std::vector<Points3> levels{points};
    while (levels.back().cols() > 1) {
        const Points3& w = levels.back();
        Points3 next(3, w.cols() - 1);
        for (Eigen::Index i = 0; i + 1 < w.cols(); ++i) next.col(i) = (1 - t) * w.col(i) + t * w.col(i + 1);
        levels.push_back(std::move(next));
    }
    return levels;
}

// ---------------------------------------------------------------- Bézier splines

Spline3 toSpline(const BezierSplineData& data)
{
    return Spline3(data.degree, data.closed, toPoints3(data.points), data.intervals);
}

BezierSplineData fromSpline(const Spline3& spline, Eigen::Index rows)
{
    BezierSplineData d;
    d.degree = spline.degree();
    d.closed = spline.closed();
    d.points = fromPoints3(spline.controlPoints(), rows);
    d.intervals = tidyIntervals(spline.intervals());
    return d;
}

BezierSplineData elevateSpline(const BezierSplineData& spline)
{
    return fromSpline(toSpline(spline).elevated(), spline.points.rows());
}

BezierSplineData insertJoint(const BezierSplineData& spline, double T)
{
    const Spline3 s = toSpline(spline);
    const auto where = s.locate(T);
    if (!(where.t > 0 && where.t < 1)) throw Error("insert joint: the parameter lies on a joint or outside the spline");
    return fromSpline(s.splitSegment(where.segment, where.t), spline.points.rows());
}

BezierSplineData deleteJoint(const BezierSplineData& spline, int joint)
{
    return fromSpline(toSpline(spline).removeJoint(joint).spline, spline.points.rows());
}

std::pair<BezierSplineData, BezierSplineData> splitSpline(const BezierSplineData& spline, double T)
{
    if (spline.closed) throw Error("split: a closed spline has no ends to split between (open it first)");
    Spline3 s = toSpline(spline);
    if (!(T > 0 && T < s.domainEnd())) throw Error("split: the parameter must lie inside the spline's domain");
    auto where = s.locate(T);
    int joint = where.segment;            // the joint to cut at
    if (where.t > 0) {
        s = s.splitSegment(where.segment, where.t);
        joint = where.segment + 1;
    }
    const int n = s.degree(), L = s.segmentCount();
    std::vector<double> h = s.intervals();
    const Spline3 left(n, false, Points3(s.controlPoints().leftCols(joint * n + 1)),
                       std::vector<double>(h.begin(), h.begin() + joint));
    const Spline3 right(n, false, Points3(s.controlPoints().rightCols((L - joint) * n + 1)),
                        std::vector<double>(h.begin() + joint, h.end()));
    return {fromSpline(left, spline.points.rows()), fromSpline(right, spline.points.rows())};
}

int jointColumn(const BezierSplineData& spline, int joint)
{
    const int L = segmentCountOf(spline);
    return spline.closed ? ((joint % L + L) % L) * spline.degree : joint * spline.degree;
}

int jointOfPoint(const BezierSplineData& spline, int point)
{
    const int n = spline.degree, L = segmentCountOf(spline);
    const int segment = point / n, k = point % n;
    int joint = k * 2 <= n ? segment : segment + 1;
    if (spline.closed) joint %= L;
    return joint;
}

int sideOfPoint(const BezierSplineData& spline, int joint, int point)
{
    const int n = spline.degree, L = segmentCountOf(spline);
    const int column = jointColumn(spline, joint);
    if (point == column) return 0;
    int offset = point - column;
    if (spline.closed) {
        const int total = L * n;
        offset = ((offset % total) + total) % total;
        if (offset > total / 2) offset -= total;
    }
    return offset < 0 ? -1 : +1;
}

bool isInnerJoint(const BezierSplineData& spline, int joint)
{
    const int L = segmentCountOf(spline);
    return spline.closed ? (L >= 2 && joint >= 0 && joint < L) : (joint >= 1 && joint <= L - 1);
}

BezierSplineData applyJointMode(const BezierSplineData& spline, int joint, JointMode mode, int keepSide)
{
    if (mode == JointMode::Free) return spline;
    if (!isInnerJoint(spline, joint)) throw Error("joint " + std::to_string(joint) + " is an end: it has no two sides");
    const JoinMove move = keepSide < 0 ? JoinMove::RightHandle : JoinMove::LeftHandle;
    const Spline3 s = toSpline(spline);
    Spline3 out = s;
    switch (mode) {
    case JointMode::Aligned: out = joinG1(s, joint, move); break;
    case JointMode::Mirrored: out = joinC1(s, joint, move); break;
    case JointMode::C2:
        if (s.degree() != 3) throw Error("C2 handle mode: the spline must be cubic (elevate or use a deboor_spline)");
        out = joinC2(s, joint, move);
        break;
    case JointMode::Free: break;
    }
    BezierSplineData d = spline;
    d.points = fromPoints3(out.controlPoints(), spline.points.rows());
    return d;
}

BezierSplineData enforceJointModes(const BezierSplineData& before, const BezierSplineData& after,
                                   const std::vector<JointMode>& modes, const std::vector<int>& moved)
{
    if (before.points.cols() != after.points.cols() || before.degree != after.degree || before.closed != after.closed)
        return after;
    BezierSplineData d = after;
    const int n = d.degree;
    const auto isMoved = [&](int k) { return std::find(moved.begin(), moved.end(), k) != moved.end(); };
    const auto total = static_cast<int>(d.points.cols());
    const auto wrap = [&](int k) { return d.closed ? ((k % total) + total) % total : k; };
    for (int j = 0; j < static_cast<int>(modes.size()); ++j) {
        if (modes[static_cast<std::size_t>(j)] == JointMode::Free || !isInnerJoint(d, j)) continue;
        const int c = jointColumn(d, j);
        const int left = wrap(c - 1), right = wrap(c + 1);
        const bool l = isMoved(left), r = isMoved(right), centre = isMoved(c);
        if (!l && !r && !centre) continue;
        if (centre && !l && !r) {
            // The joint moved alone: its handles travel with it (a translation keeps every mode).
            const Eigen::VectorXd delta = d.points.col(c) - before.points.col(c);
            d.points.col(left) += delta;
            d.points.col(right) += delta;
            if (n >= 3 && modes[static_cast<std::size_t>(j)] == JointMode::C2) {
                d.points.col(wrap(c - 2)) += delta;
                d.points.col(wrap(c + 2)) += delta;
            }
            continue;
        }
        if (l && r) continue; // both handles moved together: nothing to choose
        try {
            d = applyJointMode(d, j, modes[static_cast<std::size_t>(j)], l ? -1 : +1);
        } catch (const Error&) {
            // A handle dragged onto its joint has no direction: the joint stays free until it has one.
        }
    }
    return d;
}

std::vector<JointContinuity<double>> splineContinuity(const BezierSplineData& spline)
{
    return continuityReport(toSpline(spline));
}

EndCondition deBoorEnd(const BezierSplineData& spline)
{
    return spline.closed ? EndCondition::Closed : EndCondition::Clamped;
}

Points3 splineDeBoorPoints(const BezierSplineData& spline)
{
    if (spline.degree != 3) throw Error("de Boor points: the spline must be cubic");
    return toSpline(spline).deBoorPoints(deBoorEnd(spline));
}

BezierSplineData splineFromDeBoor(const BezierSplineData& spline, const Points3& deboor)
{
    BezierSplineData d = spline;
    d.points = fromPoints3(aframeBezierPoints<double, 3>(deboor, deBoorEnd(spline), spline.intervals), spline.points.rows());
    return d;
}

Points3 curvatureComb(const std::vector<Eigen::Matrix<double, 3, 3>>& derivatives, double scale)
{
    Points3 out(3, static_cast<Eigen::Index>(2 * derivatives.size()));
    for (std::size_t i = 0; i < derivatives.size(); ++i) {
        const Eigen::Vector3d p = derivatives[i].col(0), d1 = derivatives[i].col(1), d2 = derivatives[i].col(2);
        const double s2 = d1.squaredNorm();
        Eigen::Vector3d k = Eigen::Vector3d::Zero();
        if (s2 > 0) {
            const Eigen::Vector3d t = d1 / std::sqrt(s2);
            k = (d2 - d2.dot(t) * t) / s2; // the curvature vector: |k| = kappa, towards the centre
        }
        out.col(static_cast<Eigen::Index>(2 * i)) = p;
        out.col(static_cast<Eigen::Index>(2 * i + 1)) = p - scale * k;
    }
    return out;
}

} // namespace freeform::editor
