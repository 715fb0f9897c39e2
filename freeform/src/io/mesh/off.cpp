// OFF (Geomview: OFF, COFF, NOFF, CNOFF, STOFF, STCOFF, STNOFF, STCNOFF), format-preserving: one
// vertex or face per line as the format has it; x y z (and nx ny nz for N) are the editable slots,
// colours, texture coordinates, face colours and comments are kept as text.

#include <algorithm>
#include <cmath>
#include <ostream>

#include "freeform/io/file.h"
#include "source.h"

namespace freeform::meshio {

namespace {

class OffSource final : public IndexedSource {
public:
    std::string text;
    std::vector<TextSlot> slots;
    const std::string& fileBytes() const override { return text; }

    void writeSame(const std::string& target, const std::string&, const Values& now) const override
    {
        writeFileAtomicallyWith(target, [&](std::ostream& out) { writeText(out, text, slots, now, original()); });
    }
};

} // namespace

std::unique_ptr<Source> readOff(const std::string& path, std::string text)
{
    auto src = std::make_unique<OffSource>();
    src->path = path;
    src->format = "off";
    src->text = std::move(text);
    const std::string& t = src->text;

    // The non-empty lines (comments removed) as tokens, with their line numbers.
    std::size_t at = 0;
    int line = 0;
    std::vector<Token> tokens;
    const auto nextLine = [&]() -> bool {
        while (at < t.size()) {
            tokens.clear();
            std::size_t end = t.find('\n', at);
            if (end == std::string::npos) end = t.size();
            ++line;
            std::size_t i = at;
            while (i < end) {
                while (i < end && isSpace(t[i])) ++i;
                if (i >= end || t[i] == '#') break;
                const std::size_t start = i;
                while (i < end && !isSpace(t[i]) && t[i] != '#') ++i;
                tokens.push_back({std::string_view(t).substr(start, i - start), start});
            }
            at = end + 1;
            if (!tokens.empty()) return true;
        }
        return false;
    };
    const auto where = [&]() { return path + ":" + std::to_string(line); };

    requireText(path, t, "OFF");
    if (!nextLine()) throw Error(path + ": the file is empty");
    std::string keyword(tokens[0].text);
    std::size_t first = 1;
    if (keyword.size() < 3 || keyword.compare(keyword.size() - 3, 3, "OFF") != 0)
        throw Error(where() + ": not an OFF file (it does not start with OFF, COFF, NOFF, CNOFF or STOFF)");
    std::string prefix = keyword.substr(0, keyword.size() - 3);
    const bool st = prefix.rfind("ST", 0) == 0;
    if (st) prefix.erase(0, 2);
    const bool colored = !prefix.empty() && prefix.front() == 'C';
    if (colored) prefix.erase(0, 1);
    const bool withNormals = !prefix.empty() && prefix.front() == 'N';
    if (withNormals) prefix.erase(0, 1);
    if (!prefix.empty()) throw Error(where() + ": unsupported OFF variant '" + keyword + "' (4OFF and nOFF are not read)");
    if (tokens.size() == first) {
        if (!nextLine()) throw Error(path + ": the file ends before the vertex and face counts");
        first = 0;
    }
    long long counts[2] = {0, 0};
    if (tokens.size() < first + 2) throw Error(where() + ": expected the counts 'vertices faces edges'");
    for (int c = 0; c < 2; ++c)
        if (!parseInteger(tokens[first + static_cast<std::size_t>(c)].text, counts[c]) || counts[c] < 0 ||
            counts[c] > 2147483647LL)
            throw Error(where() + ": '" + std::string(tokens[first + static_cast<std::size_t>(c)].text) + "' is not a count");
    const int vertexCount = static_cast<int>(counts[0]);
    const int faceCount = static_cast<int>(counts[1]);
    // The counts are checked against the bytes that follow before anything is allocated: a vertex
    // line takes at least 6 bytes ("0 0 0\n"), a face at least 8 ("3 0 1 2\n").
    // A claim the bytes cannot hold is not allocated: only as many vertices as fit, and the read
    // then ends inside the vertices with a message that names the impossible count.
    const auto remaining = static_cast<unsigned long long>(t.size() - std::min(at, t.size()));
    const unsigned long long minimum = static_cast<unsigned long long>(counts[0]) * 6ULL + static_cast<unsigned long long>(counts[1]) * 8ULL;
    const bool impossible = minimum > remaining + 1;
    const std::string claim = impossible ? " (the header claims " + std::to_string(counts[0]) + " vertices and " +
                                               std::to_string(counts[1]) + " faces, which take at least " + std::to_string(minimum) +
                                               " bytes; " + std::to_string(remaining) + " bytes follow)"
                                         : std::string();
    const int allocated = static_cast<int>(std::min<unsigned long long>(counts[0], remaining / 5 + 1));

    src->positions.resize(3, allocated);
    if (withNormals) {
        src->normals.resize(3, allocated);
        src->normalAnchors.resize(static_cast<std::size_t>(allocated));
    }
    if (st) src->texcoords.resize(2, allocated);
    bool allColored = colored;
    std::vector<double> colors;

    for (int v = 0; v < vertexCount; ++v) {
        if (!nextLine() || v >= allocated)
            throw Error(path + ": the file ends after " + std::to_string(v) + " of " + std::to_string(vertexCount) + " vertices" + claim);
        std::vector<double> values(tokens.size());
        for (std::size_t k = 0; k < tokens.size(); ++k)
            if (!parseDouble(tokens[k].text, values[k]))
                throw Error(where() + ": '" + std::string(tokens[k].text) + "' is not a number");
        const std::size_t needed = 3 + (withNormals ? 3 : 0) + (st ? 2 : 0);
        if (values.size() < needed)
            throw Error(where() + ": vertex " + std::to_string(v) + " has " + std::to_string(values.size()) +
                        " numbers, the variant " + keyword + " needs at least " + std::to_string(needed));
        const int editable = withNormals ? 6 : 3;
        for (int k = 0; k < editable; ++k) {
            if (!std::isfinite(values[static_cast<std::size_t>(k)]))
                throw Error(where() + ": vertex " + std::to_string(v) + " coordinate " +
                            std::string(tokens[static_cast<std::size_t>(k)].text) + " is not finite");
            const Token& tok = tokens[static_cast<std::size_t>(k)];
            src->slots.push_back({tok.offset, tok.offset + tok.text.size(), v, k < 3 ? Field::Position : Field::Normal,
                                  static_cast<std::uint8_t>(k % 3), false});
            (k < 3 ? src->positions : src->normals)(k % 3, v) = values[static_cast<std::size_t>(k)];
        }
        if (withNormals) src->normalAnchors[static_cast<std::size_t>(v)] = v;
        const std::size_t colorCount = values.size() - needed;
        if (colored && (colorCount == 3 || colorCount == 4)) {
            const double scale = (values[static_cast<std::size_t>(editable)] > 1 || values[static_cast<std::size_t>(editable) + 1] > 1 ||
                                  values[static_cast<std::size_t>(editable) + 2] > 1)
                                     ? 255.0
                                     : 1.0;
            for (std::size_t c = 0; c < 4; ++c) {
                const double value = c < colorCount ? values[static_cast<std::size_t>(editable) + c] : 1.0;
                // Alpha takes its own scale: "1 1 1 255" is white and opaque, as in Geomview's files.
                colors.push_back(c == 3 ? (value > 1 ? value / 255.0 : value) : value / scale);
            }
        } else {
            allColored = false;
        }
        if (st)
            for (int k = 0; k < 2; ++k) src->texcoords(k, v) = values[values.size() - 2 + static_cast<std::size_t>(k)];
    }
    if (allColored && vertexCount > 0) src->colors = Eigen::Map<const Eigen::MatrixXd>(colors.data(), 4, vertexCount);

    for (int f = 0; f < faceCount; ++f) {
        if (!nextLine())
            throw Error(path + ": the file ends after " + std::to_string(f) + " of " + std::to_string(faceCount) + " faces" + claim);
        long long n = 0;
        if (!parseInteger(tokens[0].text, n) || n < 3)
            throw Error(where() + ": face " + std::to_string(f) + " must start with its vertex count (at least 3), found '" +
                        std::string(tokens[0].text) + "'");
        if (static_cast<long long>(tokens.size()) < n + 1)
            throw Error(where() + ": face " + std::to_string(f) + " lists " + std::to_string(tokens.size() - 1) + " of " +
                        std::to_string(n) + " vertices");
        for (long long k = 1; k <= n; ++k) {
            long long idx = 0;
            const std::string_view tok = tokens[static_cast<std::size_t>(k)].text;
            if (!parseInteger(tok, idx)) throw Error(where() + ": face index '" + std::string(tok) + "' is not an integer");
            if (idx < 0 || idx >= vertexCount)
                throw Error(where() + ": face " + std::to_string(f) + " refers to vertex " + std::string(tok) + ", the file has " +
                            std::to_string(vertexCount));
            src->faceVertices.push_back(static_cast<int>(idx));
        }
        src->faceStart.push_back(static_cast<int>(src->faceVertices.size()));
    }
    if (nextLine()) throw Error(where() + ": data after the last face (the counts in the header are wrong?)");
    return src;
}

void writeOffMesh(std::ostream& out, const PolygonMesh& mesh, const Eigen::MatrixXd& colors)
{
    const int v = mesh.vertexCount();
    const bool n = mesh.normals.cols() == v && v > 0;
    const bool st = mesh.texcoords.cols() == v && v > 0;
    const bool c = colors.cols() == v && colors.rows() >= 3 && v > 0;
    out << (st ? "ST" : "") << (c ? "C" : "") << (n ? "N" : "") << "OFF\n" << v << ' ' << mesh.faceCount() << " 0\n";
    for (int i = 0; i < v; ++i) {
        out << formatDouble(mesh.positions(0, i)) << ' ' << formatDouble(mesh.positions(1, i)) << ' '
            << formatDouble(mesh.positions(2, i));
        if (n)
            for (int k = 0; k < 3; ++k) out << ' ' << formatDouble(mesh.normals(k, i));
        if (c)
            for (int k = 0; k < 4; ++k) out << ' ' << formatDouble(k < colors.rows() ? colors(k, i) : 1.0);
        if (st)
            for (int k = 0; k < 2; ++k) out << ' ' << formatDouble(mesh.texcoords(k, i));
        out << '\n';
    }
    for (int f = 0; f < mesh.faceCount(); ++f) {
        out << mesh.faceSize(f);
        for (int k = 0; k < mesh.faceSize(f); ++k) out << ' ' << mesh.face(f)[k];
        out << '\n';
    }
}

} // namespace freeform::meshio
