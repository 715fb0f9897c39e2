// Deformation of points and meshes, the det J certificate, exact curve composition and direct
// manipulation (volume/deform.h). The batched kernel is in ffd_binding.cpp.

#include "freeform/volume/deform.h"

#include <Eigen/QR>

#include <algorithm>
#include <cmath>

#include "freeform/core/polynomial.h"

namespace freeform {

// ------------------------------------------------------------------------ points and meshes

DeformReport deformPoints(const Lattice& lattice, Eigen::Matrix<double, 3, Eigen::Dynamic>& points,
                          const DeformOptions& options)
{
    const FfdBinding<double> binding(lattice, points);
    Eigen::Matrix<double, 3, Eigen::Dynamic> out(3, points.cols());
    DeformReport report;
    FfdOutputs<double> o;
    o.positions = out.data();
    binding.deform(lattice, o, options, &report);
    points = std::move(out);
    return report;
}

NormalMode parseNormalMode(const std::string& text, const std::string& what)
{
    if (text == "jacobian") return NormalMode::Jacobian;
    if (text == "recompute") return NormalMode::Recompute;
    throw Error(what + ": normal mode \"" + text + "\" is not one of jacobian, recompute");
}

DeformReport deformMesh(const Lattice& lattice, PolygonMesh& mesh, const DeformOptions& options, NormalMode normals)
{
    mesh.validate("ffd: mesh");
    const FfdBinding<double> binding(lattice, mesh.positions);
    Eigen::Matrix<double, 3, Eigen::Dynamic> positions(3, mesh.positions.cols());
    Eigen::Matrix<double, 3, Eigen::Dynamic> newNormals;
    FfdOutputs<double> o;
    o.positions = positions.data();
    if (normals == NormalMode::Jacobian && mesh.normals.cols() == mesh.positions.cols() && mesh.normals.cols() > 0) {
        newNormals.resize(3, mesh.normals.cols());
        o.normalsIn = mesh.normals.data();
        o.normalsOut = newNormals.data();
    }
    DeformReport report;
    binding.deform(lattice, o, options, &report);
    mesh.positions = std::move(positions);
    if (normals == NormalMode::Recompute) {
        mesh.normals = areaWeightedNormals(mesh);
    } else if (o.normalsOut) {
        mesh.normals = std::move(newNormals);
    }
    return report;
}

Eigen::Matrix<double, 3, Eigen::Dynamic> areaWeightedNormals(const PolygonMesh& mesh)
{
    Eigen::Matrix<double, 3, Eigen::Dynamic> n = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, mesh.positions.cols());
    for (int f = 0; f < mesh.faceCount(); ++f) {
        const int* v = mesh.face(f);
        const int size = mesh.faceSize(f);
        const Eigen::Vector3d p0 = mesh.positions.col(v[0]);
        Eigen::Vector3d area = Eigen::Vector3d::Zero();
        for (int k = 1; k + 1 < size; ++k)
            area += (mesh.positions.col(v[k]) - p0).cross(mesh.positions.col(v[k + 1]) - p0);
        area *= 0.5;
        for (int k = 0; k < size; ++k) n.col(v[k]) += area;
    }
    for (Eigen::Index i = 0; i < n.cols(); ++i) {
        const double len = n.col(i).norm();
        if (len > 0) n.col(i) /= len;
    }
    return n;
}

Eigen::Vector3d transformNormal(const Eigen::Matrix3d& j, const Eigen::Vector3d& n)
{
    const Eigen::Vector3d c0 = j.col(0), c1 = j.col(1), c2 = j.col(2);
    const Eigen::Vector3d m = n.x() * c1.cross(c2) + n.y() * c2.cross(c0) + n.z() * c0.cross(c1);
    const double len = m.norm();
    return len > 0 ? Eigen::Vector3d(m / len) : m;
}

Eigen::Vector3d transformTangent(const Eigen::Matrix3d& j, const Eigen::Vector3d& t)
{
    const Eigen::Vector3d m = j * t;
    const double len = m.norm();
    return len > 0 ? Eigen::Vector3d(m / len) : m;
}

// ------------------------------------------------------------------------ certificate

