// Certified watertight tessellation of a part (brep/part_mesh.h, docs/cad.md "Tessellation").
//
// Three passes: a grid per face (the NURBS surface's knot lines, each knot span cut evenly as the
// rational patch bound asks); the samples of each edge (the points where any of its pcurves
// crosses a grid line of its face, and as many more as keep the trim polygon within the face's
// deviation target); then each face: its trim polygon from the edge samples, clipped cell by cell
// and cut into triangles by ear clipping.

#include "freeform/brep/part_mesh.h"

#include <algorithm>
#include <cstdint>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <tuple>

#include "freeform/tessellate/tessellate_rational.h"
#include "part_mesh_internal.h"

namespace freeform {
namespace {

using namespace part_mesh;

// The parts of the tolerance (tessellatePart): the grid's aim, on a face trimmed along grid lines
// only, and the least share of the trims' term.
constexpr double kGridAim = 0.86, kIsoGridAim = 0.9, kLeastTrimShare = 0.05;

AxisMap axisMap(const ParameterMap& map, double lo, double hi, double domainStart, double domainEnd, std::size_t f,
                const char* dir)
{
    AxisMap a{map, 0};
    a.invTanQuarter = invTanQuarterOf(map);
    if (map.kind == ParameterMap::Kind::Identity && map.period > 0) {
        const double tol = 1e-9 * map.period;
        double s0 = map(lo);
        if (s0 + (hi - lo) > domainEnd + tol) s0 -= map.period;
        if (s0 < domainStart - tol || s0 + (hi - lo) > domainEnd + tol)
            throw Error(faceName(f) + ": its " + dir + " range straddles the start of its periodic surface's period");
        a.centre = s0 + 0.5 * (hi - lo);
        a.lo = s0;
        a.hi = s0 + (hi - lo);
    }
    return a;
}

/// The grid of face f aimed at `target`; `least` (per axis, per knot
/// span of the face's box) the fewest cells a span gets (alignGrids), in even columns or rows.
FaceGrid makeGrid(const PartFace& face, std::size_t f, double target,
                  const std::array<std::vector<int>, 2>* least = nullptr)
{
    const TrimmedSurface& ts = face.surface;
    const NurbsSurface<double, 3>& nurbs = ts.surface().nurbs;
    const Box<double, 2>& dom = ts.domain();
    FaceGrid g;
    const std::vector<double> ku = nurbs.knotsU().breakpoints(), kv = nurbs.knotsV().breakpoints();
    g.mu = axisMap(ts.surface().mapU, dom.min().x(), dom.max().x(), ku.front(), ku.back(), f, "u");
    g.mv = axisMap(ts.surface().mapV, dom.min().y(), dom.max().y(), kv.front(), kv.back(), f, "v");
    // The box ends a hair from a knot are moved onto it (the trims then snap onto the box): a cell
    // that thin would defeat the cell walk.
    auto onKnot = [](double x, const std::vector<double>& knots, double width) {
        for (double k : knots)
            if (std::abs(k - x) <= 1e-9 * width) return k;
        return x;
    };
    double su0 = g.mu(dom.min().x()), su1 = g.mu(dom.max().x());
    double sv0 = g.mv(dom.min().y()), sv1 = g.mv(dom.max().y());
    if (!(su1 > su0) || !(sv1 > sv0)) throw Error(faceName(f) + ": its parameter box is empty");
    su0 = onKnot(su0, ku, su1 - su0);
    su1 = onKnot(su1, ku, su1 - su0);
    sv0 = onKnot(sv0, kv, sv1 - sv0);
    sv1 = onKnot(sv1, kv, sv1 - sv0);
    const NurbsSurface<double, 3> r = nurbs.restrictedU(su0, su1).restrictedV(sv0, sv1);
    const std::vector<double> bu = r.knotsU().breakpoints(), bv = r.knotsV().breakpoints();
    std::vector<RationalPatch> patches = r.bezierPatches();
    const std::size_t cols = bv.size() - 1;
    // Where the trims run (TrimZones), in NURBS parameters: the box of each trim piece's control
    // points (the parameter maps are monotone), except pieces along a side of the face's box.
    std::vector<Eigen::AlignedBox2d> trimBoxes;
    {
        const double eu = 1e-7 * (su1 - su0), ev = 1e-7 * (sv1 - sv0);
        auto onSide = [](double lo, double hi, double a, double b, double e) {
            return hi - lo <= e && (std::abs(lo - a) <= e || std::abs(hi - b) <= e);
        };
        // (The pieces as the trim curves keep them, homogeneous.)
        for (const TrimLoop& loop : ts.loops())
            for (const TrimCurve& trim : loop.curves)
                for (std::size_t k = 0; k + 1 < trim.curve.nurbs.breakpoints().size(); ++k) {
                    const auto h = trim.curve.nurbs.homogeneousPiece(k);
                    Eigen::AlignedBox2d box;
                    for (Eigen::Index i = 0; i < h.cols(); ++i) box.extend(g.toS(Eigen::Vector2d(h.col(i).head<2>() / h(2, i))));
                    if (onSide(box.min().x(), box.max().x(), su0, su1, eu) || onSide(box.min().y(), box.max().y(), sv0, sv1, ev))
                        continue;
                    trimBoxes.push_back(box);
                }
    }
    auto zonesOf = [&](std::size_t a, std::size_t b) {
        TrimZones z;
        const double u0 = bu[a], du = bu[a + 1] - bu[a], v0 = bv[b], dv = bv[b + 1] - bv[b];
        for (const Eigen::AlignedBox2d& box : trimBoxes) {
            const Eigen::Vector2d lo((box.min().x() - u0) / du, (box.min().y() - v0) / dv);
            const Eigen::Vector2d hi((box.max().x() - u0) / du, (box.max().y() - v0) / dv);
            if (lo.x() < 1 && hi.x() > 0 && lo.y() < 1 && hi.y() > 0) z.boxes.emplace_back(lo, hi);
        }
        return z;
    };
    std::vector<TrimZones> zones;
    for (std::size_t a = 0; a + 1 < bu.size(); ++a)
        for (std::size_t b = 0; b < cols; ++b) zones.push_back(zonesOf(a, b));
    std::vector<int> nu(bu.size() - 1, 1), nv(cols, 1);
    SearchHints hints;
    for (std::size_t a = 0; a + 1 < bu.size(); ++a)
        for (std::size_t b = 0; b < cols; ++b) {
            const std::array<int, 2> n = patchSegments(patches[a * cols + b], target, zones[a * cols + b], &hints);
            nu[a] = std::max(nu[a], n[0]);
            nv[b] = std::max(nv[b], n[1]);
        }
    std::vector<char> forcedU(nu.size(), 0);
    if (least) {
        for (std::size_t a = 0; a < nu.size() && a < (*least)[0].size(); ++a)
            if ((*least)[0][a] > nu[a]) nu[a] = (*least)[0][a], forcedU[a] = 1;
        for (std::size_t b = 0; b < nv.size() && b < (*least)[1].size(); ++b) nv[b] = std::max(nv[b], (*least)[1][b]);
    }
    // A face closed along an axis (a periodic surface one period wide, its seam an edge of the
    // face) gets three cells around at least: with two, both cells' sides join the same points and
    // each row is a flat double sheet (MODERN_Sink_1.brep at 15% of its size: three mesh edges in
    // four triangles); with three, a prism. Closed: the box's two ends are the same curve, its
    // first and last rows of control points (the restricted net is clamped there) equal to 1e-9 of
    // their size, the weights in one ratio. (Three spans or more give three cells anyway.)
    auto closedAlong = [&](int axis) {
        const int n = axis == 0 ? r.countV() : r.countU(), last = (axis == 0 ? r.countU() : r.countV()) - 1;
        auto point = [&](int end, int k) { return axis == 0 ? r.controlPoint(end, k) : r.controlPoint(k, end); };
        auto weight = [&](int end, int k) { return axis == 0 ? r.weight(end, k) : r.weight(k, end); };
        Eigen::AlignedBox3d box;
        for (int k = 0; k < n; ++k) box.extend(point(0, k)).extend(point(last, k));
        const double e = 1e-9 * box.diagonal().norm(), ratio = weight(last, 0) / weight(0, 0);
        for (int k = 0; k < n; ++k)
            if ((point(0, k) - point(last, k)).norm() > e || std::abs(weight(last, k) - ratio * weight(0, k)) > 1e-12 * weight(last, k))
                return false;
        return box.diagonal().norm() > 0;
    };
    auto threeAround = [](std::vector<int>& n, const std::vector<double>& knots, std::vector<char>* forced) {
        while (std::accumulate(n.begin(), n.end(), 0) < 3) {
            std::size_t widest = 0;
            for (std::size_t a = 1; a < n.size(); ++a)
                if ((knots[a + 1] - knots[a]) / n[a] > (knots[widest + 1] - knots[widest]) / n[widest]) widest = a;
            ++n[widest];
            if (forced) (*forced)[widest] = 1;
        }
    };
    const bool closedU = nu.size() < 3 && closedAlong(0);
    if (closedU) threeAround(nu, bu, &forcedU);
    if (std::accumulate(nv.begin(), nv.end(), 0) < 3 && closedAlong(1)) threeAround(nv, bv, nullptr);
    double lu = 0, lv = 0;
    // Per knot span in u: even columns, or (on weighted patches, where a trim holds some cells to
    // their parametric bound) uneven ones when they are fewer.
    std::vector<std::vector<double>> breaks(bu.size() - 1);
    std::vector<double> spanBound(bu.size() - 1, 0);
    auto evenColumns = [&](std::size_t a) {
        breaks[a].clear();
        spanBound[a] = 0;
        for (int i = 0; i <= nu[a]; ++i) breaks[a].push_back(double(i) / nu[a]);
        for (std::size_t b = 0; b < cols; ++b) {
            const RationalPatch& p = patches[a * cols + b];
            spanBound[a] = std::max(spanBound[a], gridBound(p, nu[a], nv[b], weighted(p), zones[a * cols + b]));
        }
    };
    for (std::size_t a = 0; a + 1 < bu.size(); ++a) {
        // (Only where a trim runs through the span, and for at most 2,048 even cells: the search
        // bounds each column's cells a few dozen times.)
        std::vector<const RationalPatch*> row;
        std::vector<const TrimZones*> rowZones;
        bool curved = true, trimmed = false;
        long cells = 0;
        for (std::size_t b = 0; b < cols; ++b) {
            row.push_back(&patches[a * cols + b]);
            rowZones.push_back(&zones[a * cols + b]);
            curved = curved && weighted(patches[a * cols + b]);
            trimmed = trimmed || !zones[a * cols + b].boxes.empty();
            cells += static_cast<long>(nu[a]) * nv[b];
        }
        if (curved && trimmed && nu[a] > 1 && cells <= 2048 && !forcedU[a])
            breaks[a] = unevenColumns(row, nv, rowZones, target, nu[a], spanBound[a]);
        if (breaks[a].empty()) evenColumns(a);
        for (std::size_t b = 0; b < cols; ++b) {
            const auto [su, sv] = patchSlopes(patches[a * cols + b]);
            lu = std::max(lu, su / (bu[a + 1] - bu[a]));
            lv = std::max(lv, sv / (bv[b + 1] - bv[b]));
        }
    }
    // (Uneven columns may be fewer than three around a closed face: then even ones.)
    std::size_t around = 0;
    for (const std::vector<double>& b : breaks) around += b.size() - 1;
    if (around < 3 && closedU)
        for (std::size_t a = 0; a + 1 < bu.size(); ++a)
            if (static_cast<int>(breaks[a].size()) - 1 != nu[a]) evenColumns(a);
    for (const double b : spanBound) g.bound = std::max(g.bound, b);
    g.slopeU = lu;
    g.slopeV = lv;
    g.bu = bu;
    g.bv = bv;
    g.patches = std::move(patches);
    for (std::size_t a = 0; a + 1 < bu.size(); ++a)
        for (std::size_t i = 0; i + 1 < breaks[a].size(); ++i) g.gu.push_back(bu[a] + (bu[a + 1] - bu[a]) * breaks[a][i]);
    g.gu.push_back(bu.back());
    for (std::size_t b = 0; b < cols; ++b)
        for (int j = 0; j < nv[b]; ++j) g.gv.push_back(bv[b] + (bv[b + 1] - bv[b]) * j / nv[b]);
    g.gv.push_back(bv.back());
    g.snapU = 1e-7 * (g.gu.back() - g.gu.front());
    g.snapV = 1e-7 * (g.gv.back() - g.gv.front());
    // Knots closer than twice the snapping distance (a B-spline's knot doubled to 4e-8 of its
    // span) would leave a row of cells too thin to snap into: a trim along it zigzags between
    // the two lines. The inner one goes; the cell across it then has corners up to `gap` from the
    // patch's own, which moves its triangles by at most L gap and their parameters by gap: the
    // bound grows by 2 L gap.
    auto thin = [](std::vector<double>& l, double snap) {
        double gap = 0;
        std::vector<double> kept{l.front()};
        for (std::size_t k = 1; k < l.size(); ++k) {
            if (l[k] - kept.back() >= 2 * snap) {
                kept.push_back(l[k]);
                continue;
            }
            gap = std::max(gap, l[k] - kept.back());
            if (k + 1 == l.size() && kept.size() > 1) kept.back() = l[k]; // the box's end stays
        }
        l = std::move(kept);
        return gap;
    };
    const double gapU = thin(g.gu, g.snapU), gapV = thin(g.gv, g.snapV);
    if (gapU > 0 || gapV > 0) g.bound += 2 * std::hypot(lu * gapU, lv * gapV);
    // A hole inside one cell would be a hole the cell walk cannot join to its cell: cut it. (The
    // outer loop, the one of the largest box, may lie in one cell.)
    // (The parameter maps are monotone: a box's corners map onto the box of its points' images.)
    std::vector<Box<double, 2>> boxes;
    for (const std::vector<Eigen::Vector2d>& poly : ts.polygons()) {
        Box<double, 2> file, bb;
        for (const Eigen::Vector2d& p : poly) file.extend(p);
        if (!file.isEmpty()) bb.extend(g.toS(file.min())).extend(g.toS(file.max()));
        boxes.push_back(bb);
    }
    std::size_t outer = 0;
    for (std::size_t l = 0; l < boxes.size(); ++l)
        if (boxes[l].volume() > boxes[outer].volume()) outer = l;
    for (std::size_t l = 0; l < boxes.size(); ++l) {
        const Box<double, 2>& bb = boxes[l];
        if (l == outer || bb.isEmpty() || !(bb.max().x() > bb.min().x())) continue;
        if (!lineBetween(g.gu, bb.min().x(), bb.max().x()) && !lineBetween(g.gv, bb.min().y(), bb.max().y())) {
            g.gu.push_back(0.5 * (bb.min().x() + bb.max().x()));
            std::sort(g.gu.begin(), g.gu.end());
        }
    }
    return g;
}

/// Per knot span of one axis of the grid: its cell count where its lines are even, else -1.
std::vector<int> evenCounts(const FaceGrid& g, int axis)
{
    const std::vector<double>& b = axis == 0 ? g.bu : g.bv;
    const std::vector<double>& l = axis == 0 ? g.gu : g.gv;
    std::vector<int> out;
    for (std::size_t s = 0; s + 1 < b.size(); ++s) {
        const double width = b[s + 1] - b[s], e = 1e-12 * width;
        const auto lo = std::lower_bound(l.begin(), l.end(), b[s] - e), hi = std::upper_bound(l.begin(), l.end(), b[s + 1] + e);
        const int n = static_cast<int>(hi - lo) - 1;
        bool even = n >= 1 && std::abs(*lo - b[s]) <= e && std::abs(*(hi - 1) - b[s + 1]) <= e;
        for (int k = 0; even && k <= n; ++k) even = std::abs(*(lo + k) - (b[s] + width * k / n)) <= e;
        out.push_back(even ? n : -1);
    }
    return out;
}

/// The axis along which a trim runs as an iso line of the other (its control points' other
/// coordinate all equal), or -1.
int isoAxis(const TrimCurve& c)
{
    const auto& p = c.curve.nurbs.controlPoints();
    for (int along = 0; along < 2; ++along) {
        const int other = 1 - along;
        bool iso = true;
        for (Eigen::Index i = 1; iso && i < p.cols(); ++i) iso = std::abs(p(other, i) - p(other, 0)) <= 1e-12 * (1 + std::abs(p(other, 0)));
        if (iso && p.row(along).maxCoeff() > p.row(along).minCoeff()) return along;
    }
    return -1;
}

/// Grid lines that meet on the edges two faces share (docs/cad.md, "Tessellation", step 1): an
/// edge's samples are every crossing of either face's grid lines, so where both faces cross it
/// with lines of their own (a cylinder and the torus it runs into, along their common circle)
/// it gets both sets, and both faces' polygons carry them. Where the edge is an iso line of both
/// faces, running along the same parameter map over the same knot spans, and the spans' lines
/// are even, equal counts put the lines at the same points. Each such span takes the larger
/// count on both faces where the cells that costs (the difference times the other face's rows)
/// are fewer than the smaller count, about the edge samples saved. Returns per face the least
/// counts (empty where nothing changes), found over up to four rounds (a cylinder between two
/// tori takes the larger of both).
std::vector<std::array<std::vector<int>, 2>> alignGrids(const Part& part, const std::vector<FaceGrid>& grids)
{
    const std::size_t faces = part.faces.size();
    std::vector<std::array<std::vector<int>, 2>> own(faces), least(faces);
    for (std::size_t f = 0; f < faces; ++f) own[f] = {evenCounts(grids[f], 0), evenCounts(grids[f], 1)};
    std::vector<std::array<std::vector<int>, 2>> counts = own;
    // The uses of each edge that run along an axis of their face.
    struct Use {
        std::size_t face;
        const TrimCurve* trim;
        int axis;
    };
    std::vector<std::vector<Use>> uses(part.edges.size());
    for (std::size_t f = 0; f < faces; ++f)
        for (const TrimLoop& loop : part.faces[f].surface.loops())
            for (const TrimCurve& c : loop.curves) {
                if (c.edge < 0 || static_cast<std::size_t>(c.edge) >= part.edges.size()) continue;
                uses[static_cast<std::size_t>(c.edge)].push_back({f, &c, isoAxis(c)});
            }
    struct Pair {
        std::size_t fa, fb;
        int axisA, axisB;
        std::vector<std::pair<std::size_t, std::size_t>> spans; // matching knot spans (a's, b's)
    };
    std::vector<Pair> pairs;
    for (std::size_t e = 0; e < part.edges.size(); ++e) {
        const std::vector<Use>& u = uses[e];
        if (u.size() != 2 || u[0].face == u[1].face || u[0].axis < 0 || u[1].axis < 0) continue;
        const FaceGrid& ga = grids[u[0].face];
        const FaceGrid& gb = grids[u[1].face];
        const AxisMap& ma = u[0].axis == 0 ? ga.mu : ga.mv;
        const AxisMap& mb = u[1].axis == 0 ? gb.mu : gb.mv;
        // (The same map up to rounding: a cylinder's and a torus's arcs start at 0 and at -8.9e-16.)
        const double scale = 1e-12 * (1 + std::abs(ma.map.start) + std::abs(ma.map.span) * ma.map.spans + ma.map.period);
        if (ma.map.kind != mb.map.kind || ma.map.spans != mb.map.spans || std::abs(ma.map.start - mb.map.start) > scale ||
            std::abs(ma.map.span - mb.map.span) > scale || std::abs(ma.map.period - mb.map.period) > scale ||
            std::abs(ma.centre - mb.centre) > scale)
            continue;
        // The same parameter along the edge at its ends and middle (the file's, then the NURBS').
        const PartEdge& edge = part.edges[e];
        bool same = true;
        double lo = kInf, hi = -kInf;
        for (const double t : {edge.first, 0.5 * (edge.first + edge.last), edge.last}) {
            auto param = [&](const Use& use) {
                const MappedCurve<2>& c = use.trim->curve;
                return c.point(trimParameterOf(c, edge.first, edge.last, t))[use.axis];
            };
            const double a = ma(param(u[0])), b = mb(param(u[1]));
            same = same && std::abs(a - b) <= 1e-9 * (1 + std::abs(a));
            lo = std::min(lo, a);
            hi = std::max(hi, a);
        }
        if (!same || !(hi > lo)) continue;
        const std::vector<double>& ba = u[0].axis == 0 ? ga.bu : ga.bv;
        const std::vector<double>& bb = u[1].axis == 0 ? gb.bu : gb.bv;
        Pair p{u[0].face, u[1].face, u[0].axis, u[1].axis, {}};
        for (std::size_t i = 0; i + 1 < ba.size(); ++i) {
            if (ba[i + 1] <= lo || ba[i] >= hi) continue;
            const double e = 1e-12 * (ba[i + 1] - ba[i]);
            std::size_t j = 0;
            while (j + 1 < bb.size() && !(std::abs(bb[j] - ba[i]) <= e && std::abs(bb[j + 1] - ba[i + 1]) <= e)) ++j;
            if (j + 1 < bb.size()) p.spans.emplace_back(i, j);
        }
        if (!p.spans.empty()) pairs.push_back(std::move(p));
    }
    if (pairs.empty()) return least;
    auto rows = [&](std::size_t f, int axis) {
        const std::vector<double>& l = axis == 0 ? grids[f].gv : grids[f].gu;
        return static_cast<int>(l.size()) - 1;
    };
    for (int round = 0; round < 4; ++round) {
        bool changed = false;
        for (const Pair& p : pairs)
            for (const auto& [i, j] : p.spans) {
                int& ca = counts[p.fa][static_cast<std::size_t>(p.axisA)][i];
                int& cb = counts[p.fb][static_cast<std::size_t>(p.axisB)][j];
                if (ca < 1 || cb < 1 || ca == cb) continue;
                const bool raiseA = ca < cb;
                const int low = std::min(ca, cb), high = std::max(ca, cb);
                if ((high - low) * (raiseA ? rows(p.fa, p.axisA) : rows(p.fb, p.axisB)) >= low) continue;
                (raiseA ? ca : cb) = high;
                changed = true;
            }
        if (!changed) break;
    }
    for (std::size_t f = 0; f < faces; ++f)
        if (own[f] != counts[f]) least[f] = counts[f];
    return least;
}

} // namespace

/// One meshing of the part with the grid of face f aimed at cellTarget[f]; cellBound receives the
/// grid bound e of each face.
static PartMesh meshPart(const Part& part, const PartMeshOptions& options,
                         const std::vector<double>& cellTarget, const std::vector<double>& gapReserve,
                         std::vector<double>& cellBound, std::vector<double>& faceGap)
{
    const double tol = options.tolerance;
    std::vector<FaceGrid> grids;
    grids.reserve(part.faces.size());
    long long estimate = 0;
    for (std::size_t f = 0; f < part.faces.size(); ++f) grids.push_back(makeGrid(part.faces[f], f, cellTarget[f]));
    const std::vector<std::array<std::vector<int>, 2>> least = alignGrids(part, grids);
    for (std::size_t f = 0; f < part.faces.size(); ++f) {
        if (!least[f][0].empty()) grids[f] = makeGrid(part.faces[f], f, cellTarget[f], &least[f]);
        estimate += 2LL * static_cast<long long>(grids[f].gu.size() - 1) * static_cast<long long>(grids[f].gv.size() - 1);
    }
    if (options.maxTriangles > 0 && estimate > options.maxTriangles)
        throw Error("tessellatePart: about " + std::to_string(estimate) + " triangles exceed the limit of " +
                    std::to_string(options.maxTriangles));

    // Edge samples, and the largest trim deviation of each face.
    std::vector<std::vector<EdgeUse>> uses(part.edges.size());
    std::vector<std::vector<std::size_t>> useFace(part.edges.size());
    for (std::size_t f = 0; f < part.faces.size(); ++f) {
        for (const TrimLoop& loop : part.faces[f].surface.loops())
            for (const TrimCurve& c : loop.curves) {
                if (c.edge < 0 || static_cast<std::size_t>(c.edge) >= part.edges.size())
                    throw Error(faceName(f) + ": a trim curve names no edge of the part");
                const PartEdge& e = part.edges[static_cast<std::size_t>(c.edge)];
                uses[static_cast<std::size_t>(c.edge)].push_back(
                    {&c, &grids[f], 0, e.first, e.last, invTanQuarterOf(c.curve.map)});
                useFace[static_cast<std::size_t>(c.edge)].push_back(f);
            }
    }
    // The trims' share of each face's bound: what its grid and its vertex gaps leave, at least
    // kLeastTrimShare of the tolerance. The gaps (delta, measured at the mesh vertices once they are
    // known) are guessed from each trim's ends and the middles of its first four and last four
    // Bézier pieces and of every eighth between (a file whose pcurve and 3D curve do not share
    // their parameter near an end: screw.step's largest gaps lie within its first pieces), and
    // `gapReserve` keeps at least what they were.
    std::vector<double> gapGuess(part.faces.size(), 0);
    for (std::size_t e = 0; e < part.edges.size(); ++e) {
        const PartEdge& edge = part.edges[e];
        for (std::size_t u = 0; u < uses[e].size(); ++u) {
            const std::size_t f = useFace[e][u];
            const EdgeUse& use = uses[e][u];
            const NurbsSurface<double, 3>& S = part.faces[f].surface.surface().nurbs;
            auto gapAt = [&](double t, int v) {
                Eigen::Vector3d point;
                if (v >= 0) point = part.vertices[static_cast<std::size_t>(v)].point;
                else if (edge.curve && !edge.degenerate) point = edge.curve->point(t);
                else return;
                const Eigen::Vector2d st = use.at(t);
                gapGuess[f] = std::max(gapGuess[f], (point - S.evaluate(st.x(), st.y())).norm());
            };
            gapAt(edge.first, edge.start);
            gapAt(edge.last, edge.end);
            // The pieces' middles in the edge's parameter (the trim's range mapped onto the edge's).
            const MappedCurve<2>& c = use.trim->curve;
            const std::vector<double>& b = c.nurbs.breakpoints();
            const std::size_t pieces = b.size() - 1, step = std::max<std::size_t>(1, pieces / 8);
            for (std::size_t k = 0; k < pieces; ++k) {
                if (k >= 4 && k + 4 < pieces && k % step != 0) continue;
                const double t = use.edgeParameter(c.map.inverse(0.5 * (b[k] + b[k + 1])));
                if (t > std::min(edge.first, edge.last) && t < std::max(edge.first, edge.last)) gapAt(t, -1);
            }
        }
    }
    for (std::size_t e = 0; e < part.edges.size(); ++e)
        for (std::size_t u = 0; u < uses[e].size(); ++u) {
            const std::size_t f = useFace[e][u];
            const double gaps = std::max(gapReserve[f], 1.2 * gapGuess[f] + 1e-4 * tol);
            uses[e][u].deviationTarget = std::max(tol - grids[f].bound - gaps, kLeastTrimShare * tol);
        }
    std::vector<std::vector<double>> samples(part.edges.size()), worst(part.edges.size());
    for (std::size_t e = 0; e < part.edges.size(); ++e)
        if (!uses[e].empty()) samples[e] = sampleEdge(uses[e], part.edges[e].first, part.edges[e].last, options.maxEdgeSamples, worst[e]);
    // A face thinner than its trims' share (Motor-c.brep's ring 0.05 mm wide at 0.5 mm) gets a
    // polygon that crosses itself, and its cells' triangles may then cover what lies outside
    // it, far from the face: the edges of such a face get a quarter of their target, up to six
    // times, until its polygon is simple (docs/cad.md, "Tessellation").
    // The samples in each use's face parameters (at()), per edge and use, as the polygons take them.
    std::vector<std::vector<std::vector<Eigen::Vector2d>>> sampleAt(part.edges.size());
    auto place = [&](std::size_t e) {
        sampleAt[e].resize(uses[e].size());
        for (std::size_t u = 0; u < uses[e].size(); ++u) {
            std::vector<Eigen::Vector2d>& at = sampleAt[e][u];
            at.resize(samples[e].size());
            for (std::size_t k = 0; k < at.size(); ++k) at[k] = uses[e][u].at(samples[e][k]);
        }
    };
    for (std::size_t e = 0; e < part.edges.size(); ++e) place(e);
    auto useOf = [&](const TrimCurve& c) {
        const std::size_t e = static_cast<std::size_t>(c.edge);
        std::size_t u = 0;
        while (uses[e][u].trim != &c) ++u;
        return u;
    };
    std::vector<char> check(part.faces.size(), 1); // faces whose samples changed since their last check
    std::vector<std::vector<Eigen::Vector2d>> loops; // (reused from face to face)
    std::vector<std::vector<int>> edgeOf;
    for (int round = 0; round < 6; ++round) {
        std::vector<char> refine(part.edges.size(), 0);
        for (std::size_t f = 0; f < part.faces.size(); ++f) {
            if (!check[f]) continue;
            check[f] = 0;
            const std::vector<TrimLoop>& faceLoops = part.faces[f].surface.loops();
            loops.resize(faceLoops.size());
            edgeOf.resize(faceLoops.size());
            for (std::size_t l = 0; l < faceLoops.size(); ++l) {
                loops[l].clear();
                edgeOf[l].clear();
                for (const TrimCurve& c : faceLoops[l].curves) {
                    const std::vector<Eigen::Vector2d>& at = sampleAt[static_cast<std::size_t>(c.edge)][useOf(c)];
                    if (c.reversed) loops[l].insert(loops[l].end(), at.rbegin(), at.rend());
                    else loops[l].insert(loops[l].end(), at.begin(), at.end());
                    edgeOf[l].resize(loops[l].size(), c.edge);
                }
            }
            const std::vector<int> crossing = crossingEdges(grids[f], loops, edgeOf);
            if (crossing.empty()) continue;
            for (const int e : crossing) refine[static_cast<std::size_t>(e)] = 1;
        }
        if (std::find(refine.begin(), refine.end(), 1) == refine.end()) break;
        for (std::size_t e = 0; e < part.edges.size(); ++e) {
            if (!refine[e]) continue;
            for (EdgeUse& u : uses[e]) u.deviationTarget *= 0.25;
            samples[e] = sampleEdge(uses[e], part.edges[e].first, part.edges[e].last, options.maxEdgeSamples, worst[e]);
            place(e);
            for (const std::size_t f : useFace[e]) check[f] = 1;
        }
    }
    std::vector<double> faceDeviation(part.faces.size(), 0);
    for (std::size_t e = 0; e < part.edges.size(); ++e)
        for (std::size_t u = 0; u < worst[e].size(); ++u)
            faceDeviation[useFace[e][u]] = std::max(faceDeviation[useFace[e][u]], worst[e][u]);

    // The mesh vertices of the part's vertices and of every edge sample.
    Builder out;
    std::vector<int> vertexId(part.vertices.size(), -1);
    auto partVertex = [&](int v, const Eigen::Vector3d& fallback) {
        if (v < 0) return out.add(fallback);
        int& id = vertexId[static_cast<std::size_t>(v)];
        if (id < 0) id = out.add(part.vertices[static_cast<std::size_t>(v)].point);
        return id;
    };
    std::vector<std::vector<int>> sampleVertex(part.edges.size());
    for (std::size_t e = 0; e < part.edges.size(); ++e) {
        if (samples[e].empty()) continue;
        const PartEdge& edge = part.edges[e];
        const EdgeUse& use = uses[e].front();
        auto position = [&](double t) -> Eigen::Vector3d {
            if (edge.curve && !edge.degenerate) return edge.curve->point(t);
            const Eigen::Vector2d s = use.at(t);
            return part.faces[useFace[e].front()].surface.surface().nurbs.evaluate(s.x(), s.y());
        };
        std::vector<int>& ids = sampleVertex[e];
        const std::size_t n = samples[e].size();
        ids.resize(n);
        ids.front() = partVertex(edge.start, position(samples[e].front()));
        ids.back() = edge.start == edge.end && edge.start >= 0 ? ids.front() : partVertex(edge.end, position(samples[e].back()));
        for (std::size_t k = 1; k + 1 < n; ++k) ids[k] = edge.degenerate ? ids.front() : out.add(position(samples[e][k]));
    }

    PartMesh result;
    PartMeshReport& report = result.report;
    report.faceBound.assign(part.faces.size(), 0);
    faceGap.assign(part.faces.size(), 0);
    for (std::size_t f = 0; f < part.faces.size(); ++f) {
        const PartFace& face = part.faces[f];
        // Two points of one vertex (where trims meet) this near are one polygon point.
        const FaceGrid& g = grids[f];
        auto near = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
            return std::abs(a.x() - b.x()) <= g.snapU && std::abs(a.y() - b.y()) <= g.snapV;
        };
        std::vector<std::vector<PolyPoint>> loops;
        for (const TrimLoop& loop : face.surface.loops()) {
            std::vector<PolyPoint> pts;
            for (const TrimCurve& c : loop.curves) {
                const std::size_t e = static_cast<std::size_t>(c.edge);
                const std::vector<Eigen::Vector2d>& at = sampleAt[e][useOf(c)];
                const std::size_t n = samples[e].size();
                for (std::size_t k = 0; k < n; ++k) {
                    const std::size_t idx = c.reversed ? n - 1 - k : k;
                    const PolyPoint p{at[idx], sampleVertex[e][idx]};
                    if (!pts.empty() && pts.back().vertex == p.vertex) {
                        if (near(pts.back().s, p.s)) continue;
                        joinAcrossLines(grids[f], pts.back(), p, pts);
                    }
                    if (pts.empty() || pts.back().s != p.s || pts.back().vertex != p.vertex) pts.push_back(p);
                }
            }
            while (pts.size() > 1 && pts.front().vertex == pts.back().vertex && near(pts.front().s, pts.back().s)) pts.pop_back();
            if (pts.size() > 1 && pts.front().vertex == pts.back().vertex) joinAcrossLines(grids[f], pts.back(), pts.front(), pts);
            loops.push_back(std::move(pts));
        }
        const double delta = meshFace(face, f, grids[f], std::move(loops), out);
        const double trim = faceDeviation[f];
        report.faceBound[f] = grids[f].bound + delta + trim;
        report.errorBound = std::max(report.errorBound, report.faceBound[f]);
        report.maxVertexGap = std::max(report.maxVertexGap, delta);
        faceGap[f] = delta;
        report.maxTrimDeviation = std::max(report.maxTrimDeviation, trim);
        ++report.faces;
    }
    report.certified = report.errorBound <= tol;
    cellBound.resize(part.faces.size());
    for (std::size_t f = 0; f < part.faces.size(); ++f) cellBound[f] = grids[f].bound;

