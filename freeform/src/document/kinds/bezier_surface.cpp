// The bezier_surface kind in the document layer (src/document/kind_file.h): one tensor-product
// Bézier patch on [0, 1]^2 (docs/format.md).

#include "../kind_file.h"

namespace freeform {

BezierSurfaceData toData(const BezierSurface<double, 3>& surface)
{
    BezierSurfaceData d;
    d.degree = {surface.degreeU(), surface.degreeV()};
    d.points = surface.controlPoints();
    return d;
}

namespace detail {

KindRow kindRow(std::type_identity<BezierSurfaceData>)
{
    return {"Bézier surface", KindNature::Surface, KindParameters::UV, 3, false, false, false,
            surfaceOps | kindOps({KindOperation::ToNurbs})};
}

Geometry kindBuild(const BezierSurfaceData& d, const KindBuild&)
{
    return BezierSurface<double, 3>(d.degree[0], d.degree[1], PointMatrix<double, 3>(d.points));
}

void kindNet(const BezierSurfaceData& d, const Geometry&, ControlNet& net) { gridNet(net, d.points, d.degree[0] + 1, d.degree[1] + 1); }

std::string kindDetails(const BezierSurfaceData& d) { return degreeWords(d.degree[0], d.degree[1]); }

std::optional<AnyCurve> kindCurve(const Geometry&, std::type_identity<BezierSurfaceData>) { return std::nullopt; }

std::optional<AnySurface> kindSurface(const Geometry& g, std::type_identity<BezierSurfaceData>)
{
    return AnySurface(AnySurface::Patches{PatchComplex{{std::get<BezierSurface<double, 3>>(g)}}, {1, 1}});
}

KindDeform kindDeform(const BezierSurfaceData&, const Geometry& g, const KindDeformInput& in)
{
    const auto& s = std::get<BezierSurface<double, 3>>(g);
    KindDeform r;
    r.inside = pointsInsideLattice(in.lattice, s.controlPoints());
    const BezierSurface<double, 3> moved = deformSurface(in.lattice, s, in.strength);
    r.degree = {moved.degreeU(), moved.degreeV()};
    r.result = toData(moved);
    return r;
}

std::optional<ObjectData> kindToNurbs(const BezierSurfaceData&, const Geometry& g, const std::string&)
{
    return toData(NurbsSurface<double, 3>::fromBezier(RationalBezierSurface<double, 3>(std::get<BezierSurface<double, 3>>(g))));
}

std::optional<ObjectData> kindFromNurbs(const BezierSurfaceData&, const Geometry&, const std::string&) { return std::nullopt; }

PointColumns* kindPoints(BezierSurfaceData& d) { return &d.points; }

std::string kindNonFinite(const BezierSurfaceData& d) { return nonFinitePointsWeights(d); }

} // namespace detail
} // namespace freeform
