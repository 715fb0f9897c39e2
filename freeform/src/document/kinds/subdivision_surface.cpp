// The subdivision_surface kind in the document layer (src/document/kind_file.h): a Catmull-Clark or
// Loop cage, inline or from a mesh file, with creases and corners, and the surface OpenSubdiv
// builds on it (docs/format.md, docs/subdivision.md).

#include <algorithm>
#include <set>

#include "freeform/io/geometry_data.h"

#include "../kind_file.h"

namespace freeform {

SubdivisionSurfaceData toData(const SubdivisionObject& surface)
{
    return cageToData(surface.cage(), toString(surface.surface.scheme()), toString(surface.surface.boundary()),
                      std::string(kindName(ObjectKind::SubdivisionSurface)));
}

namespace detail {

KindRow kindRow(std::type_identity<SubdivisionSurfaceData>)
{
    return {"subdivision surface", KindNature::Surface, KindParameters::FaceUV, 3, false, false, true, surfaceOps};
}

Geometry kindBuild(const SubdivisionSurfaceData& d, const KindBuild& build)
{
    // surfaceFromData prefixes its own errors with `what`; buildGeometry does not prefix them again.
    return SubdivisionObject{surfaceFromData(d, build.directory, build.what)};
}

void kindNet(const SubdivisionSurfaceData&, const Geometry& g, ControlNet& net)
{
    const SubdivisionCage& cage = std::get<SubdivisionObject>(g).cage();
    net.points = cage.mesh.positions;
    std::set<std::pair<int, int>> edges;
    for (int f = 0; f < cage.mesh.faceCount(); ++f)
        for (int k = 0; k < cage.mesh.faceSize(f); ++k) {
            const int u = cage.mesh.face(f)[k], v = cage.mesh.face(f)[(k + 1) % cage.mesh.faceSize(f)];
            edges.insert({std::min(u, v), std::max(u, v)});
        }
    net.edges.assign(edges.begin(), edges.end());
}

std::string kindDetails(const SubdivisionSurfaceData&) { return std::string(); } // its cage has a panel of its own

std::optional<AnyCurve> kindCurve(const Geometry&, std::type_identity<SubdivisionSurfaceData>) { return std::nullopt; }

std::optional<AnySurface> kindSurface(const Geometry&, std::type_identity<SubdivisionSurfaceData>) { return std::nullopt; }

KindDeform kindDeform(const SubdivisionSurfaceData& data, const Geometry& g, const KindDeformInput& in)
{
    const auto& sub = std::get<SubdivisionObject>(g);
    KindDeform r;
    r.pointwise = true;
    r.inside = pointsInsideLattice(in.lattice, sub.cage().mesh.positions);
    SubdivisionSurfaceData d = data;
    Eigen::Matrix<double, 3, Eigen::Dynamic> v;
    if (data.mesh.empty()) {
        v = data.vertices;
    } else {
        // A cage from a mesh file is written inline (its OBJ crease tags become the object's
        // creases and corners), so the document holds the deformed cage.
        d = toData(sub); // Error when the file's cage has what the inline form cannot hold
        v = d.vertices;
        r.note = "the cage from \"" + data.mesh + "\" is written inline; ";
    }
    DeformOptions deform;
    deform.strength = in.strength;
    deform.threads = in.options.threads;
    deformPoints(in.lattice, v, deform);
    d.vertices = v;
    r.result = std::move(d);
    r.note += in.affine ? "cage deformed as a cage (the lattice is affine: the limit surface moves exactly)"
                        : "cage deformed as a cage: its limit surface is not the deformed limit surface "
                          "(exact only for affine lattices)";
    return r;
}

std::optional<ObjectData> kindToNurbs(const SubdivisionSurfaceData&, const Geometry&, const std::string&) { return std::nullopt; }

std::optional<ObjectData> kindFromNurbs(const SubdivisionSurfaceData&, const Geometry&, const std::string&) { return std::nullopt; }

PointColumns* kindPoints(SubdivisionSurfaceData& d) { return &d.vertices; }

std::string kindNonFinite(const SubdivisionSurfaceData& d) { return d.vertices.allFinite() ? "" : "vertices"; }

} // namespace detail
} // namespace freeform
