// `freeform convert --to nurbs_curve|nurbs_surface` (polynomial and rational Bézier curves,
// splines, patches to NURBS) and from a nurbs_curve / nurbs_surface to its Bézier pieces
// (--to bezier_spline, rational_bezier_curve, bezier_surface, rational_bezier_surface), through the
// document layer (document/operations.h: toNurbsData, fromNurbsData).

#include "convert.h"
#include "freeform/document/operations.h"

namespace freeform::cli {

bool isRationalConversion(const ConvertOptions& o)
{
    if (const KindInfo* to = findKind(o.to); to && to->knots) return true;
    if (o.positional.size() != 1 || !given(o.objectGiven)) return false;
    const Document doc = readDocument(o.positional[0]);
    return kindInfo(doc.object(o.object).data).supports(KindOperation::FromNurbs);
}

Json convertRational(const ConvertOptions& o)
{
    if (given(o.endGiven)) throw UsageError("option --end: goes with --to deboor_spline only");
    TypedDocument doc = TypedDocument::read(o.positional[0]);
    const TypedObject& object = doc.object(o.object);
    const std::string from = object.type();
    const KindInfo* target = findKind(o.to);
    const bool toNurbs = target && target->knots;
    ObjectData converted = toNurbs ? toNurbsData(doc, object) : fromNurbsData(doc, object);
    const std::string to = objectType(converted);
    if (to != o.to)
        throw Error(doc.what(object) + ": a " + from + " converts to a " + to + ", not a " + o.to + " (use --to " + to + ")");
    const ObjectId id = object.id();
    doc.replace(id, std::move(converted));
    writeDocument(doc.toDocument(), o.output);
    Json out;
    out["object"] = o.object;
    out["from"] = from;
    out["to"] = to;
    out["output"] = o.output;
    out["points"] = std::visit(
        [](const auto& d) -> Eigen::Index {
            if constexpr (requires { d.points; }) return d.points.cols();
            else return 0;
        },
        doc.object(id).data());
    return out;
}

} // namespace freeform::cli
