// glTF 2.0 (.gltf with external or data: buffers, .glb), format-preserving: the JSON text and every
// buffer byte are kept; the float32 data of the POSITION, NORMAL and TANGENT accessors of every
// mesh primitive are the editable slots, rewritten in place in their buffers. When positions move,
// the POSITION accessors' "min" and "max" are replaced in the JSON text (nothing else of the text
// changes); a changed data: buffer is re-encoded in place; external buffers are written beside the
// output (renamed after it when the output is another file). .gltf <-> .glb: a .glb written from a
// .gltf embeds its external buffers as data: URIs (a valid GLB without a BIN chunk); a .gltf written
// from a .glb stores the BIN chunk as OUT.bin.

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>

#include "freeform/io/file.h"
#include "freeform/io/json_check.h"
#include "source.h"

namespace freeform::meshio {

namespace {

using Json = nlohmann::json;
namespace fs = std::filesystem;

constexpr std::uint32_t kGlbMagic = 0x46546C67;   // "glTF"
constexpr std::uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;   // "BIN\0"

// ---------------------------------------------------------------- base64 and URIs

const char kBase64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

std::string encodeBase64(const std::string& bytes)
{
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    std::size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const std::uint32_t v = (static_cast<std::uint8_t>(bytes[i]) << 16) | (static_cast<std::uint8_t>(bytes[i + 1]) << 8) |
                                static_cast<std::uint8_t>(bytes[i + 2]);
        for (int k = 3; k >= 0; --k) out.push_back(kBase64[(v >> (6 * k)) & 63]);
    }
    if (i < bytes.size()) {
        std::uint32_t v = static_cast<std::uint32_t>(static_cast<std::uint8_t>(bytes[i])) << 16;
        if (i + 1 < bytes.size()) v |= static_cast<std::uint32_t>(static_cast<std::uint8_t>(bytes[i + 1])) << 8;
        out.push_back(kBase64[(v >> 18) & 63]);
        out.push_back(kBase64[(v >> 12) & 63]);
        out.push_back(i + 1 < bytes.size() ? kBase64[(v >> 6) & 63] : '=');
        out.push_back('=');
    }
    return out;
}

bool decodeBase64(std::string_view text, std::string& out)
{
    std::uint32_t acc = 0;
    int bits = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '=') {
            for (std::size_t j = i; j < text.size(); ++j)
                if (text[j] != '=') return false;
            break;
        }
        const char* p = std::strchr(kBase64, c);
        if (c == '\0' || p == nullptr) return false;
        acc = (acc << 6) | static_cast<std::uint32_t>(p - kBase64);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out.push_back(static_cast<char>((acc >> bits) & 0xFF));
        }
    }
    return true;
}

std::string percentDecode(const std::string& uri)
{
    std::string out;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
            out.push_back(static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16)));
            i += 2;
        } else {
            out.push_back(uri[i]);
        }
    }
    return out;
}

std::string percentEncode(const std::string& name)
{
    static const char* const hex = "0123456789ABCDEF";
    std::string out;
    for (const char ch : name) {
        const auto c = static_cast<unsigned char>(ch);
        if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~') {
            out.push_back(ch);
        } else {
            out.push_back('%');
            out.push_back(hex[c >> 4]);
            out.push_back(hex[c & 15]);
        }
    }
    return out;
}

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

// ---------------------------------------------------------------- checked members
//
// Every number of the JSON that becomes an index, a count, an offset or a length is read through
// these: an integer (not a float, not a string), inside a stated range, so that no cast is
// undefined and no later sum or product can wrap (docs/mesh-io.md, "Hostile input").

/// Largest byte offset / length / count taken from a file: far beyond any real buffer, small
/// enough that sums and products of two of them cannot overflow 64 bits.
constexpr long long kMaxBytes = 1LL << 40;

const Json& emptyArray()
{
    static const Json empty = Json::array();
    return empty;
}

const Json& emptyObject()
{
    static const Json empty = Json::object();
    return empty;
}

/// obj[key] as an array (a reference, never a copy: lookups stay linear); empty when absent.
const Json& arrayMember(const Json& obj, const char* key, const std::string& where)
{
    if (!obj.is_object()) throw Error(where + " is not a JSON object");
    const auto it = obj.find(key);
    if (it == obj.end()) return emptyArray();
    if (!it->is_array()) throw Error(where + ": \"" + key + "\" is not an array");
    return *it;
}

