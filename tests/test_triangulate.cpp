// Polygon triangulation: fans for convex polygons, ear clipping for non-convex ones (checked by an
// independent area sum and inside tests), polygons placed in tilted and slightly bent planes, and
// whole meshes; the convex rings of the certified tessellations' leaves (mesh/convex_ring.h).

#include <catch2/catch.hpp>

#include <freeform/mesh/topology.h>
#include <freeform/mesh/triangulate.h>

#include <Eigen/Geometry>

#include <cmath>
#include <random>

#include "support/meshes.h"

// The certified tessellations' leaf triangulation (private to the library; header only).
#include "../freeform/src/mesh/convex_ring.h"

namespace test_triangulate {

using namespace freeform;
using namespace freeform::test;

namespace {

using Poly2 = Eigen::Matrix<double, 2, Eigen::Dynamic>;
constexpr double kPi = 3.14159265358979323846;

Poly2 poly(const std::vector<std::pair<double, double>>& xy)
{
    Poly2 p(2, static_cast<Eigen::Index>(xy.size()));
    for (std::size_t i = 0; i < xy.size(); ++i) p.col(static_cast<Eigen::Index>(i)) << xy[i].first, xy[i].second;
    return p;
}

long double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c)
{
    return (static_cast<long double>(b.x()) - a.x()) * (static_cast<long double>(c.y()) - a.y()) -
           (static_cast<long double>(b.y()) - a.y()) * (static_cast<long double>(c.x()) - a.x());
}

long double shoelace(const Poly2& p)
{
    long double a = 0;
    for (Eigen::Index i = 0; i < p.cols(); ++i) {
        const Eigen::Index j = (i + 1) % p.cols();
        a += static_cast<long double>(p(0, i)) * p(1, j) - static_cast<long double>(p(0, j)) * p(1, i);
    }
    return a / 2;
}

/// Crossing-number point-in-polygon test (strict interior for points off the boundary).
bool inside(const Poly2& p, const Eigen::Vector2d& q)
{
    bool in = false;
    for (Eigen::Index i = 0, j = p.cols() - 1; i < p.cols(); j = i++) {
        const Eigen::Vector2d a = p.col(i), b = p.col(j);
        if ((a.y() > q.y()) != (b.y() > q.y()) && q.x() < (b.x() - a.x()) * (q.y() - a.y()) / (b.y() - a.y()) + a.x())
            in = !in;
    }
    return in;
}

/// Segments ab and cd cross at a point interior to both.
bool properlyCross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c, const Eigen::Vector2d& d)
{
    const long double d1 = cross(a, b, c), d2 = cross(a, b, d), d3 = cross(c, d, a), d4 = cross(c, d, b);
    return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

/// The triangles tile the simple polygon: n - 2 of them, each a proper triangle turning the polygon's
/// way, every corner used, areas adding up to the polygon's, each inside it (centroid inside, no
/// edge crossing the boundary, no polygon corner strictly inside).
void requireTiling(const Poly2& p, const std::vector<std::array<int, 3>>& tris)
{
    const int n = static_cast<int>(p.cols());
    REQUIRE(static_cast<int>(tris.size()) == n - 2);
    const long double area = shoelace(p);
    const long double sense = area > 0 ? 1 : -1;
    long double sum = 0;
    std::vector<int> used(n, 0);
    for (const auto& t : tris) {
        for (int k : t) {
            REQUIRE((k >= 0 && k < n));
            ++used[k];
        }
        const Eigen::Vector2d a = p.col(t[0]), b = p.col(t[1]), c = p.col(t[2]);
        const long double twice = sense * cross(a, b, c);
        CHECK(twice > 0);
        sum += twice / 2;
        CHECK(inside(p, (a + b + c) / 3));
        for (int i = 0; i < n; ++i) {
            const Eigen::Vector2d q = p.col(i);
            if (i == t[0] || i == t[1] || i == t[2]) continue;
            const bool strictlyInside = sense * cross(a, b, q) > 0 && sense * cross(b, c, q) > 0 && sense * cross(c, a, q) > 0;
            CHECK(!strictlyInside);
            const Eigen::Vector2d r = p.col((i + 1) % n);
            for (const auto& [x, y] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) CHECK(!properlyCross(x, y, q, r));
        }
    }
    for (int k = 0; k < n; ++k) CHECK(used[k] > 0);
    CHECK(static_cast<double>(sum) == Approx(static_cast<double>(std::abs(area))).epsilon(1e-12));
}

} // namespace