    // Two faces that cut an ear from the same three samples of their common edge cover the sliver
    // between the edge's polygon and its chord twice, and a face pinched to a point can give a
    // triangle and its reverse: such a pair of one triangle goes (what is left meets along the
    // chord; leaving triangles out never moves the mesh from the part).
    {
        // The triangles grouped by their corners (sorted), each group in the triangles' order: its
        // first triangle pairs with the next that is its reverse, and so on.
        std::vector<std::pair<std::array<int, 3>, std::size_t>> byCorners;
        byCorners.reserve(out.triangles.size());
        for (std::size_t t = 0; t < out.triangles.size(); ++t) {
            std::array<int, 3> key = out.triangles[t];
            std::sort(key.begin(), key.end());
            byCorners.push_back({key, t});
        }
        std::sort(byCorners.begin(), byCorners.end());
        // The reverse of triangle t runs its corners the other way: (a, c, b) after (a, b, c).
        auto reversed = [&](const std::array<int, 3>& x, const std::array<int, 3>& y) {
            for (int r = 0; r < 3; ++r)
                if (x[0] == y[static_cast<std::size_t>(r)] && x[1] == y[static_cast<std::size_t>((r + 2) % 3)]) return true;
            return false;
        };
        std::vector<char> drop(out.triangles.size(), 0);
        for (std::size_t k = 0; k < byCorners.size();) {
            std::size_t end = k;
            while (end < byCorners.size() && byCorners[end].first == byCorners[k].first) ++end;
            std::size_t first = out.triangles.size(); // the group's unpaired first triangle, if any
            for (std::size_t g = k; g < end; ++g) {
                const std::size_t t = byCorners[g].second;
                if (first == out.triangles.size()) {
                    first = t;
                } else if (reversed(out.triangles[first], out.triangles[t])) {
                    drop[first] = drop[t] = 1;
                    first = out.triangles.size();
                }
            }
            k = end;
        }
        out.dropTriangles(drop);
    }

