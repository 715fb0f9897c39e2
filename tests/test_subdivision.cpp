// SubdivisionSurface (subdivision/subdivision_surface.h): OpenSubdiv's limit surface checked
// against independent computations: the bicubic Bézier patch of a regular face (tensor-product
// A-frame), the hand-computed limit masks of regular Catmull-Clark and Loop vertices and of crease
// vertices, the topology of the tessellated limit surface (closed, Euler characteristic, genus),
// affine cage deformation, and the errors for bad cages.

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "freeform/io/geometry_data.h"
#include "freeform/mesh/topology.h"
#include "freeform/subdivision/subdivision_surface.h"
#include "freeform/tessellate/tessellate.h"
#include "support/random.h"

namespace test_subdivision {

using namespace freeform;

namespace {

const std::string kCages = std::string(FREEFORM_SOURCE_DIR) + "/data/cages/";

/// rows x cols vertices on the integer grid with height z from a seeded random draw; quads
/// (r, c) (r + 1, c) (r + 1, c + 1) (r, c + 1), vertex (r, c) at r * cols + c.
SubdivisionCage gridCage(int rows, int cols, std::uint32_t seed)
{
    SubdivisionCage cage;
    const auto z = test::randomPoints<double, 1>(rows * cols, seed);
    cage.mesh.positions.resize(3, rows * cols);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) cage.mesh.positions.col(r * cols + c) = Eigen::Vector3d(r, c, z(0, r * cols + c));
    for (int r = 0; r + 1 < rows; ++r)
        for (int c = 0; c + 1 < cols; ++c)
            cage.mesh.addFace({r * cols + c, (r + 1) * cols + c, (r + 1) * cols + c + 1, r * cols + c + 1});
    return cage;
}

SubdivisionCage cubeCage()
{
    SubdivisionCage cage;
    cage.mesh.positions.resize(3, 8);
    for (int i = 0; i < 8; ++i) cage.mesh.positions.col(i) = Eigen::Vector3d(i & 4 ? 1 : -1, i & 2 ? 1 : -1, i & 1 ? 1 : -1);
    for (auto f : {std::array{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}})
        cage.mesh.addFace(f.begin(), f.end());
    return cage;
}

/// The limit point at cage vertex v: the corner of the first face that has it (quad corners at
/// (0,0) (1,0) (1,1) (0,1), triangle corners at (0,0) (1,0) (0,1)).
LimitPoint limitAtVertex(const SubdivisionSurface& s, int v)
{
    const PolygonMesh& m = s.cage().mesh;
    for (int f = 0; f < m.faceCount(); ++f)
        for (int k = 0; k < m.faceSize(f); ++k)
            if (m.face(f)[k] == v) {
                const double quad[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
                const double tri[3][2] = {{0, 0}, {1, 0}, {0, 1}};
                const double* uv = m.faceSize(f) == 4 ? quad[k] : tri[k];
                return s.evaluate(f, uv[0], uv[1]);
            }
    FAIL("vertex without a face");
    return {};
}

double relativeDifference(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
    return (a - b).norm() / std::max(1.0, b.norm());
}

} // namespace

TEST_CASE("regular faces: OpenSubdiv's limit surface is the A-frame Bezier patch", "[subdivision]")
{
    const SubdivisionSurface s(gridCage(6, 6, 7), SubdivisionScheme::Catmark);
    REQUIRE(s.faceCount() == 25);
    int regular = 0;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> unit(0, 1);
    double worst = 0;
    for (int f = 0; f < s.faceCount(); ++f) {
        const int r = f / 5, c = f % 5;
        const bool interior = r >= 1 && r <= 3 && c >= 1 && c <= 3;
        const auto patch = s.bezierPatch(f);
        CAPTURE(f);
        REQUIRE(patch.has_value() == interior);
        if (!patch) continue;
        ++regular;
        CHECK(s.isRegularPatch(f)); // OpenSubdiv agrees that the face is one regular patch
        // The neighbourhood is the 4 x 4 block of the grid around the face, r along u.
        const auto ring = *s.regularNeighbourhood(f);
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) CHECK(ring[static_cast<std::size_t>(i * 4 + j)] == (r - 1 + i) * 6 + (c - 1 + j));
        for (int k = 0; k < 40; ++k) {
            const double u = k < 4 ? (k & 1) : unit(rng), v = k < 4 ? (k >> 1) : unit(rng);
            const LimitPoint p = s.evaluate(f, u, v);
            const auto jet = patch->jet(u, v, 1);
            worst = std::max({worst, relativeDifference(p.position, jet.col(0)), relativeDifference(p.du, jet.col(1)),
                              relativeDifference(p.dv, jet.col(2))});
        }
    }
    CHECK(regular == 9);
    CHECK(worst < 1e-12);
}