const Json& objectMember(const Json& obj, const char* key, const std::string& where)
{
    if (!obj.is_object()) throw Error(where + " is not a JSON object");
    const auto it = obj.find(key);
    if (it == obj.end()) return emptyObject();
    if (!it->is_object()) throw Error(where + ": \"" + key + "\" is not an object");
    return *it;
}

/// An integer in [lo, hi]; Error naming where and key otherwise.
long long checkedInteger(const Json& value, const std::string& where, const char* key, long long lo, long long hi)
{
    long long v = 0;
    if (value.is_number_unsigned()) {
        const auto u = value.get<std::uint64_t>();
        if (u > static_cast<std::uint64_t>(hi)) throw Error(where + ": \"" + key + "\" is " + std::to_string(u) + ", above " + std::to_string(hi));
        v = static_cast<long long>(u);
    } else if (value.is_number_integer()) {
        v = value.get<long long>();
    } else {
        throw Error(where + ": \"" + key + "\" must be an integer");
    }
    if (v < lo || v > hi)
        throw Error(where + ": \"" + key + "\" is " + std::to_string(v) + ", outside " + std::to_string(lo) + ".." + std::to_string(hi));
    return v;
}

long long integerMember(const Json& obj, const char* key, const std::string& where, long long lo, long long hi)
{
    if (!obj.is_object()) throw Error(where + " is not a JSON object");
    const auto it = obj.find(key);
    if (it == obj.end()) throw Error(where + " has no \"" + key + "\"");
    return checkedInteger(*it, where, key, lo, hi);
}

long long integerMember(const Json& obj, const char* key, const std::string& where, long long lo, long long hi, long long fallback)
{
    if (!obj.is_object()) throw Error(where + " is not a JSON object");
    const auto it = obj.find(key);
    if (it == obj.end()) return fallback;
    return checkedInteger(*it, where, key, lo, hi);
}

int indexMember(const Json& obj, const char* key, const std::string& where)
{
    return static_cast<int>(integerMember(obj, key, where, 0, 2147483647LL));
}

// ---------------------------------------------------------------- accessors

int componentSize(int componentType)
{
    switch (componentType) {
    case 5120:
    case 5121: return 1;
    case 5122:
    case 5123: return 2;
    case 5125:
    case 5126: return 4;
    default: return 0;
    }
}

BinaryType componentBinaryType(int componentType)
{
    switch (componentType) {
    case 5120: return BinaryType::Int8;
    case 5121: return BinaryType::UInt8;
    case 5122: return BinaryType::Int16;
    case 5123: return BinaryType::UInt16;
    case 5125: return BinaryType::UInt32;
    default: return BinaryType::Float32;
    }
}

int typeComponents(const std::string& type)
{
    if (type == "SCALAR") return 1;
    if (type == "VEC2") return 2;
    if (type == "VEC3") return 3;
    if (type == "VEC4") return 4;
    return 0;
}

struct AccessorView {
    int buffer = 0;
    std::size_t offset = 0; // of element 0 in the buffer
    std::size_t stride = 0;
    int count = 0;
    int components = 0;
    int componentType = 0;
    bool normalized = false;

    std::size_t at(int element, int component) const
    {
        return offset + static_cast<std::size_t>(element) * stride +
               static_cast<std::size_t>(component) * static_cast<std::size_t>(componentSize(componentType));
    }
};

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

