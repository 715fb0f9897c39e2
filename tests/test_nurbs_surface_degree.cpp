// Knot removal, degree elevation and degree reduction of NURBS surfaces in u and v
// (surface/nurbs_surface.h): elevation leaves every point in place (1e-13), removing an inserted
// knot gives back the original net, reducing an elevated surface gives back the original surface
// with error ~0 (and, once the extra knot occurrences are removed, the original net), and the
// reported error bounds the deviation measured on a dense grid.

#include <catch2/catch.hpp>

#include <freeform/surface/nurbs_surface.h>

#include <cmath>
#include <random>

#include "support/cox_de_boor.h"
#include "support/random.h"

namespace test_nurbs_surface_degree {

using namespace freeform;
using namespace freeform::test;
using Surface = NurbsSurface<double, 3>;

namespace {

Surface randomSurface(int p, int q, bool rational, std::uint32_t seed)
{
    std::mt19937 rng(seed);
    const int cu = p + 2 + static_cast<int>(rng() % 4), cv = q + 2 + static_cast<int>(rng() % 4);
    auto ku = randomKnots(p, cu, true, rng), kv = randomKnots(q, cv, true, rng);
    Eigen::VectorXd w = Eigen::VectorXd::Ones(cu * cv);
    if (rational) {
        std::uniform_real_distribution<double> uw(0.3, 3.0);
        for (int i = 0; i < cu * cv; ++i) w[i] = uw(rng);
    }
    return Surface(p, q, ku, kv, randomPoints<double, 3>(cu * cv, seed + 1), w);
}

/// max |a - b| on an n x n grid over a's domain.
double maxDistance(const Surface& a, const Surface& b, int n = 60)
{
    double worst = 0;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
            const double u = a.knotsU().front() + (a.knotsU().back() - a.knotsU().front()) * i / n;
            const double v = a.knotsV().front() + (a.knotsV().back() - a.knotsV().front()) * j / n;
            worst = std::max(worst, (a(u, v) - b(u, v)).norm());
        }
    return worst;
}

double netDistance(const Surface& a, const Surface& b)
{
    REQUIRE(a.homogeneousPoints().cols() == b.homogeneousPoints().cols());
    return (a.homogeneousPoints() - b.homogeneousPoints()).cwiseAbs().maxCoeff();
}

/// A value strictly inside the domain that is not a knot: the midpoint of the widest span.
double midKnot(const KnotVector<double>& k)
{
    const auto br = k.breakpoints();
    std::size_t best = 0;
    for (std::size_t i = 1; i + 1 < br.size(); ++i)
        if (br[i + 1] - br[i] > br[best + 1] - br[best]) best = i;
    return 0.5 * (br[best] + br[best + 1]);
}

} // namespace

TEST_CASE("surface degree elevation in u and v leaves every point in place", "[nurbs][surface][degree]")
{
    for (std::uint32_t seed = 1; seed <= 12; ++seed) {
        const int p = 1 + static_cast<int>(seed % 4), q = 1 + static_cast<int>((seed / 4) % 3);
        const Surface s = randomSurface(p, q, seed % 2 == 0, 100 + seed);
        CAPTURE(seed, p, q);
        const Surface eu = s.elevatedU(1), ev = s.elevatedV(2);
        CHECK(eu.degreeU() == p + 1);
        CHECK(eu.degreeV() == q);
        CHECK(ev.degreeU() == p);
        CHECK(ev.degreeV() == q + 2);
        CHECK(eu.knotsU().breakpoints() == s.knotsU().breakpoints());
        for (double k : s.knotsU().breakpoints())
            if (k != s.knotsU().front() && k != s.knotsU().back())
                CHECK(eu.knotsU().multiplicity(k) == s.knotsU().multiplicity(k) + 1);
        CHECK(eu.knotsV().knots() == s.knotsV().knots());
        CHECK(maxDistance(s, eu) <= 1e-13);
        CHECK(maxDistance(s, ev) <= 1e-13);
    }
}