TEST_CASE("the limit point of a regular vertex is (16 v + 4 sum edge + sum diagonal) / 36", "[subdivision]")
{
    SECTION("grid")
    {
        const SubdivisionSurface s(gridCage(6, 6, 3), SubdivisionScheme::Catmark);
        const auto& p = s.cage().mesh.positions;
        for (int r = 1; r <= 4; ++r)
            for (int c = 1; c <= 4; ++c) {
                auto at = [&](int dr, int dc) { return Eigen::Vector3d(p.col((r + dr) * 6 + c + dc)); };
                const Eigen::Vector3d expected =
                    (16 * at(0, 0) + 4 * (at(1, 0) + at(-1, 0) + at(0, 1) + at(0, -1)) + at(1, 1) + at(1, -1) + at(-1, 1) + at(-1, -1)) / 36;
                CAPTURE(r, c);
                CHECK(relativeDifference(limitAtVertex(s, r * 6 + c).position, expected) < 1e-14);
            }
    }
    SECTION("torus cage, every vertex regular")
    {
        const SubdivisionSurface s(readCage(kCages + "torus.obj"), SubdivisionScheme::Catmark);
        const auto& p = s.cage().mesh.positions;
        auto at = [&](int i, int j) { return Eigen::Vector3d(p.col(((i + 8) % 8) * 4 + (j + 4) % 4)); };
        for (int i = 0; i < 8; ++i)
            for (int j = 0; j < 4; ++j) {
                const Eigen::Vector3d expected = (16 * at(i, j) + 4 * (at(i + 1, j) + at(i - 1, j) + at(i, j + 1) + at(i, j - 1)) +
                                                  at(i + 1, j + 1) + at(i + 1, j - 1) + at(i - 1, j + 1) + at(i - 1, j - 1)) / 36;
                CHECK(relativeDifference(limitAtVertex(s, i * 4 + j).position, expected) < 1e-14);
                CHECK(s.bezierPatch(i * 4 + j).has_value());
            }
    }
}

TEST_CASE("Loop: the limit point of a valence-n vertex follows Loop's limit mask", "[subdivision]")
{
    // Loop (1987): v_inf = (1 - n chi) v + chi sum neighbours, chi = 1 / (3 / (8 beta) + n),
    // beta = (5/8 - (3/8 + cos(2 pi / n) / 4)^2) / n. The octahedron: n = 4 everywhere.
    SubdivisionCage cage = readCage(kCages + "octahedron.obj");
    REQUIRE(defaultScheme(cage.mesh) == SubdivisionScheme::Loop);
    cage.mesh.positions.col(0) = Eigen::Vector3d(1.5, 0.25, -0.125); // break the symmetry
    const SubdivisionSurface s(cage, SubdivisionScheme::Loop);
    const long double pi = 3.141592653589793238462643383279502884L;
    const long double t = 0.375L + std::cos(2 * pi / 4) / 4;
    const long double beta = (0.625L - t * t) / 4;
    const double chi = static_cast<double>(1 / (3 / (8 * beta) + 4));
    const auto& p = cage.mesh.positions;
    const int neighbours[6][4] = {{2, 3, 4, 5}, {2, 3, 4, 5}, {0, 1, 4, 5}, {0, 1, 4, 5}, {0, 1, 2, 3}, {0, 1, 2, 3}};
    for (int v = 0; v < 6; ++v) {
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        for (int n : neighbours[v]) sum += p.col(n);
        const Eigen::Vector3d expected = (1 - 4 * chi) * p.col(v) + chi * sum;
        CAPTURE(v);
        CHECK(relativeDifference(limitAtVertex(s, v).position, expected) < 1e-12);
    }
}