/// The place of an accessor's data; Error when it has none or it lies outside its buffer. Every
/// offset, stride and count is checked in 64-bit arithmetic that cannot wrap (each term below
/// kMaxBytes) against the real sizes of the view and the buffer.
AccessorView viewOf(const GltfSource& src, int index, const std::string& what)
{
    const Json& accessors = arrayMember(src.doc, "accessors", src.path);
    if (index < 0 || index >= static_cast<int>(accessors.size()))
        throw Error(src.path + ": " + what + " refers to accessor " + std::to_string(index) + ", the file has " +
                    std::to_string(accessors.size()));
    const Json& a = accessors[static_cast<std::size_t>(index)];
    const std::string name = src.path + ": accessor " + std::to_string(index) + " (" + what + ")";
    if (!a.is_object()) throw Error(name + " is not a JSON object");
    if (a.contains("sparse")) throw Error(name + " is sparse, which is not supported");
    if (!a.contains("bufferView")) throw Error(name + " has no bufferView, which is not supported");
    AccessorView v;
    v.componentType = static_cast<int>(integerMember(a, "componentType", name, 0, 1 << 20));
    const auto type = a.find("type");
    v.components = type != a.end() && type->is_string() ? typeComponents(type->get<std::string>()) : 0;
    v.count = static_cast<int>(integerMember(a, "count", name, 0, 2147483647LL));
    const auto normalized = a.find("normalized");
    if (normalized != a.end() && !normalized->is_boolean()) throw Error(name + ": \"normalized\" must be true or false");
    v.normalized = normalized != a.end() && normalized->get<bool>();
    if (componentSize(v.componentType) == 0 || v.components == 0)
        throw Error(name + " has an unsupported componentType or type");
    const int viewIndex = indexMember(a, "bufferView", name);
    const Json& views = arrayMember(src.doc, "bufferViews", src.path);
    if (viewIndex >= static_cast<int>(views.size()))
        throw Error(name + " refers to bufferView " + std::to_string(viewIndex) + ", the file has " + std::to_string(views.size()));
    const Json& view = views[static_cast<std::size_t>(viewIndex)];
    const std::string viewName = src.path + ": bufferView " + std::to_string(viewIndex);
    v.buffer = indexMember(view, "buffer", viewName);
    if (v.buffer >= static_cast<int>(src.buffers.size()))
        throw Error(viewName + " refers to buffer " + std::to_string(v.buffer) + ", the file has " + std::to_string(src.buffers.size()));
    const std::uint64_t bufferSize = src.buffers[static_cast<std::size_t>(v.buffer)].size();
    const auto viewOffset = static_cast<std::uint64_t>(integerMember(view, "byteOffset", viewName, 0, kMaxBytes, 0));
    const auto viewLength = static_cast<std::uint64_t>(integerMember(view, "byteLength", viewName, 1, kMaxBytes));
    if (viewOffset + viewLength > bufferSize)
        throw Error(viewName + " (bytes " + std::to_string(viewOffset) + ".." + std::to_string(viewOffset + viewLength) +
                    ") reaches past the end of buffer " + std::to_string(v.buffer) + " (" + std::to_string(bufferSize) +
                    " bytes; truncated buffer?)");
    const auto elementSize = static_cast<std::uint64_t>(componentSize(v.componentType) * v.components);
    // byteStride: absent means tightly packed; present, the spec allows 4..252 (a stride smaller
    // than the element would make elements overlap, 0 would make every element the same bytes).
    const auto stride = static_cast<std::uint64_t>(integerMember(view, "byteStride", viewName, 0, 252, static_cast<long long>(elementSize)));
    if (stride < elementSize)
        throw Error(viewName + ": byteStride " + std::to_string(stride) + " is smaller than the " + std::to_string(elementSize) +
                    "-byte elements of " + name.substr(src.path.size() + 2));
    const auto accessorOffset = static_cast<std::uint64_t>(integerMember(a, "byteOffset", name, 0, kMaxBytes, 0));
    // The last element ends at accessorOffset + stride * (count - 1) + elementSize: count < 2^31,
    // stride <= 252, offsets < 2^40, so nothing here can wrap.
    const std::uint64_t needed =
        v.count == 0 ? 0 : accessorOffset + stride * static_cast<std::uint64_t>(v.count - 1) + elementSize;
    if (needed > viewLength)
        throw Error(name + ": " + std::to_string(v.count) + " elements of " + std::to_string(elementSize) + " bytes at stride " +
                    std::to_string(stride) + " from byte " + std::to_string(accessorOffset) + " need " + std::to_string(needed) +
                    " bytes: past the end of bufferView " + std::to_string(viewIndex) + ", which has " + std::to_string(viewLength) +
                    " (truncated buffer?)");
    v.stride = static_cast<std::size_t>(stride);
    v.offset = static_cast<std::size_t>(viewOffset + accessorOffset);
    return v;
}

/// Component values of an accessor as doubles (normalized integers mapped to [0, 1] / [-1, 1]).
double componentValue(const GltfSource& src, const AccessorView& v, int element, int component)
{
    const double raw = readBinary(src.buffers[static_cast<std::size_t>(v.buffer)].data() + v.at(element, component),
                                  componentBinaryType(v.componentType), false);
    if (!v.normalized) return raw;
    switch (v.componentType) {
    case 5120: return std::max(raw / 127.0, -1.0);
    case 5121: return raw / 255.0;
    case 5122: return std::max(raw / 32767.0, -1.0);
    case 5123: return raw / 65535.0;
    default: return raw;
    }
}

