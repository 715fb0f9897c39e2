// Every other format Assimp reads (FBX, Collada, 3DS, X3D, Blender's exports, ...), through Assimp:
// NOT lossless (docs/mesh-io.md, "Other formats through Assimp"). Assimp splits vertices per face
// corner where attributes differ (equal corners are joined again: aiProcess_JoinIdenticalVertices), applies the node transforms (aiProcess_PreTransformVertices:
// positions are in the scene's coordinates, meshes merged), drops the hierarchy, materials,
// animation, cameras and lights, and stores float32. The result is a mesh whose positions and
// normals a deformation may change; it is written to one of the five lossless formats, or back
// through Assimp's exporter when that format has one.

#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>

#include "freeform/io/file.h"
#include "source.h"

namespace freeform::meshio {

namespace {

class AssimpSource final : public Source {
public:
    std::shared_ptr<Assimp::Importer> importer; // owns the scene (re-exported on writeSame)
    std::vector<std::pair<unsigned, unsigned>> where; // column -> (mesh, vertex)
    std::vector<int> faceStart{0};
    std::vector<int> faceVertices;
    std::string extension;
    std::string exportFormat; // Assimp's exporter id for the extension, or empty
    std::string bytes;        // the file as read

    const std::string& fileBytes() const override { return bytes; }

    PolygonMesh polygonMesh(const Values& now) const override { return indexedMesh(now, faceStart, faceVertices); }

    bool writesSame(const std::string& target) const override { return target == extension && !exportFormat.empty(); }

    void writeSame(const std::string& target, const std::string&, const Values& now) const override
    {
        aiScene* scene = const_cast<aiScene*>(importer->GetScene());
        // The scene is this file's own copy (never shared with another MeshFile's writes at the
        // same time: MeshFile copies share it read-only, and a write restores it below).
        std::vector<aiVector3D> saved;
        const auto put = [&](bool restore) {
            for (std::size_t c = 0; c < where.size(); ++c) {
                aiMesh* m = scene->mMeshes[where[c].first];
                aiVector3D& v = m->mVertices[where[c].second];
                if (restore) {
                    v = saved[c];
                } else {
                    saved.push_back(v);
                    v = aiVector3D(static_cast<ai_real>(now.positions(0, static_cast<Eigen::Index>(c))),
                                   static_cast<ai_real>(now.positions(1, static_cast<Eigen::Index>(c))),
                                   static_cast<ai_real>(now.positions(2, static_cast<Eigen::Index>(c))));
                    if (m->mNormals != nullptr && now.normals.cols() == now.positions.cols())
                        m->mNormals[where[c].second] = aiVector3D(static_cast<ai_real>(now.normals(0, static_cast<Eigen::Index>(c))),
                                                                  static_cast<ai_real>(now.normals(1, static_cast<Eigen::Index>(c))),
                                                                  static_cast<ai_real>(now.normals(2, static_cast<Eigen::Index>(c))));
                }
            }
        };
        put(false);
        Assimp::Exporter exporter;
        const aiExportDataBlob* blob = exporter.ExportToBlob(scene, exportFormat);
        put(true);
        if (blob == nullptr) throw Error(target + ": Assimp could not export " + exportFormat + ": " + exporter.GetErrorString());
        writeFileAtomically(target, std::string(static_cast<const char*>(blob->data), blob->size));
    }
};

} // namespace

bool assimpReads(const std::string& extension)
{
    if (extension.empty()) return false;
    Assimp::Importer importer;
    return importer.IsExtensionSupported("." + extension);
}

std::unique_ptr<Source> readAssimp(const std::string& path, std::string bytes, bool fromDisk)
{
    auto src = std::make_unique<AssimpSource>();
    src->path = path;
    src->extension = extensionOf(path);
    src->format = src->extension;
    src->reader = "assimp (not lossless)";
    src->importer = std::make_shared<Assimp::Importer>();
    src->bytes = std::move(bytes);
    const unsigned flags = aiProcess_PreTransformVertices | aiProcess_JoinIdenticalVertices | aiProcess_ValidateDataStructure;
    const aiScene* scene = fromDisk ? src->importer->ReadFile(path, flags)
                                    : src->importer->ReadFileFromMemory(src->bytes.data(), src->bytes.size(), flags,
                                                                        src->extension.c_str());
    if (scene == nullptr)
        throw Error(path + ": Assimp could not read the file: " + src->importer->GetErrorString());
    Assimp::Exporter exporter;
    for (std::size_t i = 0; i < exporter.GetExportFormatCount(); ++i) {
        const aiExportFormatDesc* d = exporter.GetExportFormatDescription(i);
        if (d != nullptr && src->extension == d->fileExtension) {
            src->exportFormat = d->id;
            break;
        }
    }
    std::vector<double> positions, normals;
    bool allNormals = true;
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
        const aiMesh* mesh = scene->mMeshes[m];
        const int base = static_cast<int>(src->where.size());
        for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
            const aiVector3D& p = mesh->mVertices[v];
            positions.insert(positions.end(), {p.x, p.y, p.z});
            if (mesh->mNormals != nullptr)
                normals.insert(normals.end(), {mesh->mNormals[v].x, mesh->mNormals[v].y, mesh->mNormals[v].z});
            src->where.emplace_back(m, v);
        }
        allNormals = allNormals && mesh->mNormals != nullptr;
        for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
            const aiFace& face = mesh->mFaces[f];
            if (face.mNumIndices < 3) continue; // points and lines are not faces
            for (unsigned k = 0; k < face.mNumIndices; ++k) {
                if (face.mIndices[k] >= mesh->mNumVertices)
                    throw Error(path + ": mesh " + std::to_string(m) + " face " + std::to_string(f) + " refers to vertex " +
                                std::to_string(face.mIndices[k]) + ", the mesh has " + std::to_string(mesh->mNumVertices));
                src->faceVertices.push_back(base + static_cast<int>(face.mIndices[k]));
            }
            src->faceStart.push_back(static_cast<int>(src->faceVertices.size()));
        }
    }
    const auto columns = static_cast<Eigen::Index>(src->where.size());
    src->positions = Eigen::Map<const Matrix3X>(positions.data(), 3, columns);
    if (allNormals && columns > 0) {
        src->normals = Eigen::Map<const Matrix3X>(normals.data(), 3, columns);
        for (Eigen::Index i = 0; i < columns; ++i) src->normalAnchors.push_back(static_cast<int>(i));
    }
    return src;
}

} // namespace freeform::meshio
