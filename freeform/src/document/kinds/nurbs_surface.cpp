// The nurbs_surface kind in the document layer (src/document/kind_file.h): a tensor-product NURBS
// surface, degrees, both knot vectors, the rows x cols grid and (when rational) weights
// (docs/format.md).

#include "freeform/core/error.h"
#include "freeform/volume/deform_rational.h"

#include "../kind_file.h"

namespace freeform {

NurbsSurfaceData toData(const NurbsSurface<double, 3>& surface)
{
    NurbsSurfaceData d;
    d.degree = {surface.degreeU(), surface.degreeV()};
    d.knots = {surface.knotsU().knots(), surface.knotsV().knots()};
    d.rows = surface.countU();
    d.cols = surface.countV();
    d.points = surface.controlPoints();
    if (surface.isRational()) d.weights = detail::weightList(surface.weights());
    return d;
}

namespace detail {

KindRow kindRow(std::type_identity<NurbsSurfaceData>)
{
    return {"NURBS surface", KindNature::Surface, KindParameters::UV, 3, true, true, true, surfaceOps | kindOps({KindOperation::FromNurbs})};
}

Geometry kindBuild(const NurbsSurfaceData& d, const KindBuild&)
{
    return NurbsSurface<double, 3>(d.degree[0], d.degree[1], d.knots[0], d.knots[1], PointMatrix<double, 3>(d.points),
                                   weightVector(d.weights));
}

void kindNet(const NurbsSurfaceData& d, const Geometry&, ControlNet& net) { gridNet(net, d.points, d.rows, d.cols); }

std::string kindDetails(const NurbsSurfaceData& d)
{
    return degreeWords(d.degree[0], d.degree[1]) + ", " + std::to_string(d.rows) + " x " + std::to_string(d.cols) + " points";
}

std::optional<AnyCurve> kindCurve(const Geometry&, std::type_identity<NurbsSurfaceData>) { return std::nullopt; }

std::optional<AnySurface> kindSurface(const Geometry& g, std::type_identity<NurbsSurfaceData>)
{
    return AnySurface(std::get<NurbsSurface<double, 3>>(g));
}

KindDeform kindDeform(const NurbsSurfaceData&, const Geometry& g, const KindDeformInput& in)
{
    // Patch by patch through the Bézier extraction; the result keeps the breakpoints.
    const auto& s = std::get<NurbsSurface<double, 3>>(g);
    KindDeform r;
    r.inside = pointsInsideLattice(in.lattice, s.controlPoints());
    const NurbsSurface<double, 3> moved = deformSurface(RationalLattice(in.lattice), s, in.strength);
    r.degree = {moved.degreeU(), moved.degreeV()};
    r.result = toData(moved);
    return r;
}

std::optional<ObjectData> kindToNurbs(const NurbsSurfaceData&, const Geometry&, const std::string&) { return std::nullopt; }

std::optional<ObjectData> kindFromNurbs(const NurbsSurfaceData&, const Geometry& g, const std::string& what)
{
    const auto& s = std::get<NurbsSurface<double, 3>>(g);
    const auto patches = s.bezierPatches();
    if (patches.size() != 1)
        throw Error(what + ": a nurbs_surface of " + std::to_string(patches.size()) +
                    " Bézier patches has no single-object Bézier form (one patch per object)");
    RationalBezierSurfaceData d = toData(patches.front());
    if (!s.isRational()) return BezierSurfaceData{d.degree, std::move(d.points)};
    return d;
}

PointColumns* kindPoints(NurbsSurfaceData& d) { return &d.points; }

std::string kindNonFinite(const NurbsSurfaceData& d) { return nonFinitePointsWeights(d); }

} // namespace detail
} // namespace freeform
