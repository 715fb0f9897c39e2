#pragma once
// Mesh files: OBJ, PLY (ASCII, binary little and big endian), STL (ASCII and binary), OFF and
// glTF 2 (.gltf with external or data: buffers, .glb). Formats and guarantees: docs/mesh-io.md.
//
// MeshFile is the lossless, format-preserving view of a file: it keeps the file as read (every
// line, header, property, element, JSON member and buffer byte) and exposes only the numbers a
// deformation changes (positions, normals, tangents) as editable matrices, in file order. Writing
// it back in the same format changes exactly those numbers: a value that did not change keeps its
// original text (text formats) or bytes (binary formats), so an identity round trip reproduces the
// file byte for byte; a changed value is written in the shortest form that reads back to the same
// double (text) or as the nearest value of the file's binary type (float32 stays float32). Vertices
// are never welded, split or reordered. Every read error is a freeform::Error naming the file and
// the line (text) or byte offset / element (binary); writes go through a temporary file and a
// rename, so a failed write leaves an existing output untouched.

#include <Eigen/Core>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "freeform/mesh/polygon_mesh.h"

namespace freeform {

/// Any supported format by extension (.obj .ply .stl .off .gltf .glb, case-insensitive; any other
/// extension Assimp reads goes through Assimp, not losslessly: docs/mesh-io.md). Vertices
/// are the file's vertices in file order (STL: exactly equal corner positions are welded, since STL
/// stores no shared vertices; see docs/mesh-io.md); faces as in the file (glTF: triangles, strips
/// and fans become triangles). normals / texcoords are filled only where the file has exactly one
/// per vertex (OBJ per-corner indices: only when every vertex has one consistent value), else empty.
/// Error naming file and line on bad input.
PolygonMesh readPolygonMesh(const std::string& path);

/// Which reader a path takes, by its extension: "freeform (lossless)" (.obj .ply .stl .off .gltf
/// .glb) or "assimp (not lossless)" (any other extension Assimp reads); Error for an unknown one.
std::string meshReader(const std::string& path);

/// Format from the extension (.obj .ply .stl .off .gltf .glb), written atomically. OBJ, PLY and OFF
/// keep doubles exactly (PLY as binary little-endian float64); STL and glTF store float32 and
/// triangles (polygons are fanned). Throws Error on an invalid mesh or an unknown extension.
void writePolygonMesh(const PolygonMesh& mesh, const std::string& path);

namespace meshio {
class Source; // the file as read (internal, src/io/mesh/)
}

/// Lossless, format-preserving file: positions/normals (/tangents) editable, everything else
/// (faces, uvs, groups, materials, colours, unknown lines/properties, vertex order) written back as
/// read. Copies share the immutable file data and own their editable matrices.
///
/// Normals and tangents are the file's own records, each sitting at one position (its anchor):
///   - OBJ: the `vn` records; anchor = the position of the first face corner that uses the normal
///     (a normal shared by corners at several positions is anchored at the first), -1 when no face
///     uses it (a deformer leaves such a normal as it is);
///   - PLY / OFF (NOFF) / glTF: per-vertex normals, anchor = the vertex itself;
///   - STL: the facet normals, anchor = the facet's first corner (positions are the 3F corners).
/// glTF positions are in each mesh's own coordinate system (node transforms are not applied); the
/// positions of all meshes and primitives are concatenated in file order (an accessor shared by
/// several primitives appears once).
class MeshFile {
public:
    /// Reads any supported format by extension; Error naming the file and line/offset on bad input.
    static MeshFile read(const std::string& path);
    /// Reads a file already in memory exactly as read() reads the file at path: `path` gives the
    /// format (by its extension), names the file in messages and is what path() returns, and the
    /// disk is never touched; a .gltf's external buffers come from `companions`, keyed by the path
    /// relative to the file's folder that their uri names (as companions() returns them). With
    /// bytes() and companions() it rebuilds a file from its defining data (the Python module
    /// pickles a MeshFile so), equal to it bit for bit. Error as read() on bad input, and naming a
    /// buffer whose file is not among the companions.
    static MeshFile readBytes(const std::string& path, std::string bytes,
                              const std::map<std::string, std::string>& companions = {});
    /// The file as read, byte for byte (not as it would be written now).
    const std::string& bytes() const;
    /// The other files the file was read with: a .gltf's external buffers (each the bytes its
    /// buffer declares, byteLength) by their path relative to the file's folder. Empty for the
    /// other formats.
    std::map<std::string, std::string> companions() const;

    Eigen::Matrix<double, 3, Eigen::Dynamic>& positions() { return positions_; } // 3 x P, file order
    const Eigen::Matrix<double, 3, Eigen::Dynamic>& positions() const { return positions_; }
    Eigen::Matrix<double, 3, Eigen::Dynamic>& normals() { return normals_; }     // 3 x N (may be empty)
    const Eigen::Matrix<double, 3, Eigen::Dynamic>& normals() const { return normals_; }
    /// For each normal, the position index it sits at (-1: no face uses it, OBJ only).
    const std::vector<int>& normalAnchors() const;
    Eigen::Matrix<double, 4, Eigen::Dynamic>& tangents() { return tangents_; }   // 4 x T (xyz + handedness w), may be empty
    const Eigen::Matrix<double, 4, Eigen::Dynamic>& tangents() const { return tangents_; }
    const std::vector<int>& tangentAnchors() const;

    /// The mesh with the current positions: vertex i is positions() column i for every format (STL
    /// corners are not welded here; readPolygonMesh welds them). Faces as in the file; normals /
    /// texcoords only where every vertex has exactly one (see readPolygonMesh).
    PolygonMesh toPolygonMesh() const;

    /// Format by extension, atomic. The same format as read (.gltf and .glb count as one) writes the
    /// file back with only positions/normals/tangents changed; another format converts what the
    /// target can carry (docs/mesh-io.md lists what is dropped). Throws Error when the matrices
    /// changed shape or hold a non-finite value, or on an unknown extension.
    void write(const std::string& path) const;

    /// The format read: "obj", "ply", "stl", "off", "gltf" or "glb".
    const std::string& format() const;
    /// The path read.
    const std::string& path() const;
    /// Which path the file took: "freeform (lossless)" for the five formats above, "assimp (not
    /// lossless)" for every other format Assimp reads (FBX, Collada, 3DS, X3D, ...; docs/mesh-io.md).
    const std::string& reader() const;

private:
    MeshFile() = default;
    static MeshFile fromSource(std::shared_ptr<const meshio::Source> source);
    std::shared_ptr<const meshio::Source> source_;
    Eigen::Matrix<double, 3, Eigen::Dynamic> positions_;
    Eigen::Matrix<double, 3, Eigen::Dynamic> normals_;
    Eigen::Matrix<double, 4, Eigen::Dynamic> tangents_;
};

} // namespace freeform
