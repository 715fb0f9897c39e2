// `freeform eval` for bezier_spline and deboor_spline objects: the global parameter T in
// [0, sum of intervals], the same output as for curves (derivatives with respect to T).

#include <charconv>

#include "command.h"
#include "spline_object.h"

namespace freeform::cli {
namespace {

/// Shortest text that reads back to the same double ("3", "0.1").
std::string shortest(double v)
{
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}

template <int Dim>
Json evalSpline(const Document& doc, const DocumentObject& object, const std::string& at, int order)
{
    const BezierSpline<double, Dim> spline = splineFromObject<Dim>(doc, object);
    const double T = parseNumber(at, "--at");
    if (T < 0 || T > spline.domainEnd())
        throw Error(doc.source + ": object \"" + object.name + "\": T = " + at + " is outside the spline's domain [0, " +
                    shortest(spline.domainEnd()) + "]");
    const auto d = spline.derivatives(T, order);
    Json out;
    out["object"] = object.name;
    out["t"] = T;
    out["point"] = pointJson(d.col(0).data(), Dim);
    if (order > 0) {
        Json ders = Json::array();
        for (int k = 1; k <= order; ++k) ders.push_back(pointJson(d.col(k).data(), Dim));
        out["derivatives"] = std::move(ders);
    }
    return out;
}

Json evalAnySpline(const Document& doc, const DocumentObject& object, const std::string& at, int order)
{
    return splineDimension(doc, object) == 2 ? evalSpline<2>(doc, object, at, order)
                                             : evalSpline<3>(doc, object, at, order);
}

} // namespace

void addSplineEvaluators(std::map<std::string, Evaluator>& table)
{
    table["bezier_spline"] = evalAnySpline;
    table["deboor_spline"] = evalAnySpline;
}

} // namespace freeform::cli
