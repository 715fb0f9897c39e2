// BezierSurface: identities (corners, boundary curves, de Casteljau against the basis sum and a
// long double reference), partials against finite differences, split/elevate/transpose keep the
// surface, normals with their limits at collapsed edges, curvature in closed form, bounding box
// and closest point against brute force.

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "freeform/surface/bezier_surface.h"
#include "freeform/surface/rational_bezier_surface.h"
#include "support/random.h"

namespace test_bezier_surface {

using freeform::BezierSurface;
using S3 = BezierSurface<double, 3>;
using V3 = Eigen::Vector3d;

namespace {

S3 randomSurface(int m, int n, std::uint32_t seed)
{
    return S3(m, n, freeform::test::randomPoints<double, 3>((m + 1) * (n + 1), seed));
}

/// Independent reference: the double sum with C(n,i) t^i (1-t)^(n-i) in long double.
Eigen::Matrix<long double, 3, 1> referenceValue(const S3& s, long double u, long double v)
{
    auto basis = [](int n, int i, long double t) {
        long double c = 1;
        for (int k = 1; k <= i; ++k) c = c * (n - i + k) / k;
        return c * std::pow(t, i) * std::pow(1 - t, n - i);
    };
    Eigen::Matrix<long double, 3, 1> p = Eigen::Matrix<long double, 3, 1>::Zero();
    for (int i = 0; i <= s.degreeU(); ++i)
        for (int j = 0; j <= s.degreeV(); ++j)
            p += basis(s.degreeU(), i, u) * basis(s.degreeV(), j, v) * s.controlPoint(i, j).cast<long double>();
    return p;
}

/// The hyperbolic paraboloid f(u, v) = (u, v, uv) as a bilinear patch elevated to (3, 2).
S3 saddle()
{
    Eigen::Matrix<double, 3, Eigen::Dynamic> p(3, 4);
    p.col(0) = V3(0, 0, 0);
    p.col(1) = V3(0, 1, 0);
    p.col(2) = V3(1, 0, 0);
    p.col(3) = V3(1, 1, 1);
    return S3(1, 1, p).elevatedU(2).elevatedV(1);
}

} // namespace

TEST_CASE("construction checks the point count, the degrees and finiteness", "[surface]")
{
    CHECK_THROWS_WITH(S3(2, 2, Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, 8)),
                      Catch::Contains("needs 9 control points, found 8"));
    CHECK_THROWS_WITH(S3(-1, 2, Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, 0)), Catch::Contains("degree in u"));
    Eigen::Matrix<double, 3, Eigen::Dynamic> p = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, 4);
    p(1, 2) = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_WITH(S3(1, 1, p), Catch::Contains("point 2 coordinate 1 is not finite"));
}

TEST_CASE("corners interpolate and boundary curves are the edge Bézier curves", "[surface]")
{
    for (std::uint32_t seed = 1; seed <= 5; ++seed) {
        const int m = 1 + static_cast<int>(seed % 4), n = 1 + static_cast<int>((seed * 7) % 5);
        const S3 s = randomSurface(m, n, seed);
        CAPTURE(seed, m, n);
        CHECK(s.evaluate(0, 0) == s.controlPoint(0, 0));
        CHECK(s.evaluate(1, 0) == s.controlPoint(m, 0));
        CHECK(s.evaluate(0, 1) == s.controlPoint(0, n));
        CHECK(s.evaluate(1, 1) == s.controlPoint(m, n));
        // Rows 0 and m, columns 0 and n as curves.
        Eigen::Matrix<double, 3, Eigen::Dynamic> row0(3, n + 1), colN(3, m + 1);
        for (int j = 0; j <= n; ++j) row0.col(j) = s.controlPoint(0, j);
        for (int i = 0; i <= m; ++i) colN.col(i) = s.controlPoint(i, n);
        const freeform::BezierCurve<double, 3> c0(row0), c1(colN);
        CHECK(s.curveAtU(0).controlPoints() == row0);
        CHECK(s.curveAtV(1).controlPoints() == colN);
        for (double t : {0.0, 0.13, 0.5, 0.77, 1.0}) {
            CHECK((s.evaluate(0, t) - c0.evaluate(t)).norm() < 1e-15);
            CHECK((s.evaluate(t, 1) - c1.evaluate(t)).norm() < 1e-15);
        }
    }
}

