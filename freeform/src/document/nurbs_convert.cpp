// The NURBS conversions of the document layer (document/operations.h: toNurbsData, fromNurbsData;
// docs/format.md): every curve and surface kind with an exact NURBS form into a nurbs_curve or
// nurbs_surface, and a NURBS of one piece back into its Bézier kind. Evaluation, polylines and
// tessellation of the rational kinds go through AnyCurve / AnySurface (any_geometry.cpp).

#include <string>

#include "freeform/core/error.h"
#include "freeform/document/object_data.h"
#include "freeform/document/operations.h"

namespace freeform {
namespace {

template <int Dim>
NurbsCurveData splineData(const BezierSpline<double, Dim>& s)
{
    const int d = s.degree(), L = s.segmentCount();
    std::vector<double> knots(static_cast<std::size_t>(d + 1), 0.0);
    double t = 0;
    for (int i = 0; i < L; ++i) {
        t += s.intervals().empty() ? 1.0 : s.intervals()[static_cast<std::size_t>(i)];
        knots.insert(knots.end(), static_cast<std::size_t>(i + 1 < L ? d : d + 1), t);
    }
    PointColumns points = s.controlPoints();
    if (s.closed()) {
        points.conservativeResize(Eigen::NoChange, points.cols() + 1);
        points.col(points.cols() - 1) = points.col(0);
    }
    NurbsCurveData out;
    out.degree = d;
    out.knots = std::move(knots);
    out.points = std::move(points);
    return out;
}

template <int Dim>
ObjectData piecesData(const std::string& what, const NurbsCurve<double, Dim>& c)
{
    const auto pieces = c.bezierPieces();
    if (c.isRational()) {
        if (pieces.size() != 1)
            throw Error(what + ": a rational nurbs_curve of " + std::to_string(pieces.size()) +
                        " pieces has no single-object Bézier form (rational_bezier_curve holds one piece)");
        return toData(pieces.front());
    }
    const int p = c.degree();
    BezierSplineData d;
    d.degree = p;
    d.points.resize(Dim, static_cast<Eigen::Index>(pieces.size()) * p + 1);
    const auto& k = c.knots();
    for (std::size_t i = 0; i < pieces.size(); ++i)
        d.points.middleCols(static_cast<Eigen::Index>(i) * p, p + 1) = pieces[i].controlPoints();
    for (int i = p; i < c.controlCount(); ++i)
        if (k[static_cast<std::size_t>(i)] < k[static_cast<std::size_t>(i) + 1])
            d.intervals.push_back(k[static_cast<std::size_t>(i) + 1] - k[static_cast<std::size_t>(i)]);
    bool unit = true;
    for (double h : d.intervals) unit = unit && h == 1;
    if (unit) d.intervals.clear();
    return d;
}

} // namespace

ObjectData toNurbsData(const TypedDocument& doc, const TypedObject& object)
{
    const std::string what = doc.what(object);
    const Geometry& g = object.geometry();
    if (const auto* c = std::get_if<BezierCurve<double, 2>>(&g)) return toData(NurbsCurve<double, 2>::fromBezier(*c));
    if (const auto* c = std::get_if<BezierCurve<double, 3>>(&g)) return toData(NurbsCurve<double, 3>::fromBezier(*c));
    if (const auto* c = std::get_if<RationalBezierCurve<double, 2>>(&g)) return toData(NurbsCurve<double, 2>::fromRationalBezier(*c));
    if (const auto* c = std::get_if<RationalBezierCurve<double, 3>>(&g)) return toData(NurbsCurve<double, 3>::fromRationalBezier(*c));
    if (const auto* s = std::get_if<BezierSpline<double, 2>>(&g)) return splineData(*s);
    if (const auto* s = std::get_if<BezierSpline<double, 3>>(&g)) return splineData(*s);
    if (const auto* s = std::get_if<DeBoorSpline<2>>(&g)) return splineData(s->bezier);
    if (const auto* s = std::get_if<DeBoorSpline<3>>(&g)) return splineData(s->bezier);
    if (const auto* s = std::get_if<BezierSurface<double, 3>>(&g))
        return toData(NurbsSurface<double, 3>::fromBezier(RationalBezierSurface<double, 3>(*s)));
    if (const auto* s = std::get_if<RationalBezierSurface<double, 3>>(&g)) return toData(NurbsSurface<double, 3>::fromBezier(*s));
    if (std::holds_alternative<NurbsCurve<double, 2>>(g) || std::holds_alternative<NurbsCurve<double, 3>>(g) ||
        std::holds_alternative<NurbsSurface<double, 3>>(g))
        throw Error(what + " is already a " + object.type());
    throw Error(what + ": a " + object.type() +
                " has no NURBS form here (bezier_curve, rational_bezier_curve, bezier_spline, deboor_spline, "
                "bezier_surface, rational_bezier_surface convert)");
}

ObjectData fromNurbsData(const TypedDocument& doc, const TypedObject& object)
{
    const std::string what = doc.what(object);
    const Geometry& g = object.geometry();
    if (const auto* c = std::get_if<NurbsCurve<double, 2>>(&g)) return piecesData(what, *c);
    if (const auto* c = std::get_if<NurbsCurve<double, 3>>(&g)) return piecesData(what, *c);
    if (const auto* s = std::get_if<NurbsSurface<double, 3>>(&g)) {
        const auto patches = s->bezierPatches();
        if (patches.size() != 1)
            throw Error(what + ": a nurbs_surface of " + std::to_string(patches.size()) +
                        " Bézier patches has no single-object Bézier form (one patch per object)");
        RationalBezierSurfaceData d = toData(patches.front());
        if (!s->isRational()) return BezierSurfaceData{d.degree, std::move(d.points)};
        return d;
    }
    throw Error(what + " is a " + object.type() + ", not a nurbs_curve or nurbs_surface");
}

} // namespace freeform
