// `freeform eval` for subdivision_surface objects: --at FACE,U,V in OpenSubdiv's face
// parameterisation; prints the limit point, the first partial derivatives and the unit normal, from
// the document layer's evaluate().

#include <cmath>

#include "command.h"
#include "freeform/document/operations.h"

namespace freeform::cli {

Json evalSubdivision(const TypedDocument& doc, const TypedObject& object, const std::string& at, int order)
{
    const std::vector<double> fuv = parseNumberList(at, "--at", 3);
    if (fuv[0] != std::floor(fuv[0]) || fuv[0] < 0 || fuv[0] > 1e9)
        throw UsageError("option --at: FACE must be a non-negative integer (FACE,U,V)");
    const Evaluation e = evaluate(doc, object, fuv, order);
    Json out;
    out["object"] = object.name();
    out["face"] = e.face;
    out["u"] = fuv[1];
    out["v"] = fuv[2];
    out["point"] = pointJson(e.point.data(), 3);
    Json ders = Json::object();
    for (std::size_t k = 0; k < e.keys.size(); ++k) ders[e.keys[k]] = pointJson(e.derivatives[k].data(), 3);
    out["derivatives"] = std::move(ders);
    out["normal"] = pointJson(e.normal->data(), 3);
    return out;
}

} // namespace freeform::cli