TEST_CASE("tessellation: closed cages give closed meshes of the right genus", "[subdivision]")
{
    SECTION("cube: closed genus 0, V = 8 + 12 (n-1) + 6 (n-1)^2, normals outward")
    {
        const SubdivisionSurface s(readCage(kCages + "cube.obj"), SubdivisionScheme::Catmark);
        SubdivisionTessellationOptions o;
        o.level = 5;
        const PolygonMesh m = s.tessellate(o);
        CHECK(m.vertexCount() == 8 + 12 * 4 + 6 * 16);
        CHECK(m.isTriangleMesh());
        const MeshReport r = meshReport(m);
        CHECK(r.closed);
        CHECK(r.manifold);
        CHECK(r.oriented);
        CHECK(r.euler == 2);
        REQUIRE(r.genus.has_value());
        CHECK(*r.genus == 0);
        for (int v = 0; v < m.vertexCount(); ++v) {
            CHECK(std::abs(m.normals.col(v).norm() - 1) < 1e-12);
            CHECK(m.normals.col(v).dot(m.positions.col(v)) > 0.5 * m.positions.col(v).norm());
        }
        // Triangles agree with the analytic normals at their corners (no flipped or crossed ones).
        for (int f = 0; f < m.faceCount(); ++f) {
            const int* t = m.face(f);
            const Eigen::Vector3d n = (m.positions.col(t[1]) - m.positions.col(t[0])).cross(m.positions.col(t[2]) - m.positions.col(t[0]));
            for (int k = 0; k < 3; ++k) CHECK(n.dot(m.normals.col(t[k])) > 0);
        }
    }
    SECTION("torus cage: closed genus 1, uniform and adaptive")
    {
        const SubdivisionSurface s(readCage(kCages + "torus.obj"), SubdivisionScheme::Catmark);
        for (double tolerance : {0.0, 1e-3}) {
            SubdivisionTessellationOptions o;
            o.level = 3;
            o.tolerance = tolerance;
            o.certified = false; // the per-face rates (the certified path: test_subdivision_tessellation)
            SubdivisionTessellationReport report;
            const MeshReport r = meshReport(s.tessellate(o, &report));
            CAPTURE(tolerance);
            CHECK(r.closed);
            CHECK(r.euler == 0);
            REQUIRE(r.genus.has_value());
            CHECK(*r.genus == 1);
            if (tolerance > 0) {
                CHECK(report.regularFaces == 32);
                // The certified bound of each face's Bézier patch at its rate is within the tolerance.
                for (int f = 0; f < 32; ++f)
                    CHECK(tessellationErrorBound(*s.bezierPatch(f), report.rates[static_cast<std::size_t>(f)],
                                                 report.rates[static_cast<std::size_t>(f)]) <= 1e-3);
            }
        }
    }
    SECTION("octahedron under Loop: closed genus 0")
    {
        const SubdivisionSurface s(readCage(kCages + "octahedron.obj"), SubdivisionScheme::Loop);
        SubdivisionTessellationOptions o;
        o.level = 4;
        const PolygonMesh m = s.tessellate(o);
        CHECK(m.vertexCount() == 6 + 12 * 3 + 8 * 3); // interior points of a rate-4 triangle: 3
        const MeshReport r = meshReport(m);
        CHECK(r.closed);
        CHECK(r.euler == 2);
        CHECK(r.genus == std::optional<int>(0));
    }
    SECTION("a pentagon and a triangle under Catmull-Clark (quad sub-faces)")
    {
        SubdivisionCage cage;
        cage.mesh.positions.resize(3, 6);
        cage.mesh.positions << 0, 1, 2, 2, 0, 1, 0, 0, 0, 1, 1, 2, 0, 0.2, 0, 0.1, 0, 0.3;
        cage.mesh.addFace({0, 1, 2, 3, 4});
        cage.mesh.addFace({4, 3, 5});
        const SubdivisionSurface s(cage, SubdivisionScheme::Catmark);
        const MeshReport r = meshReport(s.tessellate());
        CHECK(r.boundaryLoops == 1);
        CHECK(r.euler == 1);
        CHECK(r.manifold);
        CHECK(r.oriented);
    }
}