TEST_CASE("nested de Casteljau equals the basis sum and a long double reference", "[surface]")
{
    for (std::uint32_t seed = 10; seed < 20; ++seed) {
        const int m = 1 + static_cast<int>(seed % 7), n = 1 + static_cast<int>((seed * 3) % 6);
        const S3 s = randomSurface(m, n, seed);
        CAPTURE(seed, m, n);
        for (double u : {0.0, 0.1, 0.3333, 0.5, 0.9, 1.0}) {
            for (double v : {0.0, 0.25, 0.61, 1.0}) {
                const V3 a = s.evaluate(u, v), b = s.bernsteinSum(u, v);
                const V3 ref = referenceValue(s, u, v).cast<double>();
                CHECK((a - b).norm() < 1e-14);
                CHECK((a - ref).norm() < 1e-14);
            }
        }
    }
}

TEST_CASE("partials and the jet agree with central finite differences", "[surface]")
{
    const S3 s = randomSurface(3, 4, 42);
    // Finite differences of the long double instance (independent evaluation, small rounding).
    const BezierSurface<long double, 3> sl(3, 4, s.controlPoints().cast<long double>());
    const long double h = 1e-4L;
    for (double u : {0.2, 0.5, 0.83}) {
        for (double v : {0.1, 0.47, 0.9}) {
            auto f = [&](long double a, long double b) { return sl.evaluate(a, b); };
            const Eigen::Matrix<long double, 3, 1> fu = (f(u + h, v) - f(u - h, v)) / (2 * h);
            const Eigen::Matrix<long double, 3, 1> fv = (f(u, v + h) - f(u, v - h)) / (2 * h);
            const Eigen::Matrix<long double, 3, 1> fuu = (f(u + h, v) - 2.0L * f(u, v) + f(u - h, v)) / (h * h);
            const Eigen::Matrix<long double, 3, 1> fvv = (f(u, v + h) - 2.0L * f(u, v) + f(u, v - h)) / (h * h);
            const Eigen::Matrix<long double, 3, 1> fuv = (f(u + h, v + h) - f(u + h, v - h) - f(u - h, v + h) + f(u - h, v - h)) / (4 * h * h);
            const auto jet = s.jet(u, v, 3);
            CHECK((jet.col(S3::jetIndex(1, 0)) - fu.cast<double>()).norm() < 1e-6);
            CHECK((jet.col(S3::jetIndex(0, 1)) - fv.cast<double>()).norm() < 1e-6);
            CHECK((jet.col(S3::jetIndex(2, 0)) - fuu.cast<double>()).norm() < 1e-4);
            CHECK((jet.col(S3::jetIndex(1, 1)) - fuv.cast<double>()).norm() < 1e-4);
            CHECK((jet.col(S3::jetIndex(0, 2)) - fvv.cast<double>()).norm() < 1e-4);
            // The jet against partial() (difference nets): every order up to 3.
            for (int a = 0; a <= 3; ++a)
                for (int b = 0; a + b <= 3; ++b)
                    CHECK((jet.col(S3::jetIndex(a, b)) - s.partial(a, b, u, v)).norm() < 1e-11);
        }
    }
    CHECK(s.partial(4, 0, 0.3, 0.3) == V3::Zero());
    CHECK(s.jet(0.3, 0.3, 5).col(S3::jetIndex(4, 1)) == V3::Zero());
}

TEST_CASE("split, sub-patch, elevation and transposition keep the surface", "[surface]")
{
    const S3 s = randomSurface(3, 2, 7);
    const auto [lu, ru] = s.splitU(0.3);
    const auto [lv, rv] = s.splitV(0.65);
    const S3 e = s.elevatedU(2).elevatedV(3);
    const S3 sub = s.subPatch(0.2, 0.7, 0.1, 0.4);
    const S3 t = s.transposed();
    CHECK(e.degreeU() == 5);
    CHECK(e.degreeV() == 5);
    for (double a : {0.0, 0.21, 0.5, 0.93, 1.0}) {
        for (double b : {0.0, 0.37, 1.0}) {
            CHECK((lu.evaluate(a, b) - s.evaluate(0.3 * a, b)).norm() < 1e-14);
            CHECK((ru.evaluate(a, b) - s.evaluate(0.3 + 0.7 * a, b)).norm() < 1e-14);
            CHECK((lv.evaluate(a, b) - s.evaluate(a, 0.65 * b)).norm() < 1e-14);
            CHECK((rv.evaluate(a, b) - s.evaluate(a, 0.65 + 0.35 * b)).norm() < 1e-14);
            CHECK((e.evaluate(a, b) - s.evaluate(a, b)).norm() < 1e-14);
            CHECK((sub.evaluate(a, b) - s.evaluate(0.2 + 0.5 * a, 0.1 + 0.3 * b)).norm() < 1e-14);
            CHECK((t.evaluate(b, a) - s.evaluate(a, b)).norm() < 1e-15);
        }
    }
    CHECK_THROWS_WITH(s.elevatedU(-1), Catch::Contains("negative"));
    CHECK_THROWS(s.elevatedV(70));
}

