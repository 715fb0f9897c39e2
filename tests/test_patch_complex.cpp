// Patch complexes: the strict .bpt reader, shared edges and continuity across them, and the
// bicubic de Boor surface (tensor-product A-frame) against the uniform B-spline basis.

#include <catch2/catch.hpp>

#include <cmath>

#include "freeform/io/bpt.h"
#include "freeform/surface/patch_complex.h"
#include "support/process.h"
#include "support/random.h"

namespace test_patch_complex {

using namespace freeform;
using V3 = Eigen::Vector3d;

namespace {
const std::string kTeapot = std::string(FREEFORM_SOURCE_DIR) + "/data/teapot.bpt";

/// The uniform cubic B-spline weights of d_a .. d_(a+3) at local parameter t.
std::array<double, 4> bsplineWeights(double t)
{
    const double s = 1 - t;
    return {s * s * s / 6, (3 * t * t * t - 6 * t * t + 4) / 6, (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6, t * t * t / 6};
}

PointMatrix<double, 3> grid(int rows, int cols, std::uint32_t seed)
{
    return test::randomPoints<double, 3>(rows * cols, seed);
}
} // namespace

TEST_CASE("the teapot: 32 bicubic patches, point (i, j) on line i*4 + j", "[bpt]")
{
    const PatchComplex teapot = readBpt(kTeapot);
    REQUIRE(teapot.patches.size() == 32);
    for (const Patch& p : teapot.patches) {
        CHECK(p.degreeU() == 3);
        CHECK(p.degreeV() == 3);
    }
    // The first patch's first points, as in the file (lines 3, 4, 5).
    CHECK(teapot.patches[0].controlPoint(0, 0) == V3(1.4, 0.0, 2.4));
    CHECK(teapot.patches[0].controlPoint(0, 1) == V3(1.4, -0.784, 2.4));
    CHECK(teapot.patches[0].controlPoint(0, 2) == V3(0.784, -1.4, 2.4));
    // write -> read gives the same numbers.
    const PatchComplex again = parseBpt(formatBpt(teapot));
    REQUIRE(again.patches.size() == 32);
    for (std::size_t k = 0; k < 32; ++k) CHECK(again.patches[k].controlPoints() == teapot.patches[k].controlPoints());
}

TEST_CASE("the .bpt reader names the line of every error", "[bpt][errors]")
{
    CHECK_THROWS_WITH(parseBpt("", "x.bpt"), Catch::Contains("x.bpt: empty file"));
    CHECK_THROWS_WITH(parseBpt("two\n", "x.bpt"), Catch::Contains("x.bpt: line 1: \"two\" is not an integer"));
    CHECK_THROWS_WITH(parseBpt("0\n", "x.bpt"), Catch::Contains("line 1: the number of patches must be at least 1"));
    CHECK_THROWS_WITH(parseBpt("1\n1 1 1\n", "x.bpt"), Catch::Contains("line 2: patch 0: expected the degrees"));
    CHECK_THROWS_WITH(parseBpt("1\n1 0\n", "x.bpt"), Catch::Contains("line 2: patch 0: degree 0 is outside 1..67"));
    CHECK_THROWS_WITH(parseBpt("1\n1 1\n0 0 0\n1 0 0\n0 1\n1 1 1\n", "x.bpt"),
                      Catch::Contains("line 5: patch 0 point 2: expected 3 coordinates, found 2"));
    CHECK_THROWS_WITH(parseBpt("1\n1 1\n0 0 0\n1 0 0\n0 1 zz\n1 1 1\n", "x.bpt"),
                      Catch::Contains("line 5: \"zz\" is not a finite number"));
    CHECK_THROWS_WITH(parseBpt("1\n1 1\n0 0 0\n1 0 0\n0 1 1e999\n1 1 1\n", "x.bpt"), Catch::Contains("line 5: \"1e999\" is out of range"));
    CHECK_THROWS_WITH(parseBpt("1\n1 1\n0 0 0\n1 0 0\n", "x.bpt"), Catch::Contains("patch 0 ends after 2 of 4 points"));
    CHECK_THROWS_WITH(parseBpt("2\n1 1\n0 0 0\n1 0 0\n0 1 0\n1 1 1\n", "x.bpt"), Catch::Contains("ends after 1 of 2 patches"));
    CHECK_THROWS_WITH(parseBpt("1\n1 1\n0 0 0\n1 0 0\n0 1 0\n1 1 1\n\n7\n", "x.bpt"),
                      Catch::Contains("line 8: unexpected content after the 1 announced patches"));
    CHECK_THROWS_WITH(readBpt(std::string(FREEFORM_TEST_TMP) + "/no_such.bpt"), Catch::Contains("no_such.bpt"));
    // Blank lines are fine.
    CHECK(parseBpt("\n1\n\n1 1\n0 0 0\n1 0 0\n0 1 0\n1 1 1\n\n").patches.size() == 1);
}

TEST_CASE("shared edges of the teapot", "[bpt][edges]")
{
    const PatchComplex teapot = readBpt(kTeapot);
    const auto shared = sharedEdges(teapot);
    // Every shared pair really coincides, and no side is paired with itself.
    for (const SharedEdge& e : shared) {
        CHECK(e.gap == 0);
        CHECK((e.a.patch != e.b.patch || e.a.side != e.b.side));
        const auto ca = edgeCurve(teapot.patches[e.a.patch], e.a.side);
        const auto cb = edgeCurve(teapot.patches[e.b.patch], e.b.side);
        const auto pb = e.reversed ? cb.reversed().controlPoints() : cb.controlPoints();
        CHECK(ca.controlPoints() == pb);
    }
    // The lid's top and the bottom's centre are collapsed sides (4 patches each).
    int collapsed = 0;
    for (const Patch& p : teapot.patches)
        for (int s = 0; s < 4; ++s) collapsed += isCollapsedEdge(p, static_cast<PatchSide>(s)) ? 1 : 0;
    CHECK(collapsed >= 8);
    CHECK(shared.size() >= 40);
}

TEST_CASE("continuity across shared edges: C1, G1 only, C0 only", "[edges]")
{
    const Patch s(3, 2, test::randomPoints<double, 3>(12, 3));
    SECTION("a split gives a C1 (and G1) edge")
    {
        const auto [a, b] = s.splitU(0.4);
        // The halves' parameter intervals differ (0.4 and 0.6): rescale to the same speed by
        // splitting at 0.5 instead, which is a C1 join of equal intervals.
        const auto [c, d] = s.splitU(0.5);
        const auto r = edgeContinuity(PatchComplex{{c, d}});
        REQUIRE(r.size() == 1);
        CHECK(r[0].c0);
        CHECK(r[0].c1);
        CHECK(r[0].g1);
        CHECK(r[0].angle < 1e-7);
        CHECK(r[0].a.side == PatchSide::U1);
        CHECK(r[0].b.side == PatchSide::U0);
        // Unequal intervals: still G1, no longer parametrically C1.
        const auto r2 = edgeContinuity(PatchComplex{{a, b}});
        REQUIRE(r2.size() == 1);
        CHECK(r2[0].g1);
        CHECK_FALSE(r2[0].c1);
    }
    SECTION("a kink gives C0 only")
    {
        auto [c, d] = s.splitU(0.5);
        PointMatrix<double, 3> pts = d.controlPoints();
        for (int j = 0; j <= 2; ++j) pts.col(d.index(1, j)) += V3(0, 0, 0.5);
        const Patch bent(3, 2, pts);
        const auto r = edgeContinuity(PatchComplex{{c, bent}});
        REQUIRE(r.size() == 1);
        CHECK(r[0].c0);
        CHECK_FALSE(r[0].c1);
        CHECK_FALSE(r[0].g1);
        CHECK(r[0].angle > 0.01);
    }
    SECTION("a reversed neighbour is found and still C1")
    {
        const auto [c, d] = s.splitU(0.5);
        // d with u and v both reversed: the shared side runs the other way, the patch is the same.
        PointMatrix<double, 3> pts(3, 12);
        for (int i = 0; i <= 3; ++i)
            for (int j = 0; j <= 2; ++j) pts.col(d.index(3 - i, 2 - j)) = d.controlPoint(i, j);
        const auto r = edgeContinuity(PatchComplex{{c, Patch(3, 2, pts)}});
        REQUIRE(r.size() == 1);
        CHECK(r[0].reversed);
        CHECK(r[0].c1);
        CHECK(r[0].b.side == PatchSide::U1);
    }
}

TEST_CASE("de Boor surface: the A-frame patches are the uniform bicubic B-spline", "[deboor]")
{
    const int rows = 6, cols = 5;
    const PointMatrix<double, 3> d = grid(rows, cols, 17);
    const PatchComplex c = deboorSurfacePatches(d, rows, cols, EndCondition::Open, EndCondition::Open);
    REQUIRE(c.patches.size() == 3 * 2);
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 2; ++b)
            for (double s : {0.0, 0.3, 1.0})
                for (double t : {0.0, 0.55, 1.0}) {
                    const auto wu = bsplineWeights(s), wv = bsplineWeights(t);
                    V3 expected = V3::Zero();
                    for (int i = 0; i < 4; ++i)
                        for (int j = 0; j < 4; ++j) expected += wu[i] * wv[j] * d.col((a + i) * cols + (b + j));
                    CHECK((c.patches[a * 2 + b].evaluate(s, t) - expected).norm() < 1e-14);
                }
    // Interior edges are C1 (equal intervals): 2*2 edges across u, 3*1 across v.
    const auto r = edgeContinuity(c);
    CHECK(r.size() == 7);
    for (const auto& e : r) CHECK(e.c1);
}

TEST_CASE("de Boor surface: closed in both directions is a torus of shared edges", "[deboor]")
{
    const int rows = 5, cols = 4;
    const PointMatrix<double, 3> d = grid(rows, cols, 8);
    const PatchComplex c = deboorSurfacePatches(d, rows, cols, EndCondition::Closed, EndCondition::Closed);
    REQUIRE(c.patches.size() == 20);
    // Periodic: patch (a, b) uses d_(a+i mod rows, b+j mod cols).
    for (int a = 0; a < rows; ++a)
        for (int b = 0; b < cols; ++b) {
            const auto wu = bsplineWeights(0.4), wv = bsplineWeights(0.7);
            V3 expected = V3::Zero();
            for (int i = 0; i < 4; ++i)
                for (int j = 0; j < 4; ++j) expected += wu[i] * wv[j] * d.col(((a + i) % rows) * cols + (b + j) % cols);
            CHECK((c.patches[a * cols + b].evaluate(0.4, 0.7) - expected).norm() < 1e-14);
        }
    // Every side is shared exactly once: 4 sides per patch, two per edge.
    CHECK(sharedEdges(c).size() == 2 * c.patches.size());
    CHECK_THROWS_WITH(deboorSurfacePatches(grid(3, 5, 1), 3, 5, EndCondition::Open, EndCondition::Open),
                      Catch::Contains("3 rows of de Boor points are too few for end condition \"open\" in u"));
    CHECK_THROWS_WITH(deboorSurfacePatches(grid(4, 2, 1), 4, 2, EndCondition::Clamped, EndCondition::Closed),
                      Catch::Contains("columns"));
}

} // namespace test_patch_complex
