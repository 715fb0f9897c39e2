// PLY (ASCII, binary little and big endian), format-preserving: the header and every element and
// property are kept; the vertex properties x y z (positions) and nx ny nz (normals) are the
// editable slots, rewritten in place in their own type (ASCII: as text, float properties as the
// shortest text of the nearest float). Faces come from the list property vertex_indices (or
// vertex_index) of the element "face".

#include <algorithm>
#include <cmath>
#include <cctype>
#include <ostream>

#include "freeform/core/warning.h"
#include "freeform/io/file.h"
#include "source.h"

namespace freeform::meshio {

namespace {

enum class Encoding { Ascii, Little, Big };

struct Property {
    std::string name;
    BinaryType type = BinaryType::Float32;
    bool list = false;
    BinaryType countType = BinaryType::UInt8;
};

struct Element {
    std::string name;
    long long count = 0;
    std::vector<Property> properties;
};

bool parseType(const std::string& name, BinaryType& type)
{
    static const std::pair<const char*, BinaryType> kTypes[] = {
        {"char", BinaryType::Int8},     {"int8", BinaryType::Int8},       {"uchar", BinaryType::UInt8},
        {"uint8", BinaryType::UInt8},   {"short", BinaryType::Int16},     {"int16", BinaryType::Int16},
        {"ushort", BinaryType::UInt16}, {"uint16", BinaryType::UInt16},   {"int", BinaryType::Int32},
        {"int32", BinaryType::Int32},   {"uint", BinaryType::UInt32},     {"uint32", BinaryType::UInt32},
        {"float", BinaryType::Float32}, {"float32", BinaryType::Float32}, {"double", BinaryType::Float64},
        {"float64", BinaryType::Float64}};
    for (const auto& [n, t] : kTypes)
        if (name == n) {
            type = t;
            return true;
        }
    return false;
}

bool isIntegerType(BinaryType t) { return t != BinaryType::Float32 && t != BinaryType::Float64; }

/// The range of an integer type (what an ASCII value of that type may hold).
std::pair<double, double> integerRange(BinaryType t)
{
    switch (t) {
    case BinaryType::Int8: return {-128, 127};
    case BinaryType::UInt8: return {0, 255};
    case BinaryType::Int16: return {-32768, 32767};
    case BinaryType::UInt16: return {0, 65535};
    case BinaryType::Int32: return {-2147483648.0, 2147483647.0};
    case BinaryType::UInt32: return {0, 4294967295.0};
    default: return {-HUGE_VAL, HUGE_VAL};
    }
}

const char* typeName(BinaryType t)
{
    switch (t) {
    case BinaryType::Int8: return "char";
    case BinaryType::UInt8: return "uchar";
    case BinaryType::Int16: return "short";
    case BinaryType::UInt16: return "ushort";
    case BinaryType::Int32: return "int";
    case BinaryType::UInt32: return "uint";
    case BinaryType::Float32: return "float";
    case BinaryType::Float64: return "double";
    }
    return "?";
}

class PlySource final : public IndexedSource {
public:
    std::string bytes; // the whole file
    const std::string& fileBytes() const override { return bytes; }
    Encoding encoding = Encoding::Ascii;
    std::vector<TextSlot> textSlots;
    std::vector<BinarySlot> binarySlots;

    void writeSame(const std::string& target, const std::string&, const Values& now) const override
    {
        if (encoding == Encoding::Ascii) {
            writeFileAtomicallyWith(target, [&](std::ostream& out) { writeText(out, bytes, textSlots, now, original()); });
        } else {
            std::string copy = bytes;
            patchBinary(copy, binarySlots, now, original(), target);
            writeFileAtomically(target, copy);
        }
    }
};

/// Reads the values of the body one at a time, ASCII tokens or binary numbers, with the place of
/// each for slots and messages.
class BodyReader {
public:
    BodyReader(const std::string& path, const std::string& bytes, std::size_t start, Encoding encoding, int headerLines)
        : path_(path), bytes_(bytes), at_(start), encoding_(encoding), line_(headerLines + 1)
    {
    }

    struct Value {
        double value = 0;
        std::size_t begin = 0;
        std::size_t end = 0;
    };

