// `freeform eval` for subdivision_surface objects: --at FACE,U,V in OpenSubdiv's face
// parameterisation; prints the limit point, the first partial derivatives and the unit normal.

#include <cmath>
#include <filesystem>

#include "command.h"
#include "freeform/io/geometry_data.h"
#include "freeform/subdivision/subdivision_surface.h"

namespace freeform::cli {
namespace {

Json evalSubdivision(const Document& doc, const DocumentObject& object, const std::string& at, int order)
{
    const std::vector<double> fuv = parseNumberList(at, "--at", 3);
    if (fuv[0] != std::floor(fuv[0]) || fuv[0] < 0 || fuv[0] > 1e9)
        throw UsageError("option --at: FACE must be a non-negative integer (FACE,U,V)");
    const std::string what = doc.source + ": object \"" + object.name + "\"";
    if (order > 1) throw Error(what + ": a subdivision surface gives first derivatives only (--derivatives 0 or 1)");
    const std::string directory = std::filesystem::path(doc.source).parent_path().string();
    const SubdivisionSurface surface = surfaceFromData(std::get<SubdivisionSurfaceData>(object.data), directory, what);
    const int face = static_cast<int>(fuv[0]);
    LimitPoint p;
    try {
        p = surface.evaluate(face, fuv[1], fuv[2]);
    } catch (const Error& e) {
        throw Error(what + ": " + e.what());
    }
    Json out;
    out["object"] = object.name;
    out["face"] = face;
    out["u"] = fuv[1];
    out["v"] = fuv[2];
    out["point"] = pointJson(p.position.data(), 3);
    Json ders = Json::object();
    ders["u"] = pointJson(p.du.data(), 3);
    ders["v"] = pointJson(p.dv.data(), 3);
    out["derivatives"] = std::move(ders);
    out["normal"] = pointJson(p.normal.data(), 3);
    return out;
}

} // namespace

void addSubdivisionEvaluators(std::map<std::string, Evaluator>& table)
{
    table["subdivision_surface"] = evalSubdivision;
}

} // namespace freeform::cli
