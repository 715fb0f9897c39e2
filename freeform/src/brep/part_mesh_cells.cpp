// One face of the part tessellation (brep/part_mesh.h, docs/cad.md "Tessellation"): its trim
// polygon cut by the grid cells. Each side of the polygon lies in one cell (the edge samples hold
// every crossing of a grid line); a cell's region is walked from chain to chain of the polygon's
// sides in it and along the cell's sides between them, and cut into triangles by ear clipping.
// Also the whole mesh's cleanup along the edges (dropEdgePockets).

#include <algorithm>
#include <cstdint>
#include <numbers>
#include <map>

#include "freeform/mesh/triangulate.h"
#include "part_mesh_internal.h"

namespace freeform::part_mesh {

namespace {

double signedArea(const std::vector<Eigen::Vector2d>& loop)
{
    double a = 0;
    for (std::size_t i = 0, n = loop.size(); i < n; ++i) {
        const Eigen::Vector2d& p = loop[i];
        const Eigen::Vector2d& q = loop[(i + 1) % n];
        a += p.x() * q.y() - q.x() * p.y();
    }
    return 0.5 * a;
}

double signedArea(const std::vector<PolyPoint>& loop)
{
    double a = 0;
    for (std::size_t i = 0, n = loop.size(); i < n; ++i) {
        const Eigen::Vector2d& p = loop[i].s;
        const Eigen::Vector2d& q = loop[(i + 1) % n].s;
        a += p.x() * q.y() - q.x() * p.y();
    }
    return 0.5 * a;
}

bool insideLoops(const std::vector<std::vector<PolyPoint>>& loops, const Eigen::Vector2d& x)
{
    bool in = false;
    for (const auto& loop : loops)
        for (std::size_t i = 0, n = loop.size(); i < n; ++i) {
            const Eigen::Vector2d& a = loop[i].s;
            const Eigen::Vector2d& b = loop[(i + 1) % n].s;
            if ((a.y() > x.y()) != (b.y() > x.y()) && x.x() < a.x() + (x.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
                in = !in;
        }
    return in;
}

} // namespace

void joinAcrossLines(const FaceGrid& g, const PolyPoint& a, const PolyPoint& b, std::vector<PolyPoint>& out)
{
    std::vector<std::pair<double, Eigen::Vector2d>> cuts;
    for (int axis = 0; axis < 2; ++axis) {
        const std::vector<double>& lines = axis == 0 ? g.gu : g.gv;
        const double lo = std::min(a.s[axis], b.s[axis]), hi = std::max(a.s[axis], b.s[axis]);
        for (auto it = std::upper_bound(lines.begin(), lines.end(), lo); it != lines.end() && *it < hi; ++it) {
            const double lambda = (*it - a.s[axis]) / (b.s[axis] - a.s[axis]);
            Eigen::Vector2d p = a.s + lambda * (b.s - a.s);
            p[axis] = *it;
            p[1 - axis] = std::clamp(p[1 - axis], std::min(a.s[1 - axis], b.s[1 - axis]), std::max(a.s[1 - axis], b.s[1 - axis]));
            cuts.push_back({lambda, g.snap(p)});
        }
    }
    std::sort(cuts.begin(), cuts.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    for (const auto& c : cuts)
        if (out.back().s != c.second) out.push_back({c.second, a.vertex});
}

/// Meshes one face: its loops (in NURBS parameters, with the vertices of the edge samples) clipped
/// by the grid cells. Returns the largest distance between a polygon vertex and the surface.
std::vector<int> crossingEdges(const FaceGrid& g, const std::vector<std::vector<Eigen::Vector2d>>& loops,
                               const std::vector<std::vector<int>>& edgeOf)
{
    struct Side {
        Eigen::Vector2d a, b;
        int edgeA, edgeB;
        std::size_t loop, index, count;
    };
    std::vector<Side> sides;
    for (std::size_t l = 0; l < loops.size(); ++l)
        for (std::size_t k = 0, n = loops[l].size(); k < n; ++k) {
            const Eigen::Vector2d &a = loops[l][k], &b = loops[l][(k + 1) % n];
            if (a != b) sides.push_back({a, b, edgeOf[l][k], edgeOf[l][(k + 1) % n], l, k, n});
        }
    // Sides a few points apart along their loop cross where trims meet at a vertex within the
    // file's tolerance, at any density: not counted.
    auto near = [](const Side& s, const Side& t) {
        if (s.loop != t.loop) return false;
        const std::size_t d = s.index > t.index ? s.index - t.index : t.index - s.index;
        return std::min(d, s.count - d) <= 3;
    };
    if (sides.size() < 4) return {};
    // Buckets: about as many as sides, over the face's box; each side in those its box meets.
    const Eigen::Vector2d lo(g.gu.front(), g.gv.front()), hi(g.gu.back(), g.gv.back());
    const int K = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(sides.size()))), 1, 512);
    const Eigen::Vector2d size = (hi - lo).cwiseMax(Eigen::Vector2d::Constant(1e-300));
    auto bucket = [&](double x, double l, double w) { return std::clamp(static_cast<int>((x - l) / w * K), 0, K - 1); };
    // (In one array, bucket by bucket: counted, then filled. A hash map of vectors was an
    // allocation per bucket.)
    std::vector<std::size_t> start(static_cast<std::size_t>(K) * K + 1, 0), entries;
    auto forBuckets = [&](const Side& s, auto&& take) {
        const int x0 = bucket(std::min(s.a.x(), s.b.x()), lo.x(), size.x()), x1 = bucket(std::max(s.a.x(), s.b.x()), lo.x(), size.x());
        const int y0 = bucket(std::min(s.a.y(), s.b.y()), lo.y(), size.y()), y1 = bucket(std::max(s.a.y(), s.b.y()), lo.y(), size.y());
        for (int x = x0; x <= x1; ++x)
            for (int y = y0; y <= y1; ++y) take(static_cast<std::size_t>(x * K + y));
    };
    for (const Side& s : sides) forBuckets(s, [&](std::size_t k) { ++start[k + 1]; });
    for (std::size_t k = 1; k < start.size(); ++k) start[k] += start[k - 1];
    entries.resize(start.back());
    {
        std::vector<std::size_t> fill(start.begin(), start.end() - 1);
        for (std::size_t i = 0; i < sides.size(); ++i) forBuckets(sides[i], [&](std::size_t k) { entries[fill[k]++] = i; });
    }
    auto orient = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
        const double v = (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
        return (v > 0) - (v < 0);
    };
    std::vector<int> out;
    for (std::size_t k = 0; k + 1 < start.size(); ++k)
        for (std::size_t x = start[k]; x < start[k + 1]; ++x)
            for (std::size_t y = x + 1; y < start[k + 1]; ++y) {
                const Side &s = sides[entries[x]], &t = sides[entries[y]];
                if (near(s, t)) continue;
                // Sides that cross in both of their interiors (not at a shared point, not along a line).
                if (orient(s.a, s.b, t.a) * orient(s.a, s.b, t.b) < 0 && orient(t.a, t.b, s.a) * orient(t.a, t.b, s.b) < 0)
                    out.insert(out.end(), {s.edgeA, s.edgeB, t.edgeA, t.edgeB});
            }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

double meshFace(const PartFace& face, std::size_t f, const FaceGrid& g, std::vector<std::vector<PolyPoint>> loops,
                Builder& out)
{
    const NurbsSurface<double, 3>& S = face.surface.surface().nurbs;
    double delta = 0;
    // Orientation: the loop of largest area counter-clockwise (the face on its left), the others
    // clockwise. The areas are the trims' own (their fine polygons; the maps to NURBS parameters
    // increase, so the signs hold): where a face is a sliver thinner than the tolerance, its
    // coarse polygon crosses itself and its area's sign says nothing (Motor-c.brep's face 207, a
    // ring 0.05 mm wide, at 0.5 mm).
    const std::vector<std::vector<Eigen::Vector2d>>& fine = face.surface.polygons();
    std::size_t outer = 0;
    std::vector<double> areas;
    for (std::size_t l = 0; l < loops.size(); ++l) {
        areas.push_back(l < fine.size() ? signedArea(fine[l]) : signedArea(loops[l]));
        if (std::abs(areas[l]) > std::abs(areas[outer])) outer = l;
    }
    std::vector<char> hole; // per loop kept
    {
        std::vector<std::vector<PolyPoint>> kept;
        for (std::size_t l = 0; l < loops.size(); ++l) {
            if ((l == outer) != (areas[l] > 0)) std::reverse(loops[l].begin(), loops[l].end());
            if (loops[l].size() < 3 || signedArea(loops[l]) == 0) continue;
            kept.push_back(std::move(loops[l]));
            hole.push_back(l != outer);
        }
        loops = std::move(kept);
    }
    // Samples of other vertices at the very point of one before them (a grid line's crossing that
    // another face needs, within this face's snapping distance of the edge's end: Bottom.brep
    // deformed, where a circle's last crossing snapped onto its end at the seam) leave the polygon,
    // whose cells would drop them as a side of no length, and go into thin triangles with the next
    // point instead: from r0 through r1 .. rm to the next point c, each (r_i, r_i+1, c) in the
    // loop's direction. The other face of the edge has the sides r_i r_i+1; these close them, and
    // lie within the snap's share of the trims' term (step 2 counts the snapped ends).
    for (auto& loop : loops) {
        const std::size_t n = loop.size();
        std::size_t first = 0; // a point that differs in s from the one before it
        while (first < n && loop[first].s == loop[(first + n - 1) % n].s) ++first;
        if (first == n) continue;
        std::vector<PolyPoint> kept;
        for (std::size_t k = 0; k < n;) {
            const std::size_t start = (first + k) % n;
            std::size_t m = 1;
            while (k + m < n && loop[(start + m) % n].s == loop[start].s) ++m;
            kept.push_back(loop[start]);
            const PolyPoint& c = loop[(start + m) % n];
            for (std::size_t i = 0; i + 1 < m; ++i) {
                const int a = loop[(start + i) % n].vertex, b = loop[(start + i + 1) % n].vertex;
                if (a == b || b == c.vertex || a == c.vertex) continue;
                out.triangles.push_back(face.reversed ? std::array<int, 3>{a, c.vertex, b} : std::array<int, 3>{a, b, c.vertex});
                out.triangleFace.push_back(static_cast<int>(f));
            }
            k += m;
        }
        loop = std::move(kept);
    }

    // A trim that runs across the seam of a closed surface leaves its parameter box on one side and
    // comes back on the other: not cut at the seam yet (docs/cad.md, "Tessellation"). Its side
    // jumps more than half the period, across grid lines (a side that long within one cell is a
    // trim along a wide cell).
    auto period = [](const AxisMap& a) {
        if (a.map.kind == ParameterMap::Kind::Identity) return a.map.period;
        if (a.map.kind == ParameterMap::Kind::HalfAngle && a.map.spans * a.map.span >= 2 * std::numbers::pi * (1 - 1e-9))
            return a.map.spans * a.map.span; // NURBS parameters run with the angle at the arcs' ends
        return 0.0;
    };
    const double pu = period(g.mu), pv = period(g.mv);
    for (const auto& loop : loops)
        for (std::size_t k = 0; k < loop.size(); ++k) {
            const Eigen::Vector2d a = loop[k].s, b = loop[(k + 1) % loop.size()].s, jump = (b - a).cwiseAbs();
            auto across = [&](const std::vector<double>& lines, int axis) {
                return lineBetween(lines, std::min(a[axis], b[axis]), std::max(a[axis], b[axis]));
            };
            if ((pu > 0 && jump.x() > 0.5 * pu && across(g.gu, 0)) || (pv > 0 && jump.y() > 0.5 * pv && across(g.gv, 1)))
                throw Error(faceName(f) + ": a trim crosses the seam of its closed surface, which the tessellation does not cut yet");
        }
    const int Nu = static_cast<int>(g.gu.size()) - 1, Nv = static_cast<int>(g.gv.size()) - 1;
    // Polygon points on grid lines (for the cells on either side) and at grid nodes.
    std::map<std::pair<double, double>, int> atPoint;
    std::vector<std::vector<std::pair<double, int>>> onU(g.gu.size()), onV(g.gv.size());
    auto lineIndex = [](const std::vector<double>& l, double x) {
        const auto it = std::lower_bound(l.begin(), l.end(), x);
        return it != l.end() && *it == x ? static_cast<int>(it - l.begin()) : -1;
    };
    for (const auto& loop : loops)
        for (const PolyPoint& p : loop) {
            delta = std::max(delta, (out.positions[static_cast<std::size_t>(p.vertex)] - S.evaluate(p.s.x(), p.s.y())).norm());
            atPoint.emplace(std::make_pair(p.s.x(), p.s.y()), p.vertex);
            if (const int i = lineIndex(g.gu, p.s.x()); i >= 0) onU[static_cast<std::size_t>(i)].push_back({p.s.y(), p.vertex});
            if (const int j = lineIndex(g.gv, p.s.y()); j >= 0) onV[static_cast<std::size_t>(j)].push_back({p.s.x(), p.vertex});
        }
    for (auto& l : onU) std::sort(l.begin(), l.end());
    for (auto& l : onV) std::sort(l.begin(), l.end());
    std::map<std::pair<int, int>, int> node;
    auto nodeVertex = [&](int i, int j) {
        const double u = g.gu[static_cast<std::size_t>(i)], v = g.gv[static_cast<std::size_t>(j)];
        if (auto it = atPoint.find({u, v}); it != atPoint.end()) return it->second;
        auto [it, fresh] = node.try_emplace({i, j}, -1);
        if (fresh) it->second = out.add(S.evaluate(u, v));
        return it->second;
    };

    // Each side of the polygon goes to the cell holding it: the cell of its midpoint, or for a side
    // along a grid line the cell on its left (the face's side).
    auto cellOf = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) -> long long {
        const Eigen::Vector2d m = 0.5 * (a + b);
        auto index = [](const std::vector<double>& l, double x, double along) {
            const auto it = std::upper_bound(l.begin(), l.end(), x);
            int i = static_cast<int>(it - l.begin()) - 1;
            if (i >= 0 && l[static_cast<std::size_t>(i)] == x && along != 0) i = along > 0 ? i - 1 : i;
            return i;
        };
        const bool alongU = a.x() == b.x() && lineIndex(g.gu, a.x()) >= 0;
        const bool alongV = a.y() == b.y() && lineIndex(g.gv, a.y()) >= 0;
        const int i = index(g.gu, m.x(), alongU ? b.y() - a.y() : 0.0);  // going up: the cell on the left
        const int j = index(g.gv, m.y(), alongV ? a.x() - b.x() : 0.0);  // going right: the cell above
        if (i < 0 || i >= Nu || j < 0 || j >= Nv) return -1;
        return static_cast<long long>(i) * Nv + j;
    };
    // A side between two points of one vertex (where trims meet) may turn back along a grid line,
    // and one between two vertices snapped to one point has no direction: such a side stays with
    // the side before it (or after it) when that cell holds it.
    auto holds = [&](long long c, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
        if (c < 0) return false;
        const std::size_t i = static_cast<std::size_t>(c / Nv), j = static_cast<std::size_t>(c % Nv);
        auto in = [&](const Eigen::Vector2d& p) {
            return p.x() >= g.gu[i] && p.x() <= g.gu[i + 1] && p.y() >= g.gv[j] && p.y() <= g.gv[j + 1];
        };
        return in(a) && in(b);
    };
    std::vector<std::vector<long long>> sideCell(loops.size());
    // The sides in each cell, in loop order (in one array, cell by cell: counted, then filled).
    std::vector<std::size_t> cellStart(static_cast<std::size_t>(Nu) * static_cast<std::size_t>(Nv) + 1, 0);
    std::vector<std::pair<int, int>> cellSides;
    for (std::size_t l = 0; l < loops.size(); ++l) {
        const auto& loop = loops[l];
        const std::size_t n = loop.size();
        for (std::size_t k = 0; k < n; ++k) sideCell[l].push_back(cellOf(loop[k].s, loop[(k + 1) % n].s));
        for (std::size_t k = 0; k < n; ++k) {
            const PolyPoint &a = loop[k], &b = loop[(k + 1) % n];
            if (a.vertex != b.vertex && a.s != b.s) continue;
            const long long before = sideCell[l][(k + n - 1) % n], after = sideCell[l][(k + 1) % n];
            if (holds(before, a.s, b.s)) sideCell[l][k] = before;
            else if (holds(after, a.s, b.s)) sideCell[l][k] = after;
        }
        for (std::size_t k = 0; k < n; ++k)
            if (sideCell[l][k] >= 0) ++cellStart[static_cast<std::size_t>(sideCell[l][k]) + 1];
    }
    for (std::size_t c = 1; c < cellStart.size(); ++c) cellStart[c] += cellStart[c - 1];
    cellSides.resize(cellStart.back());
    {
        std::vector<std::size_t> fill(cellStart.begin(), cellStart.end() - 1);
        for (std::size_t l = 0; l < loops.size(); ++l)
            for (std::size_t k = 0; k < loops[l].size(); ++k)
                if (sideCell[l][k] >= 0) cellSides[fill[static_cast<std::size_t>(sideCell[l][k])]++] = {static_cast<int>(l), static_cast<int>(k)};
    }