    /// what() names the value for messages (called only on error).
    template <typename What>
    Value next(BinaryType type, const What& what)
    {
        Value v;
        if (encoding_ == Encoding::Ascii) {
            skipSpace();
            if (at_ >= bytes_.size()) throw Error(path_ + ":" + std::to_string(line_) + ": the file ends inside " + what());
            v.begin = at_;
            while (at_ < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[at_]))) ++at_;
            v.end = at_;
            const std::string_view token(bytes_.data() + v.begin, v.end - v.begin);
            if (!parseDouble(token, v.value))
                throw Error(path_ + ":" + std::to_string(line_) + ": '" + std::string(token) + "' in " + what() + " is not a number");
            if (isIntegerType(type) && v.value != std::floor(v.value))
                throw Error(path_ + ":" + std::to_string(line_) + ": '" + std::string(token) + "' in " + what() +
                            " is not an integer");
            if (isIntegerType(type) && (v.value < integerRange(type).first || v.value > integerRange(type).second))
                throw Error(path_ + ":" + std::to_string(line_) + ": '" + std::string(token) + "' in " + what() +
                            " is out of range for its type " + typeName(type));
        } else {
            const std::size_t size = static_cast<std::size_t>(binarySize(type));
            if (bytes_.size() - at_ < size)
                throw Error(path_ + ": the file is truncated: it ends at byte " + std::to_string(bytes_.size()) + " inside " + what());
            v.begin = at_;
            v.value = readBinary(bytes_.data() + at_, type, encoding_ == Encoding::Big);
            at_ += size;
            v.end = at_;
        }
        return v;
    }

    /// Bytes not read yet.
    std::size_t remaining() const { return bytes_.size() - std::min(at_, bytes_.size()); }
    /// The fewest bytes one more value of `type` takes (ASCII: a digit and a separator).
    std::size_t minimumSize(BinaryType type) const
    {
        return encoding_ == Encoding::Ascii ? 2 : static_cast<std::size_t>(binarySize(type));
    }

    /// "path:line" (ASCII) or "path: byte N" (binary) of the value just read.
    std::string where(const Value& v) const
    {
        if (encoding_ == Encoding::Ascii) return path_ + ":" + std::to_string(line_);
        return path_ + ": byte " + std::to_string(v.begin);
    }

    /// Error when anything but white space follows the last element.
    void finish()
    {
        if (encoding_ == Encoding::Ascii) {
            skipSpace();
            if (at_ < bytes_.size())
                throw Error(path_ + ":" + std::to_string(line_) +
                            ": data after the last element (the element counts of the header are wrong?)");
        } else {
            for (std::size_t i = at_; i < bytes_.size(); ++i)
                if (!std::isspace(static_cast<unsigned char>(bytes_[i])))
                    throw Error(path_ + ": " + std::to_string(bytes_.size() - at_) + " bytes after the last element at byte " +
                                std::to_string(at_) + " (the element counts of the header are wrong?)");
        }
    }

private:
    void skipSpace()
    {
        while (at_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[at_]))) {
            if (bytes_[at_] == '\n') ++line_;
            ++at_;
        }
    }

    const std::string& path_;
    const std::string& bytes_;
    std::size_t at_;
    Encoding encoding_;
    int line_;
};

std::vector<std::string> splitWords(const std::string& line)
{
    std::vector<std::string> words;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
        const std::size_t start = i;
        while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
        if (i > start) words.push_back(line.substr(start, i - start));
    }
    return words;
}

int findProperty(const Element& e, const char* name)
{
    for (std::size_t i = 0; i < e.properties.size(); ++i)
        if (e.properties[i].name == name && !e.properties[i].list) return static_cast<int>(i);
    return -1;
}

} // namespace