Error refuseUri(const GltfSource& src, const std::string& uri, const std::string& name, const std::string& why)
{
    return Error(src.path + ": " + name + ": the uri \"" + uri + "\" " + why +
                 " (external buffers are read only from the glTF file's own folder and below)");
}

/// The path an external buffer URI names relative to the glTF file's folder, checked without the
/// disk: a relative path without ".." components, no scheme, no absolute path. Normalised ("./a"
/// is "a"), with forward slashes: the key of a companion file (MeshFile::companions).
fs::path relativeBufferPath(const GltfSource& src, const std::string& uri, const std::string& name)
{
    const std::string decoded = percentDecode(uri);
    if (decoded.empty()) throw refuseUri(src, uri, name, "is empty");
    if (decoded.find(':') != std::string::npos)
        throw refuseUri(src, uri, name, "has a scheme or a drive (only data: URIs and relative paths are read)");
    if (decoded.find('\0') != std::string::npos || decoded.find('\\') != std::string::npos)
        throw refuseUri(src, uri, name, "holds a NUL or a backslash");
    const fs::path relative(decoded);
    if (relative.is_absolute() || relative.has_root_path() || decoded.front() == '/') throw refuseUri(src, uri, name, "is an absolute path");
    for (const fs::path& part : relative)
        if (part == "..") throw refuseUri(src, uri, name, "leaves the folder (..)");
    return relative.lexically_normal();
}

/// The file an external buffer URI names, confined to the glTF file's own folder: the checks of
/// relativeBufferPath, and a regular file (not a device, a folder or a link that leads outside).
/// Error naming the buffer otherwise (docs/mesh-io.md).
std::string confinedBufferFile(const GltfSource& src, const std::string& uri, const std::string& name)
{
    const fs::path relative = relativeBufferPath(src, uri, name);
    const fs::path dir = fs::path(src.path).parent_path();
    const fs::path file = dir / relative;
    std::error_code ec;
    const fs::file_status status = fs::status(file, ec);
    if (ec || !fs::exists(status)) throw Error(src.path + ": " + name + ": " + file.string() + ": cannot open the file for reading");
    if (!fs::is_regular_file(status)) throw refuseUri(src, uri, name, "is not a regular file");
    const fs::path realDir = fs::weakly_canonical(dir.empty() ? fs::path(".") : dir, ec);
    const fs::path realFile = fs::weakly_canonical(file, ec);
    if (ec) throw refuseUri(src, uri, name, "cannot be resolved");
    const auto rel = realFile.lexically_relative(realDir);
    if (rel.empty() || *rel.begin() == "..") throw refuseUri(src, uri, name, "leads outside the folder through a link");
    return file.string();
}

/// At most maxBytes of a regular file (never more than the buffer declares).
std::string readPrefix(const std::string& file, std::uint64_t maxBytes, const GltfSource& src, const std::string& name)
{
    std::ifstream in(file, std::ios::binary);
    if (!in) throw Error(src.path + ": " + name + ": " + file + ": cannot open the file for reading");
    std::string data;
    char chunk[65536];
    while (data.size() < maxBytes && in) {
        const std::uint64_t want = std::min<std::uint64_t>(sizeof chunk, maxBytes - data.size());
        in.read(chunk, static_cast<std::streamsize>(want));
        data.append(chunk, static_cast<std::size_t>(in.gcount()));
    }
    if (in.bad()) throw Error(src.path + ": " + name + ": " + file + ": reading failed");
    return data;
}

