// freeform convert DOC.json --object NAME --to KIND: one object of a document in another form of
// the same geometry, through the document layer's convertObject (document/operations.h), whose
// route the kind table chooses: bezier_spline <-> deboor_spline (the A-frame and its inverse,
// curve/aframe.h), curves, splines and patches to nurbs_curve / nurbs_surface, and a nurbs object
// to its Bézier form. The output is the input document with the object replaced (same name, same
// editor settings). This file checks the options (docs/cli.md and the tests pin their messages).

#include <optional>

#include "convert.h"
#include "freeform/core/error.h"
#include "freeform/document/operations.h"

namespace freeform::cli {

Json convertKind(const ConvertOptions& o)
{
    expectPositional(o.positional, 1, "the document (freeform convert DOC.json --object NAME --to FORM -o OUT.json)");
    if (!given(o.objectGiven)) throw UsageError("option --object is required");
    const KindInfo* form = findKind(o.to);
    // The document is read first (a missing file is that error, whatever --to says), validated
    // after the options are checked.
    const Document plain = readDocument(o.positional[0]);
    const bool rational = (form && form->knots) || kindInfo(plain.object(o.object).data).supports(KindOperation::FromNurbs);
    std::optional<EndCondition> end;
    if (!rational && (!form || !form->supports(KindOperation::ConvertSpline)))
        throw UsageError("option --to: \"" + o.to + "\" is not one of bezier_spline, deboor_spline");
    if (given(o.endGiven)) {
        if (rational || form->kind != ObjectKind::DeBoorSpline) throw UsageError("option --end: goes with --to deboor_spline only");
        if (o.end != "open" && o.end != "clamped" && o.end != "closed")
            throw UsageError("option --end: \"" + o.end + "\" is not one of open, clamped, closed");
        end = parseEndCondition(o.end, "--end");
    }
    TypedDocument doc(plain);
    const ObjectId id = doc.object(o.object).id();
    const std::string from = doc.object(id).type();
    try {
        convertObject(doc, id, o.to, end);
    } catch (const ConversionMismatch& e) {
        throw Error(std::string(e.what()) + " (use --to " + e.converted + ")");
    }
    writeDocument(doc.toDocument(), o.output);
    const TypedObject& target = doc.object(id);

    Json out;
    out["object"] = o.object;
    out["from"] = from;
    out["to"] = o.to;
    out["output"] = o.output;
    if (const auto* d = std::get_if<DeBoorSplineData>(&target.data())) out["end"] = d->end;
    out["points"] = std::visit(
        [](const auto& d) -> Eigen::Index {
            if constexpr (requires { d.points; }) return d.points.cols();
            else return 0;
        },
        target.data());
    return out;
}

} // namespace freeform::cli