TEST_CASE("affine transformation acts on the control points exactly", "[surface]")
{
    const S3 s = randomSurface(2, 3, 9);
    Eigen::Matrix3d a;
    a << 0, -2, 0, 1, 0, 0, 0, 0, 3;
    const V3 b(1, 2, 3);
    const S3 t = s.transformed(a, b);
    for (double u : {0.0, 0.4, 1.0})
        for (double v : {0.2, 0.9}) CHECK((t.evaluate(u, v) - (a * s.evaluate(u, v) + b)).norm() < 1e-14);
}

TEST_CASE("normal and curvature of the saddle z = uv in closed form", "[surface]")
{
    const S3 s = saddle();
    for (double u : {0.0, 0.3, 0.8, 1.0}) {
        for (double v : {0.0, 0.45, 1.0}) {
            CAPTURE(u, v);
            CHECK((s.evaluate(u, v) - V3(u, v, u * v)).norm() < 1e-15);
            const double w = std::sqrt(1 + u * u + v * v);
            const V3 expected = V3(-v, -u, 1) / w;
            CHECK((s.normal(u, v) - expected).norm() < 1e-14);
            const auto k = s.curvature(u, v);
            REQUIRE(k.regular);
            CHECK(k.gaussian == Approx(-1 / std::pow(w, 4)).epsilon(1e-12));
            CHECK(k.mean == Approx(-u * v / std::pow(w, 3)).margin(1e-14).epsilon(1e-12));
            CHECK(k.k1 * k.k2 == Approx(k.gaussian).epsilon(1e-10));
            CHECK(std::abs(k.direction1.dot(k.direction2)) < 1e-9); // principal directions orthogonal
            CHECK(std::abs(k.direction1.dot(s.normal(u, v))) < 1e-12);
        }
    }
}

TEST_CASE("the normal at a collapsed edge is the limit of the normals beside it", "[surface][normal]")
{
    // A cone-like patch: row u = 0 collapses to the apex; the rest is a non-planar cap.
    Eigen::Matrix<double, 3, Eigen::Dynamic> p(3, 16);
    for (int i = 0; i <= 3; ++i)
        for (int j = 0; j <= 3; ++j) {
            const double r = i / 3.0, a = j * 0.5;
            p.col(i * 4 + j) = V3(r * std::cos(a), r * std::sin(a), 1 - r * r + 0.1 * i * j);
        }
    const S3 s(3, 3, p);
    for (double v : {0.0, 0.2, 0.5, 0.8, 1.0}) {
        CAPTURE(v);
        const V3 n0 = s.normal(0, v);
        REQUIRE(n0.allFinite());
        CHECK(n0.norm() == Approx(1).epsilon(1e-14));
        // The limit: normals at u = 1e-6 beside it (regular there) point the same way.
        const V3 nearby = s.normal(1e-6, v);
        CHECK(n0.dot(nearby) > 1 - 1e-9);
        // f_u x f_v vanishes on the edge, so the fast formula cannot produce this.
        CHECK(s.partial(0, 1, 0, v).norm() == 0);
    }
    // At a corner of the collapsed edge and a regular edge as well.
    CHECK(s.normal(0, 0).dot(s.normal(1e-6, 1e-6)) > 1 - 1e-9);
    // The grid path resolves the same points through the limit.
    Eigen::Matrix<double, 3, Eigen::Dynamic> pos, nrm;
    s.evaluateGrid({0.0, 0.5}, {0.0, 0.5, 1.0}, pos, &nrm);
    REQUIRE(nrm.allFinite());
    CHECK((nrm.col(1) - s.normal(0, 0.5)).norm() < 1e-15);
    CHECK((nrm.col(4) - s.normal(0.5, 0.5)).norm() < 1e-14);
    CHECK((pos.col(5) - s.evaluate(0.5, 1.0)).norm() < 1e-15);
}

TEST_CASE("a degenerate patch (all points on a line) has a zero normal, not NaN", "[surface][normal]")
{
    Eigen::Matrix<double, 3, Eigen::Dynamic> p(3, 4);
    p << 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3;
    const S3 s(1, 1, p);
    const V3 n = s.normal(0.5, 0.5);
    CHECK(n.allFinite());
    CHECK(n == V3::Zero());
    CHECK_FALSE(s.curvature(0.5, 0.5).regular);
}

