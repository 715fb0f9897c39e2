// freeform convert --to bezier_spline|deboor_spline: between the Bézier and the de Boor form of a
// spline in a document (the A-frame and its inverse, curve/aframe.h). The output is the input
// document with the object replaced by its other form (same name, same editor settings).

#include <optional>

#include "convert.h"
#include "freeform/core/error.h"
#include "spline_object.h"

namespace freeform::cli {
namespace {

template <int Dim>
ObjectData toBezier(const Document& doc, const DocumentObject& object)
{
    const BezierSpline<double, Dim> spline = splineFromObject<Dim>(doc, object);
    BezierSplineData out;
    out.degree = 3;
    out.closed = spline.closed();
    out.points = spline.controlPoints();
    out.intervals = std::get<DeBoorSplineData>(object.data).intervals;
    return out;
}

/// The de Boor form under `requested` (default: closed for a closed spline, clamped for an open
/// one). An open spline has de Boor points under open and clamped ends alike (both describe every
/// open C2 cubic spline, with different phantom knots); closed needs a closed spline.
template <int Dim>
ObjectData toDeBoor(const Document& doc, const DocumentObject& object, std::optional<EndCondition> requested)
{
    const auto& data = std::get<BezierSplineData>(object.data);
    if (data.degree != 3)
        throw Error(doc.source + ": object \"" + object.name + "\": de Boor points need a cubic spline, this one has degree " +
                    std::to_string(data.degree));
    const BezierSpline<double, Dim> spline = splineFromObject<Dim>(doc, object);
    const EndCondition end = requested ? *requested : spline.closed() ? EndCondition::Closed : EndCondition::Clamped;
    if ((end == EndCondition::Closed) != spline.closed())
        throw Error(doc.source + ": object \"" + object.name + "\": " + (spline.closed() ? "a closed" : "an open") +
                    " spline has no de Boor points with end condition " + toString(end) +
                    (spline.closed() ? " (use --end closed)" : " (use --end open or --end clamped)"));
    DeBoorSplineData out;
    out.degree = 3;
    out.end = toString(end);
    try {
        out.points = spline.deBoorPoints(end);
    } catch (const Error& e) {
        throw Error(doc.source + ": object \"" + object.name + "\": " + e.what());
    }
    out.intervals = data.intervals;
    return out;
}

} // namespace

Json convertSpline(const ConvertOptions& o)
{
    expectPositional(o.positional, 1, "the document (freeform convert DOC.json --object NAME --to FORM -o OUT.json)");
    if (!given(o.objectGiven)) throw UsageError("option --object is required");
    if (isRationalConversion(o)) return convertRational(o);
    const std::string& name = o.object;
    const std::string& to = o.to;
    const std::string& output = o.output;
    if (to != "bezier_spline" && to != "deboor_spline")
        throw UsageError("option --to: \"" + to + "\" is not one of bezier_spline, deboor_spline");
    std::optional<EndCondition> end;
    if (given(o.endGiven)) {
        if (to != "deboor_spline") throw UsageError("option --end: goes with --to deboor_spline only");
        if (o.end != "open" && o.end != "clamped" && o.end != "closed")
            throw UsageError("option --end: \"" + o.end + "\" is not one of open, clamped, closed");
        end = parseEndCondition(o.end, "--end");
    }
    Document doc = readDocument(o.positional[0]);
    const DocumentObject& object = doc.object(name);
    const int dim = splineDimension(doc, object);
    const std::string from = objectType(object.data);
    if (from == to) throw Error(doc.source + ": object \"" + name + "\" is already a " + to);
    ObjectData converted = to == "bezier_spline" ? (dim == 2 ? toBezier<2>(doc, object) : toBezier<3>(doc, object))
                                                 : (dim == 2 ? toDeBoor<2>(doc, object, end) : toDeBoor<3>(doc, object, end));
    DocumentObject* target = doc.find(name);
    target->data = std::move(converted);
    writeDocument(doc, output);

    Json out;
    out["object"] = name;
    out["from"] = from;
    out["to"] = to;
    out["output"] = output;
    if (const auto* d = std::get_if<DeBoorSplineData>(&target->data)) {
        out["end"] = d->end;
        out["points"] = d->points.cols();
    } else {
        out["points"] = std::get<BezierSplineData>(target->data).points.cols();
    }
    return out;
}

} // namespace freeform::cli
