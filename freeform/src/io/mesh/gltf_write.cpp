// glTF 2.0 writers (the format: gltf_read.cpp): GltfSource::writeSame, the same file with its
// editable numbers replaced (the buffers patched in place, the POSITION accessors' "min" and "max"
// replaced in the JSON text, nothing else of the text changed; .gltf <-> .glb as gltf_read.cpp
// says), and writeGltfMesh, a new file from a mesh.

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "freeform/io/file.h"
#include "gltf_internal.h"

namespace freeform::meshio {

namespace gltf_detail {

namespace {

// ---------------------------------------------------------------- where values sit in the JSON text

struct Span {
    std::size_t begin = 0;
    std::size_t end = 0;
};

/// Finds the text spans of accessors[i].min / .max, buffers[j].uri and the buffers[j] objects in a
/// JSON text that nlohmann already accepted. Keys: "accessors/3/min", "buffers/0/uri", "buffers/0".
/// It recurses once per nesting level: checkJsonText bounded the depth before (kMaxJsonDepth).
class JsonLocator {
public:
    explicit JsonLocator(const std::string& text) : s_(text) {}

    std::map<std::string, Span> locate()
    {
        std::vector<std::string> path;
        if (s_.compare(0, 3, "\xEF\xBB\xBF") == 0) i_ = 3; // a UTF-8 byte order mark
        space();
        value(path);
        return spans_;
    }

private:
    void space()
    {
        while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\n' || s_[i_] == '\r')) ++i_;
    }

    std::string string()
    {
        const std::size_t start = ++i_;
        while (i_ < s_.size() && s_[i_] != '"') i_ += s_[i_] == '\\' ? 2 : 1;
        const std::string raw = s_.substr(start, i_ - start);
        ++i_;
        // Keys are compared decoded: "\u0061ccessors" is "accessors" (nlohmann already accepted the text).
        if (raw.find('\\') != std::string::npos) return Json::parse("\"" + raw + "\"").get<std::string>();
        return raw;
    }

    void value(std::vector<std::string>& path)
    {
        const std::size_t begin = i_;
        if (s_[i_] == '{') {
            ++i_;
            space();
            while (s_[i_] != '}') {
                path.push_back(string());
                space();
                ++i_; // ':'
                space();
                value(path);
                path.pop_back();
                space();
                if (s_[i_] == ',') {
                    ++i_;
                    space();
                }
            }
            ++i_;
        } else if (s_[i_] == '[') {
            ++i_;
            space();
            int index = 0;
            while (s_[i_] != ']') {
                path.push_back(std::to_string(index++));
                value(path);
                path.pop_back();
                space();
                if (s_[i_] == ',') {
                    ++i_;
                    space();
                }
            }
            ++i_;
        } else if (s_[i_] == '"') {
            string();
        } else {
            while (i_ < s_.size() && s_[i_] != ',' && s_[i_] != '}' && s_[i_] != ']' && s_[i_] != ' ' && s_[i_] != '\n' &&
                   s_[i_] != '\r' && s_[i_] != '\t')
                ++i_;
        }
        record(path, begin);
    }

    void record(const std::vector<std::string>& path, std::size_t begin)
    {
        if (path.size() == 3 && ((path[0] == "accessors" && (path[2] == "min" || path[2] == "max")) ||
                                 (path[0] == "buffers" && path[2] == "uri")))
            spans_[path[0] + "/" + path[1] + "/" + path[2]] = {begin, i_};
        if (path.size() == 2 && path[0] == "buffers") spans_[path[0] + "/" + path[1]] = {begin, i_};
    }

