// `freeform eval` for trimmed_surface (U,V in the file's parameters) and part (FACE,U,V) objects,
// through the document layer (document/operations.h: evaluate): the point, the face's normal
// (outward on a part), with --derivatives 1 the first derivatives, and where (u, v) lies against
// the face's trims.

#include "command.h"
#include "freeform/document/operations.h"

namespace freeform::cli {

Json evalPart(const TypedDocument& doc, const TypedObject& object, const std::string& at, int order)
{
    const bool part = object.info().nature == KindNature::Part;
    const std::vector<double> values = parseNumberList(at, "--at", part ? 3 : 2);
    const Evaluation e = evaluate(doc, object, values, order);
    Json out;
    out["object"] = object.name();
    if (part) out["face"] = e.face;
    out["u"] = values[part ? 1 : 0];
    out["v"] = values[part ? 2 : 1];
    out["point"] = pointJson(e.point.data(), 3);
    if (e.normal) out["normal"] = pointJson(e.normal->data(), 3);
    if (e.trim) out["trim"] = *e.trim == TrimClass::Inside ? "inside" : *e.trim == TrimClass::Outside ? "outside" : "boundary";
    if (order > 0) {
        Json ders = Json::object();
        for (std::size_t k = 0; k < e.derivatives.size(); ++k) ders[e.keys[k]] = pointJson(e.derivatives[k].data(), 3);
        out["derivatives"] = std::move(ders);
    }
    return out;
}

} // namespace freeform::cli
