// HalfedgeMesh: the structure of hand-built meshes (counts, opposite/next/face/to-vertex, fans,
// boundary loops, valence and 1-rings), and non-manifold or inconsistent input split and reported
// with the structure left sound.

#include <catch2/catch.hpp>

#include <freeform/mesh/halfedge.h>

#include <algorithm>
#include <set>

#include "support/meshes.h"

namespace test_halfedge {

using namespace freeform;
using namespace freeform::test;

namespace {

/// Rotates a cyclic sequence so that its smallest element comes first.
std::vector<int> canonicalCycle(std::vector<int> cycle)
{
    std::rotate(cycle.begin(), std::min_element(cycle.begin(), cycle.end()), cycle.end());
    return cycle;
}

/// Every face of the input reappears in the structure with the same corners in the same order.
void requireSameFaces(const HalfedgeMesh& h, const PolygonMesh& m)
{
    REQUIRE(h.faceCount() == m.faceCount());
    for (int f = 0; f < m.faceCount(); ++f) {
        std::vector<int> corners;
        for (int v : h.faceVertices(f)) corners.push_back(h.originalVertex(v));
        CHECK(corners == std::vector<int>(m.face(f), m.face(f) + m.faceSize(f)));
    }
}

} // namespace

TEST_CASE("tetrahedron: every halfedge has its opposite, a face and the right ends", "[halfedge]")
{
    const PolygonMesh m = tetrahedron();
    const HalfedgeMesh h(m);
    CHECK(h.checkInvariants().empty());
    CHECK(h.buildReport().clean());
    CHECK(h.vertexCount() == 4);
    CHECK(h.edgeCount() == 6);
    CHECK(h.faceCount() == 4);
    CHECK(h.halfedgeCount() == 12);
    CHECK(h.eulerCharacteristic() == 2);
    CHECK(h.isClosed());
    CHECK(h.boundaryLoops().empty());
    requireSameFaces(h, m);
    for (int e = 0; e < h.halfedgeCount(); ++e) {
        CHECK(h.face(e) >= 0);
        CHECK(HalfedgeMesh::opposite(HalfedgeMesh::opposite(e)) == e);
        CHECK(h.fromVertex(e) == h.toVertex(HalfedgeMesh::opposite(e)));
        CHECK(h.face(e) != h.face(HalfedgeMesh::opposite(e)));
        CHECK(h.next(h.next(h.next(e))) == e); // triangles
    }
    for (int v = 0; v < 4; ++v) {
        CHECK(h.valence(v) == 3);
        CHECK(h.vertexFaces(v).size() == 3);
        std::vector<int> ring = h.vertexNeighbors(v);
        std::sort(ring.begin(), ring.end());
        std::vector<int> others;
        for (int w = 0; w < 4; ++w)
            if (w != v) others.push_back(w);
        CHECK(ring == others);
        CHECK(!h.isBoundaryVertex(v));
    }
}

TEST_CASE("1-ring of an interior vertex runs counter-clockwise", "[halfedge]")
{
    // Fan of 6 around the centre of the xy plane, faces counter-clockwise seen from +z.
    const HalfedgeMesh h(fanDisk(6));
    REQUIRE(h.checkInvariants().empty());
    const std::vector<int> ring = canonicalCycle(h.vertexNeighbors(0));
    CHECK(ring == std::vector<int>{1, 2, 3, 4, 5, 6});
    CHECK(h.valence(0) == 6);
    CHECK(canonicalCycle(h.vertexFaces(0)) == std::vector<int>{0, 1, 2, 3, 4, 5});
    CHECK(!h.isBoundaryVertex(0));
    // A rim vertex: the boundary halfedge first, then its neighbours counter-clockwise.
    CHECK(h.isBoundaryVertex(1));
    CHECK(h.valence(1) == 3);
    CHECK(h.vertexNeighbors(1) == std::vector<int>{6, 2, 0}); // boundary edge 1 -> 6, then 2, then centre
    CHECK(h.face(h.outgoing(1)) == -1);
    CHECK(h.vertexFaces(1) == std::vector<int>{0, 5});
}

TEST_CASE("disk: one boundary loop running against the faces", "[halfedge]")
{
    const HalfedgeMesh h(fanDisk(5));
    REQUIRE(h.checkInvariants().empty());
    CHECK(!h.isClosed());
    const auto loops = h.boundaryLoops();
    REQUIRE(loops.size() == 1);
    REQUIRE(loops[0].size() == 5);
    std::vector<int> vertices;
    for (int e : loops[0]) vertices.push_back(h.fromVertex(e));
    // The rim is 1..5 counter-clockwise; the boundary loop runs the other way.
    CHECK(canonicalCycle(vertices) == std::vector<int>{1, 5, 4, 3, 2});
    for (int e : loops[0]) {
        CHECK(h.face(e) == -1);
        CHECK(h.face(HalfedgeMesh::opposite(e)) >= 0);
        CHECK(h.isBoundaryEdge(HalfedgeMesh::edge(e)));
    }
    const HalfedgeMesh g(grid(3, 2));
    REQUIRE(g.boundaryLoops().size() == 1);
    CHECK(g.boundaryLoops()[0].size() == 10);
    CHECK(g.eulerCharacteristic() == 1);
}

TEST_CASE("cube, quad torus and a slab with two holes", "[halfedge]")
{
    const HalfedgeMesh cube3(cube());
    CHECK(cube3.checkInvariants().empty());
    CHECK(cube3.eulerCharacteristic() == 2);
    CHECK(cube3.faceSize(0) == 4);
    for (int v = 0; v < 8; ++v) CHECK(cube3.valence(v) == 3);

    const HalfedgeMesh torus(quadTorus(8, 5));
    CHECK(torus.checkInvariants().empty());
    CHECK(torus.buildReport().clean());
    CHECK(torus.vertexCount() == 40);
    CHECK(torus.edgeCount() == 80);
    CHECK(torus.eulerCharacteristic() == 0);
    for (int v = 0; v < 40; ++v) CHECK(torus.valence(v) == 4);

    const PolygonMesh slab = holedSlab(2);
    const HalfedgeMesh two(slab);
    CHECK(two.checkInvariants().empty());
    CHECK(two.buildReport().clean());
    CHECK(two.isClosed());
    CHECK(two.edgeCount() == countEdges(slab));
    CHECK(two.eulerCharacteristic() == -2); // 2 - 2 g, g = 2
}

TEST_CASE("components of the structure", "[halfedge]")
{
    const PolygonMesh m = disjointUnion(tetrahedron(), quadTorus(4, 3));
    const HalfedgeMesh h(m);
    const auto c = h.components();
    CHECK(c.count == 2);
    for (int f = 0; f < 4; ++f) CHECK(c.ofFace[f] == 0);
    for (int f = 4; f < m.faceCount(); ++f) CHECK(c.ofFace[f] == 1);
    CHECK(c.ofVertex[3] == 0);
    CHECK(c.ofVertex[4] == 1);
}

TEST_CASE("isolated vertices stay, without halfedges", "[halfedge]")
{
    PolygonMesh m = tetrahedron();
    m.positions.conservativeResize(3, 5);
    m.positions.col(4) = Eigen::Vector3d(9, 9, 9);
    const HalfedgeMesh h(m);
    CHECK(h.checkInvariants().empty());
    CHECK(h.vertexCount() == 5);
    CHECK(h.isIsolated(4));
    CHECK(h.valence(4) == 0);
    CHECK(h.vertexNeighbors(4).empty());
    CHECK(h.components().ofVertex[4] == -1);
}

TEST_CASE("three triangles on one edge: reported, split, structure sound", "[halfedge][nonmanifold]")
{
    // Edge (0, 1) carries three triangles.
    const PolygonMesh m = meshFrom({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}}, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
    const HalfedgeMesh h(m);
    CHECK(h.checkInvariants().empty());
    const auto& r = h.buildReport();
    REQUIRE(r.nonManifoldEdges.size() == 1);
    CHECK(r.nonManifoldEdges[0].from == 0);
    CHECK(r.nonManifoldEdges[0].to == 1);
    CHECK(r.nonManifoldEdges[0].faceCount == 3);
    // Both ends: their three corners are not joined through a two-face edge.
    REQUIRE(r.nonManifoldVertices.size() == 2);
    CHECK(r.nonManifoldVertices[0].vertex == 0);
    CHECK(r.nonManifoldVertices[0].fanCount == 3);
    CHECK(r.nonManifoldVertices[1].vertex == 1);
    CHECK(!r.manifold());
    CHECK(r.describe() == "edge (0, 1) has 3 faces");
    CHECK_THROWS_WITH(h.requireClean("fan.obj"), "fan.obj: edge (0, 1) has 3 faces");
    // Faces 0 and 1 pair on the edge (opposite directions); face 2 is cut off along it, so vertices
    // 0 and 1 each get one copy: 7 vertices, 8 edges, 3 faces, two disks.
    CHECK(r.splitVertices == std::vector<int>{0, 1});
    CHECK(h.vertexCount() == 7);
    CHECK(h.edgeCount() == 8);
    CHECK(h.originalVertex(5) == 0);
    CHECK(h.originalVertex(6) == 1);
    CHECK(h.position(5) == h.position(0));
    CHECK(h.boundaryLoops().size() == 2);
    CHECK(h.components().count == 2);
    requireSameFaces(h, m);
}

TEST_CASE("bow-tie vertex: reported, split into two fans", "[halfedge][nonmanifold]")
{
    const PolygonMesh m = meshFrom({{0, 0, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {-1, -1, 0}}, {{0, 1, 2}, {0, 3, 4}});
    const HalfedgeMesh h(m);
    CHECK(h.checkInvariants().empty());
    const auto& r = h.buildReport();
    CHECK(r.nonManifoldEdges.empty());
    REQUIRE(r.nonManifoldVertices.size() == 1);
    CHECK(r.nonManifoldVertices[0].vertex == 0);
    CHECK(r.nonManifoldVertices[0].fanCount == 2);
    CHECK(r.splitVertices == std::vector<int>{0});
    CHECK(h.vertexCount() == 6);
    CHECK(h.edgeCount() == 6);
    CHECK(h.boundaryLoops().size() == 2);
    CHECK(h.valence(0) == 2);
    CHECK(h.valence(5) == 2);
    requireSameFaces(h, m);
    // Two cones touching at their tips (closed fans) are split the same way.
    PolygonMesh cones = disjointUnion(tetrahedron(), tetrahedron());
    for (int& v : cones.faceVertices)
        if (v == 4) v = 0; // glue vertex 0 of the second tetrahedron onto vertex 0 of the first
    const HalfedgeMesh hc(cones);
    CHECK(hc.checkInvariants().empty());
    REQUIRE(hc.buildReport().nonManifoldVertices.size() == 1);
    CHECK(hc.buildReport().nonManifoldVertices[0].vertex == 0);
    CHECK(hc.components().count == 2);
    CHECK(hc.isClosed());
}

TEST_CASE("inconsistent orientation: reported, the edge cut", "[halfedge][orientation]")
{
    // The cube with its top face reversed: its four edges are run twice in the same direction.
    PolygonMesh m = cube();
    std::reverse(m.faceVertices.begin() + m.faceStart[1], m.faceVertices.begin() + m.faceStart[2]);
    const HalfedgeMesh h(m);
    CHECK(h.checkInvariants().empty());
    const auto& r = h.buildReport();
    CHECK(r.manifold());
    CHECK(!r.clean());
    CHECK(r.inconsistentEdges.size() == 4);
    CHECK(r.splitVertices.size() == 4);
    CHECK(r.describe().find("inconsistent orientation") != std::string::npos);
    CHECK(h.components().count == 2); // the reversed face comes loose
    requireSameFaces(h, m);
}

TEST_CASE("a Möbius band builds with one cut", "[halfedge][orientation]")
{
    const HalfedgeMesh h(mobius(5));
    CHECK(h.checkInvariants().empty());
    CHECK(h.buildReport().inconsistentEdges.size() == 1);
    CHECK(h.buildReport().manifold());
    CHECK(h.components().count == 1);
    CHECK(h.eulerCharacteristic() == 1); // cut open: a disk
}

TEST_CASE("invalid input is an Error naming the face", "[halfedge]")
{
    PolygonMesh m = tetrahedron();
    m.faceVertices[5] = 7;
    CHECK_THROWS_AS(HalfedgeMesh(m), Error);
    CHECK_THROWS_WITH(HalfedgeMesh(m), Catch::Contains("face 1") && Catch::Contains("vertex 7"));
}

TEST_CASE("toPolygonMesh gives the faces back", "[halfedge]")
{
    const PolygonMesh m = quadTorus(5, 4);
    const PolygonMesh back = HalfedgeMesh(m).toPolygonMesh();
    CHECK(back.faceVertices == m.faceVertices);
    CHECK(back.faceStart == m.faceStart);
    CHECK(back.positions == m.positions);
}

} // namespace test_halfedge