TEST_CASE("convex polygons are fanned from corner 0", "[triangulate]")
{
    const auto hexagon = triangulatePolygon2(poly({{2, 0}, {1, 2}, {-1, 2}, {-2, 0}, {-1, -2}, {1, -2}}));
    CHECK(hexagon == std::vector<std::array<int, 3>>{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}});
    CHECK(triangulatePolygon2(poly({{0, 0}, {1, 0}, {1, 1}})) == std::vector<std::array<int, 3>>{{0, 1, 2}});
    // Collinear corners on a side do not make a square non-convex.
    requireTiling(poly({{0, 0}, {1, 0}, {2, 0}, {2, 2}, {0, 2}}), triangulatePolygon2(poly({{0, 0}, {1, 0}, {2, 0}, {2, 2}, {0, 2}})));
}

TEST_CASE("ear clipping of non-convex polygons", "[triangulate]")
{
    const std::vector<Poly2> shapes{
        poly({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}),                             // L
        poly({{0, 0}, {-1, -1}, {2, 0}, {-1, 1}}),                                          // arrowhead
        poly({{0, 0}, {5, 0}, {5, 3}, {4, 3}, {4, 1}, {3, 1}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}}), // comb
        poly({{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 1}, {1.5, 2.5}, {1, 1}, {1, 3}, {0, 3}}), // U with a spike
        poly({{0, 0}, {3, 0}, {3, 3}, {2, 1}, {1, 3}, {0, 3}}),                             // notch reaching down
    };
    for (std::size_t i = 0; i < shapes.size(); ++i) {
        CAPTURE(i);
        requireTiling(shapes[i], triangulatePolygon2(shapes[i]));
        // Clockwise input: the same tiling property, triangles clockwise.
        Poly2 reversed = shapes[i].rowwise().reverse();
        requireTiling(reversed, triangulatePolygon2(reversed));
    }
}

TEST_CASE("random star-shaped polygons", "[triangulate]")
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> radius(0.2, 1.0), jitter(0, 1);
    for (int trial = 0; trial < 200; ++trial) {
        const int n = 4 + trial % 40;
        Poly2 p(2, n);
        for (int i = 0; i < n; ++i) {
            const double a = 2 * kPi * (i + 0.8 * jitter(rng)) / n;
            const double r = radius(rng);
            p.col(i) << r * std::cos(a), r * std::sin(a);
        }
        CAPTURE(trial, n);
        requireTiling(p, triangulatePolygon2(p));
    }
}

TEST_CASE("polygons in 3D: projected onto their plane, tilted or slightly bent", "[triangulate]")
{
    const Poly2 comb = poly({{0, 0}, {5, 0}, {5, 3}, {4, 3}, {4, 1}, {3, 1}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}});
    const Eigen::Matrix3d rotation = (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())).toRotationMatrix();
    for (double bend : {0.0, 0.05}) {
        Eigen::Matrix<double, 3, Eigen::Dynamic> corners(3, comb.cols());
        for (Eigen::Index i = 0; i < comb.cols(); ++i) {
            const double x = comb(0, i), y = comb(1, i);
            corners.col(i) = rotation * Eigen::Vector3d(x, y, bend * std::sin(x + 2 * y)) + Eigen::Vector3d(3, -1, 2);
        }
        CAPTURE(bend);
        // The triangles are index triples, so they can be checked on the flat original.
        requireTiling(comb, triangulatePolygon(corners));
    }
}

TEST_CASE("degenerate and invalid polygons", "[triangulate]")
{
    // All corners on a line: still n - 2 triangles.
    Eigen::Matrix<double, 3, Eigen::Dynamic> line(3, 5);
    for (int i = 0; i < 5; ++i) line.col(i) = Eigen::Vector3d(i, 2 * i, 0);
    CHECK(triangulatePolygon(line).size() == 3);
    // A bow-tie (self-intersecting): n - 2 triangles over valid corners, no hang.
    const auto bowtie = triangulatePolygon2(poly({{0, 0}, {2, 2}, {2, 0}, {0, 2}, {-1, 1}}));
    CHECK(bowtie.size() == 3);
    CHECK_THROWS_WITH(triangulatePolygon(Eigen::Matrix<double, 3, Eigen::Dynamic>(3, 2)), Catch::Contains("at least 3"));
    Eigen::Matrix<double, 3, Eigen::Dynamic> nan = line;
    nan(1, 3) = NAN;
    CHECK_THROWS_WITH(triangulatePolygon(nan), Catch::Contains("not finite"));
}

