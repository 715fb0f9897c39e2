// Wavefront OBJ, format-preserving: every line is kept as text; the numbers of the `v` and `vn`
// records are the editable slots. Faces (f v, v/t, v//n, v/t/n, negative = relative) are read for
// the topology; everything else (vt, g, o, s, usemtl, mtllib, l, p, free-form records, comments)
// passes through untouched.

#include <cctype>
#include <cmath>
#include <ostream>

#include "freeform/io/file.h"
#include "source.h"

namespace freeform::meshio {

namespace {

class ObjSource final : public Source {
public:
    std::string text;
    std::vector<TextSlot> slots;
    std::vector<int> faceStart{0};
    const std::string& fileBytes() const override { return text; }
    std::vector<int> cornerVertex, cornerTexcoord, cornerNormal;
    Matrix2X texcoords;
    Eigen::MatrixXd colors; // 3 x V when every `v` record is "v x y z r g b"

    PolygonMesh polygonMesh(const Values& now) const override
    {
        PolygonMesh mesh;
        mesh.positions = now.positions;
        mesh.faceVertices = cornerVertex;
        mesh.faceStart = faceStart;
        const int v = static_cast<int>(now.positions.cols());
        mesh.normals = perVertexAttribute<3>(v, cornerVertex, cornerNormal, now.normals);
        mesh.texcoords = perVertexAttribute<2>(v, cornerVertex, cornerTexcoord, texcoords);
        return mesh;
    }

    Eigen::MatrixXd vertexColors() const override { return colors; }

