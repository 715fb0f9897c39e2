#pragma once
// What the glTF 2.0 reader (gltf_read.cpp), writer (gltf_write.cpp) and byte encodings
// (gltf_encoding.cpp) share: the Source of a .gltf or .glb file (GltfSource), the GLB constants and
// the encodings of data: URIs, buffer URIs and GLB containers. Private to src/io/mesh/ (never
// installed). The format and what the reader keeps: gltf_read.cpp.

#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "source.h"

namespace freeform::meshio::gltf_detail {

using Json = nlohmann::json;
namespace fs = std::filesystem;

constexpr std::uint32_t kGlbMagic = 0x46546C67;   // "glTF"
constexpr std::uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;   // "BIN\0"

// ---------------------------------------------------------------- encodings (gltf_encoding.cpp)

/// The base64 text of bytes (with '=' padding), and bytes from base64 text (false where it is not
/// base64).
std::string encodeBase64(const std::string& bytes);
bool decodeBase64(std::string_view text, std::string& out);

/// A URI's %XX escapes decoded, and a file name as a URI (every byte but A-Z a-z 0-9 - _ . ~
/// escaped).
std::string percentDecode(const std::string& uri);
std::string percentEncode(const std::string& name);

/// The little-endian 32-bit word at byte `at` of b.
std::uint32_t readU32(const std::string& b, std::size_t at);

/// A GLB file: header, JSON chunk (padded with spaces), optional BIN chunk (padded with zeros),
/// then further chunks as they were.
std::string assembleGlb(std::string jsonChunk, bool jsonPadded, const std::string* bin, const std::string& trailing);

// ---------------------------------------------------------------- the file as read

class GltfSource final : public Source {
public:
    bool binary = false;            // read from .glb
    std::string json;               // the JSON text
    Json doc;                       // parsed
    std::vector<std::string> buffers; // data of each buffer (GLB: buffer 0 = the whole BIN chunk)
    std::vector<std::string> bufferFiles; // external file each buffer was read from, or empty
    std::vector<std::string> bufferNames; // that file relative to the glTF file's folder (as its uri names it), or empty
    std::string glbFile;            // a .glb as read, whole (a .gltf is its JSON text)
    bool glbHasBin = false;
    std::string glbTrailingChunks;  // chunks after JSON and BIN, kept as they were
    std::string glbJsonChunk;       // the JSON chunk's data including its padding
    std::string glbBin;             // the BIN chunk as read (written back as it was unless buffer 0 is it)
    bool binIsBuffer0 = false;      // buffer 0 has no uri: it is the BIN chunk
    std::vector<std::vector<BinarySlot>> slots; // per buffer
    struct PositionAccessor {
        int accessor = 0;
        int firstColumn = 0;
        int count = 0;
    };
    std::vector<PositionAccessor> positionAccessors;
    std::vector<int> faceStart{0};
    std::vector<int> faceVertices;
    std::vector<int> normalOfPosition; // per position: a normal index or -1
    Matrix2X texcoords;                // 2 x P, or empty
    Eigen::MatrixXd colors;            // 4 x P, or empty

    PolygonMesh polygonMesh(const Values& now) const override
    {
        PolygonMesh mesh;
        mesh.positions = now.positions;
        mesh.faceStart = faceStart;
        mesh.faceVertices = faceVertices;
        const Eigen::Index p = now.positions.cols();
        bool all = p > 0;
        for (int n : normalOfPosition) all = all && n >= 0;
        if (all) {
            mesh.normals.resize(3, p);
            for (Eigen::Index i = 0; i < p; ++i) mesh.normals.col(i) = now.normals.col(normalOfPosition[static_cast<std::size_t>(i)]);
        }
        mesh.texcoords = texcoords;
        return mesh;
    }

    Eigen::MatrixXd vertexColors() const override { return colors; }

    bool writesSame(const std::string& target) const override { return target == "gltf" || target == "glb"; }

    void writeSame(const std::string& target, const std::string& targetFormat, const Values& now) const override;

    const std::string& fileBytes() const override { return binary ? glbFile : json; }

    std::map<std::string, std::string> companions() const override
    {
        std::map<std::string, std::string> files;
        for (std::size_t j = 0; j < buffers.size(); ++j)
            if (!bufferNames[j].empty()) {
                // Buffers that share a file hold prefixes of it: keep the longest.
                const auto [at, added] = files.emplace(bufferNames[j], buffers[j]);
                if (!added && buffers[j].size() > at->second.size()) at->second = buffers[j];
            }
        return files;
    }
};

} // namespace freeform::meshio::gltf_detail