TEST_CASE("the grid path equals pointwise evaluation", "[surface]")
{
    const S3 s = randomSurface(3, 3, 77);
    std::vector<double> us, vs;
    for (int i = 0; i <= 9; ++i) us.push_back(i / 9.0);
    for (int j = 0; j <= 70; ++j) vs.push_back(j / 70.0); // more than one block of 64
    Eigen::Matrix<double, 3, Eigen::Dynamic> pos, nrm;
    s.evaluateGrid(us, vs, pos, &nrm);
    for (std::size_t i = 0; i < us.size(); ++i)
        for (std::size_t j = 0; j < vs.size(); ++j) {
            const auto k = static_cast<Eigen::Index>(i * vs.size() + j);
            CHECK((pos.col(k) - s.evaluate(us[i], vs[j])).norm() < 1e-14);
            CHECK((nrm.col(k) - s.normal(us[i], vs[j])).norm() < 1e-12);
        }
    // The generic (non-double) path too.
    const BezierSurface<float, 3> sf(3, 3, s.controlPoints().cast<float>());
    Eigen::Matrix<float, 3, Eigen::Dynamic> pf, nf;
    sf.evaluateGrid({0.25f, 0.5f}, {0.0f, 0.75f}, pf, &nf);
    CHECK((pf.col(3).cast<double>() - s.evaluate(0.5, 0.75)).norm() < 1e-5);
    CHECK((nf.col(3).cast<double>() - s.normal(0.5, 0.75)).norm() < 1e-4);
}

TEST_CASE("bounding box contains the surface and is tight", "[surface]")
{
    const S3 s = randomSurface(4, 3, 5);
    const auto box = s.boundingBox(1e-9);
    Eigen::AlignedBox3d sampled;
    for (int i = 0; i <= 400; ++i)
        for (int j = 0; j <= 400; ++j) {
            const V3 q = s.evaluate(i / 400.0, j / 400.0);
            sampled.extend(q);
            REQUIRE(box.contains(q));
        }
    // Within the tolerance plus what the sampling can miss (|f'| h^2 scale).
    CHECK((box.min() - sampled.min()).cwiseAbs().maxCoeff() < 1e-4);
    CHECK((box.max() - sampled.max()).cwiseAbs().maxCoeff() < 1e-4);
    CHECK(s.controlBox().contains(box));
}

TEST_CASE("closest point: never worse than brute force, exact near the boundary", "[surface][closest]")
{
    const S3 s = randomSurface(3, 3, 123);
    // Brute force on a 300 x 300 grid.
    const int g = 300;
    std::vector<V3> samples;
    for (int i = 0; i <= g; ++i)
        for (int j = 0; j <= g; ++j) samples.push_back(s.evaluate(static_cast<double>(i) / g, static_cast<double>(j) / g));
    const auto queries = freeform::test::randomPoints<double, 3>(40, 99, -1.5, 1.5);
    for (Eigen::Index q = 0; q < queries.cols(); ++q) {
        const V3 p = queries.col(q);
        double brute = std::numeric_limits<double>::infinity();
        for (const V3& x : samples) brute = std::min(brute, (x - p).norm());
        const auto c = s.closestPoint(p);
        CAPTURE(q, brute, c.distance, c.u, c.v);
        CHECK(c.distance <= brute + 1e-12);
        CHECK(c.distance > brute - 0.02); // the grid is dense: the minimum is nearby
        CHECK((c.point - s.evaluate(c.u, c.v)).norm() < 1e-14);
        CHECK(c.distance == Approx((c.point - p).norm()));
        // First-order optimality in the interior.
        if (c.u > 1e-6 && c.u < 1 - 1e-6 && c.v > 1e-6 && c.v < 1 - 1e-6) {
            const auto d = s.jet(c.u, c.v, 1);
            CHECK(std::abs((c.point - p).dot(d.col(1))) < 1e-8);
            CHECK(std::abs((c.point - p).dot(d.col(2))) < 1e-8);
        }
    }
    // A point beyond the corner (1, 1): the corner itself is nearest... when it lies outside the
    // surface along the diagonal of the corner's tangents.
    const V3 corner = s.controlPoint(3, 3);
    const auto d = s.jet(1, 1, 1);
    const V3 away = corner + 0.5 * (d.col(1).normalized() + d.col(2).normalized());
    const auto c = s.closestPoint(away);
    double brute = std::numeric_limits<double>::infinity();
    for (const V3& x : samples) brute = std::min(brute, (x - away).norm());
    CHECK(c.distance <= brute + 1e-12);
}

