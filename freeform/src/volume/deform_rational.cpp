// Rational FFD (NFFD) and its exact composition with rational Bézier and NURBS curves
// (volume/deform_rational.h; docs/nurbs.md).

#include "freeform/volume/deform_rational.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "freeform/core/bernstein.h"
#include "freeform/core/polynomial.h"
#include "composition.h"

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
    const OutsideRule rule = outsideRule(lattice_.toLattice(p), lattice_.outside());
    if (!rule.moves()) return {p, Eigen::Matrix3d::Identity(), true};
    const Eigen::Vector3d& q = rule.at;
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
        if (rule.follows(a)) jac += strength * ((nd[a] - dd[a] * f) / d) * lattice_.dual().row(a);
    Eigen::Vector3d moved = p;
    for (int a = 0; a < 3; ++a)
        if (strength * f[a] != 0) moved[a] += strength * f[a];
    return {moved, jac, rule.outside};
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
    // A polynomial lattice has D~ = W^(l+m+n) identically (each axis's basis sums to W^L), so the
    // quotient loses one factor W: degree d (l+m+n) instead of d (1 + l+m+n).
    const bool polynomial = rl.isPolynomial();
    const int degree = curve.degree() * detail::degreeFactor(rl);
    if (degree > kMaxDegree)
        throw Error("deformCurve: the deformed curve would have degree " + std::to_string(degree) +
                    (polynomial ? " (d (l+m+n))" : " (d (1 + l+m+n))") + ", above " + std::to_string(kMaxDegree));
    return RationalBezierCurve<double, 3>(BezierCurve<double, 4>(detail::composePiece(rl, curve, strength)));
}

namespace detail {

Eigen::Matrix<double, 4, Eigen::Dynamic> composePiece(const RationalLattice& rl, const RationalBezierCurve<double, 3>& curve,
                                                      double strength)
{
    const Lattice& lattice = rl.lattice();
    const auto& deg = lattice.degrees();
    const int d = curve.degree();
    const int sum = deg[0] + deg[1] + deg[2];
    const bool polynomial = rl.isPolynomial();
    const int degree = d * degreeFactor(rl);
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
    PointMatrix<double, 4> out(4, degree + 1);
    if (polynomial) {
        // p' = (A W^(L-1) + strength N~) / W^L, L = l+m+n.
        Poly power{1.0L};
        for (int k = 1; k < sum; ++k) power = bernsteinPolyProduct(power, W);
        const Poly weight = bernsteinPolyProduct(power, W);
        for (int c = 0; c < 3; ++c) {
            const Poly a = bernsteinPolyProduct(A[c], power);
            for (int i = 0; i <= degree; ++i)
                out(c, i) = static_cast<double>(a[i] + static_cast<long double>(strength) * N[c][i]);
        }
        for (int i = 0; i <= degree; ++i) out(3, i) = static_cast<double>(weight[i]);
        return out;
    }
    // p' = (A D~ + strength W N~) / (W D~).
    const Poly weight = bernsteinPolyProduct(W, D);
    for (int c = 0; c < 3; ++c) {
        const Poly a = bernsteinPolyProduct(A[c], D), b = bernsteinPolyProduct(W, N[c]);
        for (int i = 0; i <= degree; ++i) out(c, i) = static_cast<double>(a[i] + static_cast<long double>(strength) * b[i]);
    }
    for (int i = 0; i <= degree; ++i) out(3, i) = static_cast<double>(weight[i]);
    return out;
}

} // namespace detail

NurbsCurve<double, 3> deformCurve(const RationalLattice& lattice, const NurbsCurve<double, 3>& curve, double strength)
{
    const auto pieces = curve.bezierPieces();
    const auto& br = curve.breakpoints();
    std::vector<RationalBezierCurve<double, 3>> composed;
    for (const auto& piece : pieces) composed.push_back(deformCurve(lattice, piece, strength));
    std::vector<PointMatrix<double, 4>> nets;
    nets.reserve(composed.size());
    for (const auto& c : composed) nets.push_back(c.homogeneous().controlPoints());
    return NurbsCurve<double, 3>::fromBezierPieces(br, composed.front().degree(), nets, "deformCurve");
}

