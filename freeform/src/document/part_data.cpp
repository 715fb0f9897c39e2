// Trimmed surfaces and parts <-> their document data (docs/format.md, "Trimmed surfaces and
// parts"): the NURBS of every face, trim and edge as the nurbs_* objects hold them, the parameter
// maps and ranges as the part has them, so a part read from a CAD file and written to a document
// comes back the same to the bit.

#include "part_data.h"

#include "freeform/core/error.h"
#include "freeform/document/object_data.h"
#include "kind_file.h"

namespace freeform {
namespace {

using detail::weightVector;

template <int Dim>
MappedCurve<Dim> mappedCurve(const MappedCurveData& d)
{
    MappedCurve<Dim> c{NurbsCurve<double, Dim>(d.nurbs.degree, d.nurbs.knots, PointMatrix<double, Dim>(d.nurbs.points),
                                               weightVector(d.nurbs.weights)),
                       d.map, d.first, d.last};
    return c;
}

template <int Dim>
MappedCurveData mappedCurveData(const MappedCurve<Dim>& c)
{
    return {toData(c.nurbs), c.map, c.first, c.last};
}

} // namespace

namespace detail {

TrimmedSurface trimmedSurfaceFromData(const TrimmedSurfaceData& d)
{
    MappedSurface surface{NurbsSurface<double, 3>(d.surface.degree[0], d.surface.degree[1], d.surface.knots[0],
                                                  d.surface.knots[1], PointMatrix<double, 3>(d.surface.points),
                                                  weightVector(d.surface.weights)),
                          d.map[0], d.map[1]};
    std::vector<TrimLoop> loops;
    for (const auto& loop : d.loops) {
        TrimLoop l;
        for (const TrimCurveData& t : loop) l.curves.push_back({mappedCurve<2>(t.curve), t.reversed, t.edge});
        loops.push_back(std::move(l));
    }
    const Box<double, 2> domain(Eigen::Vector2d(d.domain[0], d.domain[2]), Eigen::Vector2d(d.domain[1], d.domain[3]));
    return TrimmedSurface(std::move(surface), domain, std::move(loops));
}

Part partFromData(const PartData& d)
{
    Part part;
    part.units = d.units;
    for (const PartVertexData& v : d.vertices) part.vertices.push_back({v.point, v.tolerance});
    for (std::size_t i = 0; i < d.edges.size(); ++i) {
        const PartEdgeData& e = d.edges[i];
        PartEdge edge;
        try {
            if (e.curve) edge.curve = mappedCurve<3>(*e.curve);
        } catch (const Error& err) {
            throw Error("edges[" + std::to_string(i) + "]: " + err.what());
        }
        edge.first = e.first;
        edge.last = e.last;
        edge.start = e.start;
        edge.end = e.end;
        edge.tolerance = e.tolerance;
        edge.degenerate = e.degenerate;
        part.edges.push_back(std::move(edge));
    }
    for (std::size_t i = 0; i < d.faces.size(); ++i) {
        const PartFaceData& f = d.faces[i];
        try {
            part.faces.push_back({trimmedSurfaceFromData(f.surface), f.reversed, f.kind, f.tolerance});
        } catch (const Error& err) {
            throw Error("faces[" + std::to_string(i) + "]: " + err.what());
        }
    }
    for (const auto& s : d.shells) part.shells.push_back({s});
    for (const auto& s : d.solids) part.solids.push_back({s});
    return part;
}

} // namespace detail

TrimmedSurfaceData toData(const TrimmedSurface& surface)
{
    TrimmedSurfaceData d;
    d.surface = toData(surface.surface().nurbs);
    d.map = {surface.surface().mapU, surface.surface().mapV};
    const Box<double, 2>& box = surface.domain();
    d.domain = {box.min().x(), box.max().x(), box.min().y(), box.max().y()};
    for (const TrimLoop& loop : surface.loops()) {
        std::vector<TrimCurveData> curves;
        for (const TrimCurve& t : loop.curves) curves.push_back({mappedCurveData(t.curve), t.reversed, t.edge});
        d.loops.push_back(std::move(curves));
    }
    return d;
}

PartData toData(const Part& part)
{
    PartData d;
    d.units = part.units;
    for (const PartVertex& v : part.vertices) d.vertices.push_back({v.point, v.tolerance});
    for (const PartEdge& e : part.edges) {
        PartEdgeData edge;
        if (e.curve) edge.curve = mappedCurveData(*e.curve);
        edge.first = e.first;
        edge.last = e.last;
        edge.start = e.start;
        edge.end = e.end;
        edge.tolerance = e.tolerance;
        edge.degenerate = e.degenerate;
        d.edges.push_back(std::move(edge));
    }
    for (const PartFace& f : part.faces) d.faces.push_back({toData(f.surface), f.reversed, f.surfaceKind, f.tolerance});
    for (const PartShell& s : part.shells) d.shells.push_back(s.faces);
    for (const PartSolid& s : part.solids) d.solids.push_back(s.shells);
    return d;
}

} // namespace freeform
