// Geometry from document data and files (io/geometry_data.h).

#include "freeform/io/geometry_data.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <vector>

#include "freeform/core/error.h"
#include "freeform/io/file.h"
#include "freeform/io/mesh_io.h"

namespace freeform {

namespace {
bool validSharpness(double s) { return std::isfinite(s) && s >= 0; }
} // namespace

Lattice latticeFromData(const LatticeData& data)
{
    return Lattice(data.degree, data.origin, data.axes, data.points, data.outside);
}

LatticeData latticeToData(const Lattice& lattice)
{
    LatticeData d;
    d.degree = lattice.degrees();
    d.origin = lattice.origin();
    d.axes = lattice.axes();
    d.points = lattice.controlPoints();
    d.outside = lattice.outside();
    return d;
}

// ------------------------------------------------------------------------ crease tags in OBJ


void parseCreaseTags(const std::string& objText, const std::string& source, SubdivisionCage& cage)
{
    std::istringstream in(objText);
    std::string line;
    int lineNumber = 0;
    while (std::getline(in, line)) {
        ++lineNumber;
        std::istringstream tokens(line);
        std::string key;
        if (!(tokens >> key) || key != "t") continue;
        const std::string where = source + ":" + std::to_string(lineNumber);
        std::string name, counts;
        if (!(tokens >> name >> counts)) throw Error(where + ": a tag needs a name and counts (t crease 2/1 V0 V1 S)");
        static const char* const kKnown[] = {"crease", "corner", "hole", "interpolateboundary", "creasemethod", "smoothtriangles",
                                             "facevaryinginterpolateboundary"};
        if (std::find_if(std::begin(kKnown), std::end(kKnown), [&](const char* k) { return name == k; }) == std::end(kKnown))
            throw Error(where + ": tag \"" + name +
                        "\" is not supported (crease, corner, hole, interpolateboundary, creasemethod, smoothtriangles, "
                        "facevaryinginterpolateboundary)");
        // "INTS/FLOATS" or "INTS/FLOATS/STRINGS".
        std::vector<int> n;
        std::size_t start = 0;
        bool ok = true;
        while (ok && start <= counts.size()) {
            const std::size_t slash = std::min(counts.find('/', start), counts.size());
            const std::string part = counts.substr(start, slash - start);
            ok = !part.empty() && part.size() < 7 && part.find_first_not_of("0123456789") == std::string::npos;
            if (ok) n.push_back(std::stoi(part));
            start = slash + 1;
        }
        if (!ok || n.size() < 2 || n.size() > 3)
            throw Error(where + ": tag counts \"" + counts + "\" are not INTS/FLOATS or INTS/FLOATS/STRINGS");
        // crease and corner also take the short INTS/FLOATS form; the other tags are read exactly as
        // OpenSubdiv's shape parser reads them, with all three counts.
        if (name != "crease" && name != "corner" && n.size() != 3)
            throw Error(where + ": tag \"" + name + "\" needs OpenSubdiv's three counts INTS/FLOATS/STRINGS (e.g. t " + name +
                        (name == "hole" ? " 1/0/0 F" : name == "creasemethod" || name == "smoothtriangles" ? " 0/0/1 VALUE" : " 1/0/0 N") + ")");
        const int ints = n[0], floats = n[1], strings = n.size() == 3 ? n[2] : 0;
        // Every value costs at least two bytes of the line: a count beyond that is not there.
        if (static_cast<std::size_t>(ints) + static_cast<std::size_t>(floats) + static_cast<std::size_t>(strings) > line.size())
            throw Error(where + ": tag counts \"" + counts + "\" promise more values than the line holds");
        std::vector<long long> iv(static_cast<std::size_t>(ints));
        std::vector<double> fv(static_cast<std::size_t>(floats));
        std::vector<std::string> sv(static_cast<std::size_t>(strings));
        for (auto& v : iv)
            if (!(tokens >> v)) throw Error(where + ": expected " + std::to_string(ints) + " integers");
        for (auto& v : fv)
            if (!(tokens >> v)) throw Error(where + ": expected " + std::to_string(floats) + " sharpness values");
        for (auto& v : sv)
            if (!(tokens >> v)) throw Error(where + ": expected " + std::to_string(strings) + " strings");
        std::string extra;
        if (tokens >> extra) throw Error(where + ": unexpected \"" + extra + "\" after the tag's values");
        const auto shape = [&](int i, int f, int st) {
            if (ints != i || floats != f || strings != st)
                throw Error(where + ": tag \"" + name + "\" takes " + std::to_string(i) + "/" + std::to_string(f) + "/" +
                            std::to_string(st) + " values, found " + counts);
        };
        if (name == "hole") {
            if (ints == 0 || floats != 0 || strings != 0) throw Error(where + ": tag \"hole\" takes face indices only (N/0/0)");
            for (long long f : iv) {
                if (f < 0 || f >= cage.mesh.faceCount())
                    throw Error(where + ": hole face " + std::to_string(f) + " is out of range 0.." + std::to_string(cage.mesh.faceCount() - 1));
                cage.holes.push_back(static_cast<int>(f));
            }
            continue;
        }
        if (name == "interpolateboundary") {
            shape(1, 0, 0);
            if (iv[0] < 0 || iv[0] > 2) throw Error(where + ": interpolateboundary " + std::to_string(iv[0]) + " is not 0, 1 or 2");
            cage.boundary = iv[0] == 0 ? BoundaryInterpolation::None
                          : iv[0] == 1 ? BoundaryInterpolation::EdgeAndCorner
                                       : BoundaryInterpolation::EdgeOnly;
            continue;
        }
        if (name == "facevaryinginterpolateboundary") {
            // Face-varying data (texture coordinates) is not subdivided by this library: the tag
            // does not change the limit surface; it is checked and otherwise has no effect.
            shape(1, 0, 0);
            if (iv[0] < 0 || iv[0] > 5) throw Error(where + ": facevaryinginterpolateboundary " + std::to_string(iv[0]) + " is not 0..5");
            continue;
        }
        if (name == "creasemethod") {
            shape(0, 0, 1);
            if (sv[0] != "normal" && sv[0] != "chaikin") throw Error(where + ": creasemethod \"" + sv[0] + "\" is not normal or chaikin");
            cage.chaikin = sv[0] == "chaikin";
            continue;
        }
        if (name == "smoothtriangles") {
            shape(0, 0, 1);
            if (sv[0] != "catmark" && sv[0] != "smooth") throw Error(where + ": smoothtriangles \"" + sv[0] + "\" is not catmark or smooth");
            cage.smoothTriangles = sv[0] == "smooth";
            continue;
        }
        if (strings != 0) throw Error(where + ": tag \"" + name + "\" takes no strings");
        for (long long v : iv)
            if (v < 0 || v >= cage.mesh.vertexCount())
                throw Error(where + ": vertex index " + std::to_string(v) + " is out of range 0.." +
                            std::to_string(cage.mesh.vertexCount() - 1) + " (tags use 0-based indices)");
        const int per = name == "crease" ? 2 : 1;
        if (ints == 0 || ints % per != 0) throw Error(where + ": " + name + " needs vertex indices in groups of " + std::to_string(per));
        const int items = ints / per;
        if (floats != 1 && floats != items)
            throw Error(where + ": " + name + " needs 1 or " + std::to_string(items) + " sharpness values");
        for (double s : fv)
            if (!validSharpness(s)) throw Error(where + ": sharpness must be finite and >= 0");
        for (int k = 0; k < items; ++k) {
            const double s = fv[static_cast<std::size_t>(floats == 1 ? 0 : k)];
            if (per == 2)
                cage.creases.push_back({static_cast<int>(iv[2 * k]), static_cast<int>(iv[2 * k + 1]), s});
            else
                cage.corners.push_back({static_cast<int>(iv[k]), s});
        }
    }
}

SubdivisionCage readCage(const std::string& path)
{
    SubdivisionCage cage;
    cage.mesh = readPolygonMesh(path);
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (ext == ".obj") parseCreaseTags(readFile(path), path, cage);
    return cage;
}

// ------------------------------------------------------------------------ documents

SubdivisionCage cageFromData(const SubdivisionSurfaceData& data, const std::string& documentDirectory,
                             const std::string& what)
{
    try {
        SubdivisionCage cage;
        if (!data.mesh.empty()) {
            std::filesystem::path path(data.mesh);
            if (path.is_relative() && !documentDirectory.empty()) path = std::filesystem::path(documentDirectory) / path;
            cage = readCage(path.string());
        } else {
            cage.mesh.positions = data.vertices.topRows(3);
            for (const auto& f : data.faces) cage.mesh.addFace(f.begin(), f.end());
        }
        for (const auto& c : data.creases)
            cage.creases.push_back({static_cast<int>(c[0]), static_cast<int>(c[1]), c[2]});
        for (const auto& c : data.corners) cage.corners.push_back({static_cast<int>(c[0]), c[1]});
        return cage;
    } catch (const Error& e) {
        throw Error(what + ": " + e.what());
    }
}

SubdivisionSurfaceData cageToData(const SubdivisionCage& cage, const std::string& scheme, const std::string& boundary,
                                  const std::string& what)
{
    if (!cage.holes.empty() || cage.chaikin || cage.smoothTriangles)
        throw Error(what + ": the cage's " +
                    std::string(!cage.holes.empty() ? "holes" : cage.chaikin ? "creasemethod chaikin" : "smoothtriangles") +
                    " cannot be written inline (keep the cage in its mesh file)");
    SubdivisionSurfaceData out;
    out.vertices = cage.mesh.positions;
    for (int f = 0; f < cage.mesh.faceCount(); ++f)
        out.faces.emplace_back(cage.mesh.face(f), cage.mesh.face(f) + cage.mesh.faceSize(f));
    out.scheme = scheme;
    for (const EdgeCrease& c : cage.creases) out.creases.push_back({double(c.v0), double(c.v1), c.sharpness});
    for (const VertexCorner& c : cage.corners) out.corners.push_back({double(c.vertex), c.sharpness});
    out.boundary = boundary;
    return out;
}

SubdivisionSurfaceData inlineCage(const SubdivisionSurfaceData& data, const std::string& documentDirectory,
                                  const std::string& what)
{
    if (data.mesh.empty()) return data;
    return cageToData(cageFromData(data, documentDirectory, what), data.scheme, data.boundary, what);
}

SubdivisionSurface surfaceFromData(const SubdivisionSurfaceData& data, const std::string& documentDirectory,
                                   const std::string& what)
{
    SubdivisionCage cage = cageFromData(data, documentDirectory, what);
    try {
        return SubdivisionSurface(std::move(cage), parseSubdivisionScheme(data.scheme, "scheme"),
                                  parseBoundaryInterpolation(data.boundary, "boundary"));
    } catch (const Error& e) {
        throw Error(what + ": " + e.what());
    }
}

} // namespace freeform