    void writeSame(const std::string& target, const std::string&, const Values& now) const override
    {
        writeFileAtomicallyWith(target, [&](std::ostream& out) { writeText(out, text, slots, now, original()); });
    }
};

/// Splits text[first, last) into tokens, stopping at a '#' comment.
void tokenize(const std::string& text, std::size_t first, std::size_t last, std::vector<Token>& tokens)
{
    std::size_t i = first;
    while (i < last) {
        while (i < last && isSpace(text[i])) ++i;
        if (i >= last || text[i] == '#') return;
        const std::size_t start = i;
        while (i < last && !isSpace(text[i]) && text[i] != '#') ++i;
        tokens.push_back({std::string_view(text).substr(start, i - start), start});
    }
}

/// One index of a face corner: 1-based, or negative relative to the `count` records read so far.
int resolveIndex(std::string_view token, int count, const std::string& path, int line, const char* what)
{
    const auto where = [&]() { return path + ":" + std::to_string(line); };
    long long raw = 0;
    if (!parseInteger(token, raw)) throw Error(where() + ": " + what + " index '" + std::string(token) + "' is not an integer");
    if (raw == 0) throw Error(where() + ": " + what + " index 0 (OBJ indices start at 1)");
    const long long index = raw > 0 ? raw - 1 : count + raw;
    if (index < 0 || index > 2147483647LL)
        throw Error(where() + ": " + what + " index " + std::string(token) + " is out of range (" + std::to_string(count) +
                    " defined so far)");
    return static_cast<int>(index);
}

} // namespace

std::unique_ptr<Source> readObj(const std::string& path, std::string text)
{
    auto src = std::make_unique<ObjSource>();
    src->path = path;
    src->format = "obj";
    src->text = std::move(text);
    const std::string& t = src->text;
    requireText(path, t, "OBJ");

    std::vector<double> positions, normals, uvs, colors;
    bool allColored = true;
    int positionCount = 0, normalCount = 0, texcoordCount = 0;
    std::vector<int> faceLine; // line of each face, for range errors
    std::vector<Token> tokens;

    std::size_t pos = 0;
    int line = 0;
    while (pos < t.size()) {
        tokens.clear();
        const int firstLine = line + 1;
        // A logical line: physical lines joined where one ends with a backslash.
        for (;;) {
            ++line;
            std::size_t end = t.find('\n', pos);
            if (end == std::string::npos) end = t.size();
            tokenize(t, pos, end, tokens);
            pos = end + 1;
            if (tokens.empty() || tokens.back().text.back() != '\\' || pos >= t.size()) break;
            Token& last = tokens.back();
            last.text.remove_suffix(1);
            if (last.text.empty()) tokens.pop_back();
        }
        if (tokens.empty()) continue;
        const auto where = [&]() { return path + ":" + std::to_string(firstLine); };
        const std::string_view key = tokens[0].text;
        // Unknown statements pass through (OBJ has many), but a statement is a word: anything else
        // is not OBJ text (random bytes, a renamed image).
        for (const char c : key)
            if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'))
                throw Error(where() + ": '" + std::string(key.substr(0, 40)) + "' is not an OBJ statement (not an OBJ text file?)");

        auto number = [&](std::size_t k, const char* what) {
            double value = 0;
            if (k >= tokens.size()) throw Error(where() + ": " + what + " has too few numbers");
            if (!parseDouble(tokens[k].text, value))
                throw Error(where() + ": '" + std::string(tokens[k].text) + "' is not a number");
            if (!std::isfinite(value)) throw Error(where() + ": " + what + " coordinate " + std::string(tokens[k].text) + " is not finite");
            return value;
        };

        if (key == "v") {
            for (std::size_t k = 1; k <= 3; ++k) {
                positions.push_back(number(k, "vertex"));
                src->slots.push_back({tokens[k].offset, tokens[k].offset + tokens[k].text.size(), positionCount, Field::Position,
                                      static_cast<std::uint8_t>(k - 1), false});
            }
            if (tokens.size() == 7) {
                for (std::size_t k = 4; k <= 6; ++k) colors.push_back(number(k, "vertex colour"));
            } else {
                allColored = false;
            }
            ++positionCount;
        } else if (key == "vn") {
            for (std::size_t k = 1; k <= 3; ++k) {
                normals.push_back(number(k, "normal"));
                src->slots.push_back({tokens[k].offset, tokens[k].offset + tokens[k].text.size(), normalCount, Field::Normal,
                                      static_cast<std::uint8_t>(k - 1), false});
            }
            ++normalCount;
        } else if (key == "vt") {
            uvs.push_back(number(1, "texture coordinate"));
            uvs.push_back(tokens.size() > 2 ? number(2, "texture coordinate") : 0.0);
            ++texcoordCount;
        } else if (key == "f" || key == "fo") {
            if (tokens.size() < 4) throw Error(where() + ": a face needs at least 3 vertices");
            for (std::size_t k = 1; k < tokens.size(); ++k) {
                const std::string_view corner = tokens[k].text;
                const std::size_t s1 = corner.find('/');
                const std::string_view vs = corner.substr(0, s1);
                std::string_view ts, ns;
                if (s1 != std::string_view::npos) {
                    const std::size_t s2 = corner.find('/', s1 + 1);
                    ts = corner.substr(s1 + 1, s2 == std::string_view::npos ? std::string_view::npos : s2 - s1 - 1);
                    if (s2 != std::string_view::npos) ns = corner.substr(s2 + 1);
                }
                src->cornerVertex.push_back(resolveIndex(vs, positionCount, path, firstLine, "vertex"));
                src->cornerTexcoord.push_back(ts.empty() ? -1 : resolveIndex(ts, texcoordCount, path, firstLine, "texture coordinate"));
                src->cornerNormal.push_back(ns.empty() ? -1 : resolveIndex(ns, normalCount, path, firstLine, "normal"));
            }
            src->faceStart.push_back(static_cast<int>(src->cornerVertex.size()));
            faceLine.push_back(firstLine);
        }
    }

    // Indices may refer forward; check them against the totals.
    for (std::size_t f = 0; f + 1 < src->faceStart.size(); ++f) {
        for (int c = src->faceStart[f]; c < src->faceStart[f + 1]; ++c) {
            const auto check = [&](int index, int count, const char* what) {
                if (index >= count)
                    throw Error(path + ":" + std::to_string(faceLine[f]) + ": face refers to " + what + " " + std::to_string(index + 1) + ", the file has " +
                                std::to_string(count));
            };
            check(src->cornerVertex[static_cast<std::size_t>(c)], positionCount, "vertex");
            check(src->cornerTexcoord[static_cast<std::size_t>(c)], texcoordCount, "texture coordinate");
            check(src->cornerNormal[static_cast<std::size_t>(c)], normalCount, "normal");
        }
    }

    src->positions = Eigen::Map<const Matrix3X>(positions.data(), 3, positionCount);
    src->normals = Eigen::Map<const Matrix3X>(normals.data(), 3, normalCount);
    src->texcoords = Eigen::Map<const Matrix2X>(uvs.data(), 2, texcoordCount);
    if (allColored && positionCount > 0) src->colors = Eigen::Map<const Eigen::MatrixXd>(colors.data(), 3, positionCount);
    src->normalAnchors.assign(static_cast<std::size_t>(normalCount), -1);
    for (std::size_t c = 0; c < src->cornerNormal.size(); ++c) {
        const int n = src->cornerNormal[c];
        if (n >= 0 && src->normalAnchors[static_cast<std::size_t>(n)] < 0)
            src->normalAnchors[static_cast<std::size_t>(n)] = src->cornerVertex[c];
    }
    return src;
}

void writeObjMesh(std::ostream& out, const PolygonMesh& mesh, const Eigen::MatrixXd& colors)
{
    out << "# written by freeform\n";
    const int v = mesh.vertexCount();
    const bool rgb = colors.cols() == v && colors.rows() >= 3 && v > 0;
    for (int i = 0; i < v; ++i) {
        out << "v " << formatDouble(mesh.positions(0, i)) << ' ' << formatDouble(mesh.positions(1, i)) << ' '
            << formatDouble(mesh.positions(2, i));
        if (rgb) out << ' ' << formatDouble(colors(0, i)) << ' ' << formatDouble(colors(1, i)) << ' ' << formatDouble(colors(2, i));
        out << '\n';
    }
    const bool uv = mesh.texcoords.cols() == v && v > 0;
    const bool n = mesh.normals.cols() == v && v > 0;
    if (uv)
        for (int i = 0; i < v; ++i) out << "vt " << formatDouble(mesh.texcoords(0, i)) << ' ' << formatDouble(mesh.texcoords(1, i)) << '\n';
    if (n)
        for (int i = 0; i < v; ++i)
            out << "vn " << formatDouble(mesh.normals(0, i)) << ' ' << formatDouble(mesh.normals(1, i)) << ' '
                << formatDouble(mesh.normals(2, i)) << '\n';
    for (int f = 0; f < mesh.faceCount(); ++f) {
        out << 'f';
        for (int k = 0; k < mesh.faceSize(f); ++k) {
            const int index = mesh.face(f)[k] + 1;
            out << ' ' << index;
            if (uv && n) out << '/' << index << '/' << index;
            else if (uv) out << '/' << index;
            else if (n) out << "//" << index;
        }
        out << '\n';
    }
}

} // namespace freeform::meshio
