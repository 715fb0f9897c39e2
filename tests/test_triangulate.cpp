// Polygon triangulation: fans for convex polygons, ear clipping for non-convex ones (checked by an
// independent area sum and inside tests), polygons placed in tilted and slightly bent planes, and
// whole meshes.

#include <catch2/catch.hpp>

#include <freeform/mesh/topology.h>
#include <freeform/mesh/triangulate.h>

#include <Eigen/Geometry>

#include <cmath>
#include <random>

#include "support/meshes.h"

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

} // namespace test_triangulate
