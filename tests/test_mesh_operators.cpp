// HalfedgeMesh local operators: hand-checked results on small meshes, V - E + F and every invariant
// kept over long seeded random edit sequences, and the refusals (boundary flip, link condition).

#include <catch2/catch.hpp>

#include <freeform/mesh/halfedge.h>
#include <freeform/mesh/topology.h>

#include <algorithm>
#include <random>
#include <set>

#include "support/meshes.h"

namespace test_mesh_operators {

using namespace freeform;
using namespace freeform::test;

namespace {

/// The faces of the structure as sorted corner triples (orientation checked separately).
std::set<std::vector<int>> cornerSets(const HalfedgeMesh& h)
{
    std::set<std::vector<int>> out;
    for (int f = 0; f < h.faceCount(); ++f) {
        auto c = h.faceVertices(f);
        std::sort(c.begin(), c.end());
        out.insert(c);
    }
    return out;
}

/// Two triangles on the unit square, diagonal (0, 2): (0, 1, 2), (0, 2, 3).
PolygonMesh square()
{
    return meshFrom({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}});
}

/// Signed area of a structure face in the xy plane (its corners in order).
double signedArea(const HalfedgeMesh& h, int f)
{
    const auto c = h.faceVertices(f);
    double a = 0;
    for (std::size_t k = 0; k < c.size(); ++k) {
        const auto& p = h.position(c[k]);
        const auto& q = h.position(c[(k + 1) % c.size()]);
        a += p.x() * q.y() - q.x() * p.y();
    }
    return a / 2;
}

} // namespace

TEST_CASE("flip turns the diagonal of a square", "[operators]")
{
    HalfedgeMesh h(square());
    const int e = HalfedgeMesh::edge(h.findHalfedge(0, 2));
    REQUIRE(h.canFlip(e));
    h.flip(e);
    CHECK(h.checkInvariants().empty());
    CHECK(h.findHalfedge(0, 2) < 0);
    CHECK(h.findHalfedge(1, 3) >= 0);
    CHECK(cornerSets(h) == std::set<std::vector<int>>{{0, 1, 3}, {1, 2, 3}});
    for (int f = 0; f < 2; ++f) CHECK(signedArea(h, f) == 0.5); // still counter-clockwise
    CHECK(h.eulerCharacteristic() == 1);
    h.flip(e); // and back
    CHECK(cornerSets(h) == std::set<std::vector<int>>{{0, 1, 2}, {0, 2, 3}});
}

TEST_CASE("flip refusals", "[operators]")
{
    HalfedgeMesh sq(square());
    std::string why;
    const int boundary = HalfedgeMesh::edge(sq.findHalfedge(0, 1));
    CHECK(!sq.canFlip(boundary, &why));
    CHECK(why == "it is a boundary edge");
    CHECK_THROWS_WITH(sq.flip(boundary), "flip of edge " + std::to_string(boundary) + ": it is a boundary edge");
    CHECK(!sq.canFlip(99, &why));
    CHECK(why.find("there is no edge 99") != std::string::npos);

    // In a tetrahedron the flipped edge would duplicate an existing one.
    HalfedgeMesh tet(tetrahedron());
    CHECK(!tet.canFlip(0, &why));
    CHECK(why.find("exists already") != std::string::npos);
    CHECK(tet.checkInvariants().empty());

    HalfedgeMesh box(cube());
    CHECK(!box.canFlip(0, &why));
    CHECK(why == "its faces are not both triangles");
}

