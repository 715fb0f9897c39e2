// The nurbs_curve kind in the document layer (src/document/kind_file.h): a NURBS curve in 2D or 3D,
// degree, knots, points and (when rational) weights (docs/format.md).

#include "freeform/core/error.h"
#include "freeform/volume/deform_rational.h"

#include "../kind_file.h"

namespace freeform {
namespace {

template <int Dim>
NurbsCurveData nurbsCurveData(const NurbsCurve<double, Dim>& c)
{
    NurbsCurveData d;
    d.degree = c.degree();
    d.knots = c.knots();
    d.points = c.controlPoints();
    if (c.isRational()) d.weights = detail::weightList(c.weights());
    return d;
}

/// A NURBS curve as its Bézier kind: one rational piece as a rational_bezier_curve, a polynomial
/// curve as a bezier_spline on its knot intervals.
template <int Dim>
ObjectData nurbsCurvePieces(const std::string& what, const NurbsCurve<double, Dim>& c)
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

NurbsCurveData toData(const NurbsCurve<double, 2>& curve) { return nurbsCurveData(curve); }
NurbsCurveData toData(const NurbsCurve<double, 3>& curve) { return nurbsCurveData(curve); }

namespace detail {

KindRow kindRow(std::type_identity<NurbsCurveData>)
{
    using Op = KindOperation;
    return {"NURBS curve", KindNature::Curve, KindParameters::T, 0, true, true, true, curveOps | kindOps({Op::Continuity, Op::FromNurbs})};
}

Geometry kindBuild(const NurbsCurveData& d, const KindBuild&)
{
    if (d.points.rows() == 2) return NurbsCurve<double, 2>(d.degree, d.knots, PointMatrix<double, 2>(d.points), weightVector(d.weights));
    return NurbsCurve<double, 3>(d.degree, d.knots, PointMatrix<double, 3>(d.points), weightVector(d.weights));
}

void kindNet(const NurbsCurveData& d, const Geometry&, ControlNet& net) { polygonNet(net, d.points, false); }

std::string kindDetails(const NurbsCurveData& d)
{
    return degreeWords(d.degree) + ", " + std::to_string(d.knots.size()) + " knots, " + dimensionWords(d.points);
}

std::optional<AnyCurve> kindCurve(const Geometry& g, std::type_identity<NurbsCurveData>)
{
    if (const auto* c = std::get_if<NurbsCurve<double, 2>>(&g)) return AnyCurve(*c);
    return AnyCurve(std::get<NurbsCurve<double, 3>>(g));
}

std::optional<AnySurface> kindSurface(const Geometry&, std::type_identity<NurbsCurveData>) { return std::nullopt; }

KindDeform kindDeform(const NurbsCurveData&, const Geometry& g, const KindDeformInput& in)
{
    // Span by span through the Bézier extraction; the result keeps the breakpoints.
    const auto& c = std::get<NurbsCurve<double, 3>>(g);
    KindDeform r;
    r.inside = pointsInsideLattice(in.lattice, c.controlPoints());
    const NurbsCurve<double, 3> moved = deformCurve(RationalLattice(in.lattice), c, in.strength);
    r.degree = {moved.degree()};
    r.result = toData(moved);
    return r;
}

std::optional<ObjectData> kindToNurbs(const NurbsCurveData&, const Geometry&, const std::string&) { return std::nullopt; }

std::optional<ObjectData> kindFromNurbs(const NurbsCurveData&, const Geometry& g, const std::string& what)
{
    if (const auto* c = std::get_if<NurbsCurve<double, 2>>(&g)) return nurbsCurvePieces(what, *c);
    return nurbsCurvePieces(what, std::get<NurbsCurve<double, 3>>(g));
}

PointColumns* kindPoints(NurbsCurveData& d) { return &d.points; }

std::string kindNonFinite(const NurbsCurveData& d) { return nonFinitePointsWeights(d); }

} // namespace detail
} // namespace freeform
