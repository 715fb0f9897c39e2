// Parts: bounds and the topology and gap check (brep/part.h, docs/cad.md "Parts").

#include "freeform/brep/part.h"

#include <algorithm>
#include <map>

namespace freeform {

std::vector<int> Part::looseFaces() const
{
    std::vector<char> inShell(faces.size(), 0);
    for (const PartShell& s : shells)
        for (int f : s.faces) inShell[static_cast<std::size_t>(f)] = 1;
    std::vector<int> loose;
    for (std::size_t f = 0; f < faces.size(); ++f)
        if (!inShell[f]) loose.push_back(static_cast<int>(f));
    return loose;
}

Part singleFacePart(const TrimmedSurface& surface)
{
    Part part;
    std::vector<TrimLoop> loops = surface.loops();
    for (TrimLoop& loop : loops) {
        // One vertex where each trim starts, shared with the end of the trim before it (the loop
        // is closed); its tolerance covers the gap between the two ends in space.
        const int first = static_cast<int>(part.vertices.size());
        const int n = static_cast<int>(loop.curves.size());
        for (int k = 0; k < n; ++k) {
            const TrimCurve& trim = loop.curves[static_cast<std::size_t>(k)];
            const TrimCurve& before = loop.curves[static_cast<std::size_t>((k + n - 1) % n)];
            const Eigen::Vector2d a = trim.start(), b = before.end();
            const Eigen::Vector3d p = surface.point(a.x(), a.y());
            part.vertices.push_back({p, (surface.point(b.x(), b.y()) - p).norm()});
        }
        for (int k = 0; k < n; ++k) {
            TrimCurve& trim = loop.curves[static_cast<std::size_t>(k)];
            PartEdge edge;
            edge.first = trim.curve.first;
            edge.last = trim.curve.last;
            int start = first + k, end = first + (k + 1) % n;
            if (trim.reversed) std::swap(start, end);
            edge.start = start;
            edge.end = end;
            edge.tolerance = std::max(part.vertices[static_cast<std::size_t>(start)].tolerance,
                                      part.vertices[static_cast<std::size_t>(end)].tolerance);
            trim.edge = static_cast<int>(part.edges.size());
            part.edges.push_back(std::move(edge));
        }
    }
    part.faces.push_back({TrimmedSurface(surface.surface(), surface.domain(), std::move(loops), surface.flatness()), false, "", 0});
    return part;
}

Box<double, 3> Part::bounds() const
{
    Box<double, 3> box;
    for (const PartFace& f : faces) box.extend(f.surface.bounds());
    for (const PartVertex& v : vertices) box.extend(v.point);
    return box;
}

int Part::maxDegree() const
{
    int degree = 0;
    for (const PartFace& f : faces) degree = std::max({degree, f.surface.surface().nurbs.degreeU(), f.surface.surface().nurbs.degreeV()});
    for (const PartEdge& e : edges)
        if (e.curve) degree = std::max(degree, e.curve->nurbs.degree());
    return degree;
}

double Part::area(double relative) const
{
    double sum = 0;
    for (const PartFace& f : faces) sum += f.surface.area(relative);
    return sum;
}

PartCheck checkPart(const Part& part, int samples)
{
    PartCheck check;
    for (const PartShell& shell : part.shells) {
        std::map<int, int> uses; // edge -> uses in this shell (a seam counts twice in its face)
        for (int f : shell.faces)
            for (const TrimLoop& loop : part.faces[static_cast<std::size_t>(f)].surface.loops())
                for (const TrimCurve& c : loop.curves)
                    if (c.edge >= 0 && !part.edges[static_cast<std::size_t>(c.edge)].degenerate) ++uses[c.edge];
        for (const auto& [edge, count] : uses) {
            if (count == 1) ++check.openEdges;
            if (count > 2) ++check.nonManifoldEdges;
        }
    }
    check.closed = !part.shells.empty() && check.openEdges == 0 && check.nonManifoldEdges == 0;

    for (const PartFace& face : part.faces)
        for (const TrimLoop& loop : face.surface.loops())
            for (const TrimCurve& c : loop.curves) {
                if (c.edge < 0) continue;
                const PartEdge& e = part.edges[static_cast<std::size_t>(c.edge)];
                if (!e.curve) continue;
                double gap = 0;
                for (int k = 0; k <= samples; ++k) {
                    const double t = e.first + (e.last - e.first) * k / samples;
                    const Eigen::Vector2d uv = c.curve.point(t);
                    gap = std::max(gap, (e.curve->point(t) - face.surface.point(uv.x(), uv.y())).norm());
                }
                check.maxGap = std::max(check.maxGap, gap);
                if (gap > e.tolerance) ++check.gapsOverTolerance;
            }
    return check;
}

} // namespace freeform