namespace {

/// A tensor Bernstein polynomial of degrees (du, dv), coefficient (i, j) at i * (dv + 1) + j.
template <typename Real>
struct Poly2 {
    int du = 0, dv = 0;
    std::vector<Real> c;
    Poly2() = default;
    Poly2(int u, int v, Real value = 0) : du(u), dv(v), c(static_cast<std::size_t>((u + 1) * (v + 1)), value) {}
    Real& at(int i, int j) { return c[static_cast<std::size_t>(i * (dv + 1) + j)]; }
    Real at(int i, int j) const { return c[static_cast<std::size_t>(i * (dv + 1) + j)]; }
};

/// C(n, k), k = 0..n (above kMaxDegree: a part's face on its way to a degree reduction).
template <typename Real>
std::vector<Real> binomialRow(int n)
{
    std::vector<Real> row(static_cast<std::size_t>(n + 1));
    for (int k = 0; k <= n; ++k) row[static_cast<std::size_t>(k)] = static_cast<Real>(binomialWide(n, k));
    return row;
}

/// The product by the Bernstein product formula in both variables:
///   (pq)_(k,l) = sum C(a,i) C(b,k-i) C(c,j) C(d,l-j) / (C(a+b,k) C(c+d,l)) p_ij q_(k-i,l-j).
template <typename Real>
Poly2<Real> product(const Poly2<Real>& p, const Poly2<Real>& q)
{
    Poly2<Real> out(p.du + q.du, p.dv + q.dv);
    const auto bpu = binomialRow<Real>(p.du), bqu = binomialRow<Real>(q.du), bpv = binomialRow<Real>(p.dv), bqv = binomialRow<Real>(q.dv);
    const auto bu = binomialRow<Real>(out.du), bv = binomialRow<Real>(out.dv);
    // q's coefficients times their binomials once, so that the inner loop is one multiply-add.
    std::vector<Real> qs(q.c.size());
    for (int k = 0; k <= q.du; ++k)
        for (int l = 0; l <= q.dv; ++l)
            qs[static_cast<std::size_t>(k * (q.dv + 1) + l)] =
                q.at(k, l) * bqu[static_cast<std::size_t>(k)] * bqv[static_cast<std::size_t>(l)];
    for (int i = 0; i <= p.du; ++i)
        for (int j = 0; j <= p.dv; ++j) {
            const Real a = p.at(i, j) * bpu[static_cast<std::size_t>(i)] * bpv[static_cast<std::size_t>(j)];
            if (a == 0) continue;
            for (int k = 0; k <= q.du; ++k) {
                Real* row = &out.at(i + k, j);
                const Real* from = &qs[static_cast<std::size_t>(k * (q.dv + 1))];
                for (int l = 0; l <= q.dv; ++l) row[l] += a * from[l];
            }
        }
    for (int k = 0; k <= out.du; ++k)
        for (int l = 0; l <= out.dv; ++l)
            out.at(k, l) /= bu[static_cast<std::size_t>(k)] * bv[static_cast<std::size_t>(l)];
    return out;
}

template <typename Real>
void addScaled(Poly2<Real>& acc, const Poly2<Real>& p, Real s)
{
    if (acc.c.empty()) acc = Poly2<Real>(p.du, p.dv);
    for (std::size_t i = 0; i < p.c.size(); ++i) acc.c[i] += s * p.c[i];
}

/// W^e (e >= 0) as a polynomial of degrees (e du, e dv); W^0 = 1.
template <typename Real>
Poly2<Real> power(const Poly2<Real>& w, int e)
{
    Poly2<Real> out(0, 0, Real(1));
    for (int k = 0; k < e; ++k) out = product(out, w);
    return out;
}

} // namespace

