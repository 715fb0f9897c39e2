// STL (ASCII and binary), format-preserving: the facet corners are the positions (3 per facet, no
// shared vertices, as in the file) and the facet normals are the normals (anchored at the facet's
// first corner); both are rewritten in place, everything else (solid names, header, attribute
// bytes, white space) is kept.

#include <Eigen/Geometry>

#include <cctype>
#include <cmath>
#include <cstring>
#include <ostream>

#include "freeform/io/file.h"
#include "source.h"

namespace freeform::meshio {

namespace {

class StlSource final : public Source {
public:
    std::string bytes;
    bool binary = false;
    const std::string& fileBytes() const override { return bytes; }
    std::vector<TextSlot> textSlots;
    std::vector<int> faceStart{0};

    PolygonMesh polygonMesh(const Values& now) const override
    {
        PolygonMesh mesh;
        mesh.positions = now.positions;
        mesh.faceStart = faceStart;
        mesh.faceVertices.resize(static_cast<std::size_t>(now.positions.cols()));
        for (std::size_t i = 0; i < mesh.faceVertices.size(); ++i) mesh.faceVertices[i] = static_cast<int>(i);
        // Each corner is its own vertex, so the facet normal is a per-vertex normal.
        mesh.normals.resize(3, now.positions.cols());
        for (int f = 0; f + 1 < static_cast<int>(faceStart.size()); ++f)
            for (int c = faceStart[static_cast<std::size_t>(f)]; c < faceStart[static_cast<std::size_t>(f) + 1]; ++c)
                mesh.normals.col(c) = now.normals.col(f);
        return mesh;
    }

    void writeSame(const std::string& target, const std::string&, const Values& now) const override
    {
        if (binary) {
            // The layout is fixed (50 bytes a facet: normal, three corners, attribute), so the
            // places of the numbers are computed rather than stored.
            std::string copy = bytes;
            const Values was = original();
            for (Eigen::Index f = 0; f < normals.cols(); ++f) {
                const std::size_t base = 84 + static_cast<std::size_t>(f) * 50;
                for (int c = 0; c < 4; ++c) {
                    const Eigen::Index column = c == 0 ? f : 3 * f + c - 1;
                    const Matrix3X& a = c == 0 ? now.normals : now.positions;
                    const Matrix3X& b = c == 0 ? was.normals : was.positions;
                    for (int r = 0; r < 3; ++r)
                        if (!sameBits(a(r, column), b(r, column)))
                            writeBinary(copy.data() + base + static_cast<std::size_t>(c * 12 + r * 4), BinaryType::Float32, false,
                                        a(r, column),
                                        target + ": " + (c == 0 ? "normal " : "position ") + std::to_string(column));
                }
            }
            writeFileAtomically(target, copy);
        } else {
            writeFileAtomicallyWith(target, [&](std::ostream& out) { writeText(out, bytes, textSlots, now, original()); });
        }
    }
};

struct LineToken {
    std::string_view text;
    std::size_t offset = 0;
    int line = 0;
};

std::vector<LineToken> tokenizeLines(const std::string& text)
{
    std::vector<LineToken> tokens;
    int line = 1;
    std::size_t i = 0;
    while (i < text.size()) {
        const char c = text[i];
        if (c == '\n') {
            ++line;
            ++i;
        } else if (std::isspace(static_cast<unsigned char>(c))) {
            ++i;
        } else {
            const std::size_t start = i;
            while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i]))) ++i;
            tokens.push_back({std::string_view(text).substr(start, i - start), start, line});
        }
    }
    return tokens;
}

void readAscii(StlSource& src)
{
    const std::string& path = src.path;
    const std::vector<LineToken> tokens = tokenizeLines(src.bytes);
    std::vector<double> positions, normals;
    std::size_t k = 0;
    const auto where = [&]() {
        const int line = k < tokens.size() ? tokens[k].line : (tokens.empty() ? 1 : tokens.back().line);
        return path + ":" + std::to_string(line);
    };
    const auto expect = [&](const char* word) {
        if (k >= tokens.size()) throw Error(where() + ": the file ends where '" + word + "' was expected");
        if (tokens[k].text != word)
            throw Error(where() + ": expected '" + word + "', found '" + std::string(tokens[k].text) + "'");
        ++k;
    };
    const auto number = [&](Field field, int column, std::uint8_t row, std::vector<double>& into) {
        if (k >= tokens.size()) throw Error(where() + ": the file ends inside a facet");
        double value = 0;
        if (!parseDouble(tokens[k].text, value))
            throw Error(where() + ": '" + std::string(tokens[k].text) + "' is not a number");
        if (!std::isfinite(value)) throw Error(where() + ": coordinate " + std::string(tokens[k].text) + " is not finite");
        src.textSlots.push_back({tokens[k].offset, tokens[k].offset + tokens[k].text.size(), column, field, row, true});
        into.push_back(value);
        ++k;
    };
    const auto skipRestOfLine = [&]() {
        const int line = tokens[k - 1].line;
        while (k < tokens.size() && tokens[k].line == line) ++k;
    };

    int facets = 0, corners = 0;
    bool anySolid = false;
    while (k < tokens.size()) {
        expect("solid");
        anySolid = true;
        skipRestOfLine(); // the solid's name
        for (;;) {
            if (k >= tokens.size()) throw Error(where() + ": the file ends without 'endsolid'");
            if (tokens[k].text == "endsolid") {
                ++k;
                skipRestOfLine();
                break;
            }
            expect("facet");
            expect("normal");
            for (std::uint8_t r = 0; r < 3; ++r) number(Field::Normal, facets, r, normals);
            expect("outer");
            expect("loop");
            int count = 0;
            while (k < tokens.size() && tokens[k].text == "vertex") {
                ++k;
                for (std::uint8_t r = 0; r < 3; ++r) number(Field::Position, corners, r, positions);
                ++corners;
                ++count;
            }
            if (count < 3) throw Error(where() + ": facet " + std::to_string(facets) + " has " + std::to_string(count) + " vertices");
            expect("endloop");
            expect("endfacet");
            src.faceStart.push_back(corners);
            ++facets;
        }
    }
    if (!anySolid) throw Error(path + ": the file is empty (no 'solid')");
    src.positions = Eigen::Map<const Matrix3X>(positions.data(), 3, corners);
    src.normals = Eigen::Map<const Matrix3X>(normals.data(), 3, facets);
}