TEST_CASE("creases stay sharp", "[subdivision]")
{
    SECTION("a cube with all twelve edges infinitely sharp is the cube")
    {
        SubdivisionCage cage = cubeCage();
        const PolygonMesh& m = cage.mesh;
        for (int f = 0; f < m.faceCount(); ++f)
            for (int k = 0; k < 4; ++k)
                if (m.face(f)[k] < m.face(f)[(k + 1) % 4]) cage.creases.push_back({m.face(f)[k], m.face(f)[(k + 1) % 4], kInfiniteSharpness});
        REQUIRE(cage.creases.size() == 12);
        const SubdivisionSurface s(cage, SubdivisionScheme::Catmark);
        for (int v = 0; v < 8; ++v) CHECK(relativeDifference(limitAtVertex(s, v).position, m.positions.col(v)) < 1e-12);
        // Every corner has three sharp edges, so the limit along an edge is the straight edge.
        for (int f = 0; f < 6; ++f)
            for (double t : {0.25, 0.5, 0.8}) {
                const Eigen::Vector3d expected = (1 - t) * m.positions.col(m.face(f)[0]) + t * m.positions.col(m.face(f)[1]);
                CHECK(relativeDifference(s.evaluate(f, t, 0).position, expected) < 1e-12);
            }
    }
    SECTION("creased_cube.obj: tags read, sharp corners interpolated, crease vertices on the B-spline")
    {
        const SubdivisionCage cage = readCage(kCages + "creased_cube.obj");
        REQUIRE(cage.creases.size() == 4);
        REQUIRE(cage.corners.size() == 2);
        CHECK(cage.creases[1].v0 == 3);
        CHECK(cage.creases[1].v1 == 7);
        CHECK(cage.creases[1].sharpness == 10);
        const SubdivisionSurface s(cage, SubdivisionScheme::Catmark);
        const auto& p = cage.mesh.positions;
        CHECK(relativeDifference(limitAtVertex(s, 1).position, p.col(1)) < 1e-12);
        CHECK(relativeDifference(limitAtVertex(s, 7).position, p.col(7)) < 1e-12);
        // Vertices 3 and 5 have two sharp edges: the crease rule's limit (a + 4 v + b) / 6.
        CHECK(relativeDifference(limitAtVertex(s, 5).position, (p.col(1) + 4 * p.col(5) + p.col(7)) / 6) < 1e-12);
        CHECK(relativeDifference(limitAtVertex(s, 3).position, (p.col(1) + 4 * p.col(3) + p.col(7)) / 6) < 1e-12);
        // Without the tags, vertex 1 is smoothed away from the cage.
        SubdivisionCage smooth = cage;
        smooth.creases.clear();
        smooth.corners.clear();
        CHECK((limitAtVertex(SubdivisionSurface(smooth, SubdivisionScheme::Catmark), 1).position - p.col(1)).norm() > 0.5);
    }
    SECTION("bad tags name the line")
    {
        SubdivisionCage cage = cubeCage();
        CHECK_THROWS_WITH(parseCreaseTags("v 0 0 0\nt crease 2/1 0 9 1\n", "c.obj", cage), Catch::Contains("c.obj:2") && Catch::Contains("out of range"));
        CHECK_THROWS_WITH(parseCreaseTags("t hole 1/0 0\n", "c.obj", cage), Catch::Contains("c.obj:1") && Catch::Contains("hole"));
        CHECK_THROWS_WITH(parseCreaseTags("t crease 2/2 0 1 1\n", "c.obj", cage), Catch::Contains("sharpness values"));
        CHECK_THROWS_WITH(parseCreaseTags("t corner 1/1 0 -1\n", "c.obj", cage), Catch::Contains(">= 0"));
    }
}

