// The deboor_spline kind in the document layer (src/document/kind_file.h): a cubic C2 spline by its
// de Boor points and end condition, held with its Bézier form from the A-frame (docs/format.md,
// docs/splines.md).

#include "freeform/core/error.h"
#include "freeform/io/geometry_data.h"

#include "../kind_file.h"

namespace freeform {
namespace {

template <int Dim>
DeBoorSpline<Dim> deBoorSpline(const DeBoorSplineData& d)
{
    using Points = PointMatrix<double, Dim>;
    if (d.degree != 3) throw Error("field \"degree\": a deboor_spline is cubic (degree 3), not " + std::to_string(d.degree));
    const EndCondition end = parseEndCondition(d.end, "field \"end\"");
    Points points(d.points);
    BezierSpline<double, Dim> bezier = BezierSpline<double, Dim>::fromDeBoor(points, end, d.intervals);
    return DeBoorSpline<Dim>{std::move(points), end, d.intervals, std::move(bezier)};
}

template <int Dim>
DeBoorSplineData deBoorSplineData(const DeBoorSpline<Dim>& s)
{
    DeBoorSplineData d;
    d.degree = 3;
    d.end = toString(s.end);
    d.points = s.points;
    d.intervals = s.intervals;
    return d;
}

} // namespace

DeBoorSplineData toData(const DeBoorSpline<2>& spline) { return deBoorSplineData(spline); }
DeBoorSplineData toData(const DeBoorSpline<3>& spline) { return deBoorSplineData(spline); }

namespace detail {

KindRow kindRow(std::type_identity<DeBoorSplineData>)
{
    using Op = KindOperation;
    return {"de Boor spline", KindNature::Curve, KindParameters::T, 0, false, false, true,
            curveOps | kindOps({Op::Continuity, Op::ConvertSpline, Op::ToNurbs})};
}

Geometry kindBuild(const DeBoorSplineData& d, const KindBuild&)
{
    if (d.points.rows() == 2) return deBoorSpline<2>(d);
    return deBoorSpline<3>(d);
}

void kindNet(const DeBoorSplineData& d, const Geometry&, ControlNet& net) { polygonNet(net, d.points, d.end == "closed"); }

std::string kindDetails(const DeBoorSplineData& d) { return degreeWords(d.degree) + ", end " + d.end; }

std::optional<AnyCurve> kindCurve(const Geometry& g, std::type_identity<DeBoorSplineData>)
{
    if (const auto* s = std::get_if<DeBoorSpline<2>>(&g)) return AnyCurve(s->bezier);
    return AnyCurve(std::get<DeBoorSpline<3>>(g).bezier);
}

std::optional<AnySurface> kindSurface(const Geometry&, std::type_identity<DeBoorSplineData>) { return std::nullopt; }

KindDeform kindDeform(const DeBoorSplineData& data, const Geometry& g, const KindDeformInput& in)
{
    const auto& s = std::get<DeBoorSpline<3>>(g);
    KindDeform r;
    r.inside = pointsInsideLattice(in.lattice, s.bezier.controlPoints());
    if (in.affine) {
        // An affine map commutes with the A-frame: the image is the cubic C2 spline on the same
        // intervals whose de Boor points are the mapped de Boor points.
        DeBoorSplineData d = data;
        d.points = mapByPolynomial(in.lattice, d.points, in.strength);
        r.degree = {3};
        r.result = std::move(d);
        return r;
    }
    BezierSplineData d = deformSplineData(in.lattice, s.bezier, in.strength);
    r.degree = {d.degree};
    r.note = "the lattice is not affine: the composition raises the degree to " + std::to_string(d.degree) +
             ", so the result is a bezier_spline, not a cubic deboor_spline";
    r.result = std::move(d);
    return r;
}

std::optional<ObjectData> kindToNurbs(const DeBoorSplineData&, const Geometry& g, const std::string&)
{
    if (const auto* s = std::get_if<DeBoorSpline<2>>(&g)) return splineNurbsData(s->bezier);
    return splineNurbsData(std::get<DeBoorSpline<3>>(g).bezier);
}

std::optional<ObjectData> kindFromNurbs(const DeBoorSplineData&, const Geometry&, const std::string&) { return std::nullopt; }

PointColumns* kindPoints(DeBoorSplineData& d) { return &d.points; }

std::string kindNonFinite(const DeBoorSplineData& d) { return nonFinitePointsWeights(d); }

} // namespace detail
} // namespace freeform