std::string toString(Verdict verdict)
{
    switch (verdict) {
    case Verdict::CertifiedInjective: return "certified injective";
    case Verdict::Folds: return "folds";
    case Verdict::Undecided: return "undecided";
    }
    return "undecided";
}

namespace {

long double lbinom(int n, int k)
{
    long double r = 1;
    for (int i = 1; i <= k; ++i) r = r * static_cast<long double>(n - k + i) / i;
    return r;
}

/// A scalar trivariate Bernstein polynomial in long double.
struct Tensor {
    std::array<int, 3> deg{};
    std::vector<long double> c;

    Tensor() = default;
    explicit Tensor(std::array<int, 3> d) : deg(d), c(static_cast<std::size_t>((d[0] + 1) * (d[1] + 1) * (d[2] + 1)), 0.0L) {}
    std::size_t idx(int i, int j, int k) const
    {
        return static_cast<std::size_t>((i * (deg[1] + 1) + j) * (deg[2] + 1) + k);
    }
    long double& at(int i, int j, int k) { return c[idx(i, j, k)]; }
    long double at(int i, int j, int k) const { return c[idx(i, j, k)]; }
};

/// Coordinate `x` of a volume's control points.
Tensor coordinate(const BezierVolume<double>& v, int x)
{
    Tensor t(v.degrees());
    for (int i = 0; i < v.pointCount(); ++i) t.c[static_cast<std::size_t>(i)] = v.controlPoints()(x, i);
    return t;
}

/// Bernstein product: (pq)_IJK = sum p_ijk q_(I-i)(J-j)(K-k) prod_axes C(a,i) C(b,I-i) / C(a+b,I).
Tensor product(const Tensor& p, const Tensor& q)
{
    Tensor r({p.deg[0] + q.deg[0], p.deg[1] + q.deg[1], p.deg[2] + q.deg[2]});
    std::vector<long double> wp(p.c.size()), wq(q.c.size());
    for (int i = 0; i <= p.deg[0]; ++i)
        for (int j = 0; j <= p.deg[1]; ++j)
            for (int k = 0; k <= p.deg[2]; ++k)
                wp[p.idx(i, j, k)] = p.at(i, j, k) * lbinom(p.deg[0], i) * lbinom(p.deg[1], j) * lbinom(p.deg[2], k);
    for (int i = 0; i <= q.deg[0]; ++i)
        for (int j = 0; j <= q.deg[1]; ++j)
            for (int k = 0; k <= q.deg[2]; ++k)
                wq[q.idx(i, j, k)] = q.at(i, j, k) * lbinom(q.deg[0], i) * lbinom(q.deg[1], j) * lbinom(q.deg[2], k);
    for (int i = 0; i <= p.deg[0]; ++i)
        for (int j = 0; j <= p.deg[1]; ++j)
            for (int k = 0; k <= p.deg[2]; ++k) {
                const long double a = wp[p.idx(i, j, k)];
                if (a == 0) continue;
                for (int I = 0; I <= q.deg[0]; ++I)
                    for (int J = 0; J <= q.deg[1]; ++J)
                        for (int K = 0; K <= q.deg[2]; ++K) r.at(i + I, j + J, k + K) += a * wq[q.idx(I, J, K)];
            }
    for (int i = 0; i <= r.deg[0]; ++i)
        for (int j = 0; j <= r.deg[1]; ++j)
            for (int k = 0; k <= r.deg[2]; ++k)
                r.at(i, j, k) /= lbinom(r.deg[0], i) * lbinom(r.deg[1], j) * lbinom(r.deg[2], k);
    return r;
}

void addScaled(Tensor& a, const Tensor& b, long double f)
{
    for (std::size_t i = 0; i < a.c.size(); ++i) a.c[i] += f * b.c[i];
}

/// The halves of t along `axis` at 1/2.
std::pair<Tensor, Tensor> halve(const Tensor& t, int axis)
{
    Tensor lo(t.deg), hi(t.deg);
    const int d = t.deg[static_cast<std::size_t>(axis)];
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    std::vector<long double> w(static_cast<std::size_t>(d + 1));
    for (int p = 0; p <= t.deg[static_cast<std::size_t>(a)]; ++p)
        for (int q = 0; q <= t.deg[static_cast<std::size_t>(b)]; ++q) {
            int ijk[3] = {0, 0, 0};
            ijk[a] = p;
            ijk[b] = q;
            auto at = [&](int r) {
                ijk[axis] = r;
                return t.idx(ijk[0], ijk[1], ijk[2]);
            };
            for (int r = 0; r <= d; ++r) w[static_cast<std::size_t>(r)] = t.c[at(r)];
            lo.c[at(0)] = w[0];
            hi.c[at(d)] = w[static_cast<std::size_t>(d)];
            for (int level = 1; level <= d; ++level) {
                for (int r = 0; r + level <= d; ++r)
                    w[static_cast<std::size_t>(r)] = 0.5L * (w[static_cast<std::size_t>(r)] + w[static_cast<std::size_t>(r + 1)]);
                lo.c[at(level)] = w[0];
                hi.c[at(d - level)] = w[static_cast<std::size_t>(d - level)];
            }
        }
    return {std::move(lo), std::move(hi)};
}

struct Search {
    int maxDepth;
    int boxes = 0;
    bool undecided = false;
    bool folds = false;
    Eigen::Vector3d witness = Eigen::Vector3d::Zero();
};

void examine(const Tensor& t, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int depth, Search& search)
{
    if (search.folds) return;
    ++search.boxes;
    if (*std::min_element(t.c.begin(), t.c.end()) > 0) return; // certified on this box
    for (int corner = 0; corner < 8; ++corner) {
        const int i = (corner & 4) ? t.deg[0] : 0, j = (corner & 2) ? t.deg[1] : 0, k = (corner & 1) ? t.deg[2] : 0;
        if (!(t.at(i, j, k) > 0)) {
            search.folds = true;
            search.witness = Eigen::Vector3d((corner & 4) ? hi[0] : lo[0], (corner & 2) ? hi[1] : lo[1], (corner & 1) ? hi[2] : lo[2]);
            return;
        }
    }
    if (depth >= search.maxDepth) {
        search.undecided = true;
        return;
    }
    // Halve along the axis of the longest box side (ties: s, t, u).
    const Eigen::Vector3d size = hi - lo;
    int axis = 0;
    for (int a = 1; a < 3; ++a)
        if (size[a] > size[axis]) axis = a;
    auto halves = halve(t, axis);
    Eigen::Vector3d mid = hi;
    mid[axis] = 0.5 * (lo[axis] + hi[axis]);
    Eigen::Vector3d midLo = lo;
    midLo[axis] = mid[axis];
    examine(halves.first, lo, mid, depth + 1, search);
    examine(halves.second, midLo, hi, depth + 1, search);
}

Tensor determinantTensor(const Lattice& lattice, double strength)
{
    const BezierVolume<double> v = lattice.volume(strength);
    const BezierVolume<double> fs = v.derivative(0), ft = v.derivative(1), fu = v.derivative(2);
    Tensor s[3], t[3], u[3];
    for (int x = 0; x < 3; ++x) {
        s[x] = coordinate(fs, x);
        t[x] = coordinate(ft, x);
        u[x] = coordinate(fu, x);
    }
    // det [f_s f_t f_u] = f_s . (f_t x f_u), divided by det [S T U] (the world map's Jacobian).
    const long double scale = 1.0L / lattice.axes().cast<long double>().determinant();
    Tensor det;
    for (int x = 0; x < 3; ++x) {
        const int y = (x + 1) % 3, z = (x + 2) % 3;
        Tensor cross = product(t[y], u[z]);
        addScaled(cross, product(t[z], u[y]), -1.0L);
        Tensor term = product(s[x], cross);
        if (x == 0) {
            det = std::move(term);
            for (auto& c : det.c) c *= scale;
        } else {
            addScaled(det, term, scale);
        }
    }
    return det;
}

} // namespace