void loadBuffers(GltfSource& src, const std::string& bin, const Companions* companions)
{
    const Json& buffers = arrayMember(src.doc, "buffers", src.path);
    for (std::size_t j = 0; j < buffers.size(); ++j) {
        const Json& b = buffers[j];
        const std::string name = "buffer " + std::to_string(j);
        const auto length = static_cast<std::uint64_t>(integerMember(b, "byteLength", src.path + ": " + name, 1, kMaxBytes));
        std::string data;
        std::string file;
        std::string relative;
        if (!b.contains("uri")) {
            if (!src.binary || j != 0 || !src.glbHasBin)
                throw Error(src.path + ": " + name + " has no uri and there is no GLB BIN chunk for it");
            data = bin;
            src.binIsBuffer0 = true;
        } else {
            if (!b.at("uri").is_string()) throw Error(src.path + ": " + name + ": \"uri\" must be a string");
            const std::string uri = b.at("uri").get<std::string>();
            if (uri.rfind("data:", 0) == 0) {
                const std::size_t comma = uri.find(',');
                if (comma == std::string::npos || comma < 7 || uri.compare(comma - 7, 7, ";base64") != 0)
                    throw Error(src.path + ": " + name + ": only base64 data: URIs are supported");
                if (!decodeBase64(std::string_view(uri).substr(comma + 1), data))
                    throw Error(src.path + ": " + name + ": the data: URI is not valid base64");
            } else if (companions != nullptr) {
                relative = relativeBufferPath(src, uri, name).generic_string();
                const auto found = companions->find(relative);
                if (found == companions->end())
                    throw Error(src.path + ": " + name + ": the uri \"" + uri + "\" names " + relative +
                                ", which is not among the files given with it");
                file = (fs::path(src.path).parent_path() / relative).string();
                data = found->second.substr(0, length); // as from the disk: never more than byteLength
            } else {
                relative = relativeBufferPath(src, uri, name).generic_string();
                file = confinedBufferFile(src, uri, name);
                data = readPrefix(file, length, src, name); // never more than byteLength (a device never ends)
            }
        }
        if (data.size() < length)
            throw Error(src.path + ": " + name + " holds " + std::to_string(data.size()) + " bytes, its byteLength is " +
                        std::to_string(length) + " (truncated?)");
        src.buffers.push_back(std::move(data));
        src.bufferFiles.push_back(file);
        src.bufferNames.push_back(relative);
    }
    src.slots.resize(src.buffers.size());
}

/// Room for `added` more elements, growing the capacity at least twofold.
template <class T>
void growFor(std::vector<T>& v, std::size_t added)
{
    if (v.size() + added > v.capacity()) v.reserve(std::max(v.size() + added, 2 * v.capacity()));
}

