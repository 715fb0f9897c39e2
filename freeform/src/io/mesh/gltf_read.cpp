// glTF 2.0 (.gltf with external or data: buffers, .glb), format-preserving: the JSON text and every
// buffer byte are kept; the float32 data of the POSITION, NORMAL and TANGENT accessors of every
// mesh primitive are the editable slots, rewritten in place in their buffers. When positions move,
// the POSITION accessors' "min" and "max" are replaced in the JSON text (nothing else of the text
// changes); a changed data: buffer is re-encoded in place; external buffers are written beside the
// output (renamed after it when the output is another file). .gltf <-> .glb: a .glb written from a
// .gltf embeds its external buffers as data: URIs (a valid GLB without a BIN chunk); a .gltf written
// from a .glb stores the BIN chunk as OUT.bin.
//
// This file: the reader (readGltf): the GLB container, the JSON checked member by member, the
// buffers (data: URIs, external files confined to the file's folder, or the companions given with
// it) and the editable accessors. The writers: gltf_write.cpp.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "freeform/io/json_check.h"
#include "gltf_internal.h"

namespace freeform::meshio {

namespace gltf_detail {

namespace {

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

} // namespace

} // namespace gltf_detail

std::unique_ptr<Source> readGltf(const std::string& path, std::string bytes, bool binary, const Companions* companions)
{
    using namespace gltf_detail;
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

} // namespace freeform::meshio