TEST_CASE("triangulating a mesh keeps vertices, attributes and topology", "[triangulate]")
{
    PolygonMesh m = cube();
    m.texcoords = Eigen::Matrix<double, 2, Eigen::Dynamic>::Random(2, 8);
    std::vector<int> origin;
    const PolygonMesh t = triangulate(m, &origin);
    CHECK(t.faceCount() == 12);
    CHECK(t.isTriangleMesh());
    CHECK(t.positions == m.positions);
    CHECK(t.texcoords == m.texcoords);
    CHECK(origin == std::vector<int>{0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5});
    const MeshReport r = meshReport(t);
    CHECK(r.manifold);
    CHECK(r.oriented);
    CHECK(r.closed);
    CHECK(r.edges == 18);
    CHECK(r.genus == 0);
    // Each triangle lies in its quad and turns the same way (outward normal kept).
    for (int f = 0; f < t.faceCount(); ++f) {
        const int* c = t.face(f);
        const Eigen::Vector3d n = (t.positions.col(c[1]) - t.positions.col(c[0])).cross(t.positions.col(c[2]) - t.positions.col(c[0]));
        const Eigen::Vector3d centre = (t.positions.col(c[0]) + t.positions.col(c[1]) + t.positions.col(c[2])) / 3;
        CHECK(n.dot(centre - Eigen::Vector3d(0.5, 0.5, 0.5)) > 0);
    }
    // A non-convex face in a mesh.
    const PolygonMesh l = meshFrom({{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}}, {{0, 1, 2, 3, 4, 5}});
    const PolygonMesh lt = triangulate(l);
    CHECK(lt.faceCount() == 4);
    CHECK(meshReport(lt).boundaryEdges == 6);
}

// ---- The leaves' convex rings (freeform/src/mesh/convex_ring.h) --------------------------------

