#pragma once
// Internal to the mesh I/O: the file as read (Source), the places of the editable numbers in it
// (text and binary slots), number formatting and parsing, and the per-format readers and writers.
//
// A Source keeps the whole file and, for each editable number (a coordinate of a position, normal
// or tangent), the place it was read from. Writing the same format copies the file and replaces
// only the numbers whose value changed, so everything else comes out byte for byte as it went in.

#include <Eigen/Core>

#include <cstdint>
#include <iosfwd>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "freeform/core/error.h"
#include "freeform/mesh/polygon_mesh.h"

namespace freeform::meshio {

/// A blank within a line of a text format: space, tab, carriage return, vertical tab, form feed.
inline bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

using Matrix3X = Eigen::Matrix<double, 3, Eigen::Dynamic>;
using Matrix4X = Eigen::Matrix<double, 4, Eigen::Dynamic>;
using Matrix2X = Eigen::Matrix<double, 2, Eigen::Dynamic>;

/// The editable numbers: as read (Source) or as they are now (MeshFile).
struct Values {
    const Matrix3X& positions;
    const Matrix3X& normals;
    const Matrix4X& tangents;
};

enum class Field : std::uint8_t { Position, Normal, Tangent };

inline double valueAt(const Values& v, Field field, int column, int row)
{
    switch (field) {
    case Field::Position: return v.positions(row, column);
    case Field::Normal: return v.normals(row, column);
    case Field::Tangent: return v.tangents(row, column);
    }
    return 0;
}

/// True when a and b are the same double, bit for bit (so -0 differs from +0).
bool sameBits(double a, double b);

/// An editable number token in a text file: text[begin, end) holds the value.
struct TextSlot {
    std::size_t begin = 0;
    std::size_t end = 0;
    int column = 0;
    Field field = Field::Position;
    std::uint8_t row = 0;
    bool single = false; // the format declares float32: a changed value is written as the nearest float
    bool integer = false; // the format declares an integer type (PLY): a changed value is rounded to it
    std::uint8_t integerType = 0; // that type, a BinaryType (declared below)
};

/// Writes `text` with the slots whose value changed (now against was) replaced by the new value's
/// shortest round-trip form. Slots are sorted by position and do not overlap.
void writeText(std::ostream& out, const std::string& text, const std::vector<TextSlot>& slots, const Values& now,
               const Values& was);

enum class BinaryType : std::uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };
int binarySize(BinaryType type);
/// Reads a value of `type` at bytes[offset] (the caller checked the bounds).
double readBinary(const char* bytes, BinaryType type, bool bigEndian);
/// Writes a value of `type` (integers: rounded; Error when out of range).
void writeBinary(char* bytes, BinaryType type, bool bigEndian, double value, const std::string& what);

/// An editable number stored in binary at bytes[offset].
struct BinarySlot {
    std::size_t offset = 0;
    int column = 0;
    Field field = Field::Position;
    std::uint8_t row = 0;
    BinaryType type = BinaryType::Float32;
    bool bigEndian = false;
};

/// Replaces, in a copy of the bytes, the slots whose value changed.
void patchBinary(std::string& bytes, const std::vector<BinarySlot>& slots, const Values& now, const Values& was,
                 const std::string& path);

/// Shortest text that reads back to exactly this double (std::to_chars).
std::string formatDouble(double value);
/// Shortest text that reads back to exactly this float.
std::string formatFloat(float value);
/// Parses a whole token as a double ("+1.5", "1e-3", "nan", "inf" accepted; finiteness is the
/// caller's check). False when the token is not a number.
bool parseDouble(std::string_view token, double& value);
/// Parses a whole token as a (signed) integer.
bool parseInteger(std::string_view token, long long& value);

/// A whitespace-separated token of a text file with its byte offset.
struct Token {
    std::string_view text;
    std::size_t offset = 0;
};

/// Error when a text format's bytes are not text: a NUL byte (binary data, a JPEG, UTF-16) or a
/// UTF-16/32 byte order mark. `format` names the format for the message ("OBJ").
void requireText(const std::string& path, const std::string& text, const char* format);

/// The lower-case extension without the dot ("obj"), or empty.
std::string extensionOf(const std::string& path);

/// The mesh of an indexed face list (OFF, PLY, Assimp): the positions as they are now, their
/// normals when there is one per position, the faces and texture coordinates as read.
inline PolygonMesh indexedMesh(const Values& now, const std::vector<int>& faceStart, const std::vector<int>& faceVertices,
                               const Matrix2X& texcoords = Matrix2X())
{
    PolygonMesh mesh;
    mesh.positions = now.positions;
    if (now.normals.cols() == now.positions.cols()) mesh.normals = now.normals;
    mesh.texcoords = texcoords;
    mesh.faceVertices = faceVertices;
    mesh.faceStart = faceStart;
    return mesh;
}

/// The file as read, with the editable numbers as they were in it.
class Source {
public:
    virtual ~Source() = default;

    std::string path;
    std::string format; // "obj", "ply", "stl", "off", "gltf", "glb"
    Matrix3X positions;
    Matrix3X normals;
    Matrix4X tangents;
    std::vector<int> normalAnchors;
    std::vector<int> tangentAnchors;

