// MeshFile, readPolygonMesh and writePolygonMesh: dispatch by extension over the per-format readers
// and writers of this folder.

#include <cmath>
#include <map>
#include <tuple>

#include "freeform/io/file.h"
#include "freeform/io/mesh_io.h"
#include "source.h"

namespace freeform {

namespace {

const char* const kFormats = ".obj .ply .stl .off .gltf .glb";

void checkMesh(const PolygonMesh& mesh, const std::string& what);

/// The one validation every reader's result passes, whichever command asked (info, ffd, convert,
/// the editor): the mesh as readPolygonMesh returns it (finite positions, normals, texture
/// coordinates; faces of at least 3 vertices inside the vertex range) and finite colours in [0, 1].
void validateSource(const meshio::Source& source)
{
    checkMesh(source.polygonMesh(source.original()), source.path);
    const Eigen::MatrixXd colors = source.vertexColors();
    for (Eigen::Index i = 0; i < colors.cols(); ++i)
        for (Eigen::Index k = 0; k < colors.rows(); ++k) {
            const double c = colors(k, i);
            if (!(c >= 0.0 && c <= 1.0))
                throw Error(source.path + ": vertex " + std::to_string(i) + " colour component " + std::to_string(k) + " is " +
                            meshio::formatDouble(c) + ", outside [0, 1] (or its type's range)");
        }
}

/// The file at path, or, when bytes is not null, the file in memory with its companions (then the
/// disk is never read).
std::unique_ptr<meshio::Source> readSourceUnchecked(const std::string& path, std::string* bytes,
                                                    const meshio::Companions* companions)
{
    const std::string ext = meshio::extensionOf(path);
    const bool known = ext == "obj" || ext == "ply" || ext == "stl" || ext == "off" || ext == "gltf" || ext == "glb";
    if (!known) {
        // Every other format Assimp reads, through Assimp (not lossless: docs/mesh-io.md).
        if (meshio::assimpReads(ext)) {
            if (bytes != nullptr) return meshio::readAssimp(path, std::move(*bytes), false);
            // readFile first: the same message as the other formats for a missing file or a folder.
            return meshio::readAssimp(path, readFile(path), true);
        }
        throw Error(path + ": unknown mesh format '" + (ext.empty() ? std::string("(no extension)") : "." + ext) +
                    "' (supported: " + kFormats + ", and through Assimp (not lossless) the formats it reads)");
    }
    std::string data = bytes != nullptr ? std::move(*bytes) : readFile(path);
    if (ext == "obj") return meshio::readObj(path, std::move(data));
    if (ext == "ply") return meshio::readPly(path, std::move(data));
    if (ext == "stl") return meshio::readStl(path, std::move(data));
    if (ext == "off") return meshio::readOff(path, std::move(data));
    return meshio::readGltf(path, std::move(data), ext == "glb", bytes != nullptr ? companions : nullptr);
}

std::unique_ptr<meshio::Source> readSource(const std::string& path, std::string* bytes = nullptr,
                                           const meshio::Companions* companions = nullptr)
{
    std::unique_ptr<meshio::Source> source = readSourceUnchecked(path, bytes, companions);
    validateSource(*source);
    return source;
}

/// Vertices, attributes and face indices consistent (PolygonMesh::validate without its ban on a
/// face that repeats a vertex, which files do contain).
void checkMesh(const PolygonMesh& mesh, const std::string& what)
{
    const int v = mesh.vertexCount();
    if (mesh.faceStart.empty() || mesh.faceStart.front() != 0 ||
        mesh.faceStart.back() != static_cast<int>(mesh.faceVertices.size()))
        throw Error(what + ": face offsets are inconsistent");
    if (mesh.normals.size() != 0 && mesh.normals.cols() != v)
        throw Error(what + ": " + std::to_string(mesh.normals.cols()) + " normals for " + std::to_string(v) + " vertices");
    if (mesh.texcoords.size() != 0 && mesh.texcoords.cols() != v)
        throw Error(what + ": " + std::to_string(mesh.texcoords.cols()) + " texture coordinates for " + std::to_string(v) +
                    " vertices");
    for (int i = 0; i < v; ++i)
        if (!mesh.positions.col(i).allFinite()) throw Error(what + ": vertex " + std::to_string(i) + " is not finite");
    for (int i = 0; i < mesh.normals.cols(); ++i)
        if (!mesh.normals.col(i).allFinite()) throw Error(what + ": normal " + std::to_string(i) + " is not finite");
    for (int i = 0; i < mesh.texcoords.cols(); ++i)
        if (!mesh.texcoords.col(i).allFinite())
            throw Error(what + ": texture coordinate " + std::to_string(i) + " is not finite");
    for (int f = 0; f < mesh.faceCount(); ++f) {
        if (mesh.faceStart[f + 1] - mesh.faceStart[f] < 3)
            throw Error(what + ": face " + std::to_string(f) + " has fewer than 3 vertices");
        for (int k = 0; k < mesh.faceSize(f); ++k) {
            const int idx = mesh.face(f)[k];
            if (idx < 0 || idx >= v)
                throw Error(what + ": face " + std::to_string(f) + " refers to vertex " + std::to_string(idx) + ", the mesh has " +
                            std::to_string(v));
        }
    }
}

/// Welds exactly equal positions (first occurrence wins, order of first occurrence kept); normals
/// are dropped when welded vertices disagree, texcoords likewise.
PolygonMesh weldEqualPositions(const PolygonMesh& mesh)
{
    std::map<std::tuple<double, double, double>, int> first;
    std::vector<int> map(static_cast<std::size_t>(mesh.vertexCount()));
    std::vector<int> kept;
    for (int i = 0; i < mesh.vertexCount(); ++i) {
        const auto key = std::make_tuple(mesh.positions(0, i), mesh.positions(1, i), mesh.positions(2, i));
        const auto [it, inserted] = first.emplace(key, static_cast<int>(kept.size()));
        if (inserted) kept.push_back(i);
        map[static_cast<std::size_t>(i)] = it->second;
    }
    PolygonMesh out;
    const int n = static_cast<int>(kept.size());
    out.positions.resize(3, n);
    for (int j = 0; j < n; ++j) out.positions.col(j) = mesh.positions.col(kept[static_cast<std::size_t>(j)]);
    out.faceStart = mesh.faceStart;
    out.faceVertices.reserve(mesh.faceVertices.size());
    for (int idx : mesh.faceVertices) out.faceVertices.push_back(map[static_cast<std::size_t>(idx)]);
    const auto weldAttribute = [&](const auto& attribute, auto& result) {
        if (attribute.cols() != mesh.vertexCount() || mesh.vertexCount() == 0) return;
        result.resize(attribute.rows(), n);
        for (int j = 0; j < n; ++j) result.col(j) = attribute.col(kept[static_cast<std::size_t>(j)]);
        for (int i = 0; i < mesh.vertexCount(); ++i)
            if (attribute.col(i) != result.col(map[static_cast<std::size_t>(i)])) {
                result.resize(attribute.rows(), 0);
                return;
            }
    };
    weldAttribute(mesh.normals, out.normals);
    weldAttribute(mesh.texcoords, out.texcoords);
    return out;
}

} // namespace

namespace meshio {

void writeMeshAs(const PolygonMesh& mesh, const Eigen::MatrixXd& colors, const std::string& path)
{
    const std::string ext = extensionOf(path);
    if (ext == "obj") writeFileAtomicallyWith(path, [&](std::ostream& out) { writeObjMesh(out, mesh, colors); });
    else if (ext == "ply") writeFileAtomicallyWith(path, [&](std::ostream& out) { writePlyMesh(out, mesh, colors); });
    else if (ext == "stl") writeFileAtomicallyWith(path, [&](std::ostream& out) { writeStlMesh(out, mesh); });
    else if (ext == "off") writeFileAtomicallyWith(path, [&](std::ostream& out) { writeOffMesh(out, mesh, colors); });
    else if (ext == "gltf" || ext == "glb") writeGltfMesh(path, mesh, colors, ext == "glb");
    else
        throw Error(path + ": unknown mesh format '" + (ext.empty() ? std::string("(no extension)") : "." + ext) +
                    "' (supported: " + kFormats + ")");
}

} // namespace meshio

std::string meshReader(const std::string& path)
{
    const std::string ext = meshio::extensionOf(path);
    if (ext == "obj" || ext == "ply" || ext == "stl" || ext == "off" || ext == "gltf" || ext == "glb") return "freeform (lossless)";
    if (meshio::assimpReads(ext)) return "assimp (not lossless)";
    throw Error(path + ": unknown mesh format '" + (ext.empty() ? std::string("(no extension)") : "." + ext) + "' (supported: " +
                kFormats + ", and through Assimp (not lossless) the formats it reads)");
}

PolygonMesh readPolygonMesh(const std::string& path)
{
    const std::unique_ptr<meshio::Source> source = readSource(path);
    PolygonMesh mesh = source->polygonMesh(source->original());
    checkMesh(mesh, path);
    if (source->format == "stl") return weldEqualPositions(mesh);
    return mesh;
}

void writePolygonMesh(const PolygonMesh& mesh, const std::string& path)
{
    checkMesh(mesh, path + ": the mesh to write");
    meshio::writeMeshAs(mesh, Eigen::MatrixXd(), path);
}

MeshFile MeshFile::fromSource(std::shared_ptr<const meshio::Source> source)
{
    MeshFile file;
    file.positions_ = source->positions;
    file.normals_ = source->normals;
    file.tangents_ = source->tangents;
    file.source_ = std::move(source);
    return file;
}

MeshFile MeshFile::read(const std::string& path) { return fromSource(readSource(path)); }

MeshFile MeshFile::readBytes(const std::string& path, std::string bytes, const std::map<std::string, std::string>& companions)
{
    return fromSource(readSource(path, &bytes, &companions));
}

const std::string& MeshFile::bytes() const { return source_->fileBytes(); }
std::map<std::string, std::string> MeshFile::companions() const { return source_->companions(); }

const std::vector<int>& MeshFile::normalAnchors() const { return source_->normalAnchors; }
const std::vector<int>& MeshFile::tangentAnchors() const { return source_->tangentAnchors; }
const std::string& MeshFile::format() const { return source_->format; }
const std::string& MeshFile::path() const { return source_->path; }
const std::string& MeshFile::reader() const { return source_->reader; }

PolygonMesh MeshFile::toPolygonMesh() const
{
    return source_->polygonMesh({positions_, normals_, tangents_});
}

void MeshFile::write(const std::string& path) const
{
    const meshio::Source& s = *source_;
    const auto checkShape = [&](const char* what, Eigen::Index cols, Eigen::Index expected) {
        if (cols != expected)
            throw Error(path + ": the " + what + " of " + s.path + " changed from " + std::to_string(expected) + " to " +
                        std::to_string(cols) + " columns; a mesh file keeps its vertex count");
    };
    checkShape("positions", positions_.cols(), s.positions.cols());
    checkShape("normals", normals_.cols(), s.normals.cols());
    checkShape("tangents", tangents_.cols(), s.tangents.cols());
    const auto checkFinite = [&](const char* what, const auto& m) {
        for (Eigen::Index i = 0; i < m.cols(); ++i)
            if (!m.col(i).allFinite()) throw Error(path + ": " + what + " " + std::to_string(i) + " is not finite");
    };
    checkFinite("position", positions_);
    checkFinite("normal", normals_);
    checkFinite("tangent", tangents_);

    const std::string ext = meshio::extensionOf(path);
    const meshio::Values now{positions_, normals_, tangents_};
    if (s.writesSame(ext)) {
        s.writeSame(path, ext, now);
        return;
    }
    PolygonMesh mesh = s.polygonMesh(now);
    checkMesh(mesh, s.path);
    meshio::writeMeshAs(mesh, s.vertexColors(), path);
}

} // namespace freeform