TEST_CASE("edge split: a vertex on the edge, adjacent triangles halved", "[operators]")
{
    HalfedgeMesh h(square());
    const int e = HalfedgeMesh::edge(h.findHalfedge(0, 2));
    const int m = h.splitEdge(e, Eigen::Vector3d(0.5, 0.5, 0));
    CHECK(m == 4);
    CHECK(h.checkInvariants().empty());
    CHECK(h.vertexCount() == 5);
    CHECK(h.edgeCount() == 8);
    CHECK(h.faceCount() == 4);
    CHECK(h.valence(m) == 4);
    CHECK(!h.isBoundaryVertex(m));
    CHECK(cornerSets(h) == std::set<std::vector<int>>{{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {0, 3, 4}});
    for (int f = 0; f < 4; ++f) CHECK(signedArea(h, f) == 0.25);
    CHECK(h.originalVertex(m) == -1);

    // A boundary edge: one triangle halved, the new vertex on the boundary.
    HalfedgeMesh b(square());
    const int mb = b.splitEdge(HalfedgeMesh::edge(b.findHalfedge(0, 1)), Eigen::Vector3d(0.5, 0, 0));
    CHECK(b.checkInvariants().empty());
    CHECK(b.isBoundaryVertex(mb));
    CHECK(b.valence(mb) == 3);
    CHECK(b.faceCount() == 3);
    CHECK(b.boundaryLoops().front().size() == 5);

    // A quad side: the quads just gain a corner.
    HalfedgeMesh c(cube());
    c.splitEdge(0, Eigen::Vector3d(0.5, 0.5, 0.5));
    CHECK(c.checkInvariants().empty());
    CHECK(c.faceCount() == 6);
    CHECK(c.eulerCharacteristic() == 2);
    CHECK_THROWS_WITH(c.splitEdge(0, Eigen::Vector3d(NAN, 0, 0)), Catch::Contains("not finite"));
}

TEST_CASE("face split: an n-gon becomes n triangles around the new vertex", "[operators]")
{
    HalfedgeMesh h(cube());
    const int m = h.splitFace(0, Eigen::Vector3d(0.5, 0.5, 0));
    CHECK(h.checkInvariants().empty());
    CHECK(h.vertexCount() == 9);
    CHECK(h.edgeCount() == 16);
    CHECK(h.faceCount() == 9);
    CHECK(h.valence(m) == 4);
    CHECK(h.eulerCharacteristic() == 2);
    std::vector<int> ring = h.vertexNeighbors(m);
    std::sort(ring.begin(), ring.end());
    CHECK(ring == std::vector<int>{0, 1, 2, 3});
    CHECK_THROWS_WITH(h.splitFace(42, Eigen::Vector3d::Zero()), Catch::Contains("there is no face 42"));
}

TEST_CASE("collapse of an interior edge of a fan", "[operators]")
{
    // Fan of 6: collapse centre -> rim vertex 1. The two triangles at the edge vanish; the rest
    // of the fan hangs on vertex 1.
    HalfedgeMesh h(fanDisk(6));
    const int he = h.findHalfedge(0, 1);
    REQUIRE(h.canCollapse(he));
    const int kept = h.collapse(he, Eigen::Vector3d(1, 0, 0));
    CHECK(h.checkInvariants().empty());
    CHECK(h.vertexCount() == 6);
    CHECK(h.faceCount() == 4);
    CHECK(h.eulerCharacteristic() == 1);
    CHECK(h.position(kept) == Eigen::Vector3d(1, 0, 0));
    CHECK(h.valence(kept) == 5);
    CHECK(h.isBoundaryVertex(kept));
    CHECK(h.boundaryLoops().size() == 1);
    CHECK(h.boundaryLoops().front().size() == 6);
}

TEST_CASE("collapse refusals: link condition, boundary pinch, folded triangle", "[operators]")
{
    std::string why;
    // Tetrahedron: the ends of every edge form a triangle with the opposite edge.
    HalfedgeMesh tet(tetrahedron());
    CHECK(!tet.canCollapse(0, &why));
    CHECK(why.find("link condition") != std::string::npos);
    CHECK_THROWS_WITH(tet.collapse(0, Eigen::Vector3d::Zero()), Catch::Contains("link condition"));
    CHECK(tet.checkInvariants().empty());
    CHECK(tet.faceCount() == 4);

    // Square: its diagonal joins two boundary vertices through the interior.
    HalfedgeMesh sq(square());
    CHECK(!sq.canCollapse(sq.findHalfedge(0, 2), &why));
    CHECK(why == "link condition: both ends lie on the boundary but the edge does not");
    // Its boundary edges may collapse (the square becomes one triangle) ...
    CHECK(sq.canCollapse(sq.findHalfedge(0, 1)));
    sq.collapse(sq.findHalfedge(0, 1), Eigen::Vector3d(0.5, 0, 0));
    CHECK(sq.checkInvariants().empty());
    CHECK(sq.faceCount() == 1);
    CHECK(sq.eulerCharacteristic() == 1);
    // ... but not the last triangle's.
    CHECK(!sq.canCollapse(0, &why));
    CHECK(why.find("fold onto the boundary") != std::string::npos);

    // Triangular bipyramid: (a, b, c) = (0, 1, 2) around the middle, apexes 3 and 4. The ends of a
    // middle edge have the third middle vertex as a common neighbour outside the edge's triangles.
    HalfedgeMesh bipyramid(meshFrom({{1, 0, 0}, {-0.5, 0.8, 0}, {-0.5, -0.8, 0}, {0, 0, 1}, {0, 0, -1}},
                                    {{3, 0, 1}, {3, 1, 2}, {3, 2, 0}, {4, 1, 0}, {4, 2, 1}, {4, 0, 2}}));
    REQUIRE(bipyramid.checkInvariants().empty());
    CHECK(!bipyramid.canCollapse(bipyramid.findHalfedge(0, 1), &why));
    CHECK(why == "link condition: the ends have the common neighbour 2 outside the edge's triangles");
    // Brute force over every halfedge: more common neighbours than the two opposite corners always
    // refuses; an apex edge is allowed and leaves a tetrahedron.
    int pinched = 0;
    for (int he = 0; he < bipyramid.halfedgeCount(); ++he) {
        std::vector<int> nu = bipyramid.vertexNeighbors(bipyramid.fromVertex(he));
        std::vector<int> nv = bipyramid.vertexNeighbors(bipyramid.toVertex(he));
        std::sort(nu.begin(), nu.end());
        std::sort(nv.begin(), nv.end());
        std::vector<int> common;
        std::set_intersection(nu.begin(), nu.end(), nv.begin(), nv.end(), std::back_inserter(common));
        if (common.size() > 2) {
            ++pinched;
            CHECK(!bipyramid.canCollapse(he));
        }
    }
    CHECK(pinched == 6);
    const int apex = bipyramid.findHalfedge(3, 0);
    REQUIRE(bipyramid.canCollapse(apex));
    bipyramid.collapse(apex, bipyramid.position(0));
    CHECK(bipyramid.checkInvariants().empty());
    CHECK(bipyramid.vertexCount() == 4);
    CHECK(bipyramid.edgeCount() == 6);
    CHECK(bipyramid.faceCount() == 4);

    // Faces that are not triangles.
    HalfedgeMesh box(cube());
    CHECK(!box.canCollapse(0, &why));
    CHECK(why == "the faces around its ends are not all triangles");
}

TEST_CASE("random edit sequences keep V - E + F, the genus and every invariant", "[operators]")
{
    struct Case {
        const char* name;
        PolygonMesh mesh;
        int euler;
        bool closed;
    };
    const std::vector<Case> cases{{"torus", splitQuads(quadTorus(7, 5)), 0, true},
                                  {"two-hole slab", splitQuads(holedSlab(2)), -2, true},
                                  {"disk", splitQuads(grid(5, 4)), 1, false},
                                  {"sphere", splitQuads(cube()), 2, true}};
    for (const Case& c : cases) {
        for (std::uint32_t seed = 1; seed <= 4; ++seed) {
            CAPTURE(c.name, seed);
            HalfedgeMesh h(c.mesh);
            REQUIRE(h.checkInvariants().empty());
            std::mt19937 rng(seed);
            int flips = 0, splits = 0, collapses = 0;
            for (int step = 0; step < 300; ++step) {
                const int op = std::uniform_int_distribution<int>(0, 3)(rng);
                const int e = std::uniform_int_distribution<int>(0, h.edgeCount() - 1)(rng);
                const int side = std::uniform_int_distribution<int>(0, 1)(rng);
                const int he = HalfedgeMesh::edgeHalfedge(e, side);
                const Eigen::Vector3d mid = (h.position(h.fromVertex(he)) + h.position(h.toVertex(he))) / 2;
                const int v0 = h.vertexCount(), e0 = h.edgeCount(), f0 = h.faceCount();
                if (op == 0) {
                    if (!h.canFlip(e)) continue;
                    h.flip(e);
                    CHECK((h.vertexCount() == v0 && h.edgeCount() == e0 && h.faceCount() == f0));
                    ++flips;
                } else if (op == 1) {
                    const int triangles = (h.face(2 * e) >= 0) + (h.face(2 * e + 1) >= 0);
                    h.splitEdge(e, mid);
                    CHECK((h.vertexCount() == v0 + 1 && h.edgeCount() == e0 + 1 + triangles && h.faceCount() == f0 + triangles));
                    ++splits;
                } else if (op == 2) {
                    const int f = std::uniform_int_distribution<int>(0, h.faceCount() - 1)(rng);
                    const int n = h.faceSize(f);
                    h.splitFace(f, mid);
                    CHECK((h.vertexCount() == v0 + 1 && h.edgeCount() == e0 + n && h.faceCount() == f0 + n - 1));
                } else {
                    if (!h.canCollapse(he)) continue;
                    const int triangles = (h.face(he) >= 0) + (h.face(he ^ 1) >= 0);
                    h.collapse(he, mid);
                    CHECK((h.vertexCount() == v0 - 1 && h.edgeCount() == e0 - 1 - triangles && h.faceCount() == f0 - triangles));
                    ++collapses;
                }
                const std::string problem = h.checkInvariants();
                INFO("step " << step << " op " << op);
                REQUIRE(problem.empty());
                REQUIRE(h.eulerCharacteristic() == c.euler);
            }
            CHECK(flips > 0);
            CHECK(splits > 0);
            CHECK(collapses > 0);
            // The edited structure, as a plain mesh, is still a manifold of the same topology.
            const MeshReport r = meshReport(h.toPolygonMesh());
            CHECK(r.manifold);
            CHECK(r.oriented);
            CHECK(r.components == 1);
            CHECK(r.euler == c.euler);
            CHECK(r.closed == c.closed);
        }
    }
}

TEST_CASE("collapse down a torus until the link condition stops it", "[operators]")
{
    HalfedgeMesh h(splitQuads(quadTorus(6, 4)));
    bool progress = true;
    while (progress) {
        progress = false;
        for (int he = 0; he < h.halfedgeCount(); ++he) {
            if (!h.canCollapse(he)) continue;
            h.collapse(he, h.position(h.toVertex(he)));
            REQUIRE(h.checkInvariants().empty());
            REQUIRE(h.eulerCharacteristic() == 0);
            progress = true;
            break;
        }
    }
    // The smallest triangulations of the torus have 7 vertices; collapses alone stop at or above it.
    CHECK(h.vertexCount() >= 7);
    CHECK(h.vertexCount() < 24);
    const MeshReport r = meshReport(h.toPolygonMesh());
    CHECK(r.manifold);
    CHECK(r.genus == 1);
}

} // namespace test_mesh_operators
