// `freeform interpolate --degree P`: global NURBS interpolation of any degree
// (curve/nurbs_interpolation.h: interpolateNurbs), written as a document with one nurbs_curve
// object "interpolant" on [0, 1] (the normalised parameters; averaged knots).

#include "command.h"
#include "freeform/core/error.h"
#include "freeform/curve/nurbs_interpolation.h"
#include "freeform/document/object_data.h"

namespace freeform::cli {
namespace {

template <int Dim>
NurbsCurveData fit(const PointColumns& points, const std::vector<double>& params, Parametrization param, int degree,
                   const std::vector<double>& start, const std::vector<double>& end, const std::string& source)
{
    NurbsFitOptions<double, Dim> opt;
    opt.parametrization = param;
    opt.params = params;
    if (!start.empty()) {
        if (start.size() != Dim || end.size() != Dim)
            throw UsageError("options --start-derivative and --end-derivative: expected " + std::to_string(Dim) +
                             " numbers each for " + std::to_string(Dim) + "D points");
        opt.startDerivative = Point<double, Dim>(Eigen::Map<const Point<double, Dim>>(start.data()));
        opt.endDerivative = Point<double, Dim>(Eigen::Map<const Point<double, Dim>>(end.data()));
    }
    NurbsCurve<double, Dim> curve = [&] {
        try {
            return interpolateNurbs<double, Dim>(PointMatrix<double, Dim>(points), degree, opt);
        } catch (const Error& e) {
            throw Error(source + ": " + e.what());
        }
    }();
    return toData(curve);
}

} // namespace

Json interpolateNurbsCommand(const PointColumns& points, const std::vector<double>& params, Parametrization param,
                             int degree, const std::vector<double>& start, const std::vector<double>& end,
                             const std::string& source, const std::string& output)
{
    if (degree < 1 || degree > 67) throw UsageError("option --degree: must be in 1..67");
    NurbsCurveData data = points.rows() == 2 ? fit<2>(points, params, param, degree, start, end, source)
                                             : fit<3>(points, params, param, degree, start, end, source);
    Json out;
    out["object"] = "interpolant";
    out["output"] = output;
    out["points"] = points.cols();
    out["degree"] = data.degree;
    out["control_points"] = data.points.cols();
    out["end"] = start.empty() ? "none" : "clamped";
    out["param"] = params.empty() ? toString(param) : std::string("given");
    Document doc;
    doc.objects.push_back({"interpolant", std::move(data), {}});
    writeDocument(doc, output);
    return out;
}

} // namespace freeform::cli
