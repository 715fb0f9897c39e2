// NurbsCurve and KnotVector against independent computations: a long-double Cox-de Boor recursion
// on random knot vectors (degrees 1-9, multiple knots, clamped and unclamped), the quotient rule in
// long double with basis derivatives from the recursive derivative formula, finite differences,
// curve identity under knot insertion / refinement / extraction / split / reversal, the A-frame of
// the cubic C2 spline, and input validation.

#include <catch2/catch.hpp>

#include <freeform/curve/aframe.h>
#include <freeform/curve/nurbs_curve.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "support/cox_de_boor.h"
#include "support/random.h"

namespace test_nurbs_curve {

using namespace freeform;
using namespace freeform::test;

namespace {


template <int Dim>
NurbsCurve<double, Dim> randomCurve(int p, bool clamped, bool rational, std::uint32_t seed)
{
    std::mt19937 rng(seed);
    const int count = p + 1 + static_cast<int>(rng() % 6);
    std::vector<double> k = randomKnots(p, count, clamped, rng);
    Eigen::VectorXd w = Eigen::VectorXd::Ones(count);
    if (rational) {
        std::uniform_real_distribution<double> uw(0.3, 3.0);
        for (int i = 0; i < count; ++i) w[i] = uw(rng);
    }
    return NurbsCurve<double, Dim>(p, k, randomPoints<double, Dim>(count, seed + 1), w);
}

template <int Dim>
Eigen::Matrix<LD, Dim, Eigen::Dynamic> referenceDerivatives(const NurbsCurve<double, Dim>& c, LD u, int order)
{
    const int p = c.degree(), n = c.controlCount() - 1;
    std::vector<LD> U(c.knots().begin(), c.knots().end());
    const int span = referenceSpan(U, p, n, u);
    // Homogeneous derivatives A^(k), w^(k) in long double, then Leibniz.
    std::vector<Eigen::Matrix<LD, Dim, 1>> A(order + 1, Eigen::Matrix<LD, Dim, 1>::Zero());
    std::vector<LD> W(order + 1, 0);
    for (int k = 0; k <= order; ++k)
        for (int i = 0; i <= n; ++i) {
            const LD b = coxDeBoorDerivative(U, i, p, k, u, span);
            const LD w = c.weight(i);
            A[k] += b * w * c.controlPoint(i).template cast<LD>();
            W[k] += b * w;
        }
    Eigen::Matrix<LD, Dim, Eigen::Dynamic> f(Dim, order + 1);
    for (int k = 0; k <= order; ++k) {
        Eigen::Matrix<LD, Dim, 1> v = A[k];
        for (int i = 1; i <= k; ++i) v -= LD(binomial(k, i)) * W[i] * f.col(k - i);
        f.col(k) = v / W[0];
    }
    return f;
}

template <typename A, typename B>
double maxDiff(const A& a, const B& b)
{
    return double((a.template cast<LD>() - b.template cast<LD>()).cwiseAbs().maxCoeff());
}

} // namespace

TEST_CASE("knot vector validation names the knot", "[nurbs][knots]")
{
    using K = KnotVector<double>;
    CHECK_THROWS_WITH(K({0, 0, 1, 0.5, 1, 1}, 2), Catch::Contains("knot 3 (0.5") && Catch::Contains("less than knot 2"));
    CHECK_THROWS_WITH(K({0, 0, 0, 0.5, 0.5, 0.5, 0.5, 1, 1, 1}, 2), Catch::Contains("knot 3") && Catch::Contains("multiplicity 4"));
    CHECK_THROWS_WITH(K({0, 0, 1, 1}, 2), Catch::Contains("too few"));
    CHECK_THROWS_WITH(K({0, 1, 1, 1, 2, 3}, 2), Catch::Contains("empty"));
    CHECK_THROWS_WITH(K({0, 0, 0, NAN, 1, 1, 1}, 2), Catch::Contains("knot 3 is not finite"));
    CHECK_NOTHROW(K({0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1}, 2)); // p + 1 inside: a break is allowed
    CHECK_THROWS_WITH((NurbsCurve<double, 2>(2, {0, 0, 0, 1, 1, 1}, randomPoints<double, 2>(4, 1))),
                      Catch::Contains("need 3 control points, got 4"));
    Eigen::VectorXd w(3);
    w << 1, -1, 1;
    CHECK_THROWS_WITH((NurbsCurve<double, 2>(2, {0, 0, 0, 1, 1, 1}, randomPoints<double, 2>(3, 1), w)),
                      Catch::Contains("weight 1"));
}

TEST_CASE("messages print parameters and knots so that they read back exactly", "[nurbs][knots]")
{
    // std::to_string (%f) printed 1 + 1e-9 as "1.000000" and a domain of size 1e-8 as
    // "(0.000000, 0.000000)", hiding the very problem the message reports.
    const NurbsCurve<double, 2> c(2, {0, 0, 0, 1, 1, 1}, randomPoints<double, 2>(3, 1));
    CHECK_THROWS_WITH(c.insertKnot(1 + 1e-9), Catch::Equals("NurbsCurve::insertKnot: 1.000000001 is not inside the domain (0, 1)"));
    CHECK_THROWS_WITH(c.split(-0.1), Catch::Contains("-0.1 is not inside the domain (0, 1)"));
    const NurbsCurve<double, 2> tiny(2, {0, 0, 0, 1e-8, 1e-8, 1e-8}, randomPoints<double, 2>(3, 2));
    CHECK_THROWS_WITH(tiny.insertKnot(2e-8), Catch::Contains("2e-08 is not inside the domain (0, 1e-08)"));
    CHECK_THROWS_WITH(KnotVector<double>({0, 0, 1, 0.1 + 0.2, 1, 1}, 2), Catch::Contains("knot 3 (0.30000000000000004)"));
    const NurbsCurve<float, 2> f(2, {0, 0, 0, 1, 1, 1}, randomPoints<float, 2>(3, 3));
    CHECK_THROWS_WITH(f.insertKnot(1.1f), Catch::Contains("1.1 is not inside the domain (0, 1)"));
}

TEST_CASE("findSpan and the basis against Cox-de Boor in long double, degrees 1-9", "[nurbs][knots]")
{
    for (int p = 1; p <= 9; ++p)
        for (int clamped = 0; clamped <= 1; ++clamped) {
            std::mt19937 rng(100 * p + clamped);
            const int count = p + 1 + 5;
            const KnotVector<double> kv(randomKnots(p, count, clamped, rng), p);
            std::vector<LD> U(kv.knots().begin(), kv.knots().end());
            std::uniform_real_distribution<double> uu(kv.front(), kv.back());
            std::vector<double> us = kv.knots();
            for (int i = 0; i < 40; ++i) us.push_back(uu(rng));
            for (double u : us) {
                if (u < kv.front() || u > kv.back()) continue;
                const int span = kv.findSpan(u);
                CAPTURE(p, clamped, u, span);
                REQUIRE(span == referenceSpan(U, p, count - 1, u));
                double N[kMaxDegree + 1];
                kv.basisFunctions(span, u, N);
                std::vector<double> ders(static_cast<std::size_t>(3 * (p + 1)));
                kv.basisDerivatives(span, u, 2, ders.data());
                LD sum = 0;
                for (int j = 0; j <= p; ++j) {
                    const LD ref = coxDeBoor(U, span - p + j, p, u, span);
                    CHECK(std::abs(N[j] - ref) <= 1e-14L);
                    CHECK(std::abs(ders[j] - ref) <= 1e-14L);
                    sum += N[j];
                    for (int k = 1; k <= 2; ++k) {
                        const LD dref = coxDeBoorDerivative(U, span - p + j, p, k, u, span);
                        CHECK(std::abs(ders[k * (p + 1) + j] - dref) <= 1e-11L * (1 + std::abs(dref)));
                    }
                }
                CHECK(std::abs(sum - 1) <= 1e-15L);
            }
        }
}

TEMPLATE_TEST_CASE_SIG("evaluation and derivatives against long double Cox-de Boor and the quotient rule",
                       "[nurbs][property]", ((int Dim), Dim), 2, 3)
{
    for (int p = 1; p <= 9; ++p)
        for (int variant = 0; variant < 4; ++variant) {
            const bool clamped = variant & 1, rational = variant & 2;
            const auto c = randomCurve<Dim>(p, clamped, rational, 1000u * p + variant);
            std::mt19937 rng(7 * p + variant);
            std::uniform_real_distribution<double> uu(c.domainStart(), c.domainEnd());
            const double scale = c.controlPoints().cwiseAbs().maxCoeff();
            for (int s = 0; s < 25; ++s) {
                const double u = s == 0 ? c.domainStart() : s == 1 ? c.domainEnd() : uu(rng);
                CAPTURE(p, clamped, rational, u);
                const auto ref = referenceDerivatives<Dim>(c, u, 3);
                CHECK(maxDiff(c.evaluate(u), ref.col(0)) <= 1e-14 * scale);
                const auto d = c.derivatives(u, 3);
                for (int k = 0; k <= 3; ++k) {
                    const double mag = double(ref.col(k).cwiseAbs().maxCoeff()) + scale;
                    CHECK(maxDiff(d.col(k), ref.col(k)) <= 1e-11 * mag);
                }
            }
        }
}

TEST_CASE("first derivative against Richardson-extrapolated central differences in long double", "[nurbs]")
{
    for (int p = 2; p <= 6; ++p) {
        const auto cd = randomCurve<3>(p, true, true, 77u + p);
        Eigen::Matrix<LD, 3, Eigen::Dynamic> pts = cd.controlPoints().cast<LD>();
        Eigen::Matrix<LD, Eigen::Dynamic, 1> w = cd.weights().cast<LD>();
        std::vector<LD> k(cd.knots().begin(), cd.knots().end());
        const NurbsCurve<LD, 3> c(p, k, pts, w);
        const auto& br = cd.breakpoints();
        for (std::size_t i = 0; i + 1 < br.size(); ++i) {
            const LD u = (3 * LD(br[i]) + LD(br[i + 1])) / 4, h = (LD(br[i + 1]) - LD(br[i])) / 64;
            auto central = [&](LD step) { return ((c(u + step) - c(u - step)) / (2 * step)).eval(); };
            const auto r1 = ((4 * central(h / 2) - central(h)) / 3).eval();
            const auto r2 = ((4 * central(h / 4) - central(h / 2)) / 3).eval();
            const auto fd = ((16 * r2 - r1) / 15).eval();
            const Eigen::Matrix<LD, 3, 1> d = c.derivatives(u, 1).col(1);
            CAPTURE(p, double(u));
            CHECK(double((fd - d).cwiseAbs().maxCoeff()) <= 1e-9 * (1 + double(d.cwiseAbs().maxCoeff())));
        }
    }
}

TEST_CASE("knot insertion (Boehm), refinement (Oslo), extraction, split and reversal keep the curve", "[nurbs]")
{
    for (int p = 1; p <= 7; ++p)
        for (int variant = 0; variant < 4; ++variant) {
            const bool clamped = variant & 1, rational = variant & 2;
            const auto c = randomCurve<3>(p, clamped, rational, 5000u * p + variant);
            const double a = c.domainStart(), b = c.domainEnd();
            const double scale = c.controlPoints().cwiseAbs().maxCoeff();
            const double u1 = a + (b - a) * 0.3, u2 = a + (b - a) * 0.71;
            const auto ins = c.insertKnot(u1, p).insertKnot(u2, 1);
            const auto ref = c.refined({u1, u2});
            const auto ref2 = ref.refined({u2}); // u2 twice in all
            const auto ins2 = c.insertKnot(u2, 1).insertKnot(u2, 1).insertKnot(u1, 1);
            CAPTURE(p, clamped, rational);
            REQUIRE(ins.controlCount() == c.controlCount() + p + 1);
            REQUIRE(ref2.controlCount() == ins2.controlCount());
            CHECK(ref2.knots() == ins2.knots());
            // Oslo and Boehm give the same control points.
            const double hscale = ins2.homogeneousPoints().cwiseAbs().maxCoeff();
            CHECK(maxDiff(ref2.homogeneousPoints(), ins2.homogeneousPoints()) <= 1e-12 * hscale);
            const auto pieces = c.bezierPieces();
            const auto& br = c.breakpoints();
            REQUIRE(pieces.size() + 1 == br.size());
            // The pieces as the curve keeps them (homogeneousPiece, which the part mesher reads
            // in place of bezierPieces' copies): p + 1 points each, the same bits, and their
            // homogeneous de Casteljau point over its span is the curve's.
            for (std::size_t k = 0; k < pieces.size(); ++k) {
                const auto piece = c.homogeneousPiece(k);
                REQUIRE(piece.cols() == p + 1);
                CHECK(piece == pieces[k].homogeneous().controlPoints());
                const double t = 0.37, u = br[k] + t * (br[k + 1] - br[k]);
                Eigen::MatrixXd h = piece;
                for (int level = 1; level <= p; ++level)
                    for (int i = 0; i + level <= p; ++i) h.col(i) = (1 - t) * h.col(i) + t * h.col(i + 1);
                CHECK(maxDiff(Eigen::Vector3d(h.col(0).head<3>() / h(3, 0)), c.evaluate(u)) <= 1e-13 * scale);
            }
            const auto [left, right] = c.split(u1);
            const auto rev = c.reversed();
            for (int s = 0; s <= 100; ++s) {
                const double u = a + (b - a) * s / 100.0;
                const auto f = c.evaluate(u);
                CHECK(maxDiff(ins.evaluate(u), f) <= 1e-13 * scale);
                CHECK(maxDiff(ref.evaluate(u), f) <= 1e-13 * scale);
                CHECK(maxDiff(rev.evaluate(a + b - u), f) <= 1e-13 * scale);
                CHECK(maxDiff((u <= u1 ? left : right).evaluate(u), f) <= 1e-13 * scale);
                std::size_t k = 0;
                while (k + 2 < br.size() && u >= br[k + 1]) ++k;
                CHECK(maxDiff(pieces[k].evaluate((u - br[k]) / (br[k + 1] - br[k])), f) <= 1e-13 * scale);
            }
        }
}

TEST_CASE("split keeps every control point away from the cut, exactly", "[nurbs]")
{
    // Boehm's insertion changes only the p - s - 1 points around the cut: the others are the
    // curve's own, bit for bit (the left piece's first k - p + 1, the right piece's last ones), and
    // the point at the cut, the curve's point there, ends the left piece and starts the right one.
    for (int p = 1; p <= 7; ++p)
        for (int variant = 0; variant < 2; ++variant) {
            const auto c = randomCurve<3>(p, true, variant == 1, 7100u * p + variant);
            const std::vector<double>& U = c.knots();
            const double u = c.domainStart() + 0.43 * (c.domainEnd() - c.domainStart());
            const int k = static_cast<int>(std::upper_bound(U.begin(), U.end(), u) - U.begin()) - 1;
            const auto [left, right] = c.split(u);
            CAPTURE(p, variant);
            const auto& h = c.homogeneousPoints();
            for (int i = 0; i <= k - p; ++i) CHECK(left.homogeneousPoints().col(i) == h.col(i));
            const int n = c.controlCount(), rn = right.controlCount();
            for (int i = k; i < n; ++i) CHECK(right.homogeneousPoints().col(rn - (n - i)) == h.col(i));
            CHECK(left.homogeneousPoints().col(left.controlCount() - 1) == right.homogeneousPoints().col(0));
            const double scale = c.controlPoints().cwiseAbs().maxCoeff();
            CHECK(maxDiff(left.controlPoints().col(left.controlCount() - 1), c.evaluate(u)) <= 1e-13 * scale);
        }
}

TEST_CASE("Bézier extraction of the clamped and open cubic C2 spline is the A-frame", "[nurbs][aframe]")
{
    const auto d = randomPoints<double, 2>(7, 42);
    const std::vector<double> h = {1.0, 0.5, 2.0, 1.5};
    for (EndCondition end : {EndCondition::Clamped, EndCondition::Open}) {
        std::vector<double> knots;
        // Interior breakpoints 0, h0, h0+h1, ...; beyond the ends 0 (clamped) or the end intervals (open).
        std::vector<double> x = {0};
        for (double hi : h) x.push_back(x.back() + hi);
        const double e0 = end == EndCondition::Clamped ? 0 : h.front(), e1 = end == EndCondition::Clamped ? 0 : h.back();
        knots = {x.front() - 2 * e0, x.front() - e0};
        knots.insert(knots.end(), x.begin(), x.end());
        knots.push_back(x.back() + e1);
        knots.push_back(x.back() + 2 * e1);
        if (end == EndCondition::Clamped) { // multiplicity 4 at both ends
            knots.insert(knots.begin(), 0.0);
            knots.push_back(x.back());
        } else {
            knots.insert(knots.begin(), x.front() - 3 * e0);
            knots.push_back(x.back() + 3 * e1);
        }
        const NurbsCurve<double, 2> c(3, knots, d);
        const auto frame = aframeBezierPoints<double, 2>(d, end, h);
        const auto pieces = c.bezierPieces();
        REQUIRE(pieces.size() == h.size());
        for (std::size_t i = 0; i < pieces.size(); ++i)
            for (int j = 0; j <= 3; ++j) {
                CAPTURE(toString(end), i, j);
                CHECK(maxDiff(pieces[i].controlPoint(j), frame.col(static_cast<Eigen::Index>(3 * i + j))) <= 1e-14);
                CHECK(pieces[i].weight(j) == 1.0);
            }
    }
}

TEST_CASE("the batch paths agree with single evaluation", "[nurbs][batch]")
{
    for (int p : {1, 2, 3, 5, 9})
        for (int variant = 0; variant < 4; ++variant) {
            const auto c = randomCurve<3>(p, variant & 1, variant & 2, 900u + 10 * p + variant);
            std::vector<double> us;
            for (int i = 0; i <= 300; ++i) us.push_back(c.domainStart() + (c.domainEnd() - c.domainStart()) * i / 300.0);
            us.push_back(c.domainStart() + 0.5); // unsorted tail
            us.push_back(c.domainStart());
            PointMatrix<double, 3> pos, d1;
            c.evaluateManyWithDerivative(us.data(), us.size(), pos, d1);
            const auto only = c.evaluateMany(us);
            const double scale = c.controlPoints().cwiseAbs().maxCoeff();
            for (std::size_t i = 0; i < us.size(); ++i) {
                CAPTURE(p, variant, us[i]);
                const auto d = c.derivatives(us[i], 1);
                CHECK(maxDiff(only.col(i), d.col(0)) <= 1e-13 * scale);
                CHECK(maxDiff(pos.col(i), d.col(0)) <= 1e-13 * scale);
                CHECK(maxDiff(d1.col(i), d.col(1)) <= 1e-11 * (scale + d.col(1).cwiseAbs().maxCoeff()));
            }
        }
}

TEST_CASE("the full circle: points on the circle, length, box, closest point", "[nurbs][conic]")
{
    const Eigen::Vector2d c(0.25, -3);
    const auto circle = NurbsCurve<double, 2>::circle(c, 2.0);
    double worst = 0;
    for (int i = 0; i <= 1000; ++i) worst = std::max(worst, std::abs((circle(i / 1000.0) - c).norm() - 2.0) / 2.0);
    CHECK(worst <= 1e-15 * 2); // relative 1e-15 to within one rounding of the norm
    CHECK(circle.arcLength(1e-12) == Approx(4 * M_PI).epsilon(1e-12));
    const auto box = circle.boundingBox();
    CHECK(maxDiff(box.min(), Eigen::Vector2d(c.x() - 2, c.y() - 2)) <= 1e-14);
    CHECK(maxDiff(box.max(), Eigen::Vector2d(c.x() + 2, c.y() + 2)) <= 1e-14);
    const Eigen::Vector2d q = c + Eigen::Vector2d(std::cos(1.0), std::sin(1.0)) * 5.0;
    const auto near = circle.closestPoint(q);
    CHECK(near.distance == Approx(3.0).epsilon(1e-12));
    CHECK(maxDiff(near.point, c + 2.0 * Eigen::Vector2d(std::cos(1.0), std::sin(1.0))) <= 1e-12);
    // Closed: the ends meet with the same tangent direction.
    const auto d0 = circle.derivatives(0, 1), d1 = circle.derivatives(1, 1);
    CHECK(maxDiff(d0.col(0), d1.col(0)) <= 1e-15);
    CHECK(maxDiff(d0.col(1).normalized(), d1.col(1).normalized()) <= 1e-15);
}

TEST_CASE("periodic curves close with C^(p-1) continuity", "[nurbs]")
{
    for (int p = 2; p <= 5; ++p) {
        const auto pts = randomPoints<double, 3>(p + 4, 31u + p);
        const auto c = NurbsCurve<double, 3>::periodic(p, pts);
        const auto a = c.derivatives(c.domainStart(), p - 1), b = c.derivatives(c.domainEnd(), p - 1);
        for (int k = 0; k < p; ++k) CHECK(maxDiff(a.col(k), b.col(k)) <= 1e-12 * (1 + b.col(k).norm()));
    }
}

TEST_CASE("polynomial Bézier curves as NURBS evaluate identically", "[nurbs]")
{
    const BezierCurve<double, 2> b({{0, 0}, {1, 2}, {3, 2}, {4, 0}});
    const auto c = NurbsCurve<double, 2>::fromBezier(b);
    CHECK_FALSE(c.isRational());
    for (int i = 0; i <= 10; ++i) CHECK(maxDiff(c(i / 10.0), b(i / 10.0)) <= 1e-15);
    CHECK(c(0.5) == Eigen::Vector2d(2, 1.5));
}

TEST_CASE("knot removal undoes insertion and reports the deviation; elevation and reduction", "[nurbs][elevation]")
{
    for (int p = 1; p <= 6; ++p)
        for (int variant = 0; variant < 4; ++variant) {
            const auto c = randomCurve<3>(p, variant & 1, variant & 2, 7000u * p + variant);
            const double a = c.domainStart(), b = c.domainEnd();
            const double scale = c.controlPoints().cwiseAbs().maxCoeff();
            const double u = a + (b - a) * 0.43;
            CAPTURE(p, variant);
            // Insert then remove: error ~ 0 and the same control points.
            const auto back = c.insertKnot(u, 1).removeKnot(u);
            CHECK(back.error <= 1e-12 * (1 + c.homogeneousPoints().cwiseAbs().maxCoeff()));
            REQUIRE(back.curve.controlCount() == c.controlCount());
            CHECK(maxDiff(back.curve.homogeneousPoints(), c.homogeneousPoints()) <= 1e-12 * (1 + c.homogeneousPoints().cwiseAbs().maxCoeff()));
            // Elevation keeps the curve and raises every interior multiplicity by the count.
            const auto e = c.elevated(2);
            CHECK(e.degree() == p + 2);
            for (double x : c.breakpoints())
                if (x > a && x < b) CHECK(e.knotVector().multiplicity(x) == c.knotVector().multiplicity(x) + 2);
            for (int s = 0; s <= 60; ++s) {
                const double v = a + (b - a) * s / 60.0;
                CHECK(maxDiff(e.evaluate(v), c.evaluate(v)) <= 1e-12 * scale);
            }
            // Reducing an elevated curve gives it back (error ~ 0, polynomial case measured).
            if (p >= 1 && !(variant & 2)) {
                const auto r = c.elevated(1).reduced(1e-9);
                CHECK(r.error <= 1e-9);
                CHECK(r.curve.degree() == p);
                for (int s = 0; s <= 60; ++s) {
                    const double v = a + (b - a) * s / 60.0;
                    CHECK(maxDiff(r.curve.evaluate(v), c.evaluate(v)) <= 1e-10 * scale);
                }
            }
        }
    // Removing a knot that is not removable: the reported error bounds the measured deviation.
    const auto c = randomCurve<2>(3, true, false, 99);
    const double u = c.breakpoints()[1];
    const auto removed = c.removeKnot(u);
    CHECK(removed.error > 1e-6);
    double worst = 0;
    for (int s = 0; s <= 400; ++s) {
        const double v = c.domainStart() + (c.domainEnd() - c.domainStart()) * s / 400.0;
        worst = std::max(worst, (removed.curve(v) - c(v)).norm());
    }
    CHECK(worst <= removed.error * (1 + 1e-12));
    CHECK(worst > 0);
    CHECK_THROWS_WITH(c.removeKnot(c.domainStart() + 1e-9), Catch::Contains("is not a knot"));
}

TEST_CASE("closest point is global: never farther than dense sampling, zero for the curve's own points", "[nurbs]")
{
    // Independent reference: the minimum over 20,001 evaluated samples can only be larger than the
    // true minimum, so the closest point must not be farther than it (up to the sampling's own
    // rounding); a point on the curve must be found at distance ~0. Random rational curves of
    // degrees 1-7 with multiple knots, whose squared distance has many local minima per span.
    for (int p = 1; p <= 7; ++p)
        for (int variant = 0; variant < 4; ++variant) {
            const auto c = randomCurve<3>(p, variant % 2 == 0, true, 900u + 10u * p + variant);
            const double a = c.domainStart(), b = c.domainEnd();
            std::mt19937 rng(77u * p + variant);
            std::uniform_real_distribution<double> ut(a, b), off(-1.5, 1.5);
            for (int trial = 0; trial < 6; ++trial) {
                const double t = ut(rng);
                const Eigen::Vector3d on = c(t);
                CHECK(c.closestPoint(on).distance <= 1e-9);
                const Eigen::Vector3d q = on + Eigen::Vector3d(off(rng), off(rng), off(rng));
                double sampled = std::numeric_limits<double>::infinity();
                for (int i = 0; i <= 20000; ++i) sampled = std::min(sampled, (c(a + (b - a) * i / 20000.0) - q).norm());
                const auto near = c.closestPoint(q);
                CHECK(near.distance <= sampled + 1e-12);
                CHECK((c(near.u) - q).norm() == Approx(near.distance).epsilon(1e-12));
            }
        }
    // The case that the old Newton-from-8-samples search missed: a degree-4 rational piece.
    const Eigen::Matrix<double, 3, 5> P = (Eigen::Matrix<double, 3, 5>() << 0.3, -1.2, 0.8, 1.9, -0.4, //
                                           1.1, 0.2, -1.6, 0.5, 0.9,                                     //
                                           -0.7, 1.4, 0.3, -1.1, 0.6)
                                              .finished();
    const auto piece = NurbsCurve<double, 3>::fromRationalBezier(
        RationalBezierCurve<double, 3>(P, (Eigen::VectorXd(5) << 0.4, 2.7, 0.5, 2.9, 0.35).finished()));
    for (int i = 0; i <= 50; ++i) CHECK(piece.closestPoint(piece(i / 50.0)).distance <= 1e-9);
}

TEST_CASE("fromBezierPieces joins pieces in Bézier form at full-multiplicity knots", "[nurbs]")
{
    using C = NurbsCurve<double, 2>;
    // Two quadratic pieces over [0, 1] and [1, 3]: (0,0) (1,2) (2,0), then (2,0) weight 1,
    // (4,1) weight 2, (5,0) weight 1. The knots by hand: 0 0 0 1 1 3 3 3.
    C::HPoints a(3, 3), b(3, 3);
    a << 0, 1, 2, 0, 2, 0, 1, 1, 1;
    b << 2, 8, 5, 0, 2, 0, 1, 2, 1;
    const C c = C::fromBezierPieces({0, 1, 3}, 2, {a, b}, "two pieces");
    CHECK(c.knots() == std::vector<double>{0, 0, 0, 1, 1, 3, 3, 3});
    REQUIRE(c.controlCount() == 5);
    // The middle of the first piece: (P0 + 2 P1 + P2) / 4 = (1, 1); of the second, at u = 2:
    // (w0 P0 + 2 w1 P1 + w2 P2) / (w0 + 2 w1 + w2) = ((2,0) + 2 (8,2) + (5,0)) / 6 = (23/6, 4/6).
    CHECK((c.evaluate(0.5) - Eigen::Vector2d(1, 1)).norm() <= 1e-15);
    CHECK((c.evaluate(2.0) - Eigen::Vector2d(23.0 / 6, 4.0 / 6)).norm() <= 1e-15);
    // A joint that differs (by rounding, here by 1e-3) keeps the left piece's end.
    C::HPoints b2 = b;
    b2(0, 0) += 1e-3;
    CHECK(C::fromBezierPieces({0, 1, 3}, 2, {a, b2}, "two pieces").controlPoint(2).x() == 2.0);
    CHECK_THROWS_WITH(C::fromBezierPieces({0, 1}, 2, {a, b}, "two pieces"), Catch::Contains("two pieces: 2 Bézier pieces need 3 breakpoints"));
    CHECK_THROWS_WITH(C::fromBezierPieces({0, 1, 3}, 3, {a, b}, "two pieces"), Catch::Contains("piece 1 has 3 control points, not 4"));
}

} // namespace test_nurbs_curve
