// The plain data of rational and NURBS geometry (document/object_data.h).

#include "freeform/document/object_data.h"

namespace freeform {
namespace {

std::vector<double> weightList(const Eigen::Matrix<double, Eigen::Dynamic, 1>& w)
{
    return std::vector<double>(w.data(), w.data() + w.size());
}

template <int Dim>
NurbsCurveData curveData(const NurbsCurve<double, Dim>& c)
{
    NurbsCurveData d;
    d.degree = c.degree();
    d.knots = c.knots();
    d.points = c.controlPoints();
    if (c.isRational()) d.weights = weightList(c.weights());
    return d;
}

template <int Dim>
RationalBezierCurveData rationalData(const RationalBezierCurve<double, Dim>& c)
{
    RationalBezierCurveData d;
    d.points = c.controlPoints();
    d.weights = weightList(c.weights());
    return d;
}

} // namespace

NurbsCurveData nurbsCurveData(const NurbsCurve<double, 2>& curve) { return curveData(curve); }
NurbsCurveData nurbsCurveData(const NurbsCurve<double, 3>& curve) { return curveData(curve); }

NurbsSurfaceData nurbsSurfaceData(const NurbsSurface<double, 3>& surface)
{
    NurbsSurfaceData d;
    d.degree = {surface.degreeU(), surface.degreeV()};
    d.knots = {surface.knotsU().knots(), surface.knotsV().knots()};
    d.rows = surface.countU();
    d.cols = surface.countV();
    d.points = surface.controlPoints();
    if (surface.isRational()) d.weights = weightList(surface.weights());
    return d;
}

RationalBezierCurveData rationalCurveData(const RationalBezierCurve<double, 2>& curve) { return rationalData(curve); }
RationalBezierCurveData rationalCurveData(const RationalBezierCurve<double, 3>& curve) { return rationalData(curve); }

RationalBezierSurfaceData rationalSurfaceData(const RationalBezierSurface<double, 3>& surface)
{
    RationalBezierSurfaceData d;
    const int m = surface.degreeU(), n = surface.degreeV();
    d.degree = {m, n};
    d.points.resize(3, (m + 1) * (n + 1));
    for (int i = 0; i <= m; ++i)
        for (int j = 0; j <= n; ++j) {
            d.points.col(i * (n + 1) + j) = surface.controlPoint(i, j);
            d.weights.push_back(surface.weight(i, j));
        }
    return d;
}

} // namespace freeform
