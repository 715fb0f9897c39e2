// Deformation of points and meshes, the det J certificate, exact composition of curves and patches
// with the lattice, and direct manipulation (volume/deform.h). The batched kernel is in
// ffd_binding.cpp.

#include "freeform/volume/deform.h"

#include <Eigen/QR>

#include <algorithm>
#include <cmath>

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

/// The tensor polynomial with all coefficients 1 (the constant 1) of the given degrees: multiplying
/// by it is exact degree elevation.
Tensor ones(std::array<int, 3> degree)
{
    Tensor t(degree);
    std::fill(t.c.begin(), t.c.end(), 1.0L);
    return t;
}

/// B_0..B_deg of degree `deg` composed with the polynomial x (a tensor polynomial over the curve's
/// or patch's domain): C(deg, i) x^i (1 - x)^(deg - i), each of `deg` times the degrees of x.
std::vector<Tensor> composedBasis(int deg, const Tensor& x)
{
    Tensor oneMinus = x;
    for (auto& c : oneMinus.c) c = 1.0L - c;
    std::vector<Tensor> powX{ones({0, 0, 0})}, powY{ones({0, 0, 0})};
    for (int e = 1; e <= deg; ++e) {
        powX.push_back(product(powX.back(), x));
        powY.push_back(product(powY.back(), oneMinus));
    }
    std::vector<Tensor> basis;
    for (int i = 0; i <= deg; ++i) {
        Tensor b = product(powX[static_cast<std::size_t>(i)], powY[static_cast<std::size_t>(deg - i)]);
        const long double c = lbinom(deg, i);
        for (auto& v : b.c) v *= c;
        basis.push_back(std::move(b));
    }
    return basis;
}

/// The geometry with Bernstein control points `points` (3 x count, world coordinates, tensor
/// index of degrees `domain`) pushed through the lattice polynomial: x + w sum B_ijk(s,t,u) d_ijk
/// as a tensor polynomial of degrees domain * (l+m+n), coordinates in x, y, z.
std::array<Tensor, 3> compose(const Lattice& lattice, const Eigen::Matrix<double, 3, Eigen::Dynamic>& points,
                              std::array<int, 3> domain, double strength)
{
    // The lattice coordinates of the geometry: an affine image, so of the same degrees.
    Tensor stu[3] = {Tensor(domain), Tensor(domain), Tensor(domain)};
    Tensor world[3] = {Tensor(domain), Tensor(domain), Tensor(domain)};
    for (Eigen::Index r = 0; r < points.cols(); ++r) {
        const Eigen::Vector3d x = points.col(r);
        const Eigen::Vector3d c = lattice.toLattice(x);
        for (int a = 0; a < 3; ++a) {
            stu[a].c[static_cast<std::size_t>(r)] = c[a];
            world[a].c[static_cast<std::size_t>(r)] = x[a];
        }
    }
    const int l = lattice.degree(0), m = lattice.degree(1), n = lattice.degree(2);
    const auto bs = composedBasis(l, stu[0]), bt = composedBasis(m, stu[1]), bu = composedBasis(n, stu[2]);

    // Displacement sum_i Bs_i (sum_j Bt_j (sum_k Bu_k w d_ijk)): the inner sum is a linear
    // combination (one degree), the outer two are Bernstein products.
    const auto& disp = lattice.displacements();
    std::array<Tensor, 3> total;
    for (int i = 0; i <= l; ++i) {
        Tensor perI[3];
        for (int j = 0; j <= m; ++j) {
            Tensor g[3] = {Tensor(bu[0].deg), Tensor(bu[0].deg), Tensor(bu[0].deg)};
            for (int k = 0; k <= n; ++k) {
                const Eigen::Vector3d d = strength * disp.col(lattice.index(i, j, k));
                for (int a = 0; a < 3; ++a)
                    if (d[a] != 0) addScaled(g[a], bu[static_cast<std::size_t>(k)], static_cast<long double>(d[a]));
            }
            for (int a = 0; a < 3; ++a) {
                Tensor t = product(bt[static_cast<std::size_t>(j)], g[a]);
                if (j == 0) perI[a] = std::move(t);
                else addScaled(perI[a], t, 1.0L);
            }
        }
        for (int a = 0; a < 3; ++a) {
            Tensor t = product(bs[static_cast<std::size_t>(i)], perI[a]);
            if (i == 0) total[static_cast<std::size_t>(a)] = std::move(t);
            else addScaled(total[static_cast<std::size_t>(a)], t, 1.0L);
        }
    }

    // Plus the geometry itself, elevated to the same degrees (a product with the constant 1).
    const int sum = l + m + n;
    const Tensor one = ones({domain[0] * (sum - 1), domain[1] * (sum - 1), domain[2] * (sum - 1)});
    for (int a = 0; a < 3; ++a) addScaled(total[static_cast<std::size_t>(a)], product(world[a], one), 1.0L);
    return total;
}

