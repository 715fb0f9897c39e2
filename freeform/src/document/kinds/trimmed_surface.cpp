// The trimmed_surface kind in the document layer (src/document/kind_file.h): a NURBS surface with
// parameter maps, a parameter box and trim loops (docs/format.md, docs/cad.md). Its data and
// geometry convert in part_data.cpp, which the part kind shares.

#include "freeform/brep/part_deform.h"
#include "freeform/volume/deform_rational.h"

#include "../kind_file.h"
#include "../part_data.h"

namespace freeform::detail {

KindRow kindRow(std::type_identity<TrimmedSurfaceData>)
{
    return {"trimmed NURBS surface", KindNature::Surface, KindParameters::UV, 3, true, true, true,
            surfaceOps | kindOps({KindOperation::Part})};
}

Geometry kindBuild(const TrimmedSurfaceData& d, const KindBuild&) { return trimmedSurfaceFromData(d); }

void kindNet(const TrimmedSurfaceData& d, const Geometry&, ControlNet& net) // its NURBS's grid
{
    gridNet(net, d.surface.points, d.surface.rows, d.surface.cols);
}

std::string kindDetails(const TrimmedSurfaceData& d)
{
    const std::size_t loops = d.loops.size();
    return degreeWords(d.surface.degree[0], d.surface.degree[1]) + ", " + std::to_string(loops) + (loops == 1 ? " trim loop" : " trim loops");
}

std::optional<AnyCurve> kindCurve(const Geometry&, std::type_identity<TrimmedSurfaceData>) { return std::nullopt; }

std::optional<AnySurface> kindSurface(const Geometry& g, std::type_identity<TrimmedSurfaceData>)
{
    return AnySurface(std::get<TrimmedSurface>(g));
}

KindDeform kindDeform(const TrimmedSurfaceData&, const Geometry& g, const KindDeformInput& in)
{
    // The face and its trims' edges composed exactly (brep/part_deform.h, no degree cap: the
    // document holds degrees up to 67), as a part of one face.
    PartDeformOptions deform;
    deform.strength = in.strength;
    deform.threads = in.options.threads;
    const DeformedPart moved = deformPart(singleFacePart(std::get<TrimmedSurface>(g)), RationalLattice(in.lattice), deform);
    KindDeform r;
    r.inside = moved.report.outsideFaces == 0;
    r.degree = {moved.report.maxDegree};
    TrimmedSurfaceData d = toData(moved.part.faces.front().surface);
    for (auto& loop : d.loops)
        for (TrimCurveData& trim : loop) trim.edge = -1; // the part's edges were singleFacePart's
    r.result = std::move(d);
    return r;
}

std::optional<ObjectData> kindToNurbs(const TrimmedSurfaceData&, const Geometry&, const std::string&) { return std::nullopt; }

std::optional<ObjectData> kindFromNurbs(const TrimmedSurfaceData&, const Geometry&, const std::string&) { return std::nullopt; }

PointColumns* kindPoints(TrimmedSurfaceData& d) { return &d.surface.points; }

std::string kindNonFinite(const TrimmedSurfaceData& d) { return d.surface.points.allFinite() ? "" : "points"; }

} // namespace freeform::detail
