#include "tools/curve_tools.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "freeform/core/error.h"

#include <Eigen/QR>

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

namespace {

/// The linear conditions of the joint modes on the stacked coordinates x (point k, coordinate i at
/// 3k + i) of a spline in 3D: mirrored (C1 in the global parameter) and C2 at their joints, and
/// aligned (G1) with the tangent direction u[j] fixed beforehand (both handle offsets parallel to
/// it). Rows are scaled so that each is of the size of the points' differences.
Eigen::MatrixXd modeConditions(const BezierSplineData& d, const std::vector<JointMode>& modes, const std::vector<Eigen::Vector3d>& u)
{
    const int n = d.degree, L = segmentCountOf(d);
    const auto total = static_cast<int>(d.points.cols());
    const auto wrap = [&](int k) { return d.closed ? ((k % total) + total) % total : k; };
    const auto h = [&](int segment) { return d.intervals.empty() ? 1.0 : d.intervals[static_cast<std::size_t>(segment)]; };
    std::vector<Eigen::VectorXd> rows;
    for (int j = 0; j < static_cast<int>(modes.size()); ++j) {
        const JointMode mode = modes[static_cast<std::size_t>(j)];
        if (mode == JointMode::Free || !isInnerJoint(d, j)) continue;
        const int c = jointColumn(d, j);
        const double hl = h(d.closed ? (j + L - 1) % L : j - 1), hr = h(d.closed ? j % L : j);
        if (mode == JointMode::Aligned) {
            const Eigen::Vector3d uj = u[static_cast<std::size_t>(j)];
            if (uj.squaredNorm() == 0) continue; // no direction (handles on the joint): nothing to align
            const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - uj * uj.transpose();
            for (const auto& [a, b] : {std::pair{wrap(c + 1), c}, std::pair{c, wrap(c - 1)}})
                for (int i = 0; i < 3; ++i) { // P (x_a - x_b) = 0
                    Eigen::VectorXd r = Eigen::VectorXd::Zero(3 * total);
                    for (int m = 0; m < 3; ++m) r(3 * a + m) += P(i, m), r(3 * b + m) -= P(i, m);
                    rows.push_back(r);
                }
            continue;
        }
        // C1: (x_{c+1} - x_c) / hr - (x_c - x_{c-1}) / hl = 0, times (hl + hr) / 2.
        const double s1 = 0.5 * (hl + hr);
        for (int i = 0; i < 3; ++i) {
            Eigen::VectorXd r = Eigen::VectorXd::Zero(3 * total);
            r(3 * wrap(c + 1) + i) += s1 / hr;
            r(3 * c + i) -= s1 / hr + s1 / hl;
            r(3 * wrap(c - 1) + i) += s1 / hl;
            rows.push_back(r);
        }
        if (mode != JointMode::C2 || n < 2) continue;
        // C2: (x_{c+2} - 2 x_{c+1} + x_c) / hr^2 - (x_c - 2 x_{c-1} + x_{c-2}) / hl^2 = 0.
        const double s2 = s1 * s1;
        for (int i = 0; i < 3; ++i) {
            Eigen::VectorXd r = Eigen::VectorXd::Zero(3 * total);
            r(3 * wrap(c + 2) + i) += s2 / (hr * hr);
            r(3 * wrap(c + 1) + i) -= 2 * s2 / (hr * hr);
            r(3 * c + i) += s2 / (hr * hr) - s2 / (hl * hl);
            r(3 * wrap(c - 1) + i) += 2 * s2 / (hl * hl);
            r(3 * wrap(c - 2) + i) -= s2 / (hl * hl);
            rows.push_back(r);
        }
    }
    Eigen::MatrixXd A(static_cast<Eigen::Index>(rows.size()), 3 * total);
    for (std::size_t r = 0; r < rows.size(); ++r) A.row(static_cast<Eigen::Index>(r)) = rows[r].transpose();
    return A;
}

/// The least change of the points not in `fixed` (stacked x) that satisfies A x = 0; nullopt when
/// no such change exists with the fixed points where they are (relative tolerance 1e-10).
std::optional<Eigen::VectorXd> leastChange(const Eigen::MatrixXd& A, const Eigen::VectorXd& x, const std::vector<bool>& fixed, double scale)
{
    std::vector<Eigen::Index> free;
    for (Eigen::Index v = 0; v < x.size(); ++v)
        if (!fixed[static_cast<std::size_t>(v / 3)]) free.push_back(v);
    const Eigen::VectorXd residual = -(A * x);
    Eigen::VectorXd out = x;
    if (!free.empty()) {
        Eigen::MatrixXd AF(A.rows(), static_cast<Eigen::Index>(free.size()));
        for (std::size_t k = 0; k < free.size(); ++k) AF.col(static_cast<Eigen::Index>(k)) = A.col(free[k]);
        const Eigen::VectorXd delta = AF.completeOrthogonalDecomposition().solve(residual);
        for (std::size_t k = 0; k < free.size(); ++k) out(free[k]) += delta(static_cast<Eigen::Index>(k));
    }
    if ((A * out).cwiseAbs().maxCoeff() > 1e-10 * scale) return std::nullopt;
    return out;
}

/// The all-C2 cubic spline: the de Boor points of `before` changed least (minimum norm) so that
/// the Bézier points `fixed` land where `after` has them; least squares when they cannot all.
std::optional<BezierSplineData> solveDeBoor(const BezierSplineData& before, const BezierSplineData& after, const std::vector<bool>& fixed)
{
    Points3 deboor;
    try {
        deboor = splineDeBoorPoints(before);
    } catch (const Error&) {
        return std::nullopt; // `before` is not C2 within tolerance
    }
    const Eigen::Index m = deboor.cols(), N = after.points.cols();
    // Bézier points = deboor * M^T: column b of M's transpose holds the weights of Bézier point b.
    Eigen::MatrixXd M(N, m);
    for (Eigen::Index i = 0; i < m; ++i) {
        Points3 unit = Points3::Zero(3, m);
        unit(0, i) = 1;
        M.col(i) = toPoints3(splineFromDeBoor(before, unit).points).row(0).transpose();
    }
    std::vector<Eigen::Index> rows;
    for (Eigen::Index b = 0; b < N; ++b)
        if (fixed[static_cast<std::size_t>(b)]) rows.push_back(b);
    if (rows.empty()) return before;
    Eigen::MatrixXd MS(static_cast<Eigen::Index>(rows.size()), m);
    Eigen::MatrixXd R(static_cast<Eigen::Index>(rows.size()), 3);
    const Points3 target = toPoints3(after.points);
    const Points3 now = toPoints3(before.points);
    for (std::size_t k = 0; k < rows.size(); ++k) {
        MS.row(static_cast<Eigen::Index>(k)) = M.row(rows[k]);
        R.row(static_cast<Eigen::Index>(k)) = (target.col(rows[k]) - now.col(rows[k])).transpose();
    }
    const Eigen::MatrixXd delta = MS.completeOrthogonalDecomposition().solve(R); // m x 3
    deboor += delta.transpose();
    BezierSplineData out = splineFromDeBoor(before, deboor);
    return out;
}

} // namespace

