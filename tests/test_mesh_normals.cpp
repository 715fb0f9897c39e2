// Face and vertex normals against hand-computed values: three weightings at a vertex whose faces
// differ in area and angle, a reflex polygon corner, Newell area vectors, and the degenerate cases.

#include <catch2/catch.hpp>

#include <freeform/mesh/normals.h>

#include <Eigen/Geometry>

#include <cmath>

#include "support/meshes.h"

namespace test_mesh_normals {

using namespace freeform;
using namespace freeform::test;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Three triangles at the origin with normals +z, +x, +y:
///   (0, (1,0,0), (1,1,0)): +z, area 1/2, angle pi/4
///   (0, (0,1,0), (0,0,3)): +x, area 3/2, angle pi/2
///   (0, (0,0,3), (2,0,0)): +y, area 3,   angle pi/2
PolygonMesh corner()
{
    return meshFrom({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 3}, {2, 0, 0}}, {{0, 1, 2}, {0, 3, 4}, {0, 4, 5}});
}

void checkClose(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double tol = 1e-15)
{
    INFO("got " << a.transpose() << ", expected " << b.transpose());
    CHECK((a - b).cwiseAbs().maxCoeff() <= tol);
}

} // namespace

TEST_CASE("face normals and area vectors", "[normals]")
{
    const PolygonMesh m = corner();
    const auto n = faceNormals(m);
    CHECK(n.col(0) == Eigen::Vector3d(0, 0, 1));
    CHECK(n.col(1) == Eigen::Vector3d(1, 0, 0));
    CHECK(n.col(2) == Eigen::Vector3d(0, 1, 0));
    const auto a = faceAreaVectors(m);
    CHECK(a.col(0) == Eigen::Vector3d(0, 0, 0.5));
    CHECK(a.col(1) == Eigen::Vector3d(1.5, 0, 0));
    CHECK(a.col(2) == Eigen::Vector3d(0, 3, 0));

    // An L-shaped hexagon of area 3 in the plane x + y + z = 1 (a rotation of the xy plane):
    // the area vector is 3 times the unit normal (1, 1, 1) / sqrt(3).
    const Eigen::Vector3d ex = Eigen::Vector3d(1, -1, 0).normalized();
    const Eigen::Vector3d ey = Eigen::Vector3d(1, 1, -2).normalized();
    const Eigen::Vector3d o(1.0 / 3, 1.0 / 3, 1.0 / 3);
    std::vector<Eigen::Vector3d> p;
    for (const auto& [x, y] : std::vector<std::pair<double, double>>{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}})
        p.push_back(o + x * ex + y * ey);
    const PolygonMesh l = meshFrom(p, {{0, 1, 2, 3, 4, 5}});
    checkClose(faceAreaVectors(l).col(0), 3 * Eigen::Vector3d(1, 1, 1) / std::sqrt(3.0), 1e-14);
    checkClose(faceNormals(l).col(0), Eigen::Vector3d(1, 1, 1) / std::sqrt(3.0));
}

TEST_CASE("vertex normals: uniform, area and angle weights", "[normals]")
{
    const PolygonMesh m = corner();
    checkClose(vertexNormals(m, NormalWeighting::Uniform).col(0), Eigen::Vector3d(1, 1, 1) / std::sqrt(3.0));
    // (3/2, 3, 1/2) / sqrt(11.5)
    checkClose(vertexNormals(m, NormalWeighting::Area).col(0), Eigen::Vector3d(1.5, 3, 0.5) / std::sqrt(11.5));
    // (pi/2, pi/2, pi/4) normalised = (2, 2, 1) / 3
    checkClose(vertexNormals(m, NormalWeighting::Angle).col(0), Eigen::Vector3d(2, 2, 1) / 3);
    // The default is angle weighting.
    CHECK(vertexNormals(m) == vertexNormals(m, NormalWeighting::Angle));
    // A vertex in one face has that face's normal under every weighting.
    for (auto w : {NormalWeighting::Uniform, NormalWeighting::Area, NormalWeighting::Angle}) {
        CHECK(vertexNormals(m, w).col(1) == Eigen::Vector3d(0, 0, 1));
        CHECK(vertexNormals(m, w).col(5) == Eigen::Vector3d(0, 1, 0));
    }
}