TEST_CASE("pieceU and pieceV equal the two splits they stand for, to the bit", "[surface]")
{
    // splitU(b).first, then splitU(a / b).second (each where it cuts): the same de Casteljau steps,
    // so every coordinate equal, not just close; and the piece is the patch over [a, b].
    for (int m = 1; m <= 5; ++m) {
        const S3 s = randomSurface(m, 6 - m, 900u + static_cast<std::uint32_t>(m));
        for (const auto& [a, b] : {std::pair{0.0, 0.41}, std::pair{0.27, 1.0}, std::pair{0.13, 0.86}, std::pair{0.0, 1.0}}) {
            S3 u = s, v = s;
            if (b < 1) u = u.splitU(b).first, v = v.splitV(b).first;
            if (a > 0) u = u.splitU(a / b).second, v = v.splitV(a / b).second;
            CAPTURE(m, a, b);
            CHECK(s.pieceU(a, b).controlPoints() == u.controlPoints());
            CHECK(s.pieceV(a, b).controlPoints() == v.controlPoints());
            for (double x : {0.0, 0.3, 1.0})
                for (double y : {0.0, 0.55, 1.0}) {
                    CHECK((s.pieceU(a, b).evaluate(x, y) - s.evaluate(a + (b - a) * x, y)).norm() < 1e-14);
                    CHECK((s.pieceV(a, b).evaluate(y, x) - s.evaluate(y, a + (b - a) * x)).norm() < 1e-14);
                }
        }
    }
}

TEST_CASE("splitOff and pieceInto equal splitU, splitV, pieceU and pieceV to the bit, reusing a net", "[surface]")
{
    // The grid searches cut cells into nets they keep (no allocation per cell): the points must be
    // the allocating calls' own, whatever the net held before (another degree, another patch).
    S3 left = randomSurface(1, 1, 70u), piece = randomSurface(7, 2, 71u);
    for (int m = 1; m <= 5; ++m) {
        const S3 s = randomSurface(m, 6 - m, 950u + static_cast<std::uint32_t>(m));
        for (double t : {0.0, 0.37, 0.5, 1.0}) {
            CAPTURE(m, t);
            const auto [lu, ru] = s.splitU(t);
            S3 rest = s;
            rest.splitOffU(t, left);
            CHECK(left.degreeU() == m);
            CHECK(left.degreeV() == 6 - m);
            CHECK(left.controlPoints() == lu.controlPoints());
            CHECK(rest.controlPoints() == ru.controlPoints());
            const auto [lv, rv] = s.splitV(t);
            rest = s;
            rest.splitOffV(t, left);
            CHECK(left.controlPoints() == lv.controlPoints());
            CHECK(rest.controlPoints() == rv.controlPoints());
        }
        for (const auto& [a, b] : {std::pair{0.0, 0.41}, std::pair{0.27, 1.0}, std::pair{0.13, 0.86}}) {
            CAPTURE(m, a, b);
            s.pieceUInto(a, b, piece);
            CHECK(piece.degreeU() == m);
            CHECK(piece.controlPoints() == s.pieceU(a, b).controlPoints());
            s.pieceVInto(a, b, piece);
            CHECK(piece.controlPoints() == s.pieceV(a, b).controlPoints());
        }
    }
    // The rational patch's forms cut its homogeneous net the same way.
    using R3 = freeform::RationalBezierSurface<double, 3>;
    const S3 net = randomSurface(2, 3, 990u);
    Eigen::VectorXd weights(net.controlPoints().cols());
    for (Eigen::Index i = 0; i < weights.size(); ++i) weights[i] = 0.5 + 0.25 * static_cast<double>(i % 5);
    const R3 r(2, 3, net.controlPoints(), weights);
    R3 rest = r, cut(net);
    rest.splitOffU(0.3, cut);
    CHECK(cut.homogeneous().controlPoints() == r.splitU(0.3).first.homogeneous().controlPoints());
    CHECK(rest.homogeneous().controlPoints() == r.splitU(0.3).second.homogeneous().controlPoints());
    rest = r;
    rest.splitOffV(0.6, cut);
    CHECK(cut.homogeneous().controlPoints() == r.splitV(0.6).first.homogeneous().controlPoints());
    CHECK(rest.homogeneous().controlPoints() == r.splitV(0.6).second.homogeneous().controlPoints());
    r.pieceUInto(0.2, 0.7, cut);
    CHECK(cut.homogeneous().controlPoints() == r.pieceU(0.2, 0.7).homogeneous().controlPoints());
    r.pieceVInto(0.1, 0.9, cut);
    CHECK(cut.homogeneous().controlPoints() == r.pieceV(0.1, 0.9).homogeneous().controlPoints());
}

} // namespace test_bezier_surface
