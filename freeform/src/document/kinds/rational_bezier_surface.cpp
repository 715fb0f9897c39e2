// The rational_bezier_surface kind in the document layer (src/document/kind_file.h): one rational
// tensor-product Bézier patch on [0, 1]^2, points and positive weights (docs/format.md).

#include "freeform/volume/deform_rational.h"

#include "../kind_file.h"

namespace freeform {

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

namespace detail {

KindRow kindRow(std::type_identity<RationalBezierSurfaceData>)
{
    return {"rational Bézier surface", KindNature::Surface, KindParameters::UV, 3, true, false, false,
            surfaceOps | kindOps({KindOperation::ToNurbs})};
}

Geometry kindBuild(const RationalBezierSurfaceData& d, const KindBuild&)
{
    return RationalBezierSurface<double, 3>(d.degree[0], d.degree[1], PointMatrix<double, 3>(d.points), weightVector(d.weights));
}

void kindNet(const RationalBezierSurfaceData& d, const Geometry&, ControlNet& net)
{
    gridNet(net, d.points, d.degree[0] + 1, d.degree[1] + 1);
}

std::string kindDetails(const RationalBezierSurfaceData& d) { return degreeWords(d.degree[0], d.degree[1]); }

std::optional<AnyCurve> kindCurve(const Geometry&, std::type_identity<RationalBezierSurfaceData>) { return std::nullopt; }

std::optional<AnySurface> kindSurface(const Geometry& g, std::type_identity<RationalBezierSurfaceData>)
{
    return AnySurface(std::get<RationalBezierSurface<double, 3>>(g));
}

KindDeform kindDeform(const RationalBezierSurfaceData&, const Geometry& g, const KindDeformInput& in)
{
    // Exact composition (volume/deform_rational.h): degrees (m (l+m+n), n (l+m+n)).
    const auto& s = std::get<RationalBezierSurface<double, 3>>(g);
    const auto& h = s.homogeneous().controlPoints();
    PointColumns points(3, h.cols());
    for (Eigen::Index i = 0; i < h.cols(); ++i) points.col(i) = h.col(i).head<3>() / h(3, i);
    KindDeform r;
    r.inside = pointsInsideLattice(in.lattice, points);
    const RationalBezierSurface<double, 3> moved = deformSurface(RationalLattice(in.lattice), s, in.strength);
    r.degree = {moved.degreeU(), moved.degreeV()};
    r.result = toData(moved);
    return r;
}

std::optional<ObjectData> kindToNurbs(const RationalBezierSurfaceData&, const Geometry& g, const std::string&)
{
    return toData(NurbsSurface<double, 3>::fromBezier(std::get<RationalBezierSurface<double, 3>>(g)));
}

std::optional<ObjectData> kindFromNurbs(const RationalBezierSurfaceData&, const Geometry&, const std::string&) { return std::nullopt; }

PointColumns* kindPoints(RationalBezierSurfaceData& d) { return &d.points; }

std::string kindNonFinite(const RationalBezierSurfaceData& d) { return nonFinitePointsWeights(d); }

} // namespace detail
} // namespace freeform
