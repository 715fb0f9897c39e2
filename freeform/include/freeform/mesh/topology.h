#pragma once
// meshReport: the topology of a polygon mesh in numbers (what `freeform info` prints).
//
// Counts are those of the input: V all vertices (isolated ones included), E its distinct undirected
// edges, F its faces, boundary edges those with exactly one face. Components are the connected pieces
// of the faces (two faces are connected when they share a vertex); isolated vertices belong to none.
// Boundary loops are counted on the halfedge structure, that is after non-manifold elements are split
// apart (docs/meshes.md). euler = V - E + F. The genus is given only where it is defined: for a
// component that is a closed, orientable 2-manifold, genus = (2 - chi) / 2 with chi its own V - E + F;
// for the mesh, the sum over the components when every component has one. Otherwise it is empty and
// genusNote says why.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "freeform/mesh/halfedge.h"
#include "freeform/mesh/polygon_mesh.h"

namespace freeform {

struct ComponentReport {
    int vertices = 0;
    int edges = 0;
    int faces = 0;
    int boundaryEdges = 0;
    int boundaryLoops = 0;
    bool manifold = true;   // no edge with more than two faces, no vertex with more than one fan
    bool closed = true;     // no boundary edge
    bool orientable = true; // the faces can be oriented consistently (judged through manifold edges)
    bool oriented = true;   // and they are: no edge run twice in the same direction
    int euler = 0;          // vertices - edges + faces
    std::optional<int> genus;
    std::string genusNote; // why genus is empty; empty when it is not
};

struct MeshReport {
    int vertices = 0;
    int edges = 0;
    int faces = 0;
    int boundaryEdges = 0;
    int boundaryLoops = 0;
    int components = 0;
    int isolatedVertices = 0;
    bool manifold = true;
    bool closed = true;
    bool orientable = true;
    bool oriented = true;
    int euler = 0;
    std::optional<int> genus;
    std::string genusNote;

    std::vector<HalfedgeMesh::NonManifoldEdge> nonManifoldEdges;
    std::vector<HalfedgeMesh::NonManifoldVertex> nonManifoldVertices;
    std::vector<std::array<int, 2>> inconsistentEdges;
    std::vector<ComponentReport> componentReports; // by smallest face id
};

/// The report of a mesh; Error (from PolygonMesh::validate) for a mesh that is not even valid input.
MeshReport meshReport(const PolygonMesh& mesh);

} // namespace freeform