RationalBezierSurface<double, 3> deformSurface(const RationalLattice& rl, const RationalBezierSurface<double, 3>& surface,
                                               double strength)
{
    const int m = surface.degreeU(), n = surface.degreeV();
    const bool rational = !rl.isPolynomial();
    const int degreeU = m * detail::degreeFactor(rl), degreeV = n * detail::degreeFactor(rl);
    if (degreeU > kMaxDegree || degreeV > kMaxDegree)
        throw Error("deformSurface: the deformed patch would have degrees (" + std::to_string(degreeU) + ", " +
                    std::to_string(degreeV) + ") (" + (rational ? "(m (1 + l+m+n), n (1 + l+m+n))" : "(m (l+m+n), n (l+m+n))") +
                    "), above " + std::to_string(kMaxDegree));
    if (!std::isfinite(strength)) throw Error("deformSurface: strength is not finite");
    const auto& h = surface.homogeneous().controlPoints(); // 4 x (m+1)(n+1): (w b, w)
    const bool unitWeights = (h.row(3).array() == 1.0).all();
    if (!rational && unitWeights) // the polynomial composition of volume/deform.h
        return RationalBezierSurface<double, 3>(deformSurface(rl.lattice(), BezierSurface<double, 3>(m, n, h.topRows<3>()), strength));
    detail::HomogeneousPatch composed = detail::composePatch(rl, surface, strength);
    return RationalBezierSurface<double, 3>(BezierSurface<double, 4>(composed.du, composed.dv, std::move(composed.points)));
}