/// enforceJointModes as computed (least squares: the moved points land where they were put up to
/// rounding).
static BezierSplineData enforceJointModesComputed(const BezierSplineData& before, const BezierSplineData& after,
                                                  const std::vector<JointMode>& modes, const std::vector<int>& moved)
{
    if (before.points.cols() != after.points.cols() || before.degree != after.degree || before.closed != after.closed)
        return after;
    const auto total = static_cast<int>(after.points.cols());
    const int n = after.degree;
    const auto wrap = [&](int k) { return after.closed ? ((k % total) + total) % total : k; };
    std::vector<bool> fixed(static_cast<std::size_t>(total), false);
    for (int k : moved)
        if (k >= 0 && k < total) fixed[static_cast<std::size_t>(k)] = true;
    Points3 x3 = toPoints3(after.points);
    const Points3 b3 = toPoints3(before.points);
    // A joint point moved without its handles carries them along (a translation keeps its mode);
    // the carried handles then count as placed by the user.
    for (int j = 0; j < static_cast<int>(modes.size()); ++j) {
        if (modes[static_cast<std::size_t>(j)] == JointMode::Free || !isInnerJoint(after, j)) continue;
        const int c = jointColumn(after, j), l = wrap(c - 1), r = wrap(c + 1);
        if (!fixed[static_cast<std::size_t>(c)] || fixed[static_cast<std::size_t>(l)] || fixed[static_cast<std::size_t>(r)]) continue;
        const Eigen::Vector3d delta = x3.col(c) - b3.col(c);
        x3.col(l) += delta;
        x3.col(r) += delta;
        fixed[static_cast<std::size_t>(l)] = fixed[static_cast<std::size_t>(r)] = true;
    }
    BezierSplineData placed = after;
    placed.points = fromPoints3(x3, after.points.rows());
    const double scale = std::max(1.0, x3.cwiseAbs().maxCoeff());

    // Every inner joint C2 on a cubic: the de Boor polygon changes least with the placed points
    // where they are (the spline is C2 by construction).
    bool allC2 = n == 3, anyInner = false;
    for (int j = 0; j < static_cast<int>(modes.size()); ++j)
        if (isInnerJoint(after, j)) anyInner = true, allC2 = allC2 && modes[static_cast<std::size_t>(j)] == JointMode::C2;
    if (!anyInner) return after;
    if (allC2)
        if (auto solved = solveDeBoor(before, placed, fixed)) return *solved;

    // Mixed modes: the aligned joints' directions first (the placed handle's when one handle of
    // the joint was placed, otherwise the bisector of the two: no side is preferred), then the
    // least change of the other points that satisfies every mode, keeping the joint points where
    // they are when possible, else only the placed points, else none.
    std::vector<Eigen::Vector3d> u(modes.size(), Eigen::Vector3d::Zero());
    for (int j = 0; j < static_cast<int>(modes.size()); ++j) {
        if (modes[static_cast<std::size_t>(j)] != JointMode::Aligned || !isInnerJoint(after, j)) continue;
        const int c = jointColumn(after, j), l = wrap(c - 1), r = wrap(c + 1);
        const Eigen::Vector3d a = x3.col(c) - x3.col(l), b = x3.col(r) - x3.col(c);
        const bool fl = fixed[static_cast<std::size_t>(l)], fr = fixed[static_cast<std::size_t>(r)];
        Eigen::Vector3d dir = Eigen::Vector3d::Zero();
        if (fl != fr) dir = fl ? a : b;
        if (dir.norm() < 1e-12 * scale) {
            dir = Eigen::Vector3d::Zero();
            if (a.norm() > 1e-12 * scale) dir += a.normalized();
            if (b.norm() > 1e-12 * scale) dir += b.normalized();
        }
        if (dir.norm() > 1e-12) u[static_cast<std::size_t>(j)] = dir.normalized();
    }
    const Eigen::MatrixXd A = modeConditions(placed, modes, u);
    if (A.rows() == 0) return placed;
    Eigen::VectorXd x(3 * total);
    for (int k = 0; k < total; ++k) x.segment<3>(3 * k) = x3.col(k);
    std::vector<bool> withJoints = fixed;
    for (int j = 0; j < static_cast<int>(modes.size()); ++j)
        if (isInnerJoint(after, j) || (!after.closed && (j == 0 || j == static_cast<int>(modes.size()) - 1)))
            withJoints[static_cast<std::size_t>(jointColumn(after, j))] = true;
    std::optional<Eigen::VectorXd> solved = leastChange(A, x, withJoints, scale);
    if (!solved) solved = leastChange(A, x, fixed, scale);
    if (!solved) solved = leastChange(A, x, std::vector<bool>(fixed.size(), false), scale);
    if (!solved) return placed;
    for (int k = 0; k < total; ++k) x3.col(k) = solved->segment<3>(3 * k);
    placed.points = fromPoints3(x3, after.points.rows());
    return placed;
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

BezierSplineData enforceJointModes(const BezierSplineData& before, const BezierSplineData& after,
                                   const std::vector<JointMode>& modes, const std::vector<int>& moved)
{
    BezierSplineData enforced = enforceJointModesComputed(before, after, modes, moved);
    if (enforced.points.cols() != after.points.cols()) return enforced;
    // A moved point the modes let stay keeps the bits it was given (a typed 1.5 stays 1.5): the
    // least squares above put it there up to rounding, and the modes hold to that rounding either way.
    const double scale = std::max(1.0, after.points.cwiseAbs().maxCoeff());
    for (int k : moved)
        if (k >= 0 && k < after.points.cols() && (enforced.points.col(k) - after.points.col(k)).cwiseAbs().maxCoeff() <= 1e-9 * scale)
            enforced.points.col(k) = after.points.col(k);
    return enforced;
}

} // namespace freeform::editor
