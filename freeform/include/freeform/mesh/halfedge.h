#pragma once
// HalfedgeMesh: the halfedge structure of a PolygonMesh, for topology queries and local edits.
//
// Guarantees (checkInvariants() tests them; the constructor and every operator keep them): the two
// halves of edge e are halfedges 2e and 2e + 1, so opposite(h) = h ^ 1 and every halfedge has one;
// a halfedge on the boundary is explicit, with face(h) == -1 (it runs against the orientation of the
// faces, around the hole), and the boundary halfedges form closed loops through next/prev like faces
// do. next/prev are inverse permutations, each face's halfedges form one cycle of at least three,
// starting at faceHalfedge(f); the two ends of every edge differ; each vertex has one fan: its
// outgoing halfedges form a single cycle under rotation, and outgoing(v) is its boundary halfedge when
// v lies on the boundary (-1 for an isolated vertex). So the structure is always an oriented
// 2-manifold with boundary. Input that is not (an edge with more than two faces, a vertex whose faces
// form several fans, two faces that run along an edge in the same direction) is built with the
// offending elements split apart and listed in buildReport(), never rejected half-way and never
// stored inconsistently: faces keep their ids, input vertices keep theirs, and the extra copies of a
// split vertex get new ids after them, with originalVertex() naming the input vertex. Vertex
// positions are stored, other attributes are not. The local operators refuse (throw Error naming the
// element and the reason) what would break the invariants, and each keeps V - E + F.
// Conventions and the math: docs/meshes.md.

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

#include "freeform/mesh/polygon_mesh.h"

namespace freeform {

class HalfedgeMesh {
public:
    /// An edge of the input with more than two faces (input vertex ids, from < to).
    struct NonManifoldEdge {
        int from = 0;
        int to = 0;
        int faceCount = 0;
    };
    /// An input vertex whose faces form several fans (its neighbourhood is not one disk or half-disk).
    struct NonManifoldVertex {
        int vertex = 0;
        int fanCount = 0;
    };
    /// What the constructor found and split; all empty for a consistently oriented manifold.
    struct BuildReport {
        std::vector<NonManifoldEdge> nonManifoldEdges;       // by increasing (from, to)
        std::vector<NonManifoldVertex> nonManifoldVertices;  // by increasing vertex, ends of non-manifold edges included
        std::vector<std::array<int, 2>> inconsistentEdges;   // (a, b): both faces of the edge run a -> b
        std::vector<int> splitVertices;                      // input vertices that got more than one structure vertex

        bool manifold() const { return nonManifoldEdges.empty() && nonManifoldVertices.empty(); }
        bool clean() const { return manifold() && inconsistentEdges.empty(); }
        /// The first problem in words ("edge (3, 7) has 3 faces"), empty when clean().
        std::string describe() const;
    };

    /// The connected components of the structure (through shared edges after the split).
    struct Components {
        int count = 0;
        std::vector<int> ofFace;   // F entries
        std::vector<int> ofVertex; // V entries, -1 for isolated vertices
    };

    HalfedgeMesh() = default;
    /// Validates the mesh (PolygonMesh::validate, Error naming the face or vertex) and builds the
    /// structure; never throws for non-manifold or inconsistently oriented input (see buildReport()).
    explicit HalfedgeMesh(const PolygonMesh& mesh);

    const BuildReport& buildReport() const { return report_; }
    /// Throws Error("<what>: <first problem>") unless buildReport().clean().
    void requireClean(const std::string& what = "mesh") const;

    int vertexCount() const { return static_cast<int>(outgoing_.size()); }
    int faceCount() const { return static_cast<int>(faceHalfedge_.size()); }
    int edgeCount() const { return static_cast<int>(to_.size() / 2); }
    int halfedgeCount() const { return static_cast<int>(to_.size()); }
    /// V - E + F of the structure (after splits; equal to the input's when buildReport().manifold()
    /// and there are no inconsistent edges).
    int eulerCharacteristic() const { return vertexCount() - edgeCount() + faceCount(); }

    // ---- navigation (no range checks: ids come from this structure)
    static int opposite(int h) { return h ^ 1; }
    static int edge(int h) { return h >> 1; }
    static int edgeHalfedge(int e, int side = 0) { return 2 * e + side; }
    int next(int h) const { return next_[h]; }
    int prev(int h) const { return prev_[h]; }
    int toVertex(int h) const { return to_[h]; }
    int fromVertex(int h) const { return to_[h ^ 1]; }
    /// The face left of h, -1 for a boundary halfedge.
    int face(int h) const { return face_[h]; }
    int faceHalfedge(int f) const { return faceHalfedge_[f]; }
    /// An outgoing halfedge: the boundary one for a boundary vertex, -1 for an isolated vertex.
    int outgoing(int v) const { return outgoing_[v]; }
    /// The input vertex this vertex stands for; -1 for a vertex made by an operator.
    int originalVertex(int v) const { return original_[v]; }
    const Eigen::Vector3d& position(int v) const { return positions_[v]; }
    void setPosition(int v, const Eigen::Vector3d& p) { positions_[v] = p; }