void readEditable(GltfSource& src)
{
    const Json& meshes = arrayMember(src.doc, "meshes", src.path);
    std::map<int, int> positionColumn;                      // POSITION accessor -> its first column
    std::map<std::pair<int, int>, int> normalColumn;        // (NORMAL accessor, POSITION accessor) -> first normal
    std::map<std::pair<int, int>, int> tangentColumn;
    std::vector<double> positions, normals, tangents;
    std::vector<double> uvs, colors;
    std::vector<int> hasUv, hasColor;
    int columns = 0, normalCount = 0, tangentCount = 0;

    const auto readFloats = [&](int accessor, int first, int rows, Field field, const std::string& what, std::vector<double>& into,
                                int expectedCount) {
        const AccessorView v = viewOf(src, accessor, what);
        if (v.componentType != 5126 || v.components != rows)
            throw Error(src.path + ": accessor " + std::to_string(accessor) + " (" + what + ") must be float " +
                        (rows == 3 ? "VEC3" : "VEC4") + " (quantized attributes are not supported)");
        if (expectedCount >= 0 && v.count != expectedCount)
            throw Error(src.path + ": accessor " + std::to_string(accessor) + " (" + what + ") has " + std::to_string(v.count) +
                        " elements, POSITION has " + std::to_string(expectedCount));
        // Reserve geometrically: an exact reserve per accessor would copy everything read so far
        // for every accessor (quadratic in the accessor count; benchmarks/bench_mesh_io.cpp).
        const std::size_t added = static_cast<std::size_t>(v.count) * static_cast<std::size_t>(rows);
        growFor(into, added);
        std::vector<BinarySlot>& slots = src.slots[static_cast<std::size_t>(v.buffer)];
        growFor(slots, added);
        for (int i = 0; i < v.count; ++i)
            for (int k = 0; k < rows; ++k) {
                const std::size_t offset = v.at(i, k);
                const double value = readBinary(src.buffers[static_cast<std::size_t>(v.buffer)].data() + offset, BinaryType::Float32, false);
                if (!std::isfinite(value))
                    throw Error(src.path + ": accessor " + std::to_string(accessor) + " (" + what + ") element " + std::to_string(i) +
                                " (buffer " + std::to_string(v.buffer) + " byte " + std::to_string(offset) + ") is not finite");
                into.push_back(value);
                slots.push_back(
                    {offset, first + i, field, static_cast<std::uint8_t>(k), BinaryType::Float32, false});
            }
        return v.count;
    };

    for (std::size_t m = 0; m < meshes.size(); ++m) {
        const Json& prims = arrayMember(meshes[m], "primitives", src.path + ": mesh " + std::to_string(m));
        for (std::size_t p = 0; p < prims.size(); ++p) {
            const Json& prim = prims[p];
            const std::string what = "mesh " + std::to_string(m) + " primitive " + std::to_string(p);
            const Json& attributes = objectMember(prim, "attributes", src.path + ": " + what);
            if (!attributes.contains("POSITION")) continue;
            const int pa = indexMember(attributes, "POSITION", src.path + ": " + what + " attributes");
            auto [it, fresh] = positionColumn.emplace(pa, columns);
            const int base = it->second;
            int count = 0;
            if (fresh) {
                count = readFloats(pa, base, 3, Field::Position, what + " POSITION", positions, -1);
                src.positionAccessors.push_back({pa, base, count});
                columns += count;
                hasUv.resize(static_cast<std::size_t>(columns), 0);
                hasColor.resize(static_cast<std::size_t>(columns), 0);
                uvs.resize(static_cast<std::size_t>(columns) * 2, 0.0);
                colors.resize(static_cast<std::size_t>(columns) * 4, 1.0);
                src.normalOfPosition.resize(static_cast<std::size_t>(columns), -1);
            } else {
                for (const auto& acc : src.positionAccessors)
                    if (acc.accessor == pa) count = acc.count;
            }
            if (attributes.contains("NORMAL")) {
                const int na = indexMember(attributes, "NORMAL", src.path + ": " + what + " attributes");
                auto [nit, nfresh] = normalColumn.emplace(std::make_pair(na, pa), normalCount);
                if (nfresh) {
                    readFloats(na, normalCount, 3, Field::Normal, what + " NORMAL", normals, count);
                    for (int i = 0; i < count; ++i) {
                        src.normalAnchors.push_back(base + i);
                        if (src.normalOfPosition[static_cast<std::size_t>(base + i)] < 0)
                            src.normalOfPosition[static_cast<std::size_t>(base + i)] = normalCount + i;
                    }
                    normalCount += count;
                }
            }
            if (attributes.contains("TANGENT")) {
                const int ta = indexMember(attributes, "TANGENT", src.path + ": " + what + " attributes");
                auto [tit, tfresh] = tangentColumn.emplace(std::make_pair(ta, pa), tangentCount);
                if (tfresh) {
                    readFloats(ta, tangentCount, 4, Field::Tangent, what + " TANGENT", tangents, count);
                    for (int i = 0; i < count; ++i) src.tangentAnchors.push_back(base + i);
                    tangentCount += count;
                }
            }
            // Texture coordinates and colours (any component type), for conversion and toPolygonMesh.
            const auto perVertex = [&](const char* key, int minRows, std::vector<double>& into, int rows, std::vector<int>& has) {
                if (!attributes.contains(key)) return;
                const int acc = indexMember(attributes, key, src.path + ": " + what + " attributes");
                const Json& accessors = arrayMember(src.doc, "accessors", src.path);
                if (acc < 0 || acc >= static_cast<int>(accessors.size()) || accessors[static_cast<std::size_t>(acc)].contains("sparse") ||
                    !accessors[static_cast<std::size_t>(acc)].contains("bufferView"))
                    return; // not carried over (kept in the file all the same)
                const AccessorView v = viewOf(src, acc, what + " " + key);
                if (v.count != count || v.components < minRows) return;
                for (int i = 0; i < count; ++i) {
                    if (has[static_cast<std::size_t>(base + i)]) continue;
                    has[static_cast<std::size_t>(base + i)] = 1;
                    for (int k = 0; k < std::min(rows, v.components); ++k)
                        into[static_cast<std::size_t>(base + i) * static_cast<std::size_t>(rows) + static_cast<std::size_t>(k)] =
                            componentValue(src, v, i, k);
                }
            };
            perVertex("TEXCOORD_0", 2, uvs, 2, hasUv);
            perVertex("COLOR_0", 3, colors, 4, hasColor);

            // Faces.
            const int mode = static_cast<int>(integerMember(prim, "mode", src.path + ": " + what, 0, 6, 4));
            std::vector<int> indices;
            if (prim.contains("indices")) {
                const int ia = indexMember(prim, "indices", src.path + ": " + what);
                const AccessorView v = viewOf(src, ia, what + " indices");
                if (v.components != 1 || v.componentType == 5126 || v.componentType == 5120 || v.componentType == 5122)
                    throw Error(src.path + ": accessor " + std::to_string(ia) + " (" + what +
                                " indices) must be unsigned byte, short or int SCALAR");
                if (v.normalized)
                    throw Error(src.path + ": accessor " + std::to_string(ia) + " (" + what +
                                " indices) is marked normalized, which indices must not be");
                indices.reserve(static_cast<std::size_t>(v.count));
                for (int i = 0; i < v.count; ++i) {
                    const double idx = componentValue(src, v, i, 0);
                    if (idx >= count)
                        throw Error(src.path + ": " + what + " index " + std::to_string(i) + " refers to vertex " +
                                    formatDouble(idx) + ", POSITION has " + std::to_string(count));
                    indices.push_back(static_cast<int>(idx));
                }
            } else {
                for (int i = 0; i < count; ++i) indices.push_back(i);
            }
            const auto triangle = [&](int a, int b, int c) {
                src.faceVertices.insert(src.faceVertices.end(), {base + a, base + b, base + c});
                src.faceStart.push_back(static_cast<int>(src.faceVertices.size()));
            };
            const int n = static_cast<int>(indices.size());
            const auto idx = [&](int i) { return indices[static_cast<std::size_t>(i)]; };
            if (mode == 4) {
                if (n % 3 != 0)
                    throw Error(src.path + ": " + what + " has " + std::to_string(n) + " triangle indices, not a multiple of 3");
                for (int i = 0; i < n; i += 3) triangle(idx(i), idx(i + 1), idx(i + 2));
            } else if (mode == 5) {
                for (int i = 0; i + 2 < n; ++i) {
                    if (i % 2 == 0) triangle(idx(i), idx(i + 1), idx(i + 2));
                    else triangle(idx(i + 1), idx(i), idx(i + 2));
                }
            } else if (mode == 6) {
                for (int i = 1; i + 1 < n; ++i) triangle(idx(0), idx(i), idx(i + 1));
            } else if (mode < 0 || mode > 6) {
                throw Error(src.path + ": " + what + " has an unknown mode " + std::to_string(mode));
            }
        }
    }
    src.positions = Eigen::Map<const Matrix3X>(positions.data(), 3, columns);
    src.normals = Eigen::Map<const Matrix3X>(normals.data(), 3, normalCount);
    src.tangents = Eigen::Map<const Matrix4X>(tangents.data(), 4, tangentCount);
    bool allUv = columns > 0, allColor = columns > 0;
    for (int i = 0; i < columns; ++i) {
        allUv = allUv && hasUv[static_cast<std::size_t>(i)];
        allColor = allColor && hasColor[static_cast<std::size_t>(i)];
    }
    if (allUv) src.texcoords = Eigen::Map<const Matrix2X>(uvs.data(), 2, columns);
    if (allColor) src.colors = Eigen::Map<const Eigen::MatrixXd>(colors.data(), 4, columns);
}

