// `freeform eval` for rational_bezier_curve, nurbs_curve (T in [0, 1] / in the knot domain
// [u_p, u_(n+1)], derivatives with respect to that parameter), rational_bezier_surface and
// nurbs_surface (U,V likewise), through the document layer (document/operations.h: evaluate).

#include "command.h"
#include "freeform/document/operations.h"

namespace freeform::cli {

Json evalRational(const TypedDocument& doc, const TypedObject& object, const std::string& at, int order)
{
    const bool surface = object.info().isSurface();
    const std::vector<double> values = parseNumberList(at, "--at", surface ? 2 : 1);
    const Evaluation e = evaluate(doc, object, values, order);
    const int dim = static_cast<int>(e.point.size());
    Json out;
    out["object"] = object.name();
    if (surface) {
        out["u"] = values[0];
        out["v"] = values[1];
    } else {
        out["t"] = values[0];
    }
    out["point"] = pointJson(e.point.data(), dim);
    if (e.normal) out["normal"] = pointJson(e.normal->data(), 3);
    if (order > 0) {
        if (surface) {
            Json ders = Json::object();
            for (std::size_t k = 0; k < e.derivatives.size(); ++k) ders[e.keys[k]] = pointJson(e.derivatives[k].data(), dim);
            out["derivatives"] = std::move(ders);
        } else {
            Json ders = Json::array();
            for (const auto& d : e.derivatives) ders.push_back(pointJson(d.data(), dim));
            out["derivatives"] = std::move(ders);
        }
    }
    return out;
}

} // namespace freeform::cli