TEST_CASE("cage deformation: affine lattices commute with the limit, others do not", "[subdivision]")
{
    const SubdivisionCage cage = readCage(kCages + "torus.obj");
    const SubdivisionSurface s(cage, SubdivisionScheme::Catmark);
    Lattice rest = Lattice::fit(cage.mesh.positions, {1, 1, 1});
    Eigen::Matrix3d a;
    a << 1.2, 0.3, -0.1, 0.05, 0.9, 0.2, -0.3, 0.1, 1.4;
    const Eigen::Vector3d b(0.5, -0.25, 2);
    Lattice affine = rest;
    Lattice::Points moved = rest.restPoints();
    for (Eigen::Index i = 0; i < moved.cols(); ++i) moved.col(i) = a * moved.col(i) + b;
    affine.setControlPoints(moved);
    const SubdivisionSurface deformed(deformCage(cage, affine), SubdivisionScheme::Catmark);
    // A degree-2 lattice with its centre point lifted: a non-affine map.
    Lattice bent = Lattice::fit(cage.mesh.positions, {2, 2, 2});
    bent.setControlPoint(1, 1, 1, bent.controlPoint(1, 1, 1) + Eigen::Vector3d(0.7, -0.4, 1.5));
    const SubdivisionCage bentCage = deformCage(cage, bent);
    const SubdivisionSurface bentSurface(bentCage, SubdivisionScheme::Catmark);
    // withPositions keeps the topology and gives the same surface as a fresh build.
    const SubdivisionSurface reused = s.withPositions(bentCage.mesh.positions);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(0, 1);
    double worst = 0, largestGap = 0;
    for (int f = 0; f < s.faceCount(); ++f)
        for (int k = 0; k < 10; ++k) {
            const double u = unit(rng), v = unit(rng);
            const LimitPoint p = s.evaluate(f, u, v), q = deformed.evaluate(f, u, v);
            worst = std::max({worst, relativeDifference(q.position, a * p.position + b), relativeDifference(q.du, a * p.du),
                              relativeDifference(q.dv, a * p.dv)});
            Eigen::Matrix3Xd point = p.position;
            deformPoints(bent, point);
            const LimitPoint r = bentSurface.evaluate(f, u, v);
            largestGap = std::max(largestGap, (r.position - point.col(0)).norm());
            CHECK(reused.evaluate(f, u, v).position == r.position);
        }
    CHECK(worst < 1e-12);
    CHECK(largestGap > 1e-2);
}

TEST_CASE("bad cages are clear errors", "[subdivision]")
{
    auto build = [](const SubdivisionCage& c, SubdivisionScheme scheme = SubdivisionScheme::Catmark) {
        return SubdivisionSurface(c, scheme);
    };
    SubdivisionCage cage = cubeCage();
    SECTION("out-of-range index")
    {
        cage.mesh.addFace({0, 1, 8});
        CHECK_THROWS_WITH(build(cage), Catch::Contains("face 6") && Catch::Contains("vertex 8"));
    }
    SECTION("repeated vertex (degenerate face)")
    {
        cage.mesh.faceVertices[2] = 0; // face 0 becomes 0 1 0 2
        CHECK_THROWS_WITH(build(cage), Catch::Contains("face 0") && Catch::Contains("vertex 0 twice"));
    }
    SECTION("two corners")
    {
        cage.mesh.addFace({0, 1});
        CHECK_THROWS_WITH(build(cage), Catch::Contains("face 6") && Catch::Contains("fewer than 3"));
    }
    SECTION("an edge with three faces")
    {
        SubdivisionCage fin = gridCage(2, 3, 1); // two quads sharing edge 1-4
        fin.mesh.positions.conservativeResize(3, 7);
        fin.mesh.positions.col(6) = Eigen::Vector3d(0.5, 1, 1);
        fin.mesh.addFace({4, 1, 6});
        CHECK_THROWS_WITH(build(fin), Catch::Contains("not manifold") || Catch::Contains("inconsistent"));
    }
    SECTION("inconsistent orientation")
    {
        std::reverse(cage.mesh.faceVertices.begin(), cage.mesh.faceVertices.begin() + 4);
        CHECK_THROWS_WITH(build(cage), Catch::Contains("runs the same way"));
    }
    SECTION("two fans at one vertex (bowtie)")
    {
        SubdivisionCage bow;
        bow.mesh.positions = test::randomPoints<double, 3>(5, 3);
        bow.mesh.addFace({0, 1, 2});
        bow.mesh.addFace({0, 3, 4});
        CHECK_THROWS_WITH(build(bow), Catch::Contains("vertex 0") && Catch::Contains("fans"));
    }
    SECTION("quads under Loop")
    {
        CHECK_THROWS_WITH(build(cage, SubdivisionScheme::Loop), Catch::Contains("face 0 has 4 vertices") && Catch::Contains("Loop"));
    }
    SECTION("a crease on a missing edge, a bad sharpness")
    {
        cage.creases.push_back({0, 7, 2});
        CHECK_THROWS_WITH(build(cage), Catch::Contains("crease 0") && Catch::Contains("no such edge"));
        cage.creases = {{0, 1, std::nan("")}};
        CHECK_THROWS_WITH(build(cage), Catch::Contains("sharpness"));
        cage.creases.clear();
        cage.corners = {{9, 1}};
        CHECK_THROWS_WITH(build(cage), Catch::Contains("corner 0") && Catch::Contains("out of range"));
    }
    SECTION("evaluation outside a face's domain")
    {
        const SubdivisionSurface s(cage, SubdivisionScheme::Catmark);
        CHECK_THROWS_WITH(s.evaluate(6, 0, 0), Catch::Contains("face 6 is out of range"));
        CHECK_THROWS_WITH(s.evaluate(0, 1.5, 0), Catch::Contains("outside the domain of face 0"));
        CHECK_THROWS_WITH(s.withPositions(Eigen::Matrix3Xd::Zero(3, 7)), Catch::Contains("7 positions for 8"));
    }
}