std::uint32_t readU32(const std::string& b, std::size_t at) { return static_cast<std::uint32_t>(readBinary(b.data() + at, BinaryType::UInt32, false)); }

void appendU32(std::string& out, std::uint32_t v)
{
    char buffer[4];
    writeBinary(buffer, BinaryType::UInt32, false, v, "glb");
    out.append(buffer, 4);
}

/// A GLB file: header, JSON chunk (padded with spaces), optional BIN chunk (padded with zeros),
/// then further chunks as they were.
std::string assembleGlb(std::string jsonChunk, bool jsonPadded, const std::string* bin, const std::string& trailing)
{
    if (!jsonPadded)
        while (jsonChunk.size() % 4 != 0) jsonChunk.push_back(' ');
    std::string binChunk;
    if (bin != nullptr) {
        binChunk = *bin;
        while (binChunk.size() % 4 != 0) binChunk.push_back('\0');
    }
    std::string out;
    appendU32(out, kGlbMagic);
    appendU32(out, 2);
    const std::size_t total = 12 + 8 + jsonChunk.size() + (bin != nullptr ? 8 + binChunk.size() : 0) + trailing.size();
    appendU32(out, static_cast<std::uint32_t>(total));
    appendU32(out, static_cast<std::uint32_t>(jsonChunk.size()));
    appendU32(out, kChunkJson);
    out += jsonChunk;
    if (bin != nullptr) {
        appendU32(out, static_cast<std::uint32_t>(binChunk.size()));
        appendU32(out, kChunkBin);
        out += binChunk;
    }
    out += trailing;
    return out;
}

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
            edits[uriSpan->second.begin] = {uriSpan->second.end, "\"" + uri.substr(0, uri.find(',') + 1) + encodeBase64(data[j]) + "\""};
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

} // namespace