JacobianPolynomial jacobianPolynomial(const Lattice& lattice, double strength)
{
    const Tensor det = determinantTensor(lattice, strength);
    JacobianPolynomial p;
    p.degree = det.deg;
    p.coefficients.assign(det.c.size(), 0.0);
    for (std::size_t i = 0; i < det.c.size(); ++i) p.coefficients[i] = static_cast<double>(det.c[i]);
    return p;
}

Certificate certify(const Lattice& lattice, double strength, int maxDepth)
{
    if (!std::isfinite(strength)) throw Error("certify: strength is not finite");
    const Tensor det = determinantTensor(lattice, strength);
    Certificate cert;
    cert.minCoefficient = static_cast<double>(*std::min_element(det.c.begin(), det.c.end()));
    cert.maxCoefficient = static_cast<double>(*std::max_element(det.c.begin(), det.c.end()));
    Search search{std::max(0, maxDepth) * 3};
    examine(det, Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 0, search);
    cert.boxes = search.boxes;
    if (search.folds) {
        cert.verdict = Verdict::Folds;
        cert.witness = search.witness;
    } else {
        cert.verdict = search.undecided ? Verdict::Undecided : Verdict::CertifiedInjective;
    }
    return cert;
}

// ------------------------------------------------------------------------ exact composition