    Values original() const { return {positions, normals, tangents}; }

    /// The mesh with the given current values; vertex i is position i.
    virtual PolygonMesh polygonMesh(const Values& now) const = 0;
    /// Per-vertex colours (3 or 4 rows, in [0, 1]) when the file has them per vertex, else empty;
    /// carried over when converting to another format.
    virtual Eigen::MatrixXd vertexColors() const { return {}; }
    /// How the file was read, for reports: "freeform (lossless)" or "assimp (not lossless)".
    std::string reader = "freeform (lossless)";
    /// True when `targetFormat` is written by writeSame (format-preserving).
    virtual bool writesSame(const std::string& targetFormat) const { return targetFormat == format; }
    /// Writes the file back with the current values (atomically).
    virtual void writeSame(const std::string& path, const std::string& targetFormat, const Values& now) const = 0;
    /// The file as read, byte for byte (MeshFile::bytes; read again from memory by readSource).
    virtual const std::string& fileBytes() const = 0;
    /// The other files it was read with: a .gltf's external buffers, by the relative path their
    /// uri names (MeshFile::companions). Empty for every other format.
    virtual std::map<std::string, std::string> companions() const { return {}; }
};

/// Files already in memory that a reader takes instead of the disk: a .gltf's external buffers by
/// the relative path their uri names (null: read them from the glTF file's folder).
using Companions = std::map<std::string, std::string>;

/// A file of positions and an indexed face list, with texture coordinates and vertex colours when
/// it has them (OFF, PLY).
class IndexedSource : public Source {
public:
    std::vector<int> faceStart{0};
    std::vector<int> faceVertices;
    Matrix2X texcoords;
    Eigen::MatrixXd colors;

    PolygonMesh polygonMesh(const Values& now) const override { return indexedMesh(now, faceStart, faceVertices, texcoords); }
    Eigen::MatrixXd vertexColors() const override { return colors; }
};

// ---- readers (the text or bytes of the whole file; path for messages)
std::unique_ptr<Source> readObj(const std::string& path, std::string text);
std::unique_ptr<Source> readPly(const std::string& path, std::string bytes);
std::unique_ptr<Source> readStl(const std::string& path, std::string bytes);
std::unique_ptr<Source> readOff(const std::string& path, std::string text);
/// companions: the external buffers from memory instead of the disk (null: from the disk).
std::unique_ptr<Source> readGltf(const std::string& path, std::string bytes, bool binary, const Companions* companions = nullptr);
/// Any other format Assimp reads (not lossless; assimp.cpp), from the file's bytes (already read):
/// from the file at path when fromDisk (so formats that refer to other files find them), from the
/// bytes alone otherwise (Assimp's format found by the path's extension). assimpReads: whether it
/// reads `extension`.
std::unique_ptr<Source> readAssimp(const std::string& path, std::string bytes, bool fromDisk);
bool assimpReads(const std::string& extension);

// ---- writers of a whole mesh (conversion); colors: 3 or 4 x V in [0, 1], or empty.
// The mesh is valid (checked by the caller).
void writeObjMesh(std::ostream& out, const PolygonMesh& mesh, const Eigen::MatrixXd& colors);
void writePlyMesh(std::ostream& out, const PolygonMesh& mesh, const Eigen::MatrixXd& colors);
void writeStlMesh(std::ostream& out, const PolygonMesh& mesh);
void writeOffMesh(std::ostream& out, const PolygonMesh& mesh, const Eigen::MatrixXd& colors);
/// glTF: .glb when binary, else .gltf with the buffer in `binPath` (written atomically first).
void writeGltfMesh(const std::string& path, const PolygonMesh& mesh, const Eigen::MatrixXd& colors, bool binary);
/// Writes any mesh by the extension of path (atomic).
void writeMeshAs(const PolygonMesh& mesh, const Eigen::MatrixXd& colors, const std::string& path);

/// Per-vertex attribute from per-corner indices: column v of the result is attribute[index] of the
/// corners at vertex v, when every vertex has corners and all of them carry the same value
/// (index < 0: the corner has none). Else an empty matrix.
template <int Rows>
Eigen::Matrix<double, Rows, Eigen::Dynamic> perVertexAttribute(int vertexCount, const std::vector<int>& cornerVertex,
                                                               const std::vector<int>& cornerAttribute,
                                                               const Eigen::Matrix<double, Rows, Eigen::Dynamic>& attribute)
{
    Eigen::Matrix<double, Rows, Eigen::Dynamic> result(Rows, vertexCount);
    std::vector<int> chosen(static_cast<std::size_t>(vertexCount), -1);
    for (std::size_t c = 0; c < cornerVertex.size(); ++c) {
        const int a = cornerAttribute[c];
        if (a < 0) return {};
        int& slot = chosen[static_cast<std::size_t>(cornerVertex[c])];
        if (slot < 0) {
            slot = a;
            result.col(cornerVertex[c]) = attribute.col(a);
        } else if (slot != a && attribute.col(slot) != attribute.col(a)) {
            return {};
        }
    }
    for (int v = 0; v < vertexCount; ++v)
        if (chosen[static_cast<std::size_t>(v)] < 0) return {};
    return result;
}

} // namespace freeform::meshio