    auto clip = [&](const std::vector<PolyPoint>& poly) {
        if (poly.size() < 3) return;
        Eigen::Matrix<double, 2, Eigen::Dynamic> corners(2, static_cast<Eigen::Index>(poly.size()));
        for (std::size_t k = 0; k < poly.size(); ++k) corners.col(static_cast<Eigen::Index>(k)) = poly[k].s;
        for (const auto& t : triangulatePolygon2(corners)) {
            const int a = poly[static_cast<std::size_t>(t[0])].vertex, b = poly[static_cast<std::size_t>(t[1])].vertex,
                      c = poly[static_cast<std::size_t>(t[2])].vertex;
            if (a == b || b == c || a == c) continue; // collapsed (a pole)
            out.triangles.push_back(face.reversed ? std::array<int, 3>{a, c, b} : std::array<int, 3>{a, b, c});
            out.triangleFace.push_back(static_cast<int>(f));
        }
    };
    // A cell's region pinched to a point passes it twice (a hole that touches a grid line from
    // inside the cell: Bottom.brep's plate, where a circle of radius 45 touches the line u = -45
    // that a hole's cut put there). Ear clipping across the pinch would cut triangles that overlap
    // (four on one mesh edge): each lobe is clipped on its own.
    auto pinched = [](const std::vector<PolyPoint>& poly) {
        if (poly.size() <= 16) { // most cells: no sort
            for (std::size_t i = 0; i < poly.size(); ++i)
                for (std::size_t j = i + 1; j < poly.size(); ++j)
                    if (poly[i].s == poly[j].s) return true;
            return false;
        }
        thread_local std::vector<Eigen::Vector2d> sorted;
        sorted.clear();
        for (const PolyPoint& p : poly) sorted.push_back(p.s);
        std::sort(sorted.begin(), sorted.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
            return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
        });
        return std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end();
    };
    auto emit = [&](const std::vector<PolyPoint>& poly) {
        if (!pinched(poly)) return clip(poly);
        // Lobes: a point met again closes the run since its first visit, which goes on its own;
        // a lobe of no area (a spike out and back) goes with nothing.
        std::vector<PolyPoint> rest;
        for (const PolyPoint& p : poly) {
            const auto again = std::find_if(rest.begin(), rest.end(), [&](const PolyPoint& q) { return q.s == p.s; });
            if (again != rest.end()) {
                const std::vector<PolyPoint> lobe(again, rest.end());
                rest.erase(again + 1, rest.end());
                if (signedArea(lobe) > 0) clip(lobe);
                continue;
            }
            rest.push_back(p);
        }
        if (signedArea(rest) > 0) clip(rest);
    };