    // The same on more samples: a run of an edge's samples that both faces close against its chord.
    dropEdgePockets(out, sampleVertex, useFace);

    // Watertightness: every mesh edge of a closed shell in exactly two of its triangles.
    std::vector<int> shellOf(part.faces.size(), -1);
    for (std::size_t s = 0; s < part.shells.size(); ++s) {
        std::map<int, int> edgeUses;
        for (int f : part.shells[s].faces)
            for (const TrimLoop& loop : part.faces[static_cast<std::size_t>(f)].surface.loops())
                for (const TrimCurve& c : loop.curves)
                    if (!part.edges[static_cast<std::size_t>(c.edge)].degenerate) ++edgeUses[c.edge];
        const bool closed = !edgeUses.empty() && std::all_of(edgeUses.begin(), edgeUses.end(), [](const auto& u) { return u.second == 2; });
        if (!closed) continue;
        ++report.closedShells;
        for (int f : part.shells[s].faces) shellOf[static_cast<std::size_t>(f)] = static_cast<int>(s);
    }
    // Per closed shell, its triangles' sides as packed keys (lower vertex, higher vertex), sorted.
    std::vector<std::vector<std::uint64_t>> meshEdges(part.shells.size());
    for (std::size_t t = 0; t < out.triangles.size(); ++t) {
        const int s = shellOf[static_cast<std::size_t>(out.triangleFace[t])];
        if (s < 0) continue;
        for (int k = 0; k < 3; ++k) {
            const int a = out.triangles[t][static_cast<std::size_t>(k)], b = out.triangles[t][static_cast<std::size_t>((k + 1) % 3)];
            meshEdges[static_cast<std::size_t>(s)].push_back(edgeKey(a, b));
        }
    }
    for (std::vector<std::uint64_t>& sides : meshEdges) {
        std::sort(sides.begin(), sides.end());
        for (std::size_t k = 0; k < sides.size();) {
            std::size_t end = k;
            while (end < sides.size() && sides[end] == sides[k]) ++end;
            report.openMeshEdges += end - k != 2 ? 1 : 0;
            k = end;
        }
    }
    report.watertight = report.closedShells > 0 && report.openMeshEdges == 0;