namespace {

using Poly = std::vector<double>;
using VecPoly = std::vector<Eigen::Vector3d>;

/// Raises a Bernstein polynomial of degree c.size()-1 to degree `target`.
Poly elevateTo(Poly c, int target)
{
    while (static_cast<int>(c.size()) - 1 < target) {
        const int n = static_cast<int>(c.size()) - 1;
        Poly e(static_cast<std::size_t>(n + 2));
        e[0] = c[0];
        e[static_cast<std::size_t>(n + 1)] = c[static_cast<std::size_t>(n)];
        for (int i = 1; i <= n; ++i) {
            const double a = double(i) / double(n + 1);
            e[static_cast<std::size_t>(i)] = a * c[static_cast<std::size_t>(i - 1)] + (1 - a) * c[static_cast<std::size_t>(i)];
        }
        c = std::move(e);
    }
    return c;
}

/// B_0..B_deg of degree `deg` composed with the polynomial x(tau) (coefficients c): each of
/// degree deg * (c.size() - 1).
std::vector<Poly> composedBasis(int deg, const Poly& x)
{
    Poly oneMinus(x.size());
    for (std::size_t r = 0; r < x.size(); ++r) oneMinus[r] = 1.0 - x[r];
    std::vector<Poly> powX{Poly{1.0}}, powY{Poly{1.0}};
    for (int e = 1; e <= deg; ++e) {
        powX.push_back(bernsteinPolyProduct(powX.back(), x));
        powY.push_back(bernsteinPolyProduct(powY.back(), oneMinus));
    }
    std::vector<Poly> basis;
    for (int i = 0; i <= deg; ++i) {
        Poly b = bernsteinPolyProduct(powX[static_cast<std::size_t>(i)], powY[static_cast<std::size_t>(deg - i)]);
        for (double& v : b) v *= double(binomial(deg, i));
        basis.push_back(std::move(b));
    }
    return basis;
}

/// sum_r a_r(tau) v_r(tau) with scalar polynomials a_r (all one degree) and vector polynomials v_r
/// (all one degree).
VecPoly productSum(const std::vector<Poly>& a, const std::vector<VecPoly>& v)
{
    VecPoly out;
    for (std::size_t r = 0; r < a.size(); ++r) {
        for (int x = 0; x < 3; ++x) {
            Poly coord(v[r].size());
            for (std::size_t i = 0; i < v[r].size(); ++i) coord[i] = v[r][i][x];
            const Poly p = bernsteinPolyProduct(a[r], coord);
            if (out.empty()) out.assign(p.size(), Eigen::Vector3d::Zero());
            for (std::size_t i = 0; i < p.size(); ++i) out[i][x] += p[i];
        }
    }
    return out;
}

} // namespace