TEST_CASE("boundary interpolation none: boundary faces have no limit surface", "[subdivision]")
{
    const SubdivisionSurface s(gridCage(5, 5, 2), SubdivisionScheme::Catmark, BoundaryInterpolation::None);
    int with = 0;
    for (int f = 0; f < s.faceCount(); ++f) with += s.hasLimitSurface(f);
    CHECK(with == 4); // the 2 x 2 inner quads
    CHECK_THROWS_WITH(s.evaluate(0, 0.5, 0.5), Catch::Contains("no limit surface"));
    const MeshReport r = meshReport(s.tessellate());
    CHECK(r.boundaryLoops == 1);
    CHECK(r.euler == 1);
    CHECK(parseBoundaryInterpolation("edge_and_corner", "x") == BoundaryInterpolation::EdgeAndCorner);
    CHECK_THROWS_WITH(parseBoundaryInterpolation("sharp", "boundary"), Catch::Contains("boundary") && Catch::Contains("edge_only"));
}

TEST_CASE("documents: creases, corners and boundary round-trip and reach the cage", "[subdivision]")
{
    const std::string text = R"({"format": "freeform", "version": 1, "objects": [
        {"name": "s", "type": "subdivision_surface", "scheme": "catmark",
         "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "faces": [[0,1,2,3]],
         "creases": [[0, 1, 10], [1, 2, 2.5]], "corners": [[3, 4]], "boundary": "edge_and_corner"}]})";
    const Document doc = parseDocument(text, "doc");
    const auto& d = std::get<SubdivisionSurfaceData>(doc.objects[0].data);
    REQUIRE(d.creases.size() == 2);
    CHECK(d.creases[1] == std::array<double, 3>{1, 2, 2.5});
    CHECK(d.boundary == "edge_and_corner");
    const Document again = parseDocument(formatDocument(doc), "again");
    const auto& e = std::get<SubdivisionSurfaceData>(again.objects[0].data);
    CHECK(e.creases == d.creases);
    CHECK(e.corners == d.corners);
    CHECK(e.boundary == d.boundary);
    const SubdivisionSurface s = surfaceFromData(d, "", "doc: s");
    CHECK(s.boundary() == BoundaryInterpolation::EdgeAndCorner);
    REQUIRE(s.cage().creases.size() == 2);
    CHECK(s.cage().corners[0].vertex == 3);
    CHECK(s.cage().corners[0].sharpness == 4);
    // A sharp crease on edge 0-1 of a single quad: the limit runs along the cage edge.
    CHECK((s.evaluate(0, 0.5, 0).position - Eigen::Vector3d(0.5, 0, 0)).norm() < 1e-12);

    CHECK_THROWS_WITH(parseDocument(R"({"format": "freeform", "version": 1, "objects": [{"name": "s", "type": "subdivision_surface",
        "mesh": "x.obj", "creases": [[0, 1]]}]})", "doc"), Catch::Contains("creases[0]"));
    CHECK_THROWS_WITH(parseDocument(R"({"format": "freeform", "version": 1, "objects": [{"name": "s", "type": "subdivision_surface",
        "mesh": "x.obj", "corners": [[0, -1]]}]})", "doc"), Catch::Contains("sharpness must be >= 0"));
    CHECK_THROWS_WITH(parseDocument(R"({"format": "freeform", "version": 1, "objects": [{"name": "s", "type": "subdivision_surface",
        "mesh": "x.obj", "boundary": "sharp"}]})", "doc"), Catch::Contains("boundary"));
    SubdivisionSurfaceData bad = d;
    bad.creases = {{0, 2, 10}};
    CHECK_THROWS_WITH(surfaceFromData(bad, "", "doc: s"), Catch::StartsWith("doc: s: ") && Catch::Contains("no such edge"));
}

} // namespace test_subdivision
