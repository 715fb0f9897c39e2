// meshReport: V, E, F, boundary, components, manifoldness, orientability, Euler characteristic and
// genus of meshes whose topology is known by construction.

#include <catch2/catch.hpp>

#include <freeform/mesh/topology.h>

#include "support/meshes.h"

namespace test_mesh_topology {

using namespace freeform;
using namespace freeform::test;

TEST_CASE("tetrahedron and cube: spheres", "[topology]")
{
    for (const PolygonMesh& m : {tetrahedron(), cube()}) {
        const MeshReport r = meshReport(m);
        CHECK(r.vertices == m.vertexCount());
        CHECK(r.edges == countEdges(m));
        CHECK(r.faces == m.faceCount());
        CHECK(r.boundaryEdges == 0);
        CHECK(r.boundaryLoops == 0);
        CHECK(r.components == 1);
        CHECK(r.manifold);
        CHECK(r.closed);
        CHECK(r.orientable);
        CHECK(r.oriented);
        CHECK(r.euler == 2);
        REQUIRE(r.genus);
        CHECK(*r.genus == 0);
        CHECK(r.genusNote.empty());
    }
    CHECK(meshReport(cube()).edges == 12);
}

TEST_CASE("quad torus: chi 0, genus 1, whatever the resolution", "[topology]")
{
    for (const auto& [n, m] : {std::pair{3, 3}, std::pair{8, 5}, std::pair{17, 9}}) {
        const MeshReport r = meshReport(quadTorus(n, m));
        CAPTURE(n, m);
        CHECK(r.vertices == n * m);
        CHECK(r.edges == 2 * n * m);
        CHECK(r.faces == n * m);
        CHECK(r.euler == 0);
        REQUIRE(r.genus);
        CHECK(*r.genus == 1);
        // Triangulated: E and F change, chi and genus do not.
        const MeshReport t = meshReport(splitQuads(quadTorus(n, m)));
        CHECK(t.edges == 3 * n * m);
        CHECK(t.euler == 0);
        CHECK(t.genus == 1);
    }
}

TEST_CASE("slabs with h holes have genus h", "[topology]")
{
    for (int holes = 0; holes <= 3; ++holes) {
        const PolygonMesh m = holedSlab(holes);
        const MeshReport r = meshReport(m);
        CAPTURE(holes);
        CHECK(r.edges == countEdges(m));
        CHECK(r.manifold);
        CHECK(r.closed);
        CHECK(r.euler == 2 - 2 * holes);
        REQUIRE(r.genus);
        CHECK(*r.genus == holes);
    }
}

TEST_CASE("disk: one boundary loop, genus undefined", "[topology]")
{
    const MeshReport r = meshReport(fanDisk(7));
    CHECK(r.vertices == 8);
    CHECK(r.edges == 14);
    CHECK(r.faces == 7);
    CHECK(r.boundaryEdges == 7);
    CHECK(r.boundaryLoops == 1);
    CHECK(r.manifold);
    CHECK(!r.closed);
    CHECK(r.euler == 1);
    CHECK(!r.genus);
    CHECK(r.genusNote == "it has 1 boundary loop; the genus is given for closed surfaces only");
    // An annulus (grid with the middle face removed): two loops, chi 0.
    PolygonMesh annulus = grid(3, 3);
    PolygonMesh ring;
    ring.positions = annulus.positions;
    for (int f = 0; f < annulus.faceCount(); ++f)
        if (f != 4) ring.addFace(annulus.face(f), annulus.face(f) + 4);
    const MeshReport a = meshReport(ring);
    CHECK(a.boundaryLoops == 2);
    CHECK(a.boundaryEdges == 16);
    CHECK(a.euler == 0);
}

TEST_CASE("two components: counts per component, genus summed", "[topology]")
{
    const MeshReport r = meshReport(disjointUnion(tetrahedron(), quadTorus(6, 4)));
    CHECK(r.components == 2);
    CHECK(r.euler == 2);
    REQUIRE(r.genus);
    CHECK(*r.genus == 1);
    REQUIRE(r.componentReports.size() == 2);
    CHECK(r.componentReports[0].vertices == 4);
    CHECK(r.componentReports[0].euler == 2);
    CHECK(r.componentReports[0].genus == 0);
    CHECK(r.componentReports[1].faces == 24);
    CHECK(r.componentReports[1].euler == 0);
    CHECK(r.componentReports[1].genus == 1);

    // A sphere and a disk: the disk has no genus, so the mesh has none; the note names it.
    const MeshReport s = meshReport(disjointUnion(cube(), fanDisk(4)));
    CHECK(s.components == 2);
    CHECK(s.componentReports[0].genus == 0);
    CHECK(!s.componentReports[1].genus);
    CHECK(!s.genus);
    CHECK(s.genusNote.rfind("component 1: it has 1 boundary loop", 0) == 0);
}

TEST_CASE("Klein bottle and Möbius band are not orientable", "[topology]")
{
    const MeshReport k = meshReport(kleinBottle(6, 4));
    CHECK(k.manifold);
    CHECK(k.closed);
    CHECK(!k.orientable);
    CHECK(!k.oriented);
    CHECK(k.euler == 0);
    CHECK(!k.genus);
    CHECK(k.genusNote.find("not orientable") != std::string::npos);

    const MeshReport m = meshReport(mobius(6));
    CHECK(m.boundaryEdges == 12);
    CHECK(m.boundaryLoops == 1);
    CHECK(!m.orientable);
    CHECK(m.euler == 0);
}

TEST_CASE("a badly oriented sphere is still orientable with genus 0", "[topology]")
{
    PolygonMesh m = cube();
    std::reverse(m.faceVertices.begin() + m.faceStart[1], m.faceVertices.begin() + m.faceStart[2]);
    const MeshReport r = meshReport(m);
    CHECK(r.manifold);
    CHECK(r.closed);
    CHECK(r.orientable);
    CHECK(!r.oriented);
    CHECK(r.inconsistentEdges.size() == 4);
    CHECK(r.components == 1);
    CHECK(r.euler == 2);
    CHECK(r.genus == 0);
}

TEST_CASE("non-manifold input: reported, counted on the input", "[topology][nonmanifold]")
{
    const MeshReport fan =
        meshReport(meshFrom({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}}, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}));
    CHECK(fan.vertices == 5);
    CHECK(fan.edges == 7);
    CHECK(fan.faces == 3);
    CHECK(fan.boundaryEdges == 6);
    CHECK(fan.components == 1);
    CHECK(!fan.manifold);
    CHECK(fan.nonManifoldEdges.size() == 1);
    CHECK(fan.euler == 1);
    CHECK(!fan.genus);
    CHECK(fan.genusNote.rfind("not a manifold", 0) == 0);

    const MeshReport bowtie = meshReport(meshFrom({{0, 0, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {-1, -1, 0}}, {{0, 1, 2}, {0, 3, 4}}));
    CHECK(bowtie.components == 1); // connected through the vertex
    CHECK(!bowtie.manifold);
    CHECK(bowtie.nonManifoldVertices.size() == 1);
    CHECK(bowtie.boundaryLoops == 2);
    CHECK(bowtie.euler == 5 - 6 + 2);
}

TEST_CASE("isolated vertices and the empty mesh", "[topology]")
{
    PolygonMesh m = tetrahedron();
    m.positions.conservativeResize(3, 6);
    m.positions.col(4).setZero();
    m.positions.col(5).setOnes();
    const MeshReport r = meshReport(m);
    CHECK(r.vertices == 6);
    CHECK(r.isolatedVertices == 2);
    CHECK(r.components == 1);
    CHECK(r.euler == 4); // V - E + F with the two loose points
    CHECK(r.genus == 0); // from the component's own chi
    CHECK(r.manifold);

    const MeshReport empty = meshReport(PolygonMesh{});
    CHECK(empty.vertices == 0);
    CHECK(empty.components == 0);
    CHECK(!empty.genus);
    CHECK(empty.genusNote == "the mesh has no faces");
}

} // namespace test_mesh_topology