BezierCurve<double, 3> deformCurve(const Lattice& lattice, const BezierCurve<double, 3>& curve, double strength)
{
    const int d = curve.degree();
    const int l = lattice.degree(0), m = lattice.degree(1), n = lattice.degree(2);
    const int degree = d * (l + m + n);
    if (degree > kMaxDegree)
        throw Error("deformCurve: the deformed curve would have degree " + std::to_string(degree) + " (d (l+m+n)), above " +
                    std::to_string(kMaxDegree));
    if (d == 0) {
        return BezierCurve<double, 3>(Eigen::Matrix<double, 3, Eigen::Dynamic>(
            lattice.map(lattice.toLattice(curve.controlPoint(0)), strength).point));
    }
    // Lattice coordinates of the curve: an affine image, so again of degree d.
    Poly sc[3];
    for (int x = 0; x < 3; ++x) sc[x].resize(static_cast<std::size_t>(d + 1));
    for (int r = 0; r <= d; ++r) {
        const Eigen::Vector3d stu = lattice.toLattice(curve.controlPoint(r));
        for (int x = 0; x < 3; ++x) sc[x][static_cast<std::size_t>(r)] = stu[x];
    }
    const auto bs = composedBasis(l, sc[0]), bt = composedBasis(m, sc[1]), bu = composedBasis(n, sc[2]);
    const auto& disp = lattice.displacements();
    std::vector<VecPoly> perI;
    for (int i = 0; i <= l; ++i) {
        std::vector<VecPoly> perJ;
        for (int j = 0; j <= m; ++j) {
            VecPoly g(bu[0].size(), Eigen::Vector3d::Zero());
            for (int k = 0; k <= n; ++k) {
                const Eigen::Vector3d c = strength * disp.col(lattice.index(i, j, k));
                for (std::size_t r = 0; r < g.size(); ++r) g[r] += bu[static_cast<std::size_t>(k)][r] * c;
            }
            perJ.push_back(std::move(g));
        }
        perI.push_back(productSum(bt, perJ));
    }
    const VecPoly disp3 = productSum(bs, perI);
    Eigen::Matrix<double, 3, Eigen::Dynamic> points(3, degree + 1);
    for (int x = 0; x < 3; ++x) {
        Poly c(static_cast<std::size_t>(d + 1));
        for (int r = 0; r <= d; ++r) c[static_cast<std::size_t>(r)] = curve.controlPoints()(x, r);
        const Poly e = elevateTo(c, degree);
        for (int r = 0; r <= degree; ++r) points(x, r) = e[static_cast<std::size_t>(r)] + disp3[static_cast<std::size_t>(r)][x];
    }
    return BezierCurve<double, 3>(std::move(points));
}

// ------------------------------------------------------------------------ direct manipulation

DirectManipulation directManipulation(const Lattice& lattice, const Eigen::Matrix<double, 3, Eigen::Dynamic>& points,
                                      const Eigen::Matrix<double, 3, Eigen::Dynamic>& targets, double strength)
{
    if (points.cols() != targets.cols())
        throw Error("directManipulation: " + std::to_string(points.cols()) + " points but " +
                    std::to_string(targets.cols()) + " targets");
    if (points.cols() == 0) throw Error("directManipulation: no points given");
    requireFinite(points, "directManipulation: points");
    requireFinite(targets, "directManipulation: targets");
    if (!std::isfinite(strength) || strength == 0)
        throw Error("directManipulation: strength must be finite and non-zero");
    const Eigen::Index k = points.cols(), n = lattice.pointCount();
    Eigen::MatrixXd b = Eigen::MatrixXd::Zero(k, n);
    Eigen::MatrixXd rhs(k, 3);
    for (Eigen::Index p = 0; p < k; ++p) {
        const Eigen::Vector3d x = points.col(p);
        const auto jet = lattice.deform(x, strength);
        rhs.row(p) = (targets.col(p) - jet.point).transpose();
        Eigen::Vector3d stu = lattice.toLattice(x);
        const bool outside = !Lattice::insideBox(stu);
        if (outside && lattice.outside() == OutsidePolicy::Keep) continue;
        if (outside && lattice.outside() == OutsidePolicy::Clamp) stu = stu.cwiseMax(0.0).cwiseMin(1.0);
        b.row(p) = strength * lattice.basisWeights(stu).transpose();
    }
    const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(b);
    const Eigen::MatrixXd change = cod.solve(rhs); // N x 3, the minimal-norm least-squares solution
    Lattice moved = lattice;
    moved.setControlPoints(lattice.controlPoints() + change.transpose());
    double residual = 0;
    for (Eigen::Index p = 0; p < k; ++p)
        residual = std::max(residual, (moved.deform(points.col(p), strength).point - targets.col(p)).norm());
    return {std::move(moved), change.transpose(), residual, static_cast<int>(cod.rank())};
}

} // namespace freeform