std::unique_ptr<Source> readPly(const std::string& path, std::string bytes)
{
    auto src = std::make_unique<PlySource>();
    src->path = path;
    src->format = "ply";
    src->bytes = std::move(bytes);
    const std::string& b = src->bytes;

    // ---- header
    std::vector<Element> elements;
    std::size_t at = 0;
    int line = 0;
    bool haveFormat = false, ended = false;
    while (at < b.size() && !ended) {
        std::size_t end = b.find('\n', at);
        if (end == std::string::npos) end = b.size();
        const std::string text = b.substr(at, end - at);
        at = end + 1;
        ++line;
        const std::string where = path + ":" + std::to_string(line);
        const std::vector<std::string> w = splitWords(text);
        if (line == 1) {
            if (w.size() != 1 || w[0] != "ply") throw Error(path + ":1: not a PLY file (it does not start with 'ply')");
            continue;
        }
        if (w.empty()) continue;
        if (w[0] == "comment" || w[0] == "obj_info") continue;
        if (w[0] == "format") {
            if (w.size() != 3) throw Error(where + ": malformed format line");
            if (w[1] == "ascii") src->encoding = Encoding::Ascii;
            else if (w[1] == "binary_little_endian") src->encoding = Encoding::Little;
            else if (w[1] == "binary_big_endian") src->encoding = Encoding::Big;
            else throw Error(where + ": unknown PLY format '" + w[1] + "'");
            haveFormat = true;
        } else if (w[0] == "element") {
            long long count = 0;
            if (w.size() != 3 || !parseInteger(w[2], count) || count < 0 || count > 2147483647LL)
                throw Error(where + ": malformed element line (expected 'element NAME COUNT')");
            elements.push_back({w[1], count, {}});
        } else if (w[0] == "property") {
            if (elements.empty()) throw Error(where + ": property before any element");
            Property p;
            if (w.size() == 5 && w[1] == "list") {
                p.list = true;
                if (!parseType(w[2], p.countType) || !isIntegerType(p.countType))
                    throw Error(where + ": bad list count type '" + w[2] + "'");
                if (!parseType(w[3], p.type)) throw Error(where + ": unknown property type '" + w[3] + "'");
                p.name = w[4];
            } else if (w.size() == 3) {
                if (!parseType(w[1], p.type)) throw Error(where + ": unknown property type '" + w[1] + "'");
                p.name = w[2];
            } else {
                throw Error(where + ": malformed property line");
            }
            elements.back().properties.push_back(p);
        } else if (w[0] == "end_header") {
            ended = true;
        } else {
            // Not a PLY keyword: old exporters wrote free text here (Blender 2.4x: "Created by
            // Blender3D 247 - www.blender.org, source file: ..."). Like the widely used readers, the
            // line is kept as a comment (written back unchanged) with one warning on stderr.
            warn(where + ": unknown header line '" + w[0] + "' kept as a comment");
        }
    }
    if (!ended) throw Error(path + ": the PLY header has no end_header line");
    if (!haveFormat) throw Error(path + ": the PLY header has no format line");

    // ---- the vertex element's roles
    const Element* vertex = nullptr;
    for (const Element& e : elements)
        if (e.name == "vertex") vertex = &e;
    if (vertex == nullptr) throw Error(path + ": the PLY file has no 'vertex' element");
    const int px = findProperty(*vertex, "x"), py = findProperty(*vertex, "y"), pz = findProperty(*vertex, "z");
    if (px < 0 || py < 0 || pz < 0) throw Error(path + ": the vertex element lacks one of the properties x, y, z");
    const int nxp = findProperty(*vertex, "nx"), nyp = findProperty(*vertex, "ny"), nzp = findProperty(*vertex, "nz");
    const bool hasNormals = nxp >= 0 && nyp >= 0 && nzp >= 0;
    int tu = -1, tv = -1;
    for (const auto& [u, v] : {std::pair{"s", "t"}, std::pair{"u", "v"}, std::pair{"texture_u", "texture_v"},
                               std::pair{"texture_s", "texture_t"}})
        if (tu < 0 && findProperty(*vertex, u) >= 0 && findProperty(*vertex, v) >= 0) {
            tu = findProperty(*vertex, u);
            tv = findProperty(*vertex, v);
        }
    int colorProps[4] = {findProperty(*vertex, "red"), findProperty(*vertex, "green"), findProperty(*vertex, "blue"),
                         findProperty(*vertex, "alpha")};
    if (colorProps[0] < 0) {
        colorProps[0] = findProperty(*vertex, "diffuse_red");
        colorProps[1] = findProperty(*vertex, "diffuse_green");
        colorProps[2] = findProperty(*vertex, "diffuse_blue");
        colorProps[3] = -1;
    }
    const bool hasColors = colorProps[0] >= 0 && colorProps[1] >= 0 && colorProps[2] >= 0;
    const int colorRows = hasColors ? (colorProps[3] >= 0 ? 4 : 3) : 0;

    // ---- the counts against the bytes that follow: each row of an element takes at least its
    // fixed-size properties (binary) or one digit and a separator per value (ASCII). A claim the
    // bytes cannot hold is never allocated: only as many vertices as fit, and the read then ends
    // inside the elements with a message that names the impossible count.
    const std::size_t bodyStart = std::min(at, b.size());
    const auto remaining = static_cast<unsigned long long>(b.size() - bodyStart);
    std::string claim;
    unsigned long long vertexRow = 1;
    {
        unsigned long long minimum = 0;
        for (const Element& e : elements) {
            unsigned long long row = 0;
            for (const Property& p : e.properties)
                row += src->encoding == Encoding::Ascii ? 2ULL : static_cast<unsigned long long>(binarySize(p.list ? p.countType : p.type));
            if (&e == vertex) vertexRow = std::max(row, 1ULL);
            // counts < 2^31 and a row < 2^31 (the header is in memory): each product < 2^62.
            minimum += row * static_cast<unsigned long long>(e.count);
            if (claim.empty() && minimum > remaining + 1)
                claim = " (the header claims " + std::to_string(e.count) + " '" + e.name + "' elements, which with the elements before take at least " +
                        std::to_string(minimum) + " bytes; " + std::to_string(remaining) + " bytes follow the header)";
        }
    }
    const int allocated = static_cast<int>(std::min<unsigned long long>(static_cast<unsigned long long>(vertex->count), (remaining + 1) / vertexRow + 1));

    const int vertexCount = static_cast<int>(vertex->count);
    src->positions.resize(3, allocated);
    if (hasNormals) {
        src->normals.resize(3, allocated);
        src->normalAnchors.resize(static_cast<std::size_t>(allocated));
        for (int i = 0; i < allocated; ++i) src->normalAnchors[static_cast<std::size_t>(i)] = i;
    }
    if (tu >= 0) src->texcoords.resize(2, allocated);
    if (hasColors) src->colors.resize(colorRows, allocated);

    // ---- body
    BodyReader body(path, b, bodyStart, src->encoding, line);
    try {
    for (const Element& e : elements) {
        const bool isVertex = &e == vertex;
        const bool isFace = e.name == "face";
        int faceList = -1;
        if (isFace)
            for (std::size_t i = 0; i < e.properties.size(); ++i)
                if (e.properties[i].list && (e.properties[i].name == "vertex_indices" || e.properties[i].name == "vertex_index"))
                    faceList = static_cast<int>(i);
        if (e.properties.empty()) continue; // rows without properties take no bytes
        for (long long r = 0; r < e.count; ++r) {
            const int row = static_cast<int>(r);
            for (std::size_t pi = 0; pi < e.properties.size(); ++pi) {
                const Property& p = e.properties[pi];
                const int prop = static_cast<int>(pi);
                const auto what = [&]() { return "element '" + e.name + "' " + std::to_string(r) + " property '" + p.name + "'"; };
                if (p.list) {
                    const BodyReader::Value n = body.next(p.countType, [&]() { return what() + " (list count)"; });
                    if (n.value < 0) throw Error(body.where(n) + ": " + what() + " has a negative list count");
                    // In the count type's range (checked by next()), and no more items than bytes remain.
                    if (n.value > static_cast<double>(body.remaining() / body.minimumSize(p.type) + 1))
                        throw Error(body.where(n) + ": " + what() + " has a list count of " + std::to_string(static_cast<long long>(n.value)) + ", the " +
                                    std::to_string(body.remaining()) + " bytes that remain cannot hold that many values");
                    const long long count = static_cast<long long>(n.value);
                    if (prop == faceList && count < 3)
                        throw Error(body.where(n) + ": face " + std::to_string(r) + " has " + std::to_string(count) +
                                    " vertices (at least 3 needed)");
                    for (long long k = 0; k < count; ++k) {
                        const BodyReader::Value item = body.next(p.type, what);
                        if (prop == faceList) {
                            const double idx = item.value;
                            if (!(idx >= 0 && idx < static_cast<double>(vertexCount)) || idx != std::floor(idx))
                                throw Error(body.where(item) + ": face " + std::to_string(r) + " refers to vertex " +
                                            formatDouble(idx) + ", the file has " + std::to_string(vertexCount));
                            src->faceVertices.push_back(static_cast<int>(idx));
                        }
                    }
                    if (prop == faceList) src->faceStart.push_back(static_cast<int>(src->faceVertices.size()));
                    continue;
                }
                const BodyReader::Value v = body.next(p.type, what);
                if (!isVertex) continue;
                if (row >= allocated) throw Error(body.where(v) + ": " + what() + ": more vertices than the file can hold");
                const auto slot = [&](Field field, std::uint8_t k) {
                    if (!std::isfinite(v.value))
                        throw Error(body.where(v) + ": vertex " + std::to_string(r) + " coordinate " + p.name + " is not finite");
                    if (src->encoding == Encoding::Ascii)
                        src->textSlots.push_back({v.begin, v.end, row, field, k, p.type == BinaryType::Float32, isIntegerType(p.type),
                                                  static_cast<std::uint8_t>(p.type)});
                    else
                        src->binarySlots.push_back({v.begin, row, field, k, p.type, src->encoding == Encoding::Big});
                };
                if (prop == px || prop == py || prop == pz) {
                    const std::uint8_t k = static_cast<std::uint8_t>(prop == px ? 0 : prop == py ? 1 : 2);
                    slot(Field::Position, k);
                    src->positions(k, row) = v.value;
                } else if (hasNormals && (prop == nxp || prop == nyp || prop == nzp)) {
                    const std::uint8_t k = static_cast<std::uint8_t>(prop == nxp ? 0 : prop == nyp ? 1 : 2);
                    slot(Field::Normal, k);
                    src->normals(k, row) = v.value;
                } else if (prop == tu || prop == tv) {
                    src->texcoords(prop == tu ? 0 : 1, row) = v.value;
                } else if (hasColors) {
                    for (int c = 0; c < colorRows; ++c)
                        if (prop == colorProps[c]) {
                            const double scale = p.type == BinaryType::UInt8 ? 255.0 : p.type == BinaryType::UInt16 ? 65535.0 : 1.0;
                            src->colors(c, row) = v.value / scale;
                        }
                }
            }
        }
    }
    body.finish();
    } catch (const Error& e) {
        if (claim.empty()) throw;
        throw Error(e.what() + claim);
    }
    if (allocated != vertexCount) throw Error(path + ": the vertex count is impossible" + claim); // unreachable: read fails first
    return src;
}

