// The plain data of every kind of geometry (document/object_data.h).

#include "freeform/document/object_data.h"

#include "freeform/io/geometry_data.h"

#include <type_traits>
#include <variant>

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

template <int Dim>
BezierSplineData splineToData(const BezierSpline<double, Dim>& s)
{
    BezierSplineData d;
    d.degree = s.degree();
    d.closed = s.closed();
    d.points = s.controlPoints();
    d.intervals = s.intervals();
    return d;
}

template <int Dim>
DeBoorSplineData deBoorToData(const DeBoorSpline<Dim>& s)
{
    DeBoorSplineData d;
    d.degree = 3;
    d.end = toString(s.end);
    d.points = s.points;
    d.intervals = s.intervals;
    return d;
}

} // namespace

BezierCurveData toData(const BezierCurve<double, 2>& curve) { return {curve.controlPoints()}; }
BezierCurveData toData(const BezierCurve<double, 3>& curve) { return {curve.controlPoints()}; }
BezierSplineData toData(const BezierSpline<double, 2>& spline) { return splineToData(spline); }
BezierSplineData toData(const BezierSpline<double, 3>& spline) { return splineToData(spline); }
DeBoorSplineData toData(const DeBoorSpline<2>& spline) { return deBoorToData(spline); }
DeBoorSplineData toData(const DeBoorSpline<3>& spline) { return deBoorToData(spline); }

BezierSurfaceData toData(const BezierSurface<double, 3>& surface)
{
    BezierSurfaceData d;
    d.degree = {surface.degreeU(), surface.degreeV()};
    d.points = surface.controlPoints();
    return d;
}

DeBoorSurfaceData toData(const DeBoorSurface& surface)
{
    DeBoorSurfaceData d;
    d.degree = {3, 3};
    d.end = {toString(surface.end[0]), toString(surface.end[1])};
    d.rows = surface.rows;
    d.cols = surface.cols;
    d.points = surface.points;
    return d;
}

LatticeData toData(const Lattice& lattice) { return latticeToData(lattice); }

SubdivisionSurfaceData toData(const SubdivisionObject& surface)
{
    return cageToData(surface.cage(), toString(surface.surface.scheme()), toString(surface.surface.boundary()),
                      "subdivision_surface");
}

ObjectData toData(const Geometry& geometry)
{
    return std::visit([](const auto& g) -> ObjectData { return toData(g); }, geometry);
}

NurbsCurveData toData(const NurbsCurve<double, 2>& curve) { return curveData(curve); }
NurbsCurveData toData(const NurbsCurve<double, 3>& curve) { return curveData(curve); }

NurbsSurfaceData toData(const NurbsSurface<double, 3>& surface)
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

RationalBezierCurveData toData(const RationalBezierCurve<double, 2>& curve) { return rationalData(curve); }
RationalBezierCurveData toData(const RationalBezierCurve<double, 3>& curve) { return rationalData(curve); }

RationalBezierSurfaceData toData(const RationalBezierSurface<double, 3>& surface)
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

PointColumns* dataPoints(ObjectData& data)
{
    return std::visit(
        [](auto& d) -> PointColumns* {
            using T = std::decay_t<decltype(d)>;
            if constexpr (std::is_same_v<T, SubdivisionSurfaceData>) return &d.vertices;
            else if constexpr (std::is_same_v<T, TrimmedSurfaceData>) return &d.surface.points;
            else if constexpr (std::is_same_v<T, PartData>) return nullptr;
            else return &d.points;
        },
        data);
}

const PointColumns* dataPoints(const ObjectData& data) { return dataPoints(const_cast<ObjectData&>(data)); }

} // namespace freeform
