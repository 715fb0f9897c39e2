// The bezier_curve kind in the document layer (src/document/kind_file.h): a Bézier curve of any
// degree in 2D or 3D on [0, 1] (docs/format.md).

#include "../kind_file.h"

namespace freeform {

BezierCurveData toData(const BezierCurve<double, 2>& curve) { return {curve.controlPoints()}; }
BezierCurveData toData(const BezierCurve<double, 3>& curve) { return {curve.controlPoints()}; }

namespace detail {

KindRow kindRow(std::type_identity<BezierCurveData>)
{
    return {"Bézier curve", KindNature::Curve, KindParameters::T, 0, false, false, false, curveOps | kindOps({KindOperation::ToNurbs})};
}

Geometry kindBuild(const BezierCurveData& d, const KindBuild&)
{
    if (d.points.rows() == 2) return BezierCurve<double, 2>(PointMatrix<double, 2>(d.points));
    return BezierCurve<double, 3>(PointMatrix<double, 3>(d.points));
}

void kindNet(const BezierCurveData& d, const Geometry&, ControlNet& net) { polygonNet(net, d.points, false); }

std::string kindDetails(const BezierCurveData& d) { return degreeWords(d.points.cols() - 1) + ", " + dimensionWords(d.points); }

std::optional<AnyCurve> kindCurve(const Geometry& g, std::type_identity<BezierCurveData>)
{
    if (const auto* c = std::get_if<BezierCurve<double, 2>>(&g)) return AnyCurve(*c);
    return AnyCurve(std::get<BezierCurve<double, 3>>(g));
}

std::optional<AnySurface> kindSurface(const Geometry&, std::type_identity<BezierCurveData>) { return std::nullopt; }

KindDeform kindDeform(const BezierCurveData&, const Geometry& g, const KindDeformInput& in)
{
    const auto& c = std::get<BezierCurve<double, 3>>(g);
    KindDeform r;
    r.inside = pointsInsideLattice(in.lattice, c.controlPoints());
    BezierCurveData d;
    d.points = deformCurve(in.lattice, c, in.strength).controlPoints();
    r.degree = {static_cast<int>(d.points.cols()) - 1};
    r.result = std::move(d);
    return r;
}

std::optional<ObjectData> kindToNurbs(const BezierCurveData&, const Geometry& g, const std::string&)
{
    if (const auto* c = std::get_if<BezierCurve<double, 2>>(&g)) return toData(NurbsCurve<double, 2>::fromBezier(*c));
    return toData(NurbsCurve<double, 3>::fromBezier(std::get<BezierCurve<double, 3>>(g)));
}

std::optional<ObjectData> kindFromNurbs(const BezierCurveData&, const Geometry&, const std::string&) { return std::nullopt; }

PointColumns* kindPoints(BezierCurveData& d) { return &d.points; }

std::string kindNonFinite(const BezierCurveData& d) { return nonFinitePointsWeights(d); }

} // namespace detail
} // namespace freeform