std::unique_ptr<Source> readGltf(const std::string& path, std::string bytes, bool binary, const Companions* companions)
{
    auto src = std::make_unique<GltfSource>();
    src->path = path;
    src->format = binary ? "glb" : "gltf";
    src->binary = binary;
    std::string bin;
    if (binary) {
        const std::size_t size = bytes.size();
        if (size < 20) throw Error(path + ": " + std::to_string(size) + " bytes, too short for a GLB file (truncated?)");
        if (readU32(bytes, 0) != kGlbMagic) throw Error(path + ": not a GLB file (the magic 'glTF' is missing)");
        if (readU32(bytes, 4) != 2) throw Error(path + ": GLB version " + std::to_string(readU32(bytes, 4)) + " (only 2 is read)");
        const std::uint32_t length = readU32(bytes, 8);
        if (length != size)
            throw Error(path + ": the GLB header says " + std::to_string(length) + " bytes, the file has " + std::to_string(size) +
                        (length > size ? " (truncated?)" : ""));
        std::size_t at = 12;
        int chunk = 0;
        while (at < size) {
            if (size - at < 8) throw Error(path + ": byte " + std::to_string(at) + ": truncated GLB chunk header");
            const std::uint32_t chunkLength = readU32(bytes, at);
            const std::uint32_t type = readU32(bytes, at + 4);
            if (chunkLength > size - at - 8)
                throw Error(path + ": byte " + std::to_string(at) + ": GLB chunk " + std::to_string(chunk) + " claims " +
                            std::to_string(chunkLength) + " bytes, " + std::to_string(size - at - 8) + " remain (truncated?)");
            const std::string content = bytes.substr(at + 8, chunkLength);
            if (chunk == 0) {
                if (type != kChunkJson) throw Error(path + ": the first GLB chunk is not JSON");
                src->glbJsonChunk = content;
                src->json = content;
            } else if (chunk == 1 && type == kChunkBin) {
                src->glbHasBin = true;
                bin = content;
                src->glbBin = content;
            } else {
                src->glbTrailingChunks += bytes.substr(at, 8 + static_cast<std::size_t>(chunkLength));
            }
            at += 8 + static_cast<std::size_t>(chunkLength);
            ++chunk;
        }
        if (chunk == 0) throw Error(path + ": the GLB file has no JSON chunk");
        src->glbFile = std::move(bytes);
    } else {
        src->json = std::move(bytes);
    }

    checkJsonText(src->json, path); // depth limit (the locator below recurses on depth) and duplicate keys
    try {
        src->doc = Json::parse(src->json);
    } catch (const Json::parse_error& e) {
        throw Error(path + ": invalid JSON at byte " + std::to_string(e.byte) + ": " + e.what());
    } catch (const Json::exception& e) {
        // A number out of double's range (1e99999): found by fuzz_mesh_gltf.
        throw Error(path + ": invalid JSON: " + e.what());
    }
    try {
        if (!src->doc.is_object()) throw Error(path + ": the glTF JSON is not an object");
        const Json& asset = objectMember(src->doc, "asset", path);
        const auto versionMember = asset.find("version");
        const std::string version = versionMember != asset.end() && versionMember->is_string() ? versionMember->get<std::string>() : "";
        if (version.rfind("2.", 0) != 0) throw Error(path + ": glTF asset version '" + version + "' (only 2.x is read)");
        for (const Json& ext : arrayMember(src->doc, "extensionsRequired", path))
            if (ext == "KHR_draco_mesh_compression" || ext == "EXT_meshopt_compression" || ext == "KHR_mesh_quantization")
                throw Error(path + ": the file requires the extension " + ext.get<std::string>() +
                            ", which the lossless reader does not support");
        loadBuffers(*src, bin, companions);
        readEditable(*src);
    } catch (const Json::exception& e) {
        throw Error(path + ": malformed glTF: " + e.what());
    }
    return src;
}

void writeGltfMesh(const std::string& path, const PolygonMesh& mesh, const Eigen::MatrixXd& colors, bool binary)
{
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