void readBinary(StlSource& src, std::uint32_t count)
{
    const std::string& b = src.bytes;
    src.positions.resize(3, static_cast<Eigen::Index>(count) * 3);
    src.normals.resize(3, count);
    for (std::uint32_t f = 0; f < count; ++f) {
        const std::size_t base = 84 + static_cast<std::size_t>(f) * 50;
        for (int c = 0; c < 4; ++c) {
            const int column = c == 0 ? static_cast<int>(f) : static_cast<int>(f) * 3 + c - 1;
            for (std::uint8_t r = 0; r < 3; ++r) {
                const std::size_t offset = base + static_cast<std::size_t>(c) * 12 + r * 4u;
                const double value = meshio::readBinary(b.data() + offset, BinaryType::Float32, false);
                if (!std::isfinite(value))
                    throw Error(src.path + ": byte " + std::to_string(offset) + ": facet " + std::to_string(f) +
                                (c == 0 ? " normal" : " vertex") + " coordinate is not finite");
                (c == 0 ? src.normals : src.positions)(r, column) = value;
            }
        }
        src.faceStart.push_back(static_cast<int>(f + 1) * 3);
    }
}

} // namespace

std::unique_ptr<Source> readStl(const std::string& path, std::string bytes)
{
    auto src = std::make_unique<StlSource>();
    src->path = path;
    src->format = "stl";
    src->bytes = std::move(bytes);
    const std::string& b = src->bytes;

    std::uint32_t count = 0;
    if (b.size() >= 84) count = static_cast<std::uint32_t>(meshio::readBinary(b.data() + 80, BinaryType::UInt32, false));
    const bool sizeMatches = b.size() >= 84 && b.size() == 84 + static_cast<std::size_t>(count) * 50;
    std::size_t first = 0;
    while (first < b.size() && std::isspace(static_cast<unsigned char>(b[first]))) ++first;
    const bool startsSolid = b.compare(first, 5, "solid") == 0;

    if (sizeMatches) {
        src->binary = true;
        readBinary(*src, count);
    } else if (startsSolid) {
        readAscii(*src);
    } else if (b.size() < 84) {
        throw Error(path + ": not an STL file: " + std::to_string(b.size()) +
                    " bytes, too short for a binary STL and not starting with 'solid'");
    } else {
        throw Error(path + ": binary STL of the wrong size: the header says " + std::to_string(count) + " triangles (" +
                    std::to_string(84 + static_cast<std::size_t>(count) * 50) + " bytes), the file has " +
                    std::to_string(b.size()) + " bytes (truncated?)");
    }
    src->normalAnchors.resize(static_cast<std::size_t>(src->normals.cols()));
    for (std::size_t f = 0; f < src->normalAnchors.size(); ++f) src->normalAnchors[f] = src->faceStart[f];
    return src;
}

void writeStlMesh(std::ostream& out, const PolygonMesh& mesh)
{
    // Fan triangulation of every face; facet normals from the triangle's geometry.
    std::uint32_t count = 0;
    for (int f = 0; f < mesh.faceCount(); ++f) count += static_cast<std::uint32_t>(mesh.faceSize(f) - 2);
    char header[84] = {};
    std::memcpy(header, "binary STL written by freeform", 30);
    writeBinary(header + 80, BinaryType::UInt32, false, count, "stl");
    out.write(header, 84);
    char record[50];
    for (int f = 0; f < mesh.faceCount(); ++f) {
        const int* face = mesh.face(f);
        for (int k = 1; k + 1 < mesh.faceSize(f); ++k) {
            const Eigen::Vector3d a = mesh.positions.col(face[0]);
            const Eigen::Vector3d b = mesh.positions.col(face[k]);
            const Eigen::Vector3d c = mesh.positions.col(face[k + 1]);
            Eigen::Vector3d n = (b - a).cross(c - a);
            const double length = n.norm();
            n = length > 0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
            const Eigen::Vector3d* rows[4] = {&n, &a, &b, &c};
            for (int r = 0; r < 4; ++r)
                for (int i = 0; i < 3; ++i) writeBinary(record + r * 12 + i * 4, BinaryType::Float32, false, (*rows[r])(i), "stl");
            record[48] = record[49] = 0;
            out.write(record, 50);
        }
    }
}

} // namespace freeform::meshio
