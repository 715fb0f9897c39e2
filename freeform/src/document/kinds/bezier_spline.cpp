// The bezier_spline kind in the document layer (src/document/kind_file.h): Bézier segments of one
// degree joined end to end, open or closed, on intervals (docs/format.md, docs/splines.md).

#include "../kind_file.h"

namespace freeform {
namespace {

template <int Dim>
BezierSplineData bezierSplineData(const BezierSpline<double, Dim>& s)
{
    BezierSplineData d;
    d.degree = s.degree();
    d.closed = s.closed();
    d.points = s.controlPoints();
    d.intervals = s.intervals();
    return d;
}

} // namespace

BezierSplineData toData(const BezierSpline<double, 2>& spline) { return bezierSplineData(spline); }
BezierSplineData toData(const BezierSpline<double, 3>& spline) { return bezierSplineData(spline); }

namespace detail {

BezierSplineData deformSplineData(const Lattice& lattice, const BezierSpline<double, 3>& spline, double strength)
{
    BezierSplineData out;
    out.closed = spline.closed();
    out.intervals = spline.intervals();
    const int segments = spline.segmentCount();
    for (int i = 0; i < segments; ++i) {
        const BezierCurve<double, 3> piece = deformCurve(lattice, spline.segment(i), strength);
        const int d = piece.degree();
        if (i == 0) {
            out.degree = d;
            out.points.resize(3, static_cast<Eigen::Index>(spline.closed() ? segments * d : segments * d + 1));
        }
        // Segment i owns its first d points; the last open segment also its end point.
        out.points.middleCols(static_cast<Eigen::Index>(i) * d, d) = piece.controlPoints().leftCols(d);
        if (!spline.closed() && i + 1 == segments) out.points.col(out.points.cols() - 1) = piece.controlPoints().col(d);
    }
    return out;
}

KindRow kindRow(std::type_identity<BezierSplineData>)
{
    using Op = KindOperation;
    return {"Bézier spline", KindNature::Curve, KindParameters::T, 0, false, false, true,
            curveOps | kindOps({Op::Continuity, Op::ConvertSpline, Op::ToNurbs})};
}

Geometry kindBuild(const BezierSplineData& d, const KindBuild&)
{
    if (d.points.rows() == 2) return BezierSpline<double, 2>(d.degree, d.closed, PointMatrix<double, 2>(d.points), d.intervals);
    return BezierSpline<double, 3>(d.degree, d.closed, PointMatrix<double, 3>(d.points), d.intervals);
}

void kindNet(const BezierSplineData& d, const Geometry&, ControlNet& net) { polygonNet(net, d.points, d.closed); }

std::string kindDetails(const BezierSplineData& d) { return degreeWords(d.degree) + (d.closed ? ", closed" : ", open"); }

std::optional<AnyCurve> kindCurve(const Geometry& g, std::type_identity<BezierSplineData>)
{
    if (const auto* s = std::get_if<BezierSpline<double, 2>>(&g)) return AnyCurve(*s);
    return AnyCurve(std::get<BezierSpline<double, 3>>(g));
}

std::optional<AnySurface> kindSurface(const Geometry&, std::type_identity<BezierSplineData>) { return std::nullopt; }

KindDeform kindDeform(const BezierSplineData&, const Geometry& g, const KindDeformInput& in)
{
    const auto& s = std::get<BezierSpline<double, 3>>(g);
    KindDeform r;
    r.inside = pointsInsideLattice(in.lattice, s.controlPoints());
    BezierSplineData d = deformSplineData(in.lattice, s, in.strength);
    r.degree = {d.degree};
    r.result = std::move(d);
    return r;
}

std::optional<ObjectData> kindToNurbs(const BezierSplineData&, const Geometry& g, const std::string&)
{
    if (const auto* s = std::get_if<BezierSpline<double, 2>>(&g)) return splineNurbsData(*s);
    return splineNurbsData(std::get<BezierSpline<double, 3>>(g));
}

std::optional<ObjectData> kindFromNurbs(const BezierSplineData&, const Geometry&, const std::string&) { return std::nullopt; }

PointColumns* kindPoints(BezierSplineData& d) { return &d.points; }

std::string kindNonFinite(const BezierSplineData& d) { return nonFinitePointsWeights(d); }

} // namespace detail
} // namespace freeform
