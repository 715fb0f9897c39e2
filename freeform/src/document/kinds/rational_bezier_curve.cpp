// The rational_bezier_curve kind in the document layer (src/document/kind_file.h): a rational
// Bézier curve in 2D or 3D on [0, 1], its points and positive weights (docs/format.md).

#include "freeform/volume/deform_rational.h"

#include "../kind_file.h"

namespace freeform {
namespace {

template <int Dim>
RationalBezierCurveData rationalCurveData(const RationalBezierCurve<double, Dim>& c)
{
    RationalBezierCurveData d;
    d.points = c.controlPoints();
    d.weights = detail::weightList(c.weights());
    return d;
}

} // namespace

RationalBezierCurveData toData(const RationalBezierCurve<double, 2>& curve) { return rationalCurveData(curve); }
RationalBezierCurveData toData(const RationalBezierCurve<double, 3>& curve) { return rationalCurveData(curve); }

namespace detail {

KindRow kindRow(std::type_identity<RationalBezierCurveData>)
{
    return {"rational Bézier curve", KindNature::Curve, KindParameters::T, 0, true, false, false,
            curveOps | kindOps({KindOperation::ToNurbs})};
}

Geometry kindBuild(const RationalBezierCurveData& d, const KindBuild&)
{
    if (d.points.rows() == 2) return RationalBezierCurve<double, 2>(PointMatrix<double, 2>(d.points), weightVector(d.weights));
    return RationalBezierCurve<double, 3>(PointMatrix<double, 3>(d.points), weightVector(d.weights));
}

void kindNet(const RationalBezierCurveData& d, const Geometry&, ControlNet& net) { polygonNet(net, d.points, false); }

std::string kindDetails(const RationalBezierCurveData& d) { return degreeWords(d.points.cols() - 1) + ", " + dimensionWords(d.points); }

std::optional<AnyCurve> kindCurve(const Geometry& g, std::type_identity<RationalBezierCurveData>)
{
    if (const auto* c = std::get_if<RationalBezierCurve<double, 2>>(&g)) return AnyCurve(*c);
    return AnyCurve(std::get<RationalBezierCurve<double, 3>>(g));
}

std::optional<AnySurface> kindSurface(const Geometry&, std::type_identity<RationalBezierCurveData>) { return std::nullopt; }

KindDeform kindDeform(const RationalBezierCurveData&, const Geometry& g, const KindDeformInput& in)
{
    // Exact composition through the lattice (volume/deform_rational.h).
    const auto& c = std::get<RationalBezierCurve<double, 3>>(g);
    KindDeform r;
    r.inside = pointsInsideLattice(in.lattice, c.controlPoints());
    const RationalBezierCurve<double, 3> moved = deformCurve(RationalLattice(in.lattice), c, in.strength);
    r.degree = {moved.degree()};
    r.result = toData(moved);
    return r;
}

std::optional<ObjectData> kindToNurbs(const RationalBezierCurveData&, const Geometry& g, const std::string&)
{
    if (const auto* c = std::get_if<RationalBezierCurve<double, 2>>(&g)) return toData(NurbsCurve<double, 2>::fromRationalBezier(*c));
    return toData(NurbsCurve<double, 3>::fromRationalBezier(std::get<RationalBezierCurve<double, 3>>(g)));
}

std::optional<ObjectData> kindFromNurbs(const RationalBezierCurveData&, const Geometry&, const std::string&) { return std::nullopt; }

PointColumns* kindPoints(RationalBezierCurveData& d) { return &d.points; }

std::string kindNonFinite(const RationalBezierCurveData& d) { return nonFinitePointsWeights(d); }

} // namespace detail
} // namespace freeform