    std::vector<std::pair<double, PolyPoint>> rim; // (reused from cell to cell)
    std::vector<PolyPoint> whole;
    for (int i = 0; i < Nu; ++i)
        for (int j = 0; j < Nv; ++j) {
            const double u0 = g.gu[static_cast<std::size_t>(i)], u1 = g.gu[static_cast<std::size_t>(i) + 1];
            const double v0 = g.gv[static_cast<std::size_t>(j)], v1 = g.gv[static_cast<std::size_t>(j) + 1];
            auto perimeter = [&](const Eigen::Vector2d& p) {
                if (p.y() == v0 && p.x() < u1) return (p.x() - u0) / (u1 - u0);
                if (p.x() == u1 && p.y() < v1) return 1 + (p.y() - v0) / (v1 - v0);
                if (p.y() == v1 && p.x() > u0) return 2 + (u1 - p.x()) / (u1 - u0);
                if (p.x() == u0 && p.y() > v0) return 3 + (v1 - p.y()) / (v1 - v0);
                return -1.0;
            };
            // The cell's boundary points: its corners and the polygon points on its sides.
            rim.assign({{0, {{u0, v0}, -2}}, {1, {{u1, v0}, -3}}, {2, {{u1, v1}, -4}}, {3, {{u0, v1}, -5}}});
            auto addSide = [&](const std::vector<std::pair<double, int>>& l, double lo, double hi, bool vertical, double fixed) {
                for (auto it = std::upper_bound(l.begin(), l.end(), std::make_pair(lo, std::numeric_limits<int>::max()));
                     it != l.end() && it->first < hi; ++it) {
                    const Eigen::Vector2d p = vertical ? Eigen::Vector2d(fixed, it->first) : Eigen::Vector2d(it->first, fixed);
                    rim.push_back({perimeter(p), {p, it->second}});
                }
            };
            addSide(onV[static_cast<std::size_t>(j)], u0, u1, false, v0);
            addSide(onU[static_cast<std::size_t>(i) + 1], v0, v1, true, u1);
            addSide(onV[static_cast<std::size_t>(j) + 1], u0, u1, false, v1);
            addSide(onU[static_cast<std::size_t>(i)], v0, v1, true, u0);
            std::sort(rim.begin(), rim.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
            auto vertexOf = [&](const PolyPoint& p) {
                if (p.vertex >= 0) return p;
                const int k = -p.vertex - 2;
                return PolyPoint{p.s, nodeVertex(i + (k == 1 || k == 2), j + (k >= 2))};
            };

            const long long cell = static_cast<long long>(i) * Nv + j;
            const std::size_t first = cellStart[static_cast<std::size_t>(cell)], last = cellStart[static_cast<std::size_t>(cell) + 1];
            if (first == last) {
                if (!insideLoops(loops, {0.5 * (u0 + u1), 0.5 * (v0 + v1)})) continue;
                whole.clear();
                for (const auto& r : rim) whole.push_back(vertexOf(r.second));
                emit(whole);
                continue;
            }
            // Chains: maximal runs of consecutive sides in this cell.
            struct Chain {
                std::vector<PolyPoint> points;
                double in = 0, out = 0;
            };
            std::vector<Chain> chains;
            for (std::size_t side = first; side < last; ++side) {
                const auto [l, k] = cellSides[side];
                const auto& loop = loops[static_cast<std::size_t>(l)];
                const int n = static_cast<int>(loop.size());
                const auto& cells = sideCell[static_cast<std::size_t>(l)];
                const bool closed = std::all_of(cells.begin(), cells.end(), [&](long long c) { return c == cell; });
                if (closed) {
                    if (k != 0) continue;
                    if (hole[static_cast<std::size_t>(l)]) throw Error(faceName(f) + ": a hole lies inside one grid cell");
                    emit(loop);
                    continue;
                }
                if (cells[static_cast<std::size_t>((k + n - 1) % n)] == cell) continue; // not a chain's first side
                Chain ch;
                int m = k;
                ch.points.push_back(loop[static_cast<std::size_t>(m)]);
                while (cells[static_cast<std::size_t>(m)] == cell) {
                    m = (m + 1) % n;
                    ch.points.push_back(loop[static_cast<std::size_t>(m)]);
                }
                ch.in = perimeter(ch.points.front().s);
                ch.out = perimeter(ch.points.back().s);
                if (ch.in < 0 || ch.out < 0)
                    throw Error(faceName(f) + ": the trim polygon leaves grid cell (" + std::to_string(i) + ", " +
                                std::to_string(j) + ") away from its sides");
                chains.push_back(std::move(ch));
            }
            auto ahead = [](double from, double to) { return to >= from ? to - from : to - from + 4; };
            std::vector<char> used(chains.size(), 0);
            for (std::size_t c0 = 0; c0 < chains.size(); ++c0) {
                if (used[c0]) continue;
                std::vector<PolyPoint> poly;
                auto push = [&](const PolyPoint& p) {
                    if (poly.empty() || poly.back().s != p.s) poly.push_back(p);
                };
                std::size_t cur = c0;
                for (std::size_t guard = 0;; ++guard) {
                    if (guard > chains.size()) throw Error(faceName(f) + ": the trim polygon does not close in a grid cell");
                    used[cur] = 1;
                    for (const PolyPoint& p : chains[cur].points) push(p);
                    const double exit = chains[cur].out;
                    // Where chains start at the very point this one leaves (the face pinched to a
                    // point on the cell's side), the turn farthest to the left keeps to this
                    // region: one of those chains, or on along the side.
                    const std::vector<PolyPoint>& pts = chains[cur].points;
                    const Eigen::Vector2d in = pts.back().s - pts[pts.size() - 2].s;
                    auto turn = [&](const Eigen::Vector2d& d) { return std::atan2(in.x() * d.y() - in.y() * d.x(), in.dot(d)); };
                    const double side = std::floor(exit);
                    const Eigen::Vector2d along = side == 0 || side == 4 ? Eigen::Vector2d(1, 0) : side == 1 ? Eigen::Vector2d(0, 1)
                                                : side == 2 ? Eigen::Vector2d(-1, 0) : Eigen::Vector2d(0, -1);
                    double leftmost = turn(along);
                    std::size_t next = chains.size();
                    double best = kInf;
                    for (std::size_t c = 0; c < chains.size(); ++c) {
                        if (used[c] && c != c0) continue;
                        const double d = ahead(exit, chains[c].in);
                        if (d == 0 && chains[c].points.size() > 1) {
                            const double t = turn(chains[c].points[1].s - chains[c].points[0].s);
                            if (t > leftmost) {
                                leftmost = t;
                                best = 0;
                                next = c;
                            }
                        } else if (d > 0 && d < best && !(best == 0)) {
                            best = d;
                            next = c;
                        }
                    }
                    if (best > 0) { // no chain at the point won: the nearest one ahead (a full turn for those at it)
                        best = kInf;
                        for (std::size_t c = 0; c < chains.size(); ++c) {
                            if (used[c] && c != c0) continue;
                            const double d = ahead(exit, chains[c].in) == 0 ? 4 : ahead(exit, chains[c].in);
                            if (d < best) {
                                best = d;
                                next = c;
                            }
                        }
                    }
                    if (next == chains.size()) throw Error(faceName(f) + ": the trim polygon does not close in a grid cell");
                    std::vector<std::pair<double, PolyPoint>> between;
                    for (const auto& r : rim) {
                        const double d = ahead(exit, r.first);
                        if (d > 0 && d < best) between.push_back({d, r.second});
                    }
                    std::sort(between.begin(), between.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
                    for (const auto& b : between) push(vertexOf(b.second));
                    if (next == c0) break;
                    cur = next;
                }
                if (poly.size() > 1 && poly.front().s == poly.back().s) poly.pop_back();
                emit(poly);
            }
        }
    return delta;
}

void dropEdgePockets(Builder& out, const std::vector<std::vector<int>>& sampleVertex,
                     const std::vector<std::vector<std::size_t>>& useFace)
{
    // Each interior sample's edge and index, by mesh vertex (-1: none; an edge's ends are the
    // part's vertices, shared). (Arrays by vertex, not hash maps: this pass was 4% of the mesh.)
    const std::size_t vertices = out.positions.size();
    std::vector<std::pair<int, int>> sampleOf(vertices, {-1, -1});
    bool any = false;
    for (std::size_t e = 0; e < sampleVertex.size(); ++e)
        if (useFace[e].size() == 2 && useFace[e][0] != useFace[e][1])
            for (std::size_t k = 1; k + 1 < sampleVertex[e].size(); ++k) {
                std::pair<int, int>& at = sampleOf[static_cast<std::size_t>(sampleVertex[e][k])];
                if (at.first < 0) at = {static_cast<int>(e), static_cast<int>(k)};
                any = true;
            }
    if (!any) return;
    auto isSample = [&](int v) { return sampleOf[static_cast<std::size_t>(v)].first >= 0; };
    auto key = [](int a, int b) { return std::make_pair(std::min(a, b), std::max(a, b)); };
    auto sidesOf = [&](const std::array<int, 3>& t) {
        return std::array<std::pair<int, int>, 3>{key(t[0], t[1]), key(t[1], t[2]), key(t[2], t[0])};
    };
    // Each mesh edge and its triangles' count, sorted (as a map would be, without its nodes): the
    // edges as packed keys (edgeKey), which sort faster than pairs.
    auto packed = [](const std::pair<int, int>& side) { return edgeKey(side.first, side.second); };
    std::vector<std::uint64_t> edgeKeys;
    edgeKeys.reserve(3 * out.triangles.size());
    for (const auto& t : out.triangles)
        for (const auto& side : sidesOf(t)) edgeKeys.push_back(packed(side));
    std::sort(edgeKeys.begin(), edgeKeys.end());
    std::vector<std::pair<std::pair<int, int>, int>> uses; // uses[u] the edge of key edgeKeys[u]
    std::size_t n = 0;
    for (std::size_t k = 0; k < edgeKeys.size(); ++k) {
        if (n > 0 && edgeKeys[n - 1] == edgeKeys[k]) {
            ++uses.back().second;
            continue;
        }
        edgeKeys[n++] = edgeKeys[k];
        uses.push_back({{static_cast<int>(edgeKeys[k] >> 32), static_cast<int>(edgeKeys[k] & 0xffffffffu)}, 1});
    }
    edgeKeys.resize(n);
    auto usesOf = [&](const std::pair<int, int>& side) -> int& {
        return uses[static_cast<std::size_t>(std::lower_bound(edgeKeys.begin(), edgeKeys.end(), packed(side)) - edgeKeys.begin())].second;
    };
    // The index of vertex v among edge e's samples, -1 when it is none of them.
    auto indexOn = [&](int v, std::size_t e) {
        const std::vector<int>& ids = sampleVertex[e];
        if (v == ids.front()) return 0;
        if (v == ids.back()) return static_cast<int>(ids.size()) - 1;
        const std::pair<int, int>& at = sampleOf[static_cast<std::size_t>(v)];
        return at.first == static_cast<int>(e) ? at.second : -1;
    };
    // The triangles at each sample, in order: byVertex[start[v] .. start[v + 1]).
    std::vector<std::size_t> start(vertices + 1, 0), byVertex;
    for (const auto& tri : out.triangles)
        for (int v : tri)
            if (isSample(v)) ++start[static_cast<std::size_t>(v) + 1];
    for (std::size_t v = 0; v < vertices; ++v) start[v + 1] += start[v];
    byVertex.resize(start.back());
    {
        std::vector<std::size_t> fill(start.begin(), start.end() - 1);
        for (std::size_t t = 0; t < out.triangles.size(); ++t)
            for (int v : out.triangles[t])
                if (isSample(v)) byVertex[fill[static_cast<std::size_t>(v)]++] = t;
    }
    std::vector<char> drop(out.triangles.size(), 0);
    for (std::size_t u = 0; u < uses.size(); ++u) {
        const auto [side, count] = uses[u];
        if (count != 4) continue;
        const int found = isSample(side.first) ? side.first : side.second;
        if (!isSample(found)) continue;
        const std::size_t e = static_cast<std::size_t>(sampleOf[static_cast<std::size_t>(found)].first);
        int i = indexOn(side.first, e), j = indexOn(side.second, e);
        if (i < 0 || j < 0) continue;
        if (i > j) std::swap(i, j);
        if (j - i < 2) continue;
        // Each face's triangles over samples i..j (all found through the run's inner samples).
        std::map<std::size_t, std::vector<std::size_t>> perFace;
        std::vector<std::size_t> seen;
        for (int k = i + 1; k < j; ++k) {
            const std::size_t v = static_cast<std::size_t>(sampleVertex[e][static_cast<std::size_t>(k)]);
            for (std::size_t x = start[v]; x < start[v + 1]; ++x) {
                const std::size_t t = byVertex[x];
                if (drop[t] || std::find(seen.begin(), seen.end(), t) != seen.end()) continue;
                seen.push_back(t);
                const auto& tri = out.triangles[t];
                if (std::all_of(tri.begin(), tri.end(), [&](int w) { const int y = indexOn(w, e); return y >= i && y <= j; }))
                    perFace[static_cast<std::size_t>(out.triangleFace[t])].push_back(t);
            }
        }
        const std::size_t need = static_cast<std::size_t>(j - i - 1);
        if (perFace.size() != 2 || perFace[useFace[e][0]].size() != need || perFace[useFace[e][1]].size() != need) continue;
        std::map<std::pair<int, int>, int> own;
        for (const auto& [f, ts] : perFace)
            for (std::size_t t : ts)
                for (const auto& s : sidesOf(out.triangles[t])) ++own[s];
        if (!std::all_of(own.begin(), own.end(), [&](const auto& o) { const int left = usesOf(o.first) - o.second; return left == 0 || left == 2; }))
            continue;
        for (const auto& [s, c] : own) usesOf(s) -= c;
        for (const auto& [f, ts] : perFace)
            for (std::size_t t : ts) drop[t] = 1;
    }
    out.dropTriangles(drop);
}

} // namespace freeform::part_mesh