namespace detail {

namespace {

/// composePatch in Real: long double up to kMaxDegree (the exact compositions the library keeps),
/// double above (a reduction follows, and long double is several times slower there).
template <typename Real>
HomogeneousPatch composeIn(const RationalLattice& rl, const RationalBezierSurface<double, 3>& surface, double strength)
{
    const Lattice& lattice = rl.lattice();
    const auto& deg = lattice.degrees();
    const int m = surface.degreeU(), n = surface.degreeV();
    const int sum = deg[0] + deg[1] + deg[2];
    const bool rational = !rl.isPolynomial();
    const int degreeU = m * degreeFactor(rl), degreeV = n * degreeFactor(rl);
    if (!std::isfinite(strength)) throw Error("deformSurface: strength is not finite");
    const auto& h = surface.homogeneous().controlPoints(); // 4 x (m+1)(n+1): (w b, w)
    Poly2<Real> W(m, n), A[3] = {Poly2<Real>(m, n), Poly2<Real>(m, n), Poly2<Real>(m, n)};
    for (Eigen::Index r = 0; r < h.cols(); ++r) {
        W.c[static_cast<std::size_t>(r)] = h(3, r);
        for (int c = 0; c < 3; ++c) A[c].c[static_cast<std::size_t>(r)] = h(c, r);
    }
    // Homogeneous lattice coordinates S_a = dual_a . (A - X0 W) and the composed basis
    // C(L,i) Real^i (W - Real)^(L-i), of degrees (m L, n L) per axis.
    std::vector<Poly2<Real>> basis[3];
    for (int a = 0; a < 3; ++a) {
        Poly2<Real> S(m, n), R(m, n);
        for (std::size_t r = 0; r < W.c.size(); ++r) {
            Real x = 0;
            for (int c = 0; c < 3; ++c)
                x += static_cast<Real>(lattice.dual()(a, c)) *
                     (A[c].c[r] - static_cast<Real>(lattice.origin()[c]) * W.c[r]);
            S.c[r] = x;
            R.c[r] = W.c[r] - x;
        }
        const int L = deg[a];
        std::vector<Poly2<Real>> sp{Poly2<Real>(0, 0, Real(1))}, rp{Poly2<Real>(0, 0, Real(1))};
        for (int k = 1; k <= L; ++k) {
            sp.push_back(product(sp.back(), S));
            rp.push_back(product(rp.back(), R));
        }
        for (int i = 0; i <= L; ++i) {
            Poly2<Real> b = product(sp[static_cast<std::size_t>(i)], rp[static_cast<std::size_t>(L - i)]);
            const Real c = static_cast<Real>(binomial(L, i));
            for (auto& v : b.c) v *= c;
            basis[a].push_back(std::move(b));
        }
    }
    // N~ (3 coordinates) and, for a rational lattice, D~: degrees (m L, n L). The sum over k is a
    // linear combination, the sums over i and j Bernstein products.
    Poly2<Real> N[3], D;
    const auto& disp = lattice.displacements();
    for (int i = 0; i <= deg[0]; ++i) {
        // sum_j B_j(t) sum_k w_ijk c_ijk B_k(u), then times B_i(s): the products nest, so the
        // largest ones (by B_i) are one per i, not one per (i, j).
        Poly2<Real> hN[3], hD;
        for (int j = 0; j <= deg[1]; ++j) {
            Poly2<Real> gN[3], gD;
            for (int k = 0; k <= deg[2]; ++k) {
                const int idx = lattice.index(i, j, k);
                const Real w = rl.weights()[idx];
                const Poly2<Real>& bk = basis[2][static_cast<std::size_t>(k)];
                if (rational) addScaled(gD, bk, w);
                for (int c = 0; c < 3; ++c) addScaled(gN[c], bk, w * static_cast<Real>(disp(c, idx)));
            }
            const Poly2<Real>& bj = basis[1][static_cast<std::size_t>(j)];
            if (rational) addScaled(hD, product(bj, gD), Real(1));
            for (int c = 0; c < 3; ++c) addScaled(hN[c], product(bj, gN[c]), Real(1));
        }
        const Poly2<Real>& bi = basis[0][static_cast<std::size_t>(i)];
        if (rational) addScaled(D, product(bi, hD), Real(1));
        for (int c = 0; c < 3; ++c) addScaled(N[c], product(bi, hN[c]), Real(1));
    }
    // Rational lattice: (A D~ + s W N~) / (W D~). Polynomial lattice: (A W^(L-1) + s N~) / W^L.
    const Poly2<Real> left = rational ? D : power(W, sum - 1);
    const Poly2<Real> weight = product(W, left);
    PointMatrix<double, 4> out(4, (degreeU + 1) * (degreeV + 1));
    const Real s = strength;
    for (int c = 0; c < 3; ++c) {
        const Poly2<Real> a = product(A[c], left);
        const Poly2<Real> b = rational ? product(W, N[c]) : N[c];
        for (std::size_t r = 0; r < a.c.size(); ++r) out(c, static_cast<Eigen::Index>(r)) = static_cast<double>(a.c[r] + s * b.c[r]);
    }
    for (std::size_t r = 0; r < weight.c.size(); ++r) out(3, static_cast<Eigen::Index>(r)) = static_cast<double>(weight.c[r]);
    for (Eigen::Index r = 0; r < out.cols(); ++r)
        if (!(out(3, r) > 0))
            throw Error("deformSurface: composed weight " + std::to_string(r) +
                        " is not positive (the patch leaves the rational lattice's box)");
    return HomogeneousPatch{degreeU, degreeV, std::move(out)};
}

} // namespace

HomogeneousPatch composePatch(const RationalLattice& rl, const RationalBezierSurface<double, 3>& surface, double strength)
{
    const int factor = degreeFactor(rl);
    if (std::max(surface.degreeU(), surface.degreeV()) * factor <= kMaxDegree) return composeIn<long double>(rl, surface, strength);
    return composeIn<double>(rl, surface, strength);
}

} // namespace detail

NurbsSurface<double, 3> deformSurface(const RationalLattice& lattice, const NurbsSurface<double, 3>& surface, double strength)
{
    const auto patches = surface.bezierPatches();
    const std::vector<double> bu = surface.knotsU().breakpoints(), bv = surface.knotsV().breakpoints();
    std::vector<RationalBezierSurface<double, 3>> composed;
    composed.reserve(patches.size());
    for (const auto& patch : patches) {
        if (surface.isRational()) {
            composed.push_back(deformSurface(lattice, patch, strength));
        } else {
            // A polynomial surface's patches: the extracted points themselves, weights exactly 1.
            const BezierSurface<double, 3> poly(patch.degreeU(), patch.degreeV(),
                                                patch.homogeneous().controlPoints().topRows<3>());
            composed.push_back(deformSurface(lattice, RationalBezierSurface<double, 3>(poly), strength));
        }
    }
    std::vector<PointMatrix<double, 4>> nets;
    nets.reserve(composed.size());
    for (const auto& c : composed) nets.push_back(c.homogeneous().controlPoints());
    return NurbsSurface<double, 3>::fromBezierPatches(bu, bv, composed.front().degreeU(), composed.front().degreeV(), nets,
                                                      "deformSurface");
}

} // namespace freeform
