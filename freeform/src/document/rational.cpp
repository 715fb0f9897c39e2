// The rational object types in the document layer (docs/format.md): rational_bezier_curve,
// rational_bezier_surface, nurbs_curve, nurbs_surface; evaluation in their own parameters
// (rational Bézier on [0, 1], NURBS on [u_p, u_(n+1)] of their knot vectors), certified
// polylines and tessellations, control nets, and conversion to nurbs_curve / nurbs_surface.

#include "rational.h"

#include <cmath>

#include "freeform/core/error.h"
#include "freeform/document/object_data.h"
#include "freeform/tessellate/tessellate_rational.h"
#include "evaluation.h"

namespace freeform {
namespace detail {
namespace {

template <class Curve>
Evaluation curveEval(const std::string& what, const Curve& c, const std::vector<double>& at, int order, double a, double b,
                     const char* name)
{
    expectCount(what, at, 1, "T");
    inDomain(what, name, at[0], a, b, "curve");
    return curveEvaluation(c.derivatives(at[0], order), order);
}

template <class Surface>
Evaluation surfaceEval(const std::string& what, const Surface& s, const std::vector<double>& uv, int order,
                       std::array<double, 4> domain)
{
    expectCount(what, uv, 2, "U,V");
    inDomain(what, "u", uv[0], domain[0], domain[1], "surface");
    inDomain(what, "v", uv[1], domain[2], domain[3], "surface");
    return surfaceEvaluation(s.jet(uv[0], uv[1], order), s.normal(uv[0], uv[1]), order);
}

/// Certified flattening of a rational Bézier piece (positive weights: the curve lies in the
/// convex hull of its control points): split at 1/2 until every control point is within
/// tolerance of the chord; the end points are appended (the first only when `first`).
template <int Dim>
void flatten(const RationalBezierCurve<double, Dim>& c, double tolerance, std::vector<Eigen::Vector3d>& out, int depth)
{
    const auto p = c.controlPoints();
    const Eigen::Matrix<double, Dim, 1> a = p.col(0), b = p.col(p.cols() - 1);
    const Eigen::Matrix<double, Dim, 1> ab = b - a;
    const double len2 = ab.squaredNorm();
    double dev = 0;
    for (Eigen::Index i = 1; i + 1 < p.cols(); ++i) {
        const Eigen::Matrix<double, Dim, 1> ap = p.col(i) - a;
        const double t = len2 > 0 ? std::clamp(ap.dot(ab) / len2, 0.0, 1.0) : 0.0;
        dev = std::max(dev, (ap - t * ab).norm());
    }
    if (dev <= tolerance || depth >= 40) {
        Eigen::Vector3d q = Eigen::Vector3d::Zero();
        q.head<Dim>() = b;
        out.push_back(q);
        return;
    }
    const auto [l, r] = c.split(0.5);
    flatten(l, tolerance, out, depth + 1);
    flatten(r, tolerance, out, depth + 1);
}

template <int Dim>
Eigen::Matrix<double, 3, Eigen::Dynamic> polylineOf(const std::vector<RationalBezierCurve<double, Dim>>& pieces, double tolerance)
{
    if (!(tolerance > 0)) throw Error("polyline: the tolerance must be positive");
    std::vector<Eigen::Vector3d> pts;
    Eigen::Vector3d first = Eigen::Vector3d::Zero();
    first.head<Dim>() = pieces.front().controlPoint(0);
    pts.push_back(first);
    for (const auto& piece : pieces) flatten(piece, tolerance, pts, 0);
    Eigen::Matrix<double, 3, Eigen::Dynamic> out(3, static_cast<Eigen::Index>(pts.size()));
    for (std::size_t i = 0; i < pts.size(); ++i) out.col(static_cast<Eigen::Index>(i)) = pts[i];
    return out;
}

void polygonEdges(std::vector<std::pair<int, int>>& edges, int count)
{
    for (int i = 0; i + 1 < count; ++i) edges.emplace_back(i, i + 1);
}


Eigen::Matrix<double, 3, Eigen::Dynamic> to3d(const PointColumns& p)
{
    Eigen::Matrix<double, 3, Eigen::Dynamic> out = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, p.cols());
    out.topRows(p.rows()) = p;
    return out;
}

} // namespace

std::optional<Evaluation> evaluateRational(const std::string& what, const TypedObject& object, const std::vector<double>& at,
                                           int order)
{
    const Geometry& g = object.geometry();
    if (const auto* c = std::get_if<RationalBezierCurve<double, 2>>(&g)) return curveEval(what, *c, at, order, 0, 1, "t");
    if (const auto* c = std::get_if<RationalBezierCurve<double, 3>>(&g)) return curveEval(what, *c, at, order, 0, 1, "t");
    if (const auto* c = std::get_if<NurbsCurve<double, 2>>(&g))
        return curveEval(what, *c, at, order, c->domainStart(), c->domainEnd(), "T");
    if (const auto* c = std::get_if<NurbsCurve<double, 3>>(&g))
        return curveEval(what, *c, at, order, c->domainStart(), c->domainEnd(), "T");
    if (const auto* s = std::get_if<RationalBezierSurface<double, 3>>(&g)) return surfaceEval(what, *s, at, order, {0, 1, 0, 1});
    if (const auto* s = std::get_if<NurbsSurface<double, 3>>(&g))
        return surfaceEval(what, *s, at, order,
                           {s->knotsU().front(), s->knotsU().back(), s->knotsV().front(), s->knotsV().back()});
    return std::nullopt;
}

std::optional<std::vector<double>> rationalDomain(const TypedObject& object)
{
    const Geometry& g = object.geometry();
    if (std::holds_alternative<RationalBezierCurve<double, 2>>(g) || std::holds_alternative<RationalBezierCurve<double, 3>>(g))
        return std::vector<double>{1};
    if (std::holds_alternative<RationalBezierSurface<double, 3>>(g)) return std::vector<double>{1, 1};
    if (const auto* c = std::get_if<NurbsCurve<double, 2>>(&g)) return std::vector<double>{c->domainEnd()};
    if (const auto* c = std::get_if<NurbsCurve<double, 3>>(&g)) return std::vector<double>{c->domainEnd()};
    if (const auto* s = std::get_if<NurbsSurface<double, 3>>(&g)) return std::vector<double>{s->knotsU().back(), s->knotsV().back()};
    return std::nullopt;
}

std::optional<Eigen::Matrix<double, 3, Eigen::Dynamic>> rationalPolyline(const TypedObject& object, double tolerance)
{
    const Geometry& g = object.geometry();
    if (const auto* c = std::get_if<RationalBezierCurve<double, 2>>(&g)) return polylineOf<2>({*c}, tolerance);
    if (const auto* c = std::get_if<RationalBezierCurve<double, 3>>(&g)) return polylineOf<3>({*c}, tolerance);
    if (const auto* c = std::get_if<NurbsCurve<double, 2>>(&g)) return polylineOf<2>(c->bezierPieces(), tolerance);
    if (const auto* c = std::get_if<NurbsCurve<double, 3>>(&g)) return polylineOf<3>(c->bezierPieces(), tolerance);
    return std::nullopt;
}

std::optional<PolygonMesh> tessellateRationalObject(const TypedObject& object, const ObjectTessellation& options,
                                                    TessellationReport* report)
{
    TessellationOptions o;
    if (options.tolerance > 0) {
        o.tolerance = options.tolerance;
    } else {
        o.tolerance = 0;
        o.segmentsU = o.segmentsV = options.segments;
    }
    o.flipNormals = options.flip;
    const Geometry& g = object.geometry();
    if (const auto* s = std::get_if<RationalBezierSurface<double, 3>>(&g)) return tessellateRational({*s}, 1, 1, o, report);
    if (const auto* s = std::get_if<NurbsSurface<double, 3>>(&g)) return tessellateNurbs(*s, o, report);
    return std::nullopt;
}

bool rationalControlNet(const TypedObject& object, ControlNet& net)
{
    const ObjectData& d = object.data();
    if (const auto* c = std::get_if<RationalBezierCurveData>(&d)) {
        net.points = to3d(c->points);
        polygonEdges(net.edges, static_cast<int>(c->points.cols()));
    } else if (const auto* n = std::get_if<NurbsCurveData>(&d)) {
        net.points = to3d(n->points);
        polygonEdges(net.edges, static_cast<int>(n->points.cols()));
    } else if (const auto* s = std::get_if<RationalBezierSurfaceData>(&d)) {
        net.points = s->points;
        gridEdges(net.edges, s->degree[0] + 1, s->degree[1] + 1);
    } else if (const auto* ns = std::get_if<NurbsSurfaceData>(&d)) {
        net.points = ns->points;
        gridEdges(net.edges, ns->rows, ns->cols);
    } else {
        return false;
    }
    return true;
}

} // namespace detail
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
