// freeform convert --to bezier_spline|deboor_spline: between the Bézier and the de Boor form of a
// spline in a document (the A-frame and its inverse, curve/aframe.h). The output is the input
// document with the object replaced by its other form (same name, same editor settings).

#include <optional>

#include "convert.h"
#include "freeform/core/error.h"
#include "freeform/document/operations.h"

namespace freeform::cli {

Json convertSpline(const ConvertOptions& o)
{
    expectPositional(o.positional, 1, "the document (freeform convert DOC.json --object NAME --to FORM -o OUT.json)");
    if (!given(o.objectGiven)) throw UsageError("option --object is required");
    if (isRationalConversion(o)) return convertRational(o);
    const std::string& name = o.object;
    const std::string& to = o.to;
    const std::string& output = o.output;
    const KindInfo* form = findKind(to);
    if (!form || !form->supports(KindOperation::ConvertSpline))
        throw UsageError("option --to: \"" + to + "\" is not one of bezier_spline, deboor_spline");
    std::optional<EndCondition> end;
    if (given(o.endGiven)) {
        if (form->kind != ObjectKind::DeBoorSpline) throw UsageError("option --end: goes with --to deboor_spline only");
        if (o.end != "open" && o.end != "clamped" && o.end != "closed")
            throw UsageError("option --end: \"" + o.end + "\" is not one of open, clamped, closed");
        end = parseEndCondition(o.end, "--end");
    }
    TypedDocument doc = TypedDocument::read(o.positional[0]);
    const ObjectId id = doc.object(name).id();
    const std::string from = doc.object(id).type();
    freeform::convertSpline(doc, id, to, end); // the document layer: the A-frame or its inverse
    writeDocument(doc.toDocument(), output);
    const TypedObject& target = doc.object(id);

    Json out;
    out["object"] = name;
    out["from"] = from;
    out["to"] = to;
    out["output"] = output;
    if (const auto* d = std::get_if<DeBoorSplineData>(&target.data())) {
        out["end"] = d->end;
        out["points"] = d->points.cols();
    } else {
        out["points"] = std::get<BezierSplineData>(target.data()).points.cols();
    }
    return out;
}

} // namespace freeform::cli