namespace {

using Ring = std::vector<std::array<long long, 2>>;
using Tri = std::array<int, 3>;

/// Twice the signed area of ring points a, b, c (integers: exact).
long long orient(const Ring& r, int a, int b, int c)
{
    const auto& p = r[static_cast<std::size_t>(a)];
    const auto& q = r[static_cast<std::size_t>(b)];
    const auto& s = r[static_cast<std::size_t>(c)];
    return (q[0] - p[0]) * (s[1] - p[1]) - (q[1] - p[1]) * (s[0] - p[0]);
}

template <class Order>
std::vector<Tri> clip(const Ring& r, const Order& order, bool* ok = nullptr)
{
    std::vector<int> ring(r.size());
    for (std::size_t i = 0; i < r.size(); ++i) ring[i] = static_cast<int>(i);
    std::vector<Tri> out;
    const bool done = detail::clipConvexRing(
        ring, [&](int a, int b, int c) { return orient(r, a, b, c); }, [&](int a, int b, int c) { out.push_back({a, b, c}); },
        order);
    if (ok) *ok = done;
    return out;
}

/// Checks what every triangulation of a convex ring must be: n - 2 triangles of positive area that
/// tile it (twice-areas summing to the ring's, by the shoelace formula), none with a ring point on
/// one of its edges or inside it but its own corners (so the mesh is conforming).
void checkTiling(const Ring& r, const std::vector<Tri>& tris)
{
    REQUIRE(tris.size() == r.size() - 2);
    long long shoelace = 0;
    for (std::size_t i = 0; i < r.size(); ++i) {
        const auto& p = r[i];
        const auto& q = r[(i + 1) % r.size()];
        shoelace += p[0] * q[1] - p[1] * q[0];
    }
    long long sum = 0;
    for (const Tri& t : tris) {
        const long long a = orient(r, t[0], t[1], t[2]);
        CHECK(a > 0);
        sum += a;
        for (int o = 0; o < static_cast<int>(r.size()); ++o) {
            if (o == t[0] || o == t[1] || o == t[2]) continue;
            const bool inClosed = orient(r, t[0], t[1], o) >= 0 && orient(r, t[1], t[2], o) >= 0 && orient(r, t[2], t[0], o) >= 0;
            INFO("triangle " << t[0] << " " << t[1] << " " << t[2] << ", point " << o);
            CHECK_FALSE(inClosed);
        }
    }
    CHECK(sum == shoelace);
}

// A 2 x 2 square with a point inside each side, counter-clockwise from (0, 0).
const Ring kSquare = {{0, 0}, {1, 0}, {2, 0}, {2, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};

} // namespace

TEST_CASE("convex ring: the next ear in turn, as the subdivision surfaces' leaves are cut", "[triangulate][ring]")
{
    // By hand: the first ear from index 0 is 0 (neighbours 7 and 1); after each cut the search
    // starts at the cut's place, whose point is now the next one, so the ring is fanned from 7
    // until (5, 6, 7) is the last triangle.
    bool ok = false;
    const std::vector<Tri> tris = clip(kSquare, detail::FirstEarInTurn{}, &ok);
    CHECK(ok);
    CHECK(tris == std::vector<Tri>{{7, 0, 1}, {7, 1, 2}, {7, 2, 3}, {7, 3, 4}, {7, 4, 5}, {5, 6, 7}});
    checkTiling(kSquare, tris);
}

TEST_CASE("convex ring: the ear whose new edge costs least, as the patches' leaves are cut", "[triangulate][ring]")
{
    SECTION("the cost is the squared distance of the ring points lifted onto the paraboloid z = x^2 + y^2")
    {
        const auto cost = [](int a, int c) {
            const auto d2 = [](const std::array<long long, 2>& p) { return double(p[0] * p[0] + p[1] * p[1]); };
            const auto& p = kSquare[static_cast<std::size_t>(a)];
            const auto& q = kSquare[static_cast<std::size_t>(c)];
            const double dx = double(p[0] - q[0]), dy = double(p[1] - q[1]), dz = d2(p) - d2(q);
            return dx * dx + dy * dy + dz * dz;
        };
        // By hand (heights 0, 1, 4, 5, 8, 5, 4, 1 round the ring): the corners 1, 3, 5, 7 lie inside
        // sides; the ears at 0 (new edge 7-1) and 4 (3-5) cost 2, those at 2 and 6 cost 18. Of equal
        // costs the first in the ring goes: (7, 0, 1). Then (3, 4, 5) at cost 2; then 2-5 and 3-6
        // cost 6: (2, 3, 5); then 2-6 costs 8: (2, 5, 6); then the four ears of 1, 2, 6, 7 all cost 14
        // and the first goes, (7, 1, 2), leaving (2, 6, 7).
        const std::vector<Tri> tris = clip(kSquare, cost);
        CHECK(tris == std::vector<Tri>{{7, 0, 1}, {3, 4, 5}, {2, 3, 5}, {2, 5, 6}, {7, 1, 2}, {2, 6, 7}});
        checkTiling(kSquare, tris);
    }
    SECTION("an ear that would leave the rest on one line is never cut, however cheap")
    {
        // (0, 0), (1, 0), (2, 0), (2, 1): cutting corner 3 would leave 0, 1, 2 on a line. Its new
        // edge 2-0 is made the cheapest (0), then the ear at 2 (edge 1-3, cost 1), then the one at 0
        // (edge 3-1, cost 2): the ear at 2 is cut, (1, 2, 3), leaving (0, 1, 3).
        const Ring r = {{0, 0}, {1, 0}, {2, 0}, {2, 1}};
        const auto cost = [](int a, int c) { return (a == 2 && c == 0) ? 0.0 : (a == 1 && c == 3) ? 1.0 : 2.0; };
        const std::vector<Tri> tris = clip(r, cost);
        CHECK(tris == std::vector<Tri>{{1, 2, 3}, {0, 1, 3}});
        checkTiling(r, tris);
        // In turn: corner 0 (neighbours 3 and 1) is the first ear, (3, 0, 1), leaving (1, 2, 3).
        const std::vector<Tri> turn = clip(r, detail::FirstEarInTurn{});
        CHECK(turn == std::vector<Tri>{{3, 0, 1}, {1, 2, 3}});
        checkTiling(r, turn);
    }
    SECTION("a ring without an area is refused")
    {
        const Ring flat = {{0, 0}, {1, 0}, {2, 0}, {3, 0}};
        bool ok = true;
        CHECK(clip(flat, detail::FirstEarInTurn{}, &ok).empty());
        CHECK_FALSE(ok);
        CHECK(clip(flat, [](int, int) { return 1.0; }, &ok).empty());
        CHECK_FALSE(ok);
    }
}

} // namespace test_triangulate
