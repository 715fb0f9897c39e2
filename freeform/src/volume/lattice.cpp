// Lattice: frame, rest points, lattice coordinates, the reference deformation (volume/lattice.h).

#include "freeform/volume/lattice.h"

#include <algorithm>
#include <cmath>

#include "freeform/core/bernstein.h"

namespace freeform {

OutsidePolicy parseOutsidePolicy(const std::string& text, const std::string& what)
{
    if (text == "keep") return OutsidePolicy::Keep;
    if (text == "clamp") return OutsidePolicy::Clamp;
    if (text == "extrapolate") return OutsidePolicy::Extrapolate;
    throw Error(what + ": outside policy \"" + text + "\" is not one of keep, clamp, extrapolate");
}

std::string toString(OutsidePolicy policy)
{
    switch (policy) {
    case OutsidePolicy::Keep: return "keep";
    case OutsidePolicy::Clamp: return "clamp";
    case OutsidePolicy::Extrapolate: return "extrapolate";
    }
    return "clamp";
}

Lattice::Lattice(std::array<int, 3> degree, const Eigen::Vector3d& origin, const Eigen::Matrix3d& axes, Points points,
                 OutsidePolicy outside)
    : degree_(degree), origin_(origin), axes_(axes), points_(std::move(points)), outside_(outside)
{
    static const char* const names[3] = {"l", "m", "n"};
    for (int a = 0; a < 3; ++a) {
        if (degree_[static_cast<std::size_t>(a)] < 1 || degree_[static_cast<std::size_t>(a)] > kMaxDegree)
            throw Error("lattice: degree " + std::string(names[a]) + " = " + std::to_string(degree_[static_cast<std::size_t>(a)]) +
                        " is outside 1.." + std::to_string(kMaxDegree));
    }
    if (!origin_.allFinite()) throw Error("lattice: origin is not finite");
    if (!axes_.allFinite()) throw Error("lattice: axes are not finite");
    const Eigen::Vector3d s = axes_.col(0), t = axes_.col(1), u = axes_.col(2);
    const double scale = s.norm() * t.norm() * u.norm();
    const double det = axes_.determinant();
    if (!(scale > 0) || !(std::abs(det) > 1e-12 * scale))
        throw Error("lattice: axes: the edge vectors S, T, U are (nearly) linearly dependent");
    dualNumerator_.row(0) = t.cross(u).transpose();
    dualNumerator_.row(1) = s.cross(u).transpose();
    dualNumerator_.row(2) = s.cross(t).transpose();
    dualDenominator_ = Eigen::Vector3d(dualNumerator_.row(0).dot(s), dualNumerator_.row(1).dot(t),
                                       dualNumerator_.row(2).dot(u));
    for (int a = 0; a < 3; ++a) dual_.row(a) = dualNumerator_.row(a) / dualDenominator_[a];
    const Eigen::Index expected = Eigen::Index(degree_[0] + 1) * (degree_[1] + 1) * (degree_[2] + 1);
    if (points_.cols() != expected)
        throw Error("lattice: points: has " + std::to_string(points_.cols()) + " points, degree needs " +
                    std::to_string(expected));
    requireFinite(points_, "lattice: points");
    updateDisplacements();
}

Lattice Lattice::identity(std::array<int, 3> degree, const Eigen::Vector3d& origin, const Eigen::Matrix3d& axes,
                          OutsidePolicy outside)
{
    // Validate the frame and degrees first with a throw-away point set of the right size.
    for (int a = 0; a < 3; ++a)
        if (degree[static_cast<std::size_t>(a)] < 1 || degree[static_cast<std::size_t>(a)] > kMaxDegree)
            return Lattice(degree, origin, axes, Points(3, 0), outside); // throws with the message
    const Eigen::Index count = Eigen::Index(degree[0] + 1) * (degree[1] + 1) * (degree[2] + 1);
    Lattice lattice(degree, origin, axes, Points::Zero(3, count), outside);
    lattice.points_ = lattice.restPoints();
    requireFinite(lattice.points_, "lattice: points");
    lattice.updateDisplacements();
    return lattice;
}

Lattice Lattice::fit(const Points& positions, std::array<int, 3> degree, double margin, OutsidePolicy outside)
{
    if (positions.cols() < 1) throw Error("lattice fit: the mesh has no vertices");
    if (!std::isfinite(margin) || margin < 0) throw Error("lattice fit: margin must be a finite number >= 0");
    requireFinite(positions, "lattice fit: vertex");
    Eigen::Vector3d lo = positions.rowwise().minCoeff(), hi = positions.rowwise().maxCoeff();
    const double largest = (hi - lo).maxCoeff();
    lo.array() -= margin * largest;
    hi.array() += margin * largest;
    double big = (hi - lo).maxCoeff();
    if (!(big > 0)) big = 1;
    for (int a = 0; a < 3; ++a) {
        if (hi[a] - lo[a] <= 1e-9 * big) {
            const double centre = 0.5 * (lo[a] + hi[a]);
            lo[a] = centre - 0.5 * big;
            hi[a] = centre + 0.5 * big;
        }
    }
    const Eigen::Matrix3d axes = (hi - lo).asDiagonal();
    return identity(degree, lo, axes, outside);
}

void Lattice::setControlPoint(int i, int j, int k, const Eigen::Vector3d& p)
{
    if (i < 0 || i > degree_[0] || j < 0 || j > degree_[1] || k < 0 || k > degree_[2])
        throw Error("lattice: control point (" + std::to_string(i) + ", " + std::to_string(j) + ", " + std::to_string(k) +
                    ") is out of range");
    if (!p.allFinite())
        throw Error("lattice: control point (" + std::to_string(i) + ", " + std::to_string(j) + ", " + std::to_string(k) +
                    ") is not finite");
    const int c = index(i, j, k);
    points_.col(c) = p;
    displacement_.col(c) = p - restPoint(i, j, k);
}

void Lattice::setControlPoints(const Points& points)
{
    if (points.cols() != points_.cols())
        throw Error("lattice: points: has " + std::to_string(points.cols()) + " points, degree needs " +
                    std::to_string(points_.cols()));
    requireFinite(points, "lattice: points");
    points_ = points;
    updateDisplacements();
}

Eigen::Vector3d Lattice::restPoint(int i, int j, int k) const
{
    return origin_ + (double(i) / degree_[0]) * axes_.col(0) + (double(j) / degree_[1]) * axes_.col(1) +
           (double(k) / degree_[2]) * axes_.col(2);
}

Lattice::Points Lattice::restPoints() const
{
    Points r(3, points_.cols());
    for (int i = 0; i <= degree_[0]; ++i)
        for (int j = 0; j <= degree_[1]; ++j)
            for (int k = 0; k <= degree_[2]; ++k) r.col(index(i, j, k)) = restPoint(i, j, k);
    return r;
}

void Lattice::updateDisplacements()
{
    displacement_ = points_ - restPoints();
}

Eigen::Vector3d Lattice::toLattice(const Eigen::Vector3d& p) const
{
    const Eigen::Vector3d q = p - origin_;
    return Eigen::Vector3d(dualNumerator_.row(0).dot(q) / dualDenominator_[0],
                           dualNumerator_.row(1).dot(q) / dualDenominator_[1],
                           dualNumerator_.row(2).dot(q) / dualDenominator_[2]);
}

BezierVolume<double> Lattice::volume() const
{
    return BezierVolume<double>(degree_[0], degree_[1], degree_[2], points_);
}

BezierVolume<double> Lattice::volume(double strength) const
{
    return BezierVolume<double>(degree_[0], degree_[1], degree_[2], Points(restPoints() + strength * displacement_));
}

BezierVolume<double> Lattice::displacementVolume() const
{
    return BezierVolume<double>(degree_[0], degree_[1], degree_[2], displacement_);
}

BezierVolume<double>::Jet Lattice::map(const Eigen::Vector3d& stu, double strength) const
{
    auto jet = displacementVolume().derivatives(stu[0], stu[1], stu[2]);
    jet.point = toWorld(stu) + strength * jet.point;
    jet.ds = axes_.col(0) + strength * jet.ds;
    jet.dt = axes_.col(1) + strength * jet.dt;
    jet.du = axes_.col(2) + strength * jet.du;
    return jet;
}

OutsideRule outsideRule(const Eigen::Vector3d& stu, OutsidePolicy policy)
{
    OutsideRule r{stu, 0x0fu, !Lattice::insideBox(stu)};
    if (!r.outside || !clampsOutside(policy)) return r;
    r.mask = policy == OutsidePolicy::Keep ? 0u : 0x08u;
    for (int a = 0; a < 3; ++a) {
        if (stu[a] >= 0 && stu[a] <= 1) r.mask |= 1u << a;
        r.at[a] = std::clamp(stu[a], 0.0, 1.0);
    }
    return r;
}

Lattice::PointJet Lattice::deform(const Eigen::Vector3d& p, double strength) const
{
    const OutsideRule rule = outsideRule(toLattice(p), outside_);
    if (!rule.moves()) return {p, Eigen::Matrix3d::Identity(), true};
    const Eigen::Vector3d& q = rule.at;
    const auto jet = displacementVolume().derivatives(q[0], q[1], q[2]);
    const Eigen::Vector3d dstu[3] = {jet.ds, jet.dt, jet.du};
    Eigen::Matrix3d j = Eigen::Matrix3d::Identity();
    for (int a = 0; a < 3; ++a)
        if (rule.follows(a)) j += strength * dstu[a] * dual_.row(a);
    Eigen::Vector3d moved = p;
    for (int a = 0; a < 3; ++a)
        if (strength * jet.point[a] != 0) moved[a] += strength * jet.point[a]; // keeps -0.0 where nothing moves
    return {moved, j, rule.outside};
}

Eigen::VectorXd Lattice::basisWeights(const Eigen::Vector3d& stu) const
{
    double bs[kMaxDegree + 1], bt[kMaxDegree + 1], bu[kMaxDegree + 1];
    bernsteinAll(degree_[0], stu[0], bs);
    bernsteinAll(degree_[1], stu[1], bt);
    bernsteinAll(degree_[2], stu[2], bu);
    Eigen::VectorXd w(points_.cols());
    for (int i = 0; i <= degree_[0]; ++i)
        for (int j = 0; j <= degree_[1]; ++j)
            for (int k = 0; k <= degree_[2]; ++k) w[index(i, j, k)] = bs[i] * bt[j] * bu[k];
    return w;
}

void Lattice::sensitivities(const Eigen::Vector3d& p, double strength, double* out) const
{
    const OutsideRule rule = outsideRule(toLattice(p), outside_);
    if (!rule.moves()) {
        std::fill(out, out + points_.cols(), 0.0);
        return;
    }
    double bs[kMaxDegree + 1], bt[kMaxDegree + 1], bu[kMaxDegree + 1];
    bernsteinTriangle(degree_[0], rule.at[0], bs);
    bernsteinTriangle(degree_[1], rule.at[1], bt);
    bernsteinTriangle(degree_[2], rule.at[2], bu);
    int q = 0;
    for (int i = 0; i <= degree_[0]; ++i)
        for (int j = 0; j <= degree_[1]; ++j) {
            const double a = strength * bs[i] * bt[j];
            for (int k = 0; k <= degree_[2]; ++k) out[q++] = a * bu[k];
        }
}

void Lattice::sensitivityBlock(const double* p, std::size_t count, double strength, double* out) const
{
    constexpr int L = kSensitivityLanes;
    constexpr int M = kMaxDegree + 1;
    alignas(64) double bs[M][L], bt[M][L], bu[M][L];
    double tmp[M];
    for (int lane = 0; lane < L; ++lane) {
        Eigen::Vector3d stu = Eigen::Vector3d::Zero();
        double scale = 0;
        if (static_cast<std::size_t>(lane) < count) {
            const OutsideRule rule = outsideRule(toLattice(Eigen::Vector3d(p[3 * lane], p[3 * lane + 1], p[3 * lane + 2])), outside_);
            if (rule.moves()) stu = rule.at, scale = strength;
        }
        bernsteinTriangle(degree_[0], stu[0], tmp);
        for (int i = 0; i <= degree_[0]; ++i) bs[i][lane] = scale * tmp[i];
        bernsteinTriangle(degree_[1], stu[1], tmp);
        for (int i = 0; i <= degree_[1]; ++i) bt[i][lane] = tmp[i];
        bernsteinTriangle(degree_[2], stu[2], tmp);
        for (int i = 0; i <= degree_[2]; ++i) bu[i][lane] = tmp[i];
    }
    int q = 0;
    for (int i = 0; i <= degree_[0]; ++i)
        for (int j = 0; j <= degree_[1]; ++j) {
            alignas(64) double a[L];
            for (int lane = 0; lane < L; ++lane) a[lane] = bs[i][lane] * bt[j][lane];
            for (int k = 0; k <= degree_[2]; ++k, ++q)
                for (int lane = 0; lane < L; ++lane) out[q * L + lane] = a[lane] * bu[k][lane];
        }
}

Lattice Lattice::elevated(int dl, int dm, int dn) const
{
    const BezierVolume<double> d = displacementVolume().elevated(dl, dm, dn);
    Lattice out = identity({degree_[0] + dl, degree_[1] + dm, degree_[2] + dn}, origin_, axes_, outside_);
    out.setControlPoints(out.restPoints() + d.controlPoints());
    return out;
}

} // namespace freeform