    bool isBoundaryHalfedge(int h) const { return face_[h] < 0; }
    bool isBoundaryEdge(int e) const { return face_[2 * e] < 0 || face_[2 * e + 1] < 0; }
    bool isBoundaryVertex(int v) const { return outgoing_[v] >= 0 && face_[outgoing_[v]] < 0; }
    bool isIsolated(int v) const { return outgoing_[v] < 0; }

    // ---- circulation
    /// The next outgoing halfedge counter-clockwise around fromVertex(h) (seen from the front, faces
    /// counter-clockwise): opposite(prev(h)).
    int rotate(int h) const { return prev_[h] ^ 1; }
    /// Calls fn(h) for each outgoing halfedge of v, counter-clockwise, starting at outgoing(v) (so at
    /// the boundary halfedge of a boundary vertex).
    template <typename Fn>
    void forEachOutgoing(int v, Fn&& fn) const
    {
        const int start = outgoing_[v];
        if (start < 0) return;
        int h = start;
        do {
            fn(h);
            h = rotate(h);
        } while (h != start);
    }
    /// Calls fn(h) for each halfedge of face f in order, starting at faceHalfedge(f).
    template <typename Fn>
    void forEachFaceHalfedge(int f, Fn&& fn) const
    {
        const int start = faceHalfedge_[f];
        int h = start;
        do {
            fn(h);
            h = next_[h];
        } while (h != start);
    }
    /// Number of edges at v (= number of neighbours).
    int valence(int v) const;
    /// The 1-ring: the neighbours of v, counter-clockwise, starting at toVertex(outgoing(v)).
    std::vector<int> vertexNeighbors(int v) const;
    /// The faces around v, counter-clockwise (each once).
    std::vector<int> vertexFaces(int v) const;
    std::vector<int> faceVertices(int f) const;
    int faceSize(int f) const;
    /// The halfedge from a to b, -1 when a and b are not adjacent.
    int findHalfedge(int a, int b) const;

    // ---- global queries
    bool isClosed() const;
    /// Each boundary loop as its halfedges in next order, loops ordered by their smallest halfedge.
    std::vector<std::vector<int>> boundaryLoops() const;
    Components components() const;

    // ---- local operators (Error naming the element and the reason when refused)
    /// Flip is allowed for an interior edge between two triangles whose opposite corners differ and
    /// are not adjacent yet. On refusal, false and *reason (when given) says why.
    bool canFlip(int e, std::string* reason = nullptr) const;
    /// Replaces edge e (a, b) of triangles (a, b, c), (b, a, d) by (c, d): triangles (d, c, a), (c, d, b).
    void flip(int e);
    /// Inserts a vertex at p on edge e and connects it to the opposite corner of each adjacent triangle
    /// (faces with more sides just gain the corner). Returns the new vertex.
    int splitEdge(int e, const Eigen::Vector3d& p);
    /// Inserts a vertex at p in face f and connects it to every corner: an n-gon becomes n triangles.
    /// Returns the new vertex.
    int splitFace(int f, const Eigen::Vector3d& p);
    /// Collapse of halfedge h (from u to v) is allowed when the faces around u and v are triangles, the
    /// triangles at the edge have different third corners, and the link condition holds:
    /// Lk(u) ∩ Lk(v) = Lk(uv), with the boundary as an extra vertex joined to every boundary vertex.
    bool canCollapse(int h, std::string* reason = nullptr) const;
    /// Merges fromVertex(h) into toVertex(h), moves it to p, and removes the edge and its triangles.
    /// Elements are renumbered: each removed vertex, edge or face id is taken by the last one. Returns
    /// the id of the kept vertex after renumbering.
    int collapse(int h, const Eigen::Vector3d& p);

    // ---- conversion and checks
    /// The structure as a polygon mesh: structure vertices (split copies included) and faces in id
    /// order, each face starting at fromVertex(faceHalfedge(f)); positions only.
    PolygonMesh toPolygonMesh() const;
    /// The first violated invariant in words, empty when the structure is sound.
    std::string checkInvariants() const;

private:
    int addVertex(const Eigen::Vector3d& p, int original);
    int addEdge();
    int addFace();
    void link(int a, int b)
    {
        next_[a] = b;
        prev_[b] = a;
    }
    int insertDiagonal(int ha, int hb);
    void takePlace(int dead, int heir);
    void preferBoundaryOutgoing(int v);
    void removeEdge(int e);
    void removeFace(int f);
    void removeVertex(int v);

    // per halfedge
    std::vector<int> to_, next_, prev_, face_;
    // per face
    std::vector<int> faceHalfedge_;
    // per vertex
    std::vector<int> outgoing_, original_;
    std::vector<Eigen::Vector3d> positions_;
    BuildReport report_;
};

} // namespace freeform
