// The part kind in the document layer (src/document/kind_file.h): a CAD part, trimmed faces
// stitched along edges, with vertices, shells, solids and units (docs/format.md, docs/cad.md). Its
// data and geometry convert in part_data.cpp, which the trimmed_surface kind shares.

#include "freeform/brep/part_deform.h"
#include "freeform/core/format.h"
#include "freeform/volume/deform_rational.h"

#include "../kind_file.h"
#include "../part_data.h"

namespace freeform {

std::string partSummary(const PartData& part)
{
    auto count = [](std::size_t n, const char* one, const char* many) { return std::to_string(n) + " " + (n == 1 ? one : many); };
    return count(part.faces.size(), "face", "faces") + ", " + count(part.edges.size(), "edge", "edges") + ", " +
           count(part.vertices.size(), "vertex", "vertices") + ", " + count(part.shells.size(), "shell", "shells") + ", " +
           count(part.solids.size(), "solid", "solids") + ", units " + part.units;
}

namespace detail {

KindRow kindRow(std::type_identity<PartData>)
{
    return {"CAD part", KindNature::Part, KindParameters::FaceUV, 3, true, true, true, surfaceOps | kindOps({KindOperation::Part})};
}

Geometry kindBuild(const PartData& d, const KindBuild&) { return partFromData(d); }

void kindNet(const PartData&, const Geometry&, ControlNet&) {} // its faces are not edited point by point: no net drawn

std::string kindDetails(const PartData& d) { return partSummary(d); }

std::optional<AnyCurve> kindCurve(const Geometry&, std::type_identity<PartData>) { return std::nullopt; }

std::optional<AnySurface> kindSurface(const Geometry&, std::type_identity<PartData>) { return std::nullopt; }

KindDeform kindDeform(const PartData&, const Geometry& g, const KindDeformInput& in)
{
    // Every face and edge composed exactly (brep/part_deform.h, no degree cap: the document holds
    // degrees up to 67).
    PartDeformOptions deform;
    deform.strength = in.strength;
    deform.threads = in.options.threads;
    const DeformedPart moved = deformPart(std::get<Part>(g), RationalLattice(in.lattice), deform);
    KindDeform r;
    r.inside = moved.report.outsideFaces == 0;
    r.degree = {moved.report.maxDegree};
    r.result = toData(moved.part);
    r.note = std::to_string(moved.report.faces) + " faces composed exactly; edge tolerances x " +
             formatNumber(moved.report.lipschitz) + " (the lattice's Lipschitz bound), largest gap " +
             formatNumber(moved.report.maxGap);
    return r;
}

std::optional<ObjectData> kindToNurbs(const PartData&, const Geometry&, const std::string&) { return std::nullopt; }

std::optional<ObjectData> kindFromNurbs(const PartData&, const Geometry&, const std::string&) { return std::nullopt; }

PointColumns* kindPoints(PartData&) { return nullptr; }

std::string kindNonFinite(const PartData& d)
{
    for (const PartFaceData& f : d.faces)
        if (!f.surface.surface.points.allFinite()) return "face points";
    for (const PartEdgeData& e : d.edges)
        if (e.curve && !e.curve->nurbs.points.allFinite()) return "edge points";
    for (const PartVertexData& v : d.vertices)
        if (!v.point.allFinite()) return "vertices";
    return "";
}

} // namespace detail
} // namespace freeform
