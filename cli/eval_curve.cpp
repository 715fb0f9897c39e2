// `freeform eval` for bezier_curve objects.

#include "command.h"
#include "freeform/curve/bezier_curve.h"

namespace freeform::cli {
namespace {

template <int Dim>
Json evalCurve(const DocumentObject& object, double t, int order)
{
    const auto& data = std::get<BezierCurveData>(object.data);
    const BezierCurve<double, Dim> curve(typename BezierCurve<double, Dim>::Points(data.points));
    const auto d = curve.derivatives(t, order);
    Json out;
    out["object"] = object.name;
    out["t"] = t;
    out["point"] = pointJson(d.col(0).data(), Dim);
    if (order > 0) {
        Json ders = Json::array();
        for (int k = 1; k <= order; ++k) ders.push_back(pointJson(d.col(k).data(), Dim));
        out["derivatives"] = std::move(ders);
    }
    return out;
}

Json evalBezierCurve(const Document& doc, const DocumentObject& object, const std::string& at, int order)
{
    const double t = parseNumber(at, "--at");
    if (t < 0 || t > 1)
        throw Error(doc.source + ": object \"" + object.name + "\": t = " + at + " is outside the curve's domain [0, 1]");
    const auto& data = std::get<BezierCurveData>(object.data);
    return data.points.rows() == 2 ? evalCurve<2>(object, t, order) : evalCurve<3>(object, t, order);
}

} // namespace

void addCurveEvaluators(std::map<std::string, Evaluator>& table)
{
    table["bezier_curve"] = evalBezierCurve;
}

} // namespace freeform::cli
