// `freeform eval` for bezier_curve, bezier_spline and deboor_spline objects: t in [0, 1] for a
// curve, the global parameter T in [0, sum of intervals] for a spline; the point and the
// derivatives (with respect to t or T) from the document layer's evaluate(), in 2D or 3D.

#include <charconv>

#include "command.h"
#include "freeform/document/operations.h"

namespace freeform::cli {
namespace {

/// Shortest text that reads back to the same double ("3", "0.1").
std::string shortest(double v)
{
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}

} // namespace

Json evalCurve(const TypedDocument& doc, const TypedObject& object, const std::string& at, int order)
{
    const double t = parseNumber(at, "--at");
    const std::vector<double> domain = parameterDomain(object);
    const bool spline = object.info().pieces;
    if (t < 0 || t > domain.at(0))
        throw Error(doc.what(object) + ": " + (spline ? "T" : "t") + " = " + at + " is outside the " +
                    (spline ? "spline" : "curve") + "'s domain [0, " + shortest(domain[0]) + "]");
    const Evaluation e = evaluate(doc, object, {t}, order);
    const int dim = static_cast<int>(e.point.size());
    Json out;
    out["object"] = object.name();
    out["t"] = t;
    out["point"] = pointJson(e.point.data(), dim);
    if (order > 0) {
        Json ders = Json::array();
        for (const Eigen::VectorXd& d : e.derivatives) ders.push_back(pointJson(d.data(), dim));
        out["derivatives"] = std::move(ders);
    }
    return out;
}

} // namespace freeform::cli
