#pragma once
// PolygonMesh: the shared-vertex (indexed) polygon mesh every part of the library exchanges:
// tessellation produces it, mesh files read into it, the halfedge structure is built from it, and
// the editor draws it.
//
// Layout (compressed rows, like a sparse matrix): face f has the vertex indices
// faceVertices[faceStart[f] .. faceStart[f+1]), counter-clockwise seen from the front.
// Per-vertex attributes are optional: an empty matrix means "absent".

#include <Eigen/Core>

#include <string>
#include <vector>

#include "freeform/core/error.h"

namespace freeform {

struct PolygonMesh {
    Eigen::Matrix<double, 3, Eigen::Dynamic> positions; // 3 x V
    Eigen::Matrix<double, 3, Eigen::Dynamic> normals;   // 3 x V or empty
    Eigen::Matrix<double, 2, Eigen::Dynamic> texcoords; // 2 x V (u, v) or empty
    std::vector<int> faceVertices;                      // all faces' vertex indices, concatenated
    std::vector<int> faceStart{0};                      // F + 1 offsets into faceVertices

    int vertexCount() const { return static_cast<int>(positions.cols()); }
    int faceCount() const { return static_cast<int>(faceStart.size()) - 1; }
    int faceSize(int f) const { return faceStart[f + 1] - faceStart[f]; }
    const int* face(int f) const { return faceVertices.data() + faceStart[f]; }

    /// Appends a face; its indices are checked when validate() runs.
    void addFace(std::initializer_list<int> vertices) { addFace(vertices.begin(), vertices.end()); }
    template <typename It>
    void addFace(It first, It last)
    {
        faceVertices.insert(faceVertices.end(), first, last);
        faceStart.push_back(static_cast<int>(faceVertices.size()));
    }

    bool isTriangleMesh() const
    {
        for (int f = 0; f < faceCount(); ++f)
            if (faceSize(f) != 3) return false;
        return true;
    }

    /// Throws Error naming the face or vertex when an index is out of range, a face has fewer than
    /// three corners or repeats a vertex, an attribute has the wrong size, or a position is not
    /// finite.
    void validate(const std::string& what = "mesh") const
    {
        const int v = vertexCount();
        if (faceStart.empty() || faceStart.front() != 0 || faceStart.back() != static_cast<int>(faceVertices.size()))
            throw Error(what + ": face offsets are inconsistent");
        if (normals.size() != 0 && normals.cols() != v)
            throw Error(what + ": " + std::to_string(normals.cols()) + " normals for " + std::to_string(v) + " vertices");
        if (texcoords.size() != 0 && texcoords.cols() != v)
            throw Error(what + ": " + std::to_string(texcoords.cols()) + " texture coordinates for " + std::to_string(v) + " vertices");
        for (int i = 0; i < v; ++i)
            if (!positions.col(i).allFinite()) throw Error(what + ": vertex " + std::to_string(i) + " is not finite");
        for (int f = 0; f < faceCount(); ++f) {
            if (faceSize(f) < 3) throw Error(what + ": face " + std::to_string(f) + " has fewer than 3 vertices");
            for (int k = 0; k < faceSize(f); ++k) {
                const int idx = face(f)[k];
                if (idx < 0 || idx >= v)
                    throw Error(what + ": face " + std::to_string(f) + " refers to vertex " + std::to_string(idx) +
                                ", the mesh has " + std::to_string(v));
                for (int j = 0; j < k; ++j)
                    if (face(f)[j] == idx)
                        throw Error(what + ": face " + std::to_string(f) + " uses vertex " + std::to_string(idx) + " twice");
            }
        }
    }
};

/// The meshes as one, in order (each mesh's vertex indices shifted by the vertices before it);
/// normals and texture coordinates are kept when every mesh has them, else left out.
PolygonMesh mergeMeshes(const std::vector<const PolygonMesh*>& meshes);

} // namespace freeform