void writePlyMesh(std::ostream& out, const PolygonMesh& mesh, const Eigen::MatrixXd& colors)
{
    const int v = mesh.vertexCount();
    const bool n = mesh.normals.cols() == v && v > 0;
    const bool uv = mesh.texcoords.cols() == v && v > 0;
    const int colorRows = colors.cols() == v && v > 0 ? static_cast<int>(std::min<Eigen::Index>(colors.rows(), 4)) : 0;
    int largest = 0;
    for (int f = 0; f < mesh.faceCount(); ++f) largest = std::max(largest, mesh.faceSize(f));
    const bool byteCount = largest <= 255;

    out << "ply\nformat binary_little_endian 1.0\ncomment written by freeform\n";
    out << "element vertex " << v << "\nproperty double x\nproperty double y\nproperty double z\n";
    if (n) out << "property double nx\nproperty double ny\nproperty double nz\n";
    if (uv) out << "property double s\nproperty double t\n";
    static const char* const kColor[4] = {"red", "green", "blue", "alpha"};
    for (int c = 0; c < colorRows; ++c) out << "property uchar " << kColor[c] << '\n';
    out << "element face " << mesh.faceCount() << "\nproperty list " << (byteCount ? "uchar" : "int")
        << " int vertex_indices\nend_header\n";

    std::string record;
    const auto put = [&](BinaryType type, double value) {
        char buffer[8];
        writeBinary(buffer, type, false, value, "ply");
        record.append(buffer, static_cast<std::size_t>(binarySize(type)));
    };
    for (int i = 0; i < v; ++i) {
        record.clear();
        for (int k = 0; k < 3; ++k) put(BinaryType::Float64, mesh.positions(k, i));
        if (n)
            for (int k = 0; k < 3; ++k) put(BinaryType::Float64, mesh.normals(k, i));
        if (uv)
            for (int k = 0; k < 2; ++k) put(BinaryType::Float64, mesh.texcoords(k, i));
        for (int c = 0; c < colorRows; ++c) put(BinaryType::UInt8, std::clamp(colors(c, i), 0.0, 1.0) * 255.0);
        out.write(record.data(), static_cast<std::streamsize>(record.size()));
    }
    for (int f = 0; f < mesh.faceCount(); ++f) {
        record.clear();
        put(byteCount ? BinaryType::UInt8 : BinaryType::Int32, mesh.faceSize(f));
        for (int k = 0; k < mesh.faceSize(f); ++k) put(BinaryType::Int32, mesh.face(f)[k]);
        out.write(record.data(), static_cast<std::streamsize>(record.size()));
    }
}

} // namespace freeform::meshio