    // The mesh, without the vertices no triangle uses.
    std::vector<int> remap(out.positions.size(), -1);
    int used = 0;
    for (const auto& t : out.triangles)
        for (int v : t)
            if (remap[static_cast<std::size_t>(v)] < 0) remap[static_cast<std::size_t>(v)] = used++;
    PolygonMesh& mesh = result.mesh;
    mesh.positions.resize(3, used);
    for (std::size_t v = 0; v < out.positions.size(); ++v)
        if (remap[v] >= 0) mesh.positions.col(remap[v]) = out.positions[v];
    mesh.faceVertices.reserve(3 * out.triangles.size());
    for (const auto& t : out.triangles) mesh.addFace({remap[static_cast<std::size_t>(t[0])], remap[static_cast<std::size_t>(t[1])],
                                                      remap[static_cast<std::size_t>(t[2])]});
    result.triangleFace = std::move(out.triangleFace);
    return result;
}

/// Whether every trim of the surface is a line of constant u or constant v in its parameters (its
/// pcurve's control points share one coordinate, to 1e-9 of the face's box: files write such
/// lines as B-splines with noise in the last bits): the parameter maps keep it one, so its
/// polygon lies on it and the trims leave the grid nearly the whole tolerance. (Only the grid's
/// first aim depends on it; the deviation is measured all the same.)
static bool isoTrimmed(const TrimmedSurface& surface)
{
    const Eigen::Vector2d size = surface.domain().diagonal();
    for (const TrimLoop& loop : surface.loops())
        for (const TrimCurve& c : loop.curves) {
            const NurbsCurve<double, 2>& n = c.curve.nurbs;
            Eigen::AlignedBox2d box;
            for (int i = 0; i < n.controlCount(); ++i) box.extend(n.controlPoint(i));
            const Eigen::Vector2d spread = box.diagonal();
            if (!(spread.x() <= 1e-9 * size.x()) && !(spread.y() <= 1e-9 * size.y())) return false;
        }
    return true;
}