    const std::string& s_;
    std::size_t i_ = 0;
    std::map<std::string, Span> spans_;
};

/// The file name for buffer j of an output: OUT.bin, or OUT_j.bin when there are several.
std::string bufferFileName(const std::string& target, std::size_t j, std::size_t externalCount)
{
    const std::string stem = fs::path(target).stem().string();
    return externalCount > 1 ? stem + "_" + std::to_string(j) + ".bin" : stem + ".bin";
}

bool sameFile(const std::string& a, const std::string& b)
{
    std::error_code ec;
    return fs::equivalent(a, b, ec) && !ec;
}

} // namespace

void GltfSource::writeSame(const std::string& target, const std::string& targetFormat, const Values& now) const
{
    const Values was = original();
    // 1. The buffers with the new numbers.
    std::vector<std::string> data = buffers;
    std::vector<bool> changed(buffers.size(), false);
    for (std::size_t j = 0; j < buffers.size(); ++j) {
        patchBinary(data[j], slots[j], now, was, target);
        changed[j] = data[j] != buffers[j];
    }

    // 2. Text replacements in the JSON, sorted by position.
    const std::map<std::string, Span> spans = JsonLocator(json).locate();
    std::map<std::size_t, std::pair<std::size_t, std::string>> edits; // begin -> (end, text)
    for (const PositionAccessor& pa : positionAccessors) {
        bool moved = false;
        for (int i = 0; i < pa.count && !moved; ++i)
            for (int k = 0; k < 3; ++k) moved = moved || !sameBits(now.positions(k, pa.firstColumn + i), was.positions(k, pa.firstColumn + i));
        if (!moved) continue;
        for (const char* which : {"min", "max"}) {
            const auto span = spans.find("accessors/" + std::to_string(pa.accessor) + "/" + which);
            if (span == spans.end()) continue; // the file had none; adding members is left to validators
            std::string text = "[";
            for (int k = 0; k < 3; ++k) {
                float bound = static_cast<float>(now.positions(k, pa.firstColumn));
                for (int i = 1; i < pa.count; ++i) {
                    const float v = static_cast<float>(now.positions(k, pa.firstColumn + i));
                    bound = which[1] == 'i' ? std::min(bound, v) : std::max(bound, v);
                }
                text += (k ? ", " : "") + formatFloat(bound);
            }
            text += "]";
            edits[span->second.begin] = {span->second.end, text};
        }
    }

    const bool toGlb = targetFormat == "glb";
    const bool inPlace = sameFile(target, path);
    std::size_t externalCount = 0;
    for (std::size_t j = 0; j < buffers.size(); ++j)
        if (!bufferFiles[j].empty() || (binary && j == 0 && glbHasBin && !toGlb)) ++externalCount;
    std::vector<std::pair<std::string, std::string>> binFiles; // (path, bytes) written before the JSON
    const fs::path targetDir = fs::path(target).parent_path();
    for (std::size_t j = 0; j < buffers.size(); ++j) {
        const std::string key = "buffers/" + std::to_string(j);
        const auto uriSpan = spans.find(key + "/uri");
        const bool isBin = uriSpan == spans.end(); // the GLB BIN chunk
        const bool isData = !isBin && bufferFiles[j].empty();
        if (isBin) {
            if (toGlb) continue; // stays the BIN chunk
            // .glb -> .gltf: the BIN chunk becomes an external file; "uri" goes first into the object.
            const std::string name = bufferFileName(target, j, externalCount);
            binFiles.emplace_back((targetDir / name).string(), data[j]);
            edits[spans.at(key).begin + 1] = {spans.at(key).begin + 1, "\"uri\": \"" + percentEncode(name) + "\", "};
        } else if (isData) {
            if (!changed[j]) continue;
            const std::string uri = doc["buffers"][j]["uri"].get<std::string>();
            // Appended piece by piece: "\"" + uri.substr(...) draws a false -Wrestrict from g++ 12 -O3.
            std::string text = "\"";
            text += uri.substr(0, uri.find(',') + 1);
            text += encodeBase64(data[j]);
            text += "\"";
            edits[uriSpan->second.begin] = {uriSpan->second.end, std::move(text)};
        } else if (toGlb) {
            // External buffers are embedded, so the .glb stands alone.
            edits[uriSpan->second.begin] = {uriSpan->second.end,
                                            "\"data:application/octet-stream;base64," + encodeBase64(data[j]) + "\""};
        } else if (inPlace) {
            if (changed[j]) binFiles.emplace_back(bufferFiles[j], data[j]);
        } else {
            // Never overwrite a buffer file the input still refers to.
            const auto takenByInput = [&](const std::string& name) {
                for (const std::string& f : bufferFiles)
                    if (!f.empty() && sameFile(f, (targetDir / name).string())) return true;
                return false;
            };
            std::string name = bufferFileName(target, j, externalCount);
            for (int attempt = 1; takenByInput(name); ++attempt)
                name = fs::path(target).stem().string() + "_" + std::to_string(j) + "_" + std::to_string(attempt) + ".bin";
            binFiles.emplace_back((targetDir / name).string(), data[j]);
            edits[uriSpan->second.begin] = {uriSpan->second.end, "\"" + percentEncode(name) + "\""};
        }
    }

    std::string text;
    std::size_t at = 0;
    for (const auto& [begin, edit] : edits) {
        text.append(json, at, begin - at);
        text += edit.second;
        at = edit.first;
    }
    text.append(json, at, std::string::npos);

    for (const auto& [file, bytes] : binFiles) writeFileAtomically(file, bytes);
    if (!toGlb) {
        writeFileAtomically(target, text);
        return;
    }
    // The BIN chunk: buffer 0 with its new numbers when buffer 0 is the chunk, else the chunk as it
    // was (a BIN chunk no buffer refers to: data[0] may not exist, found by fuzz_mesh_glb).
    const bool keepBin = binary && glbHasBin;
    const std::string* bin = !keepBin ? nullptr : binIsBuffer0 ? &data[0] : &glbBin;
    if (binary && edits.empty()) writeFileAtomically(target, assembleGlb(glbJsonChunk, true, bin, glbTrailingChunks));
    else writeFileAtomically(target, assembleGlb(text, false, bin, binary ? glbTrailingChunks : std::string()));
}

} // namespace gltf_detail

void writeGltfMesh(const std::string& path, const PolygonMesh& mesh, const Eigen::MatrixXd& colors, bool binary)
{
    using namespace gltf_detail;
    using Ordered = nlohmann::ordered_json;
    const int v = mesh.vertexCount();
    const bool n = mesh.normals.cols() == v && v > 0;
    const bool uv = mesh.texcoords.cols() == v && v > 0;
    const int colorRows = colors.cols() == v && v > 0 && colors.rows() >= 3 ? (colors.rows() >= 4 ? 4 : 3) : 0;

    std::string buffer;
    const auto putFloat = [&](double value) {
        char b[4];
        writeBinary(b, BinaryType::Float32, false, value, path);
        buffer.append(b, 4);
    };
    Ordered accessors = Ordered::array(), views = Ordered::array(), attributes = Ordered::object();
    const auto addView = [&](std::size_t begin, int target) {
        Ordered view = {{"buffer", 0}, {"byteOffset", begin}, {"byteLength", buffer.size() - begin}};
        if (target) view["target"] = target;
        views.push_back(view);
        return static_cast<int>(views.size()) - 1;
    };
    const auto addFloats = [&](const char* name, const auto& m, int rows, bool bounds) {
        const std::size_t begin = buffer.size();
        for (int i = 0; i < v; ++i)
            for (int k = 0; k < rows; ++k) putFloat(m(k, i));
        Ordered accessor = {{"bufferView", addView(begin, 34962)}, {"componentType", 5126}, {"count", v},
                            {"type", rows == 2 ? "VEC2" : rows == 3 ? "VEC3" : "VEC4"}};
        if (bounds) {
            Ordered lo = Ordered::array(), hi = Ordered::array();
            for (int k = 0; k < rows; ++k) {
                float a = static_cast<float>(m(k, 0)), b = a;
                for (int i = 1; i < v; ++i) {
                    a = std::min(a, static_cast<float>(m(k, i)));
                    b = std::max(b, static_cast<float>(m(k, i)));
                }
                double da = 0, db = 0;
                parseDouble(formatFloat(a), da);
                parseDouble(formatFloat(b), db);
                lo.push_back(da);
                hi.push_back(db);
            }
            accessor["min"] = lo;
            accessor["max"] = hi;
        }
        accessors.push_back(accessor);
        attributes[name] = static_cast<int>(accessors.size()) - 1;
    };
    if (v > 0) addFloats("POSITION", mesh.positions, 3, true);
    if (n) addFloats("NORMAL", mesh.normals, 3, false);
    if (uv) addFloats("TEXCOORD_0", mesh.texcoords, 2, false);
    if (colorRows) addFloats("COLOR_0", colors, colorRows, false);

    Ordered primitive = {{"attributes", attributes}, {"mode", 4}};
    std::size_t triangles = 0;
    for (int f = 0; f < mesh.faceCount(); ++f) triangles += static_cast<std::size_t>(mesh.faceSize(f) - 2);
    if (triangles > 0) {
        const std::size_t begin = buffer.size();
        for (int f = 0; f < mesh.faceCount(); ++f)
            for (int k = 1; k + 1 < mesh.faceSize(f); ++k)
                for (int c : {mesh.face(f)[0], mesh.face(f)[k], mesh.face(f)[k + 1]}) {
                    char b[4];
                    writeBinary(b, BinaryType::UInt32, false, c, path);
                    buffer.append(b, 4);
                }
        accessors.push_back({{"bufferView", addView(begin, 34963)}, {"componentType", 5125}, {"count", triangles * 3}, {"type", "SCALAR"}});
        primitive["indices"] = static_cast<int>(accessors.size()) - 1;
    }
    Ordered doc = {{"asset", {{"version", "2.0"}, {"generator", "freeform"}}},
                   {"scene", 0},
                   {"scenes", Ordered::array({{{"nodes", {0}}}})},
                   {"nodes", Ordered::array({{{"mesh", 0}}})},
                   {"meshes", Ordered::array({{{"primitives", Ordered::array({primitive})}}})}};
    if (!accessors.empty()) {
        Ordered b = {{"byteLength", buffer.size()}};
        std::string binName;
        if (!binary) {
            binName = fs::path(path).stem().string() + ".bin";
            b = {{"uri", percentEncode(binName)}, {"byteLength", buffer.size()}};
        }
        doc["buffers"] = Ordered::array({b});
        doc["bufferViews"] = views;
        doc["accessors"] = accessors;
        if (!binary) writeFileAtomically((fs::path(path).parent_path() / binName).string(), buffer);
    }
    const std::string text = doc.dump(2) + "\n";
    if (binary) writeFileAtomically(path, assembleGlb(text, false, accessors.empty() ? nullptr : &buffer, std::string()));
    else writeFileAtomically(path, text);
}

} // namespace freeform::meshio