TEST_CASE("angle weight of a reflex polygon corner is its interior angle", "[normals]")
{
    // Arrowhead (0,0), (-1,-1), (2,0), (-1,1) in the xy plane: interior angle 3 pi / 2 at the origin.
    // With a triangle of normal +x and angle pi/2 at the origin: normalise(3pi/2 z + pi/2 x) = (1, 0, 3) / sqrt(10).
    const PolygonMesh m = meshFrom({{0, 0, 0}, {-1, -1, 0}, {2, 0, 0}, {-1, 1, 0}, {0, 1, 0}, {0, 0, 1}},
                                   {{0, 1, 2, 3}, {0, 4, 5}});
    checkClose(vertexNormals(m, NormalWeighting::Angle).col(0), Eigen::Vector3d(1, 0, 3) / std::sqrt(10.0));
    CHECK(faceAreaVectors(m).col(0) == Eigen::Vector3d(0, 0, 2));
    // The arrowhead's four angles add up to 2 pi: its other corners see normal +z only.
    checkClose(vertexNormals(m, NormalWeighting::Angle).col(2), Eigen::Vector3d(0, 0, 1));
}

TEST_CASE("closed meshes: vertex normals of a cube corner and a torus", "[normals]")
{
    // Cube corner: three unit quads, every weight equal -> (+-1, +-1, +-1) / sqrt(3), outward.
    const PolygonMesh c = cube();
    for (auto w : {NormalWeighting::Uniform, NormalWeighting::Area, NormalWeighting::Angle}) {
        const auto n = vertexNormals(c, w);
        for (int v = 0; v < 8; ++v) {
            const Eigen::Vector3d outward = (c.positions.col(v) - Eigen::Vector3d(0.5, 0.5, 0.5)) * 2 / std::sqrt(3.0);
            checkClose(n.col(v), outward, 1e-15);
        }
    }
    // Torus with fine quads: vertex normals approach the analytic normal (cos b cos a, cos b sin a, sin b).
    const int n = 64, m = 32;
    const PolygonMesh t = quadTorus(n, m);
    const auto normals = vertexNormals(t, NormalWeighting::Area);
    double worst = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < m; ++j) {
            const double a = 2 * kPi * i / n, b = 2 * kPi * j / m;
            const Eigen::Vector3d exact(std::cos(b) * std::cos(a), std::cos(b) * std::sin(a), std::sin(b));
            worst = std::max(worst, (normals.col(i * m + j) - exact).norm());
        }
    CHECK(worst < 1e-2); // second order in the grid spacing
}

TEST_CASE("degenerate cases give zero vectors, never NaN", "[normals]")
{
    // Face 0 has zero area (collinear corners); vertex 5 is isolated; vertex 6 sits between two
    // faces of opposite normals (a folded pair), whose uniform sum cancels.
    const PolygonMesh m = meshFrom({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {7, 7, 7}, {0, 0, 5}},
                                   {{0, 1, 2}, {6, 3, 4}, {6, 4, 3}});
    const auto fn = faceNormals(m);
    CHECK(fn.col(0) == Eigen::Vector3d::Zero());
    CHECK(fn.col(1).norm() == Approx(1));
    for (auto w : {NormalWeighting::Uniform, NormalWeighting::Area, NormalWeighting::Angle}) {
        const auto vn = vertexNormals(m, w);
        CHECK(vn.allFinite());
        CHECK(vn.col(0) == Eigen::Vector3d::Zero()); // only in the zero-area face
        CHECK(vn.col(5) == Eigen::Vector3d::Zero());
        CHECK(vn.col(6) == Eigen::Vector3d::Zero());
    }
}

TEST_CASE("weighting names and invalid meshes", "[normals]")
{
    CHECK(parseNormalWeighting("area", "--weights") == NormalWeighting::Area);
    CHECK(toString(NormalWeighting::Uniform) == "uniform");
    CHECK_THROWS_WITH(parseNormalWeighting("cotan", "--weights"), Catch::Contains("--weights") && Catch::Contains("cotan"));
    PolygonMesh bad = corner();
    bad.positions(1, 2) = NAN;
    CHECK_THROWS_WITH(vertexNormals(bad), Catch::Contains("vertex 2"));
}

} // namespace test_mesh_normals
