// Geometry from document data and files (io/geometry_data.h).

#include "freeform/io/geometry_data.h"

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
    return Lattice(data.degree, data.origin, data.axes, data.points, parseOutsidePolicy(data.outside, "lattice: outside"));
}

LatticeData latticeToData(const Lattice& lattice)
{
    LatticeData d;
    d.degree = lattice.degrees();
    d.origin = lattice.origin();
    d.axes = lattice.axes();
    d.points = lattice.controlPoints();
    d.outside = toString(lattice.outside());
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
        if (name != "crease" && name != "corner")
            throw Error(where + ": tag \"" + name + "\" is not supported (crease, corner)");
        // "INTS/FLOATS" or "INTS/FLOATS/0" (no string arguments).
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
        if (!ok || n.size() < 2 || n.size() > 3 || (n.size() == 3 && n[2] != 0))
            throw Error(where + ": tag counts \"" + counts + "\" are not INTS/FLOATS");
        const int ints = n[0], floats = n[1];
        std::vector<long long> iv(static_cast<std::size_t>(ints));
        std::vector<double> fv(static_cast<std::size_t>(floats));
        for (auto& v : iv)
            if (!(tokens >> v)) throw Error(where + ": expected " + std::to_string(ints) + " vertex indices");
        for (auto& v : fv)
            if (!(tokens >> v)) throw Error(where + ": expected " + std::to_string(floats) + " sharpness values");
        std::string extra;
        if (tokens >> extra) throw Error(where + ": unexpected \"" + extra + "\" after the tag's values");
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
