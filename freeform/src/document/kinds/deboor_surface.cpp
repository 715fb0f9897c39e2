// The deboor_surface kind in the document layer (src/document/kind_file.h): a bicubic C2 surface
// by its grid of de Boor points and end conditions, held as its Bézier patches (docs/format.md).

#include "freeform/curve/aframe.h"

#include "../kind_file.h"

namespace freeform {

DeBoorSurfaceData toData(const DeBoorSurface& surface)
{
    DeBoorSurfaceData d;
    d.degree = {3, 3};
    d.end = {toString(surface.end[0]), toString(surface.end[1])};
    d.rows = surface.rows;
    d.cols = surface.cols;
    d.points = surface.points;
    return d;
}

namespace detail {

KindRow kindRow(std::type_identity<DeBoorSurfaceData>)
{
    // Deformed only by an affine lattice (it stays a deboor_surface); any other is skipped, so it
    // claims no Deform.
    return {"de Boor surface", KindNature::Surface, KindParameters::UV, 3, false, false, true,
            kindOps({KindOperation::Evaluate, KindOperation::Tessellate})};
}

Geometry kindBuild(const DeBoorSurfaceData& d, const KindBuild&)
{
    DeBoorSurface s;
    s.points = d.points;
    s.rows = d.rows;
    s.cols = d.cols;
    s.end = {parseEndCondition(d.end[0], "field \"end[0]\""), parseEndCondition(d.end[1], "field \"end[1]\"")};
    s.segments = deboorSurfaceSegments(d.rows, d.cols, s.end[0], s.end[1]);
    s.patches = deboorSurfacePatches(s.points, d.rows, d.cols, s.end[0], s.end[1]);
    return s;
}

void kindNet(const DeBoorSurfaceData& d, const Geometry&, ControlNet& net) { gridNet(net, d.points, d.rows, d.cols); }

std::string kindDetails(const DeBoorSurfaceData& d) { return degreeWords(d.degree[0], d.degree[1]); }

std::optional<AnyCurve> kindCurve(const Geometry&, std::type_identity<DeBoorSurfaceData>) { return std::nullopt; }

std::optional<AnySurface> kindSurface(const Geometry& g, std::type_identity<DeBoorSurfaceData>)
{
    const auto& s = std::get<DeBoorSurface>(g);
    return AnySurface(AnySurface::Patches{s.patches, s.segments});
}

KindDeform kindDeform(const DeBoorSurfaceData& data, const Geometry& g, const KindDeformInput& in)
{
    if (!in.affine) return KindDeform::skipped("no exact deformation for a " + std::string(kindName(ObjectKind::DeBoorSurface)));
    const auto& s = std::get<DeBoorSurface>(g);
    KindDeform r;
    r.inside = true;
    for (const Patch& p : s.patches.patches) r.inside = r.inside && pointsInsideLattice(in.lattice, p.controlPoints());
    DeBoorSurfaceData d = data;
    d.points = mapByPolynomial(in.lattice, d.points, in.strength);
    r.degree = {3, 3};
    r.result = std::move(d);
    return r;
}

std::optional<ObjectData> kindToNurbs(const DeBoorSurfaceData&, const Geometry&, const std::string&) { return std::nullopt; }

std::optional<ObjectData> kindFromNurbs(const DeBoorSurfaceData&, const Geometry&, const std::string&) { return std::nullopt; }

PointColumns* kindPoints(DeBoorSurfaceData& d) { return &d.points; }

std::string kindNonFinite(const DeBoorSurfaceData& d) { return nonFinitePointsWeights(d); }

} // namespace detail
} // namespace freeform