PartMesh tessellatePart(const Part& part, const PartMeshOptions& options)
{
    if (!(options.tolerance > 0) || !std::isfinite(options.tolerance))
        throw Error("tessellatePart: the tolerance must be positive and finite");
    const double tol = options.tolerance;
    // The grid aims at 86/100 of the tolerance, leaving the rest to the trims' deviation and the
    // gaps (delta); a face whose trims all run along grid lines (a cylinder's or a torus's
    // circles: the polygon is on them) has no deviation, and its grid aims at 9/10 of it. A face
    // over the tolerance is meshed again with more room for the gaps it had, and where they and
    // the deviation leave less than its grid's aim, with the grid aimed at what they leave: up
    // to three times, for gaps up to 9/10 of the tolerance (bearing.iges, gaps of 0.002 mm, is
    // certified at 0.0032 mm on the third).
    // Measured (grid aim, least trim share: screw.step at 0.1 mm, linkrods.step at 0.01 mm, the
    // 26 closed .brep samples at 1e-3 of their size, with the gaps' reserve of 1.5x the guess):
    // 0.7, 0.25: 1,008, 4,526, 103,924 triangles; 0.8, 0.1: 974, 4,278; 0.85, 0.05: 952, 4,270,
    // 88,784; 0.93, 0.05: 1,020, 4,408 (the trims take more than the cells save). With 1.2x
    // the guess and a share of 0.05: 0.8: 970 (meshed twice), 4,272; 0.82: 948, 4,272; 0.84:
    // 946, 4,194; 0.86: 924, 4,204, 88,988; 0.88: 926, 4,198, 89,034; 0.9: 944, 89,168.
    // Half the tolerance, with half of the rest kept for the gaps, gave 1,232 and 5,088. With
    // the trims' sides cut into as many parts as their term asks for (2026-12-07; also hammer.iges
    // at 50 mm): 0.82: 932, 4,250, 1,012, 89,392; 0.84: 934, 4,170, 1,030, 88,818; 0.86: 912,
    // 4,200, 1,030, 88,896; 0.88: 918, 4,190, 1,030, 89,046; 0.9: 932, 4,246, 1,030, 89,122.
    std::vector<double> target(part.faces.size(), kGridAim * tol), reserve(part.faces.size(), 0), bound, gap;
    for (std::size_t f = 0; f < part.faces.size(); ++f)
        if (isoTrimmed(part.faces[f].surface)) target[f] = kIsoGridAim * tol;
    PartMesh mesh = meshPart(part, options, target, reserve, bound, gap);
    for (int pass = 0; pass < 3 && !mesh.report.certified; ++pass) {
        bool again = false;
        for (std::size_t f = 0; f < part.faces.size(); ++f) {
            if (!(mesh.report.faceBound[f] > tol)) continue;
            const double rest = mesh.report.faceBound[f] - bound[f]; // delta + trim deviation
            if (gap[f] > reserve[f] && gap[f] < 0.9 * tol) {
                reserve[f] = 1.25 * gap[f];
                again = true;
            }
            if (bound[f] + reserve[f] > (1 - kLeastTrimShare) * tol && rest < 0.9 * tol) {
                target[f] = std::min(target[f], 0.95 * (tol - rest));
                again = true;
            }
        }
        if (!again) break;
        mesh = meshPart(part, options, target, reserve, bound, gap);
    }
    return mesh;
}

} // namespace freeform
