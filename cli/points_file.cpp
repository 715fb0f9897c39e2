// freeform interpolate's points file (cli/points_file.h).

#include "points_file.h"

#include <nlohmann/json.hpp>

#include <cmath>

#include "freeform/core/error.h"
#include "freeform/io/file.h"
#include "freeform/io/json_check.h"

namespace freeform::cli {

/// POINTS.json: {"points": [[x, y(, z)], ...], "params": [...]} (params optional), strictly.
PointsFile parsePointsFile(const std::string& text, const std::string& path)
{
    checkJsonText(text, path); // depth limit and duplicate keys before the tree is built
    nlohmann::ordered_json root;
    try {
        root = nlohmann::ordered_json::parse(text);
    } catch (const nlohmann::json::exception&) {
        throw Error(path + ": not valid JSON");
    }
    if (!root.is_object()) throw Error(path + ": expected a JSON object {\"points\": [...]}");
    for (auto it = root.begin(); it != root.end(); ++it)
        if (it.key() != "points" && it.key() != "params") throw Error(path + ": field \"" + it.key() + "\": unknown field");
    if (!root.contains("points")) throw Error(path + ": field \"points\": is missing");
    const nlohmann::ordered_json& pts = root["points"];
    if (!pts.is_array() || pts.empty()) throw Error(path + ": field \"points\": expected a non-empty array of points");
    PointsFile out;
    int dim = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        const std::string field = path + ": field \"points[" + std::to_string(i) + "]\": ";
        const nlohmann::ordered_json& p = pts[i];
        if (!p.is_array()) throw Error(field + "expected a point (an array of numbers)");
        if (i == 0) {
            if (p.size() != 2 && p.size() != 3) throw Error(field + "a point has 2 or 3 coordinates");
            dim = static_cast<int>(p.size());
            out.points.resize(dim, static_cast<Eigen::Index>(pts.size()));
        }
        if (static_cast<int>(p.size()) != dim)
            throw Error(field + "expected " + std::to_string(dim) + " coordinates, found " + std::to_string(p.size()));
        for (int k = 0; k < dim; ++k) {
            if (!p[k].is_number() || !std::isfinite(p[k].get<double>())) throw Error(field + "expected finite numbers");
            out.points(k, static_cast<Eigen::Index>(i)) = p[k].get<double>();
        }
    }
    if (root.contains("params")) {
        const nlohmann::ordered_json& u = root["params"];
        if (!u.is_array()) throw Error(path + ": field \"params\": expected an array of numbers");
        for (std::size_t i = 0; i < u.size(); ++i) {
            if (!u[i].is_number() || !std::isfinite(u[i].get<double>()))
                throw Error(path + ": field \"params[" + std::to_string(i) + "]\": expected a finite number");
            out.params.push_back(u[i].get<double>());
        }
    }
    return out;
}

PointsFile readPointsFile(const std::string& path)
{
    return parsePointsFile(readFile(path), path);
}

} // namespace freeform::cli