TEST_CASE("removing an inserted knot in u or v gives back the original net", "[nurbs][surface][degree]")
{
    for (std::uint32_t seed = 1; seed <= 12; ++seed) {
        const int p = 1 + static_cast<int>(seed % 4), q = 1 + static_cast<int>((seed / 4) % 3);
        const Surface s = randomSurface(p, q, seed % 3 == 0, 200 + seed);
        CAPTURE(seed, p, q);
        const double u = midKnot(s.knotsU()), v = midKnot(s.knotsV());
        const auto ru = s.refinedU({u}).removeKnotU(u);
        CHECK(ru.error <= 1e-13);
        CHECK(ru.surface.knotsU().knots() == s.knotsU().knots());
        CHECK(netDistance(ru.surface, s) <= 1e-13);
        const auto rv = s.refinedV({v}).removeKnotV(v);
        CHECK(rv.error <= 1e-13);
        CHECK(rv.surface.knotsV().knots() == s.knotsV().knots());
        CHECK(netDistance(rv.surface, s) <= 1e-13);
    }
    const Surface s = randomSurface(2, 2, false, 7);
    CHECK_THROWS_WITH(s.removeKnotU(midKnot(s.knotsU())), Catch::Contains("is not a knot"));
}

TEST_CASE("reducing an elevated surface gives back the original, error ~0", "[nurbs][surface][degree]")
{
    for (std::uint32_t seed = 1; seed <= 12; ++seed) {
        const int p = 1 + static_cast<int>(seed % 3), q = 1 + static_cast<int>((seed / 3) % 3);
        const Surface s = randomSurface(p, q, seed % 2 == 1, 300 + seed);
        CAPTURE(seed, p, q);
        for (const bool inU : {true, false}) {
            CAPTURE(inU);
            const Surface elevated = inU ? s.elevatedU() : s.elevatedV();
            const auto red = inU ? elevated.reducedU(1e-12) : elevated.reducedV(1e-12);
            CHECK(red.error <= 1e-12);
            CHECK(red.surface.degreeU() == p);
            CHECK(red.surface.degreeV() == q);
            CHECK(maxDistance(s, red.surface) <= 1e-12);
            // The reduction keeps the elevated surface's multiplicities (one more at every interior
            // knot below the degree): removing that occurrence gives back the original net.
            Surface back = red.surface;
            const auto& k = inU ? s.knotsU() : s.knotsV();
            for (double b : k.breakpoints()) {
                if (b == k.front() || b == k.back()) continue;
                const auto& now = inU ? back.knotsU() : back.knotsV();
                while (now.multiplicity(b) > k.multiplicity(b)) {
                    const auto r = inU ? back.removeKnotU(b) : back.removeKnotV(b);
                    CHECK(r.error <= 1e-12);
                    back = r.surface;
                }
            }
            CHECK((inU ? back.knotsU() : back.knotsV()).knots() == k.knots());
            CHECK(netDistance(back, s) <= 1e-12);
        }
    }
}

TEST_CASE("the reported error of removal and reduction bounds the deviation on a dense grid", "[nurbs][surface][degree]")
{
    for (std::uint32_t seed = 1; seed <= 10; ++seed) {
        const int p = 2 + static_cast<int>(seed % 3), q = 2 + static_cast<int>((seed / 3) % 2);
        const Surface s = randomSurface(p, q, false, 400 + seed);
        CAPTURE(seed, p, q);
        const auto ru = s.reducedU(1e9), rv = s.reducedV(1e9);
        CHECK(ru.error > 1e-6); // random control points: not of a lower degree
        const double du = maxDistance(s, ru.surface, 120), dv = maxDistance(s, rv.surface, 120);
        CHECK(du <= ru.error * (1 + 1e-12));
        CHECK(dv <= rv.error * (1 + 1e-12));
        CHECK(du >= 1e-3 * ru.error); // the bound is not vacuous
        const auto br = s.knotsU().breakpoints();
        if (br.size() > 2) {
            const auto rk = s.removeKnotU(br[1]);
            CHECK(maxDistance(s, rk.surface, 120) <= rk.error * (1 + 1e-12));
        }
        const auto bv = s.knotsV().breakpoints();
        if (bv.size() > 2) {
            const auto rk = s.removeKnotV(bv[1]);
            CHECK(maxDistance(s, rk.surface, 120) <= rk.error * (1 + 1e-12));
        }
    }
    CHECK_THROWS_WITH(randomSurface(1, 2, false, 5).reducedU(), Catch::Contains("cannot be reduced"));
}

} // namespace test_nurbs_surface_degree