/// The coordinates of `t` as the columns of a 3 x count matrix (tensor index order).
Eigen::Matrix<double, 3, Eigen::Dynamic> columns(const std::array<Tensor, 3>& t)
{
    Eigen::Matrix<double, 3, Eigen::Dynamic> points(3, static_cast<Eigen::Index>(t[0].c.size()));
    for (int a = 0; a < 3; ++a)
        for (std::size_t r = 0; r < t[0].c.size(); ++r)
            points(a, static_cast<Eigen::Index>(r)) = static_cast<double>(t[static_cast<std::size_t>(a)].c[r]);
    return points;
}

} // namespace

BezierCurve<double, 3> deformCurve(const Lattice& lattice, const BezierCurve<double, 3>& curve, double strength)
{
    const int d = curve.degree();
    const int degree = d * (lattice.degree(0) + lattice.degree(1) + lattice.degree(2));
    if (degree > kMaxDegree)
        throw Error("deformCurve: the deformed curve would have degree " + std::to_string(degree) + " (d (l+m+n)), above " +
                    std::to_string(kMaxDegree));
    if (!std::isfinite(strength)) throw Error("deformCurve: strength is not finite");
    return BezierCurve<double, 3>(columns(compose(lattice, curve.controlPoints(), {d, 0, 0}, strength)));
}

BezierSurface<double, 3> deformSurface(const Lattice& lattice, const BezierSurface<double, 3>& surface, double strength)
{
    const int p = surface.degreeU(), q = surface.degreeV();
    const int sum = lattice.degree(0) + lattice.degree(1) + lattice.degree(2);
    const int degreeU = p * sum, degreeV = q * sum;
    if (degreeU > kMaxDegree || degreeV > kMaxDegree)
        throw Error("deformSurface: the deformed patch would have degrees (" + std::to_string(degreeU) + ", " +
                    std::to_string(degreeV) + ") ((p (l+m+n), q (l+m+n))), above " + std::to_string(kMaxDegree));
    if (!std::isfinite(strength)) throw Error("deformSurface: strength is not finite");
    // Tensor index (i, j, 0) = i*(q+1) + j: the patch's own column order.
    return BezierSurface<double, 3>(degreeU, degreeV, columns(compose(lattice, surface.controlPoints(), {p, q, 0}, strength)));
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
        const OutsideRule rule = outsideRule(lattice.toLattice(x), lattice.outside());
        if (!rule.moves()) continue;
        b.row(p) = strength * lattice.basisWeights(rule.at).transpose();
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

std::optional<AffineMap> affineMap(const Lattice& lattice, double strength)
{
    if (strength == 0 || lattice.isRest()) return AffineMap{};
    const auto& deg = lattice.degrees();
    const Lattice::Points& d = lattice.displacements();
    const Eigen::Vector3d d0 = d.col(lattice.index(0, 0, 0));
    Eigen::Matrix3d D;
    D.col(0) = d.col(lattice.index(deg[0], 0, 0)) - d0;
    D.col(1) = d.col(lattice.index(0, deg[1], 0)) - d0;
    D.col(2) = d.col(lattice.index(0, 0, deg[2])) - d0;
    const double scale = std::max(lattice.axes().colwise().norm().maxCoeff(), d.colwise().norm().maxCoeff());
    for (int i = 0; i <= deg[0]; ++i)
        for (int j = 0; j <= deg[1]; ++j)
            for (int k = 0; k <= deg[2]; ++k) {
                const Eigen::Vector3d stu(double(i) / deg[0], double(j) / deg[1], double(k) / deg[2]);
                if ((d.col(lattice.index(i, j, k)) - (d0 + D * stu)).norm() > 1e-12 * scale) return std::nullopt;
            }
    AffineMap map;
    map.linear = Eigen::Matrix3d::Identity() + strength * D * lattice.dual();
    map.offset = strength * (d0 - D * lattice.dual() * lattice.origin());
    return map;
}

double lipschitzBound(const Lattice& lattice, double strength)
{
    const auto& deg = lattice.degrees();
    const Lattice::Points& d = lattice.displacements();
    double sum = 0;
    for (int a = 0; a < 3; ++a) {
        double largest = 0;
        for (int i = 0; i <= deg[0]; ++i)
            for (int j = 0; j <= deg[1]; ++j)
                for (int k = 0; k <= deg[2]; ++k) {
                    const int next[3] = {i + (a == 0), j + (a == 1), k + (a == 2)};
                    if (next[0] > deg[0] || next[1] > deg[1] || next[2] > deg[2]) continue;
                    largest = std::max(largest, (d.col(lattice.index(next[0], next[1], next[2])) -
                                                 d.col(lattice.index(i, j, k))).norm());
                }
        sum += deg[static_cast<std::size_t>(a)] * largest * lattice.dual().row(a).norm();
    }
    return 1 + std::abs(strength) * sum;
}

} // namespace freeform
