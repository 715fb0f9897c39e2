// `freeform eval` for every curve (T), surface (U,V) and part (FACE,U,V): the document layer's
// evaluate() (document/operations.h), which checks the parameter against the object's domain, as
// JSON: "t" or "u", "v" (a part's "face" first), the point, the unit normal of a surface (outward
// on a part's face), "trim" on a trimmed face (inside, outside or boundary), and with
// --derivatives K the derivatives: for a curve an array (order 1..K, with respect to t or the
// spline's global T), for a surface an object keyed "u", "v", "uu", "uv", ... (docs/cli.md).

#include "command.h"
#include "freeform/document/operations.h"

namespace freeform::cli {

Json evalObject(const TypedDocument& doc, const TypedObject& object, const std::string& at, int order)
{
    const KindInfo& kind = object.info();
    const bool part = kind.nature == KindNature::Part, surface = part || kind.parameters == KindParameters::UV;
    const std::vector<double> values = surface ? parseNumberList(at, "--at", part ? 3 : 2) : std::vector<double>{parseNumber(at, "--at")};
    const Evaluation e = evaluate(doc, object, values, order);
    const int dim = static_cast<int>(e.point.size());
    Json out;
    out["object"] = object.name();
    if (part) out["face"] = e.face;
    if (surface) {
        out["u"] = values[part ? 1 : 0];
        out["v"] = values[part ? 2 : 1];
    } else {
        out["t"] = values[0];
    }
    out["point"] = pointJson(e.point.data(), dim);
    if (e.normal) out["normal"] = pointJson(e.normal->data(), 3);
    if (e.trim) out["trim"] = *e.trim == TrimClass::Inside ? "inside" : *e.trim == TrimClass::Outside ? "outside" : "boundary";
    if (order > 0) {
        Json ders = surface ? Json::object() : Json::array();
        for (std::size_t k = 0; k < e.derivatives.size(); ++k) {
            if (surface) ders[e.keys[k]] = pointJson(e.derivatives[k].data(), dim);
            else ders.push_back(pointJson(e.derivatives[k].data(), dim));
        }
        out["derivatives"] = std::move(ders);
    }
    return out;
}

} // namespace freeform::cli
