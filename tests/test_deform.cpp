// Deformation: identity and affine lattices, normals and det J on a sphere against the deformed
// geometry, fold-overs and the det J certificate, direct manipulation against an independent
// least-norm solve, exact curve composition, float against double, 1 against 2 threads.

#include <catch2/catch.hpp>

#include <freeform/volume/deform.h>

#include <Eigen/LU>

#include <cmath>
#include <map>

#include "support/random.h"

namespace test_deform {

using freeform::DeformOptions;
using freeform::DeformReport;
using freeform::FfdBinding;
using freeform::FfdOutputs;
using freeform::Lattice;
using freeform::OutsidePolicy;
using Points = Lattice::Points;

namespace {

/// Icosphere: the icosahedron with every triangle split in four `levels` times, projected to the
/// sphere of radius r; normals are the exact sphere normals.
freeform::PolygonMesh icosphere(int levels, double r)
{
    const double g = (1 + std::sqrt(5.0)) / 2;
    std::vector<Eigen::Vector3d> v = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                                      {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                         {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                                         {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    for (auto& p : v) p.normalize();
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<int, int>, int> mid;
        auto midpoint = [&](int a, int b) {
            const auto key = std::minmax(a, b);
            const auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            v.push_back((v[static_cast<std::size_t>(a)] + v[static_cast<std::size_t>(b)]).normalized());
            return mid[key] = static_cast<int>(v.size()) - 1;
        };
        std::vector<std::array<int, 3>> next;
        for (const auto& t : f) {
            const int ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
            next.push_back({t[0], ab, ca});
            next.push_back({t[1], bc, ab});
            next.push_back({t[2], ca, bc});
            next.push_back({ab, bc, ca});
        }
        f = std::move(next);
    }
    freeform::PolygonMesh mesh;
    mesh.positions.resize(3, static_cast<Eigen::Index>(v.size()));
    mesh.normals.resize(3, static_cast<Eigen::Index>(v.size()));
    for (std::size_t i = 0; i < v.size(); ++i) {
        mesh.positions.col(static_cast<Eigen::Index>(i)) = r * v[i];
        mesh.normals.col(static_cast<Eigen::Index>(i)) = v[i];
    }
    for (const auto& t : f) mesh.addFace({t[0], t[1], t[2]});
    return mesh;
}

/// A cubic lattice on [-1,1]^3 with every control point moved by a seeded random offset.
Lattice smoothLattice(double amplitude, std::uint32_t seed, std::array<int, 3> degree = {3, 3, 3})
{
    Lattice lat = Lattice::identity(degree, Eigen::Vector3d(-1, -1, -1), 2 * Eigen::Matrix3d::Identity());
    lat.setControlPoints(lat.controlPoints() +
                         freeform::test::randomPoints<double, 3>(lat.pointCount(), seed, -amplitude, amplitude));
    return lat;
}

Points randomInBox(int count, std::uint32_t seed, double lo = -1, double hi = 1)
{
    return freeform::test::randomPoints<double, 3>(count, seed, lo, hi);
}

double angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
    return std::atan2(a.cross(b).norm(), a.dot(b));
}

} // namespace

TEST_CASE("the rest lattice returns every point and normal bit for bit", "[unit]")
{
    const freeform::PolygonMesh sphere = icosphere(3, 0.9);
    for (const auto& d : {std::array<int, 3>{1, 1, 1}, {2, 3, 1}, {3, 3, 3}, {4, 2, 5}}) {
        Eigen::Matrix3d sheared;
        sheared << 2.5, 0.3, 0.0, 0.2, 2.5, -0.4, 0.1, 0.0, 2.2;
        for (const Lattice& lat : {Lattice::identity(d, Eigen::Vector3d(-1, -1, -1), 2 * Eigen::Matrix3d::Identity()),
                                   Lattice::identity(d, Eigen::Vector3d(-1.2, -1.3, -1.1), sheared)}) {
            CAPTURE(d[0], d[1], d[2]);
            freeform::PolygonMesh mesh = sphere;
            const DeformReport report = freeform::deformMesh(lat, mesh);
            CHECK(mesh.positions == sphere.positions);
            CHECK((mesh.normals - sphere.normals).cwiseAbs().maxCoeff() < 1e-15); // renormalised unit vectors
            CHECK(report.vertices == static_cast<std::size_t>(sphere.vertexCount()));
            CHECK(report.foldCount == 0);
            CHECK(report.minDetJ == 1.0);
            CHECK(report.maxDetJ == 1.0);
            CHECK(report.outside == 0);
        }
    }
}

TEST_CASE("the rest lattice keeps the sign of zero coordinates", "[unit]")
{
    // p + 0 is +0 for p = -0: the deformation must not add a zero displacement.
    Points p(3, 2);
    p << -0.0, 0.5, 0.25, -0.0, -0.0, 0.0;
    const Lattice lat = Lattice::identity({3, 3, 3}, Eigen::Vector3d(-1, -1, -1), 2 * Eigen::Matrix3d::Identity());
    Points q = p;
    freeform::deformPoints(lat, q);
    CHECK(std::signbit(q(0, 0)));
    CHECK(std::signbit(q(1, 1)));
    CHECK(std::signbit(q(2, 0)));
    CHECK(!std::signbit(q(2, 1)));
    CHECK(std::signbit(lat.deform(p.col(0)).point[0]));
    freeform::DeformOptions options;
    options.threads = 1;
    const Eigen::Matrix<float, 3, Eigen::Dynamic> pf = p.cast<float>();
    Eigen::Matrix<float, 3, Eigen::Dynamic> of(3, 2);
    FfdBinding<float>(lat, pf.data(), 2).deform(lat, {of.data(), nullptr, nullptr, nullptr, nullptr}, options);
    CHECK(std::signbit(of(0, 0)));
    CHECK(std::signbit(of(1, 1)));
}

TEST_CASE("an affine lattice maps every point to A x + b and normals to normalise(A^-T n)", "[unit]")
{
    Eigen::Matrix3d a;
    a << 1.2, 0.3, -0.2, 0.1, 0.8, 0.4, -0.3, 0.2, 1.1;
    const Eigen::Vector3d b(0.25, -0.5, 1.0);
    for (const auto& d : {std::array<int, 3>{1, 1, 1}, {3, 3, 3}, {2, 4, 3}}) {
        for (OutsidePolicy policy : {OutsidePolicy::Clamp, OutsidePolicy::Extrapolate}) {
            CAPTURE(d[0], d[1], d[2], freeform::toString(policy));
            Lattice lat = Lattice::identity(d, Eigen::Vector3d(-1, -1, -1), 2 * Eigen::Matrix3d::Identity(), policy);
            lat.setControlPoints((a * lat.controlPoints()).colwise() + b);
            // Clamp: points inside; extrapolate: linear precision holds everywhere.
            const Points p = policy == OutsidePolicy::Clamp ? randomInBox(200, 3) : randomInBox(200, 3, -2, 2);
            const Points n = randomInBox(200, 4);
            const FfdBinding<double> binding(lat, p);
            Points out(3, p.cols()), nout(3, p.cols());
            Eigen::Matrix<double, 9, Eigen::Dynamic> jac(9, p.cols());
            Eigen::VectorXd det(p.cols());
            FfdOutputs<double> o;
            o.positions = out.data();
            o.normalsIn = n.data();
            o.normalsOut = nout.data();
            o.jacobians = jac.data();
            o.determinants = det.data();
            binding.deform(lat, o);
            const Eigen::Matrix3d inverseTranspose = a.inverse().transpose();
            for (int i = 0; i < p.cols(); ++i) {
                const Eigen::Vector3d expected = a * p.col(i) + b;
                CHECK((out.col(i) - expected).norm() < 1e-13);
                CHECK((nout.col(i) - (inverseTranspose * n.col(i)).normalized()).norm() < 1e-13);
                CHECK((Eigen::Map<const Eigen::Matrix3d>(jac.col(i).data()) - a).norm() < 1e-13);
                CHECK(std::abs(det[i] - a.determinant()) < 1e-13);
            }
        }
    }
}

TEST_CASE("sphere: Jacobian normals match recomputed normals, det J matches the volume change", "[unit]")
{
    const Lattice lat = smoothLattice(0.12, 99);
    // The discretisation error of area-weighted vertex normals shrinks like h^2 on average and like
    // h at the worst (irregular) vertices: compare two resolutions (h halves from level 4 to 5).
    double worst[2] = {0, 0}, mean[2] = {0, 0};
    for (int level : {4, 5}) {
        freeform::PolygonMesh jacobianMesh = icosphere(level, 0.8);
        freeform::PolygonMesh recomputed = jacobianMesh;
        const auto r1 = freeform::deformMesh(lat, jacobianMesh, {}, freeform::NormalMode::Jacobian);
        const auto r2 = freeform::deformMesh(lat, recomputed, {}, freeform::NormalMode::Recompute);
        CHECK(jacobianMesh.positions == recomputed.positions);
        CHECK(r1.minDetJ == r2.minDetJ);
        double w = 0, sum = 0;
        for (int i = 0; i < jacobianMesh.vertexCount(); ++i) {
            const double e = angle(jacobianMesh.normals.col(i), recomputed.normals.col(i));
            w = std::max(w, e);
            sum += e;
        }
        worst[level - 4] = w;
        mean[level - 4] = sum / jacobianMesh.vertexCount();
    }
    INFO("max angle " << worst[0] << " -> " << worst[1] << ", mean " << mean[0] << " -> " << mean[1]);
    CHECK(worst[1] < 5e-3);
    CHECK(mean[1] < 1e-3);
    CHECK(worst[1] < worst[0] / 1.7); // first order at the worst vertex
    CHECK(mean[1] < mean[0] / 3);     // second order on average

    // det J against central differences of the deformed positions (computed by the same binding).
    const Points p = randomInBox(50, 7, -0.9, 0.9);
    const double h = 1e-5;
    Points probes(3, 7 * p.cols());
    for (int i = 0; i < p.cols(); ++i) {
        probes.col(7 * i) = p.col(i);
        for (int a = 0; a < 3; ++a) {
            probes.col(7 * i + 1 + 2 * a) = p.col(i) + h * Eigen::Vector3d::Unit(a);
            probes.col(7 * i + 2 + 2 * a) = p.col(i) - h * Eigen::Vector3d::Unit(a);
        }
    }
    const FfdBinding<double> binding(lat, probes);
    Points out(3, probes.cols());
    Eigen::VectorXd det(probes.cols());
    FfdOutputs<double> o;
    o.positions = out.data();
    o.determinants = det.data();
    binding.deform(lat, o);
    for (int i = 0; i < p.cols(); ++i) {
        Eigen::Matrix3d fd;
        for (int a = 0; a < 3; ++a) fd.col(a) = (out.col(7 * i + 1 + 2 * a) - out.col(7 * i + 2 + 2 * a)) / (2 * h);
        CHECK(std::abs(det[7 * i] - fd.determinant()) < 1e-8);
        // And against the reference evaluation of volume/lattice.h.
        CHECK(std::abs(det[7 * i] - lat.deform(p.col(i)).jacobian.determinant()) < 1e-13);
        CHECK((out.col(7 * i) - lat.deform(p.col(i)).point).norm() < 1e-14);
    }
}

TEST_CASE("a crossed lattice reports fold-overs, a gentle one none; the certificate agrees", "[unit]")
{
    const Points grid = randomInBox(4000, 13, -0.999, 0.999);
    SECTION("identity")
    {
        const Lattice lat = Lattice::identity({3, 2, 2}, Eigen::Vector3d(-1, -1, -1), 2 * Eigen::Matrix3d::Identity());
        const auto poly = freeform::jacobianPolynomial(lat);
        CHECK(poly.degree == std::array<int, 3>{8, 5, 5});
        for (double c : poly.coefficients) CHECK(c == Approx(1.0).margin(1e-15));
        CHECK(freeform::certify(lat).verdict == freeform::Verdict::CertifiedInjective);
    }
    SECTION("gentle")
    {
        const Lattice lat = smoothLattice(0.05, 5);
        Points p = grid;
        const DeformReport r = freeform::deformPoints(lat, p);
        CHECK(r.foldCount == 0);
        CHECK(r.minDetJ > 0.5);
        const auto cert = freeform::certify(lat);
        CHECK(cert.verdict == freeform::Verdict::CertifiedInjective);
        CHECK(cert.minCoefficient > 0);
        CHECK(cert.minCoefficient <= r.minDetJ); // the coefficients bound det J from below
        CHECK(cert.maxCoefficient >= r.maxDetJ);
    }
    SECTION("crossed")
    {
        Lattice lat = Lattice::identity({2, 2, 2}, Eigen::Vector3d(-1, -1, -1), 2 * Eigen::Matrix3d::Identity());
        // Push the middle layer in s far beyond the last one: the map folds over in s.
        for (int j = 0; j <= 2; ++j)
            for (int k = 0; k <= 2; ++k) lat.setControlPoint(1, j, k, lat.controlPoint(1, j, k) + Eigen::Vector3d(3, 0, 0));
        Points p = grid;
        const DeformReport r = freeform::deformPoints(lat, p);
        CHECK(r.foldCount > 0);
        CHECK(r.folds.size() == r.foldCount);
        CHECK(r.minDetJ <= 0);
        for (int v : r.folds) CHECK(lat.deform(grid.col(v)).jacobian.determinant() <= 1e-12);
        CHECK(std::is_sorted(r.folds.begin(), r.folds.end()));
        const auto cert = freeform::certify(lat);
        CHECK(cert.verdict == freeform::Verdict::Folds);
        // The witness is a place where det J <= 0 indeed.
        const auto jet = lat.map(cert.witness);
        CHECK(jet.jacobian().determinant() / lat.axes().determinant() <= 1e-12);
    }
}

TEST_CASE("the det J polynomial's Bernstein coefficients evaluate to det J", "[unit]")
{
    Eigen::Matrix3d axes;
    axes << 2.0, 0.4, 0.0, -0.3, 1.5, 0.2, 0.1, 0.0, 1.8;
    for (const auto& d : {std::array<int, 3>{1, 1, 1}, {2, 1, 3}, {3, 3, 3}}) {
        Lattice lat = Lattice::identity(d, Eigen::Vector3d(0.5, -1, 0), axes);
        lat.setControlPoints(lat.controlPoints() + freeform::test::randomPoints<double, 3>(lat.pointCount(), 8, -0.3, 0.3));
        const double w = 0.7;
        const auto poly = freeform::jacobianPolynomial(lat, w);
        CHECK(poly.degree == std::array<int, 3>{3 * d[0] - 1, 3 * d[1] - 1, 3 * d[2] - 1});
        const Points stu = freeform::test::randomPoints<double, 3>(20, 4, 0, 1);
        for (int q = 0; q < stu.cols(); ++q) {
            // Independent: the Bernstein sum in long double.
            long double value = 0;
            const int a = poly.degree[0], b = poly.degree[1], c = poly.degree[2];
            auto bern = [](int n, int i, long double t) {
                long double r = 1;
                for (int k = 1; k <= i; ++k) r = r * (n - i + k) / k;
                return r * std::pow(t, (long double)i) * std::pow(1 - t, (long double)(n - i));
            };
            for (int i = 0; i <= a; ++i)
                for (int j = 0; j <= b; ++j)
                    for (int k = 0; k <= c; ++k)
                        value += poly.coefficients[static_cast<std::size_t>((i * (b + 1) + j) * (c + 1) + k)] *
                                 bern(a, i, stu(0, q)) * bern(b, j, stu(1, q)) * bern(c, k, stu(2, q));
            const Eigen::Vector3d x = lat.toWorld(stu.col(q));
            const double reference = lat.deform(x, w).jacobian.determinant();
            CHECK(std::abs(double(value) - reference) < 1e-12);
        }
    }
}

TEST_CASE("direct manipulation hits the targets with the minimal-norm change", "[unit]")
{
    const Lattice lat = smoothLattice(0.05, 21);
    const Points p = randomInBox(6, 31, -0.8, 0.8);
    const Points targets = p + randomInBox(6, 32, -0.1, 0.1);
    const auto dm = freeform::directManipulation(lat, p, targets);
    CHECK(dm.residual < 1e-9);
    CHECK(dm.rank == 6);
    for (int i = 0; i < p.cols(); ++i) CHECK((dm.lattice.deform(p.col(i)).point - targets.col(i)).norm() < 1e-9);

    // Independent least-norm solve: dP = B^T (B B^T)^-1 r in long double, B from the closed-form
    // Bernstein polynomials.
    using MatrixL = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
    MatrixL b(p.cols(), lat.pointCount()), r(p.cols(), 3);
    for (int q = 0; q < p.cols(); ++q) {
        const Eigen::Vector3d stu = lat.toLattice(p.col(q));
        for (int i = 0; i <= 3; ++i)
            for (int j = 0; j <= 3; ++j)
                for (int k = 0; k <= 3; ++k) {
                    auto cubic = [](int idx, long double t) {
                        const long double c[4] = {1, 3, 3, 1};
                        return c[idx] * std::pow(t, (long double)idx) * std::pow(1 - t, (long double)(3 - idx));
                    };
                    b(q, lat.index(i, j, k)) = cubic(i, stu[0]) * cubic(j, stu[1]) * cubic(k, stu[2]);
                }
        r.row(q) = (targets.col(q) - lat.deform(p.col(q)).point).cast<long double>().transpose();
    }
    const MatrixL gram = b * b.transpose();
    const MatrixL reference = b.transpose() * gram.partialPivLu().solve(r);
    CHECK((dm.change.transpose().cast<long double>() - reference).cwiseAbs().maxCoeff() < 1e-10);

    // Over-determined and inconsistent (two different targets for one point): least squares, and
    // still the minimal-norm solution (its change lies in the row space of B).
    Points p2(3, 2), t2(3, 2);
    p2 << 0.1, 0.1, 0.2, 0.2, 0.3, 0.3;
    t2 << 0.2, 0.4, 0.2, 0.2, 0.3, 0.3;
    const auto ls = freeform::directManipulation(lat, p2, t2);
    CHECK(ls.rank == 1);
    const Eigen::Vector3d mid = 0.5 * (t2.col(0) + t2.col(1));
    CHECK((ls.lattice.deform(p2.col(0)).point - mid).norm() < 1e-12);
    CHECK(ls.residual == Approx(0.1).epsilon(1e-9));
    CHECK_THROWS_AS(freeform::directManipulation(lat, p2, Points(3, 1)), freeform::Error);
}

TEST_CASE("exact curve composition equals point-wise deformation", "[unit]")
{
    for (const auto& d : {std::array<int, 3>{1, 1, 1}, {2, 1, 3}, {3, 3, 3}}) {
        const Lattice lat = smoothLattice(0.1, 3, d);
        for (int cd : {1, 2, 3}) {
            CAPTURE(d[0], d[1], d[2], cd);
            const freeform::BezierCurve<double, 3> curve(randomInBox(cd + 1, static_cast<std::uint32_t>(cd), -0.9, 0.9));
            const auto deformed = freeform::deformCurve(lat, curve, 0.8);
            CHECK(deformed.degree() == cd * (d[0] + d[1] + d[2]));
            for (int i = 0; i <= 40; ++i) {
                const double t = i / 40.0;
                CHECK((deformed.evaluate(t) - lat.deform(curve.evaluate(t), 0.8).point).norm() < 1e-13);
            }
        }
    }
    // Through the identity lattice the curve is unchanged (degree elevated).
    const Lattice id = Lattice::identity({2, 2, 2}, Eigen::Vector3d(-1, -1, -1), 2 * Eigen::Matrix3d::Identity());
    const freeform::BezierCurve<double, 3> c({{0, 0, 0}, {0.5, 0.2, -0.1}, {0.3, -0.4, 0.6}});
    const auto same = freeform::deformCurve(id, c);
    for (int i = 0; i <= 10; ++i) CHECK((same.evaluate(i / 10.0) - c.evaluate(i / 10.0)).norm() < 1e-15);
}

TEST_CASE("the float path agrees with the double path within float tolerance", "[unit]")
{
    const Lattice lat = smoothLattice(0.1, 41);
    const freeform::PolygonMesh sphere = icosphere(4, 0.9);
    const Eigen::Index v = sphere.positions.cols();
    const Eigen::Matrix<float, 3, Eigen::Dynamic> pf = sphere.positions.cast<float>();
    const Eigen::Matrix<float, 3, Eigen::Dynamic> nf = sphere.normals.cast<float>();
    const FfdBinding<float> bf(lat, pf.data(), static_cast<std::size_t>(v));
    const FfdBinding<double> bd(lat, sphere.positions);
    Eigen::Matrix<float, 3, Eigen::Dynamic> of(3, v), nof(3, v);
    Points od(3, v), nod(3, v);
    Eigen::VectorXf detf(v);
    Eigen::VectorXd detd(v);
    bf.deform(lat, {of.data(), nf.data(), nof.data(), nullptr, detf.data()});
    bd.deform(lat, {od.data(), sphere.normals.data(), nod.data(), nullptr, detd.data()});
    const double positionError = (of.cast<double>() - od).cwiseAbs().maxCoeff();
    const double normalError = (nof.cast<double>() - nod).cwiseAbs().maxCoeff();
    const double detError = (detf.cast<double>() - detd).cwiseAbs().maxCoeff();
    INFO(positionError << " " << normalError << " " << detError);
    CHECK(positionError < 2e-6);  // ~ 16 float ulps of coordinates of size 1
    CHECK(normalError < 2e-6);
    CHECK(detError < 4e-6);
    CHECK(positionError > 0);     // it really ran in float
}

TEST_CASE("1 and 2 threads give identical results", "[unit]")
{
    const Lattice clamp = smoothLattice(0.2, 51);
    const Points p = randomInBox(100003, 61, -1.2, 1.2); // some outside, a partial last block
    const Points n = randomInBox(100003, 62);
    for (OutsidePolicy policy : {OutsidePolicy::Keep, OutsidePolicy::Clamp, OutsidePolicy::Extrapolate}) {
        Lattice lat = clamp;
        lat.setOutside(policy);
        const FfdBinding<double> binding(lat, p);
        CHECK(!binding.outsideVertices().empty());
        Points out[2] = {Points(3, p.cols()), Points(3, p.cols())}, nout[2] = {Points(3, p.cols()), Points(3, p.cols())};
        DeformReport report[2];
        for (int t = 0; t < 2; ++t) {
            DeformOptions options;
            options.threads = t + 1;
            binding.deform(lat, {out[t].data(), n.data(), nout[t].data(), nullptr, nullptr}, options, &report[t]);
        }
        CHECK(out[0] == out[1]);
        CHECK(nout[0] == nout[1]);
        CHECK(report[0].folds == report[1].folds);
        CHECK(report[0].minDetJ == report[1].minDetJ);
        CHECK(report[0].outside == binding.outsideVertices().size());
        // Against the reference evaluation, every policy, inside and outside.
        double worst = 0, worstJ = 0;
        for (int i = 0; i < p.cols(); i += 97) {
            const auto ref = lat.deform(p.col(i));
            worst = std::max(worst, (out[0].col(i) - ref.point).norm());
            worstJ = std::max(worstJ, (nout[0].col(i) - freeform::transformNormal(ref.jacobian, n.col(i))).norm());
        }
        CHECK(worst < 1e-14);
        CHECK(worstJ < 1e-12);
        if (policy == OutsidePolicy::Keep)
            for (int v : binding.outsideVertices()) CHECK(out[0].col(v) == p.col(v));
    }
}

TEST_CASE("normals through cof(J) flip where the map mirrors; area-weighted normals", "[unit]")
{
    const Eigen::Matrix3d mirror = Eigen::Vector3d(-1, 1, 1).asDiagonal();
    // cof(J) n = det(J) J^-T n: the mirror keeps (1,0,0) (the surface's front turns with it).
    CHECK(freeform::transformNormal(mirror, Eigen::Vector3d(1, 0, 0)) == Eigen::Vector3d(1, 0, 0));
    CHECK(freeform::transformNormal(mirror, Eigen::Vector3d(0, 1, 0)) == Eigen::Vector3d(0, -1, 0));
    CHECK(freeform::transformNormal(Eigen::Matrix3d::Zero(), Eigen::Vector3d(0, 1, 0)) == Eigen::Vector3d::Zero());
    Eigen::Matrix3d shear = Eigen::Matrix3d::Identity();
    shear(0, 1) = 1; // x += y
    // The plane x = c becomes x - y = c; the plane y = c stays.
    CHECK((freeform::transformNormal(shear, Eigen::Vector3d(1, 0, 0)) - Eigen::Vector3d(1, -1, 0) / std::sqrt(2.0)).norm() < 1e-15);
    CHECK(freeform::transformNormal(shear, Eigen::Vector3d(0, 1, 0)) == Eigen::Vector3d(0, 1, 0));
    CHECK((freeform::transformTangent(shear, Eigen::Vector3d(0, 1, 0)) - Eigen::Vector3d(1, 1, 0) / std::sqrt(2.0)).norm() < 1e-15);

    // A unit square (quad) and a triangle standing on its edge: hand-computed vertex normals.
    freeform::PolygonMesh m;
    m.positions.resize(3, 5);
    m.positions << 0, 1, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 0, 2;
    m.addFace({0, 1, 2, 3}); // area 1, normal +z
    m.addFace({1, 0, 4});    // area 1 (base 1, height 2), normal -y... (0,0,0),(1,0,0)... see below
    const auto n = freeform::areaWeightedNormals(m);
    // Face 2: (1,0,0),(0,0,0),(0,0,2): (a-b) = (-1,0,0), (c-b)... vector area = 0.5 (b-a) x (c-a).
    const Eigen::Vector3d f2 = 0.5 * (Eigen::Vector3d(-1, 0, 0).cross(Eigen::Vector3d(-1, 0, 2)));
    CHECK((n.col(0) - (Eigen::Vector3d(0, 0, 1) + f2).normalized()).norm() < 1e-15);
    CHECK((n.col(2) - Eigen::Vector3d(0, 0, 1)).norm() < 1e-15);
    CHECK((n.col(4) - f2.normalized()).norm() < 1e-15);
}

} // namespace test_deform
