// Rational FFD (NFFD) and its exact composition with rational Bézier and NURBS curves
// (volume/deform_rational.h; docs/nurbs.md).

#include "freeform/volume/deform_rational.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "freeform/core/bernstein.h"
#include "freeform/core/polynomial.h"

namespace freeform {

RationalLattice::RationalLattice(Lattice lattice, Eigen::VectorXd weights)
    : lattice_(std::move(lattice)), weights_(std::move(weights))
{
    if (weights_.size() != lattice_.pointCount())
        throw Error("RationalLattice: " + std::to_string(weights_.size()) + " weights for " +
                    std::to_string(lattice_.pointCount()) + " control points");
    for (Eigen::Index i = 0; i < weights_.size(); ++i) {
        if (!(weights_[i] > 0) || !std::isfinite(weights_[i]))
            throw Error("RationalLattice: weight " + std::to_string(i) + " is not a positive finite number");
        if (weights_[i] != 1.0) unit_ = false;
    }
}

RationalLattice::RationalLattice(Lattice lattice)
    : RationalLattice(lattice, Eigen::VectorXd::Ones(lattice.pointCount()))
{
}

Lattice::PointJet RationalLattice::deform(const Eigen::Vector3d& p, double strength) const
{
    if (unit_) return lattice_.deform(p, strength);
    const Eigen::Vector3d stu = lattice_.toLattice(p);
    const bool outside = !Lattice::insideBox(stu);
    if (outside && lattice_.outside() == OutsidePolicy::Keep) return {p, Eigen::Matrix3d::Identity(), true};
    Eigen::Vector3d q = stu;
    bool active[3] = {true, true, true};
    if (outside && lattice_.outside() == OutsidePolicy::Clamp) {
        for (int a = 0; a < 3; ++a) {
            if (stu[a] < 0 || stu[a] > 1) active[a] = false;
            q[a] = std::clamp(stu[a], 0.0, 1.0);
        }
    }
    const auto& deg = lattice_.degrees();
    double b[3][kMaxDegree + 1], db[3][kMaxDegree + 1], scratch[kMaxDegree + 1];
    for (int a = 0; a < 3; ++a) {
        bernsteinAll(deg[a], q[a], b[a]);
        bernsteinDerivativeAll(deg[a], 1, q[a], db[a], scratch);
    }
    Eigen::Vector3d n = Eigen::Vector3d::Zero(), nd[3] = {n, n, n};
    double d = 0, dd[3] = {0, 0, 0};
    const auto& disp = lattice_.displacements();
    for (int i = 0; i <= deg[0]; ++i)
        for (int j = 0; j <= deg[1]; ++j)
            for (int k = 0; k <= deg[2]; ++k) {
                const int idx = lattice_.index(i, j, k);
                const double w = weights_[idx];
                const double basis = b[0][i] * b[1][j] * b[2][k];
                const double partial[3] = {db[0][i] * b[1][j] * b[2][k], b[0][i] * db[1][j] * b[2][k],
                                           b[0][i] * b[1][j] * db[2][k]};
                n += w * basis * disp.col(idx);
                d += w * basis;
                for (int a = 0; a < 3; ++a) {
                    nd[a] += w * partial[a] * disp.col(idx);
                    dd[a] += w * partial[a];
                }
            }
    const Eigen::Vector3d f = n / d;
    Eigen::Matrix3d jac = Eigen::Matrix3d::Identity();
    for (int a = 0; a < 3; ++a)
        if (active[a]) jac += strength * ((nd[a] - dd[a] * f) / d) * lattice_.dual().row(a);
    Eigen::Vector3d moved = p;
    for (int a = 0; a < 3; ++a)
        if (strength * f[a] != 0) moved[a] += strength * f[a];
    return {moved, jac, outside};
}

namespace {

void record(DeformReport& report, double det, std::size_t v, bool outside)
{
    if (outside) ++report.outside;
    if (report.vertices == 0) report.minDetJ = report.maxDetJ = det;
    report.minDetJ = std::min(report.minDetJ, det);
    report.maxDetJ = std::max(report.maxDetJ, det);
    if (det <= 0) {
        ++report.foldCount;
        report.folds.push_back(static_cast<int>(v));
    }
    ++report.vertices;
}

using Poly = std::vector<long double>;

Poly scaled(const Poly& p, long double s)
{
    Poly out = p;
    for (auto& x : out) x *= s;
    return out;
}

void addTo(Poly& acc, const Poly& p, long double s)
{
    if (acc.empty()) acc.assign(p.size(), 0.0L);
    for (std::size_t i = 0; i < p.size(); ++i) acc[i] += s * p[i];
}

} // namespace

DeformReport deformPoints(const RationalLattice& lattice, Eigen::Matrix<double, 3, Eigen::Dynamic>& points,
                          const DeformOptions& options)
{
    if (lattice.isPolynomial()) return deformPoints(lattice.lattice(), points, options);
    DeformReport report;
    for (Eigen::Index v = 0; v < points.cols(); ++v) {
        const auto jet = lattice.deform(points.col(v), options.strength);
        points.col(v) = jet.point;
        record(report, jet.jacobian.determinant(), static_cast<std::size_t>(v), jet.outside);
    }
    return report;
}

DeformReport deformMesh(const RationalLattice& lattice, PolygonMesh& mesh, const DeformOptions& options)
{
    if (lattice.isPolynomial()) return deformMesh(lattice.lattice(), mesh, options, NormalMode::Jacobian);
    DeformReport report;
    const bool normals = mesh.normals.cols() == mesh.positions.cols() && mesh.normals.cols() > 0;
    for (Eigen::Index v = 0; v < mesh.positions.cols(); ++v) {
        const auto jet = lattice.deform(mesh.positions.col(v), options.strength);
        mesh.positions.col(v) = jet.point;
        if (normals) mesh.normals.col(v) = transformNormal(jet.jacobian, mesh.normals.col(v));
        record(report, jet.jacobian.determinant(), static_cast<std::size_t>(v), jet.outside);
    }
    return report;
}

RationalBezierCurve<double, 3> deformCurve(const RationalLattice& rl, const RationalBezierCurve<double, 3>& curve,
                                           double strength)
{
    const Lattice& lattice = rl.lattice();
    const auto& deg = lattice.degrees();
    const int d = curve.degree();
    const int sum = deg[0] + deg[1] + deg[2];
    const int degree = d * (1 + sum);
    if (degree > kMaxDegree)
        throw Error("deformCurve: the deformed curve would have degree " + std::to_string(degree) +
                    " (d (1 + l+m+n)), above " + std::to_string(kMaxDegree));
    if (!std::isfinite(strength)) throw Error("deformCurve: strength is not finite");
    const auto& h = curve.homogeneous().controlPoints(); // 4 x (d+1): (w b, w)
    Poly W(static_cast<std::size_t>(d + 1)), A[3];
    for (int c = 0; c < 3; ++c) A[c].resize(static_cast<std::size_t>(d + 1));
    for (int i = 0; i <= d; ++i) {
        W[i] = h(3, i);
        for (int c = 0; c < 3; ++c) A[c][i] = h(c, i);
    }
    // Homogeneous lattice coordinates S_a = dual_a . (A - X0 W) and the basis polynomials
    // C(L,i) S^i (W - S)^(L-i) of degree d L per axis.
    std::vector<Poly> basis[3];
    for (int a = 0; a < 3; ++a) {
        Poly S(static_cast<std::size_t>(d + 1)), R(static_cast<std::size_t>(d + 1));
        for (int i = 0; i <= d; ++i) {
            long double s = 0;
            for (int c = 0; c < 3; ++c)
                s += static_cast<long double>(lattice.dual()(a, c)) * (A[c][i] - static_cast<long double>(lattice.origin()[c]) * W[i]);
            S[i] = s;
            R[i] = W[i] - s;
        }
        const int L = deg[a];
        std::vector<Poly> sp(static_cast<std::size_t>(L + 1)), rp(static_cast<std::size_t>(L + 1));
        sp[0] = rp[0] = Poly{1.0L};
        for (int k = 1; k <= L; ++k) {
            sp[k] = bernsteinPolyProduct(sp[k - 1], S);
            rp[k] = bernsteinPolyProduct(rp[k - 1], R);
        }
        for (int i = 0; i <= L; ++i)
            basis[a].push_back(scaled(bernsteinPolyProduct(sp[i], rp[L - i]), static_cast<long double>(binomial(L, i))));
    }
    // N~ (3 coordinates) and D~, degree d (l+m+n).
    Poly N[3], D;
    const auto& disp = lattice.displacements();
    for (int i = 0; i <= deg[0]; ++i)
        for (int j = 0; j <= deg[1]; ++j) {
            const Poly st = bernsteinPolyProduct(basis[0][i], basis[1][j]);
            for (int k = 0; k <= deg[2]; ++k) {
                const Poly stu = bernsteinPolyProduct(st, basis[2][k]);
                const int idx = lattice.index(i, j, k);
                const long double w = rl.weights()[idx];
                addTo(D, stu, w);
                for (int c = 0; c < 3; ++c) addTo(N[c], stu, w * static_cast<long double>(disp(c, idx)));
            }
        }
    // p' = (A D~ + strength W N~) / (W D~).
    const Poly weight = bernsteinPolyProduct(W, D);
    PointMatrix<double, 4> out(4, degree + 1);
    for (int c = 0; c < 3; ++c) {
        const Poly a = bernsteinPolyProduct(A[c], D), b = bernsteinPolyProduct(W, N[c]);
        for (int i = 0; i <= degree; ++i) out(c, i) = static_cast<double>(a[i] + static_cast<long double>(strength) * b[i]);
    }
    for (int i = 0; i <= degree; ++i) out(3, i) = static_cast<double>(weight[i]);
    return RationalBezierCurve<double, 3>(BezierCurve<double, 4>(std::move(out)));
}

NurbsCurve<double, 3> deformCurve(const RationalLattice& lattice, const NurbsCurve<double, 3>& curve, double strength)
{
    const auto pieces = curve.bezierPieces();
    const auto& br = curve.breakpoints();
    std::vector<RationalBezierCurve<double, 3>> composed;
    for (const auto& piece : pieces) composed.push_back(deformCurve(lattice, piece, strength));
    const int D = composed.front().degree();
    std::vector<double> knots(static_cast<std::size_t>(D + 1), br.front());
    for (std::size_t k = 1; k + 1 < br.size(); ++k) knots.insert(knots.end(), static_cast<std::size_t>(D), br[k]);
    knots.insert(knots.end(), static_cast<std::size_t>(D + 1), br.back());
    const int count = static_cast<int>(composed.size()) * D + 1;
    PointMatrix<double, 4> h(4, count);
    for (std::size_t k = 0; k < composed.size(); ++k) // joints: the left piece's end (equal to rounding)
        h.middleCols(static_cast<Eigen::Index>(k) * D, D + 1) = composed[k].homogeneous().controlPoints();
    for (std::size_t k = 1; k < composed.size(); ++k)
        h.col(static_cast<Eigen::Index>(k) * D) = composed[k - 1].homogeneous().controlPoints().col(D);
    return NurbsCurve<double, 3>(KnotVector<double>(std::move(knots), D, "deformCurve"), std::move(h));
}

} // namespace freeform
