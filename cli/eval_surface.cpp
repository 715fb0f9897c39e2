// `freeform eval` for bezier_surface and deboor_surface objects: point, unit normal (limits at
// collapsed edges) and, with --derivatives K, every partial derivative up to order K, from the
// document layer's evaluate().

#include "command.h"
#include "freeform/document/operations.h"

namespace freeform::cli {

Json evalSurface(const TypedDocument& doc, const TypedObject& object, const std::string& at, int order)
{
    const std::vector<double> uv = parseNumberList(at, "--at", 2);
    // Bézier surfaces live on [0,1]^2; de Boor surfaces on [0, Lu] x [0, Lv] (unit intervals).
    const std::vector<double> segments = parameterDomain(object);
    for (std::size_t d = 0; d < 2; ++d) {
        const double t = uv[d];
        if (t < 0 || t > segments.at(d))
            throw Error(doc.what(object) + ": " + (d == 0 ? "u" : "v") + " = " + Json(t).dump() +
                        " is outside the surface's domain [0, " + std::to_string(static_cast<int>(segments[d])) + "]");
    }
    const Evaluation e = evaluate(doc, object, uv, order);
    Json out;
    out["object"] = object.name();
    out["u"] = uv[0];
    out["v"] = uv[1];
    out["point"] = pointJson(e.point.data(), 3);
    out["normal"] = pointJson(e.normal->data(), 3);
    if (order > 0) {
        Json ders = Json::object();
        for (std::size_t k = 0; k < e.keys.size(); ++k) ders[e.keys[k]] = pointJson(e.derivatives[k].data(), 3);
        out["derivatives"] = std::move(ders);
    }
    return out;
}

} // namespace freeform::cli
