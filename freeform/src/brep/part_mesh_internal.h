#pragma once
// Internals of the part tessellation (brep/part_mesh.h), shared by part_mesh.cpp (grids, edge
// samples, the whole part), part_mesh_bounds.cpp (the grids' certified bounds and their search)
// and part_mesh_cells.cpp (one face's trim polygon cut by its grid cells).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "freeform/brep/part.h"
#include "freeform/tessellate/tessellate_rational.h"

namespace freeform::part_mesh {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// A mesh edge between vertices a and b (either order) as one key that sorts fast: the lower
/// vertex in the high 32 bits.
inline std::uint64_t edgeKey(int a, int b)
{
    return static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(a, b))) << 32 | static_cast<std::uint32_t>(std::max(a, b));
}

/// Face f as errors name it: counted from 1, as Open CASCADE and the reader, the writer and the
/// deformation count them (docs/cad.md, "The model").
inline std::string faceName(std::size_t f) { return "face " + std::to_string(f + 1); }

/// Whether a line of the sorted `lines` lies strictly between lo and hi.
inline bool lineBetween(const std::vector<double>& lines, double lo, double hi)
{
    const auto it = std::upper_bound(lines.begin(), lines.end(), lo);
    return it != lines.end() && *it < hi;
}

/// 1 / tan(span / 4) of a half-angle map (0 for the other kinds), for halfAngleOf.
inline double invTanQuarterOf(const ParameterMap& map)
{
    return map.kind == ParameterMap::Kind::HalfAngle ? 1 / std::tan(0.25 * map.span) : 0.0;
}

/// A half-angle map's NURBS parameter of the angle u: ParameterMap's own, with its constant
/// tangent (invTanQuarterOf) kept. The edge samples map every trim point they evaluate, through
/// the trim's map and the face's, and a tenth of screw.step's time went to tan.
inline double halfAngleOf(const ParameterMap& map, double invTanQuarter, double u)
{
    const int k = std::clamp(static_cast<int>(std::floor((u - map.start) / map.span)), 0, map.spans - 1);
    const double mid = map.start + (k + 0.5) * map.span;
    return map.start + (k + 0.5 * (1 + std::tan(0.5 * (u - mid)) * invTanQuarter)) * map.span;
}

/// A face's file parameter to its NURBS parameter in one direction; a periodic direction is
/// unrolled next to `centre` so that the face's box stays in one piece.
struct AxisMap {
    ParameterMap map;
    double centre = 0;
    double lo = 0, hi = 0; // a periodic direction: the face's box, unrolled
    double invTanQuarter = 0; // a half-angle map: invTanQuarterOf(map), once (axisMap)

    double operator()(double u) const
    {
        if (map.kind == ParameterMap::Kind::HalfAngle && invTanQuarter > 0) return halfAngleOf(map, invTanQuarter, u);
        if (map.kind == ParameterMap::Kind::Identity && map.period > 0) {
            // A parameter already in the box stays: on a face one period wide, a point on the seam
            // is half a period from the centre either way (u = 0 would round to 2 pi), and a
            // pcurve's point an ulp past 2 pi would wrap to 0.
            const double tol = 1e-9 * map.period;
            if (u >= lo - tol && u <= hi + tol) return u;
            const double s = map(u);
            return s + std::round((centre - s) / map.period) * map.period;
        }
        return map(u);
    }
    /// Bounds on |ds/du| and |d2s/du2| for u in [lo, hi].
    std::pair<double, double> slopes(double lo, double hi) const
    {
        switch (map.kind) {
        case ParameterMap::Kind::Identity:
            return {1, 0};
        case ParameterMap::Kind::Exponential:
            return {std::exp(hi), std::exp(hi)};
        case ParameterMap::Kind::HalfAngle: {
            // s' = span sec^2(phi/2) / (4 tan(span/4)), s'' = s' tan(phi/2), |phi| <= span/2 on an
            // arc (more where [lo, hi] reaches past the arcs).
            const double end = map.start + map.spans * map.span;
            const double over = std::max({0.0, map.start - lo, hi - end});
            const double half = 0.5 * (0.5 * map.span + over);
            if (half >= 0.49 * std::numbers::pi) return {kInf, kInf};
            const double c = std::cos(half), d1 = map.span / (4 * std::tan(0.25 * map.span) * c * c);
            return {d1, d1 * std::tan(half)};
        }
        }
        return {kInf, kInf};
    }
};

/// The grid of one face in its NURBS parameters.
struct FaceGrid {
    AxisMap mu, mv;
    std::vector<double> gu, gv; // grid lines
    double snapU = 0, snapV = 0;
    double bound = 0;     // the largest certified cell bound
    double slopeU = 0, slopeV = 0; // bounds on |S_u| and |S_v| over the face's box
    std::vector<RationalPatch> patches; // the face's Bézier patches, knot span (a, b) at a * (bv.size() - 1) + b
    std::vector<double> bu, bv;         // their knot lines

    /// Bounds on |S_u| and |S_v| over the box [lo, hi] of NURBS parameters: the largest of the
    /// cells' own (the first differences of each cell's sub-net) where the box meets at most four
    /// cells, the face's otherwise.
    std::pair<double, double> slopesOver(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) const;
    /// A bound on |n_u S_u + n_v S_v| over the box (the derivative along n, of unit length): from
    /// each cell's sub-net (its first differences raised to a common degree, so a plane's is
    /// exact), where the box meets at most four cells; otherwise from the slopes, |n_u| lu + |n_v| lv.
    double slopeAlong(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, const Eigen::Vector2d& n) const;

    Eigen::Vector2d toS(const Eigen::Vector2d& uv) const { return {mu(uv.x()), mv(uv.y())}; }

    struct Cell {
        std::pair<double, double> slopes; // bounds on |S_u|, |S_v|
        std::optional<RationalPatch> net; // its sub-net, where the cell lies in one patch
        double width = 0, height = 0;     // in NURBS parameters
        // The sub-net's first differences along u and v raised to its degree, shifted by the
        // control box's centre, per NURBS parameter (slopeAlong); and rho / w_min, 1 / w_min.
        std::vector<Eigen::Vector4d> alongU, alongV;
        double rhoOverW = 0, overW = 0;
    };

private:
    mutable std::unordered_map<long long, Cell> cells_; // by cell, as computed
    Cell& cell(std::size_t i, std::size_t j) const; // computed once (the cache is mutable)
    /// The cells [i0, i1] x [j0, j1] the box [lo, hi] meets; false where it meets more than four.
    bool cellsOf(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, std::size_t& i0, std::size_t& i1, std::size_t& j0,
                 std::size_t& j1) const;

public:
    static double snapTo(double s, const std::vector<double>& lines, double tol)
    {
        if (s <= lines.front()) return lines.front();
        if (s >= lines.back()) return lines.back();
        const auto it = std::lower_bound(lines.begin(), lines.end(), s);
        if (*it - s <= tol) return *it;
        if (s - *(it - 1) <= tol) return *(it - 1);
        return s;
    }
    /// On a grid line when within the snapping distance of it, and inside the grid's box.
    Eigen::Vector2d snap(const Eigen::Vector2d& s) const { return {snapTo(s.x(), gu, snapU), snapTo(s.y(), gv, snapV)}; }

    /// A grid line strictly between a and b, the one nearest a of its axis: (axis, value), axis -1
    /// when there is none. (Nearest a: the part of the side from a to the cut crosses no line of
    /// that axis, so cutting a side across thousands of lines does not nest a cut per line.)
    std::pair<int, double> crossing(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const
    {
        for (int axis = 0; axis < 2; ++axis) {
            const std::vector<double>& lines = axis == 0 ? gu : gv;
            if (a[axis] < b[axis]) {
                const auto it = std::upper_bound(lines.begin(), lines.end(), a[axis]);
                if (it != lines.end() && *it < b[axis]) return {axis, *it};
            } else {
                const auto it = std::lower_bound(lines.begin(), lines.end(), a[axis]);
                if (it != lines.begin() && *(it - 1) > b[axis]) return {axis, *(it - 1)};
            }
        }
        return {-1, 0};
    }
};

/// A point of a face's trim polygon: its NURBS parameters and its mesh vertex.
struct PolyPoint {
    Eigen::Vector2d s;
    int vertex;
};

/// The mesh being built: positions, triangles and their faces.
struct Builder {
    std::vector<Eigen::Vector3d> positions;
    std::vector<std::array<int, 3>> triangles;
    std::vector<int> triangleFace;
    int add(const Eigen::Vector3d& p)
    {
        positions.push_back(p);
        return static_cast<int>(positions.size()) - 1;
    }
    /// Removes the triangles t with drop[t] set, keeping the others' order.
    void dropTriangles(const std::vector<char>& drop)
    {
        std::size_t kept = 0;
        for (std::size_t t = 0; t < triangles.size(); ++t)
            if (!drop[t]) {
                triangles[kept] = triangles[t];
                triangleFace[kept++] = triangleFace[t];
            }
        triangles.resize(kept);
        triangleFace.resize(kept);
    }
};

/// Where the trims of two edges (or of one closed edge) do not quite meet in the parameter plane,
/// the polygon joins them by a side whose ends are the same vertex; its points on grid lines
/// (the same vertex again) keep every side inside one cell. Appends them to `out`.
void joinAcrossLines(const FaceGrid& g, const PolyPoint& a, const PolyPoint& b, std::vector<PolyPoint>& out);

/// The trim's parameter at the edge's parameter t (the edge's range [edgeFirst, edgeLast] mapped
/// linearly onto the trim's).
inline double trimParameterOf(const MappedCurve<2>& c, double edgeFirst, double edgeLast, double t)
{
    if (c.first == edgeFirst && c.last == edgeLast) return t;
    return c.first + (t - edgeFirst) / (edgeLast - edgeFirst) * (c.last - c.first);
}

/// One use of an edge by a face: the trim curve and the face's grid.
struct EdgeUse {
    const TrimCurve* trim;
    const FaceGrid* grid;
    double deviationTarget; // what deviation() may reach on every side (the face's trim share)
    double edgeFirst, edgeLast;
    double invTanQuarter = 0; // the trim's map: invTanQuarterOf, once

    double trimParameter(double t) const { return trimParameterOf(trim->curve, edgeFirst, edgeLast, t); }
    /// The trim's NURBS parameter of its parameter u (its map, with the constant tangent kept).
    double trimNurbsParameter(double u) const
    {
        const ParameterMap& map = trim->curve.map;
        return invTanQuarter > 0 && map.kind == ParameterMap::Kind::HalfAngle ? halfAngleOf(map, invTanQuarter, u) : map(u);
    }
    /// The trim's point at its parameter u.
    Eigen::Vector2d trimPoint(double u) const { return trim->curve.nurbs.evaluate(trimNurbsParameter(u)); }
    /// The edge's parameter of the trim's parameter u (the inverse of trimParameter).
    double edgeParameter(double u) const
    {
        const MappedCurve<2>& c = trim->curve;
        if (c.first == edgeFirst && c.last == edgeLast) return u;
        return edgeFirst + (u - c.first) / (c.last - c.first) * (edgeLast - edgeFirst);
    }
    Eigen::Vector2d raw(double t) const { return grid->toS(trimPoint(trimParameter(t))); }
    Eigen::Vector2d at(double t) const { return grid->snap(raw(t)); }

    /// A certified bound on how far the points of the face's surface at parameters between the
    /// polygon side from at(ta) to at(tb) and the trim between them lie from the trim's points
    /// (part_mesh_edges.cpp). A bound at most `enough` may be returned without the tightest step.
    /// `moved` (when given) receives the part of it that the snap of the side's ends costs: where
    /// the trim runs outside the face's parameter box (hammer.iges: 1.2e-4 past its edge), the
    /// snap into the box moves them, and cutting the side does not shrink that part. `tightest`
    /// (when given) is set to whether the bound is the one `enough` = 0 would give.
    double deviation(double ta, double tb, double enough = 0, double* moved = nullptr, bool* tightest = nullptr) const;
};

/// The samples of one edge: every crossing of a grid line by a use, and cuts in half until every
/// use's polygon side is within its deviation target. Returns the samples (increasing, from
/// first to last); `worst` receives per use the largest deviation left (part_mesh_edges.cpp).
std::vector<double> sampleEdge(const std::vector<EdgeUse>& uses, double first, double last, int maxSamples,
                               std::vector<double>& worst);

/// The edges (edgeOf: per loop point, the edge it samples) whose sides cross another side of the
/// face's polygon in both their interiors (part_mesh_cells.cpp).
std::vector<int> crossingEdges(const FaceGrid& g, const std::vector<std::vector<Eigen::Vector2d>>& loops,
                               const std::vector<std::vector<int>>& edgeOf);

/// Meshes one face: its loops (in NURBS parameters, with the vertices of the edge samples) clipped
/// by the grid cells, each clipped cell cut by ear clipping. Returns the largest distance between a
/// polygon vertex and the surface.
double meshFace(const PartFace& face, std::size_t f, const FaceGrid& g, std::vector<std::vector<PolyPoint>> loops,
                Builder& out);

/// Removes the pockets of no volume that two faces close between a run of one edge's samples and
/// its chord (meshPart): a chord between samples i and j of an edge in four triangles, where each
/// of the edge's two faces has j - i - 1 triangles with all corners among samples i..j (it
/// triangulates the run's polygon), goes with those triangles when every mesh edge they touch is
/// then in none or two triangles. (sampleVertex: the mesh vertex of each edge's samples; useFace:
/// the face of each use of each edge.)
void dropEdgePockets(Builder& out, const std::vector<std::vector<int>>& sampleVertex,
                     const std::vector<std::vector<std::size_t>>& useFace);

/// Bounds on |S_u| and |S_v| of a rational patch over [0, 1]^2 (part_mesh_bounds.cpp).
std::pair<double, double> patchSlopes(const RationalPatch& patch);
/// A patch whose weights differ (where the cells' own bounds beat the whole net's).
bool weighted(const RationalPatch& p);
/// Where a face's trims run through a patch, in the patch's parameters [0, 1]^2: the box of each
/// trim piece's control points, except pieces along a side of the face's parameter box. The
/// bounds from curves (revolutionCellBound, conicalCellBound) pair a triangle point with a surface
/// point elsewhere in its cell (not at the point's own parameters, which lie in the triangle and
/// so in the face): in a cell no trim runs through, that point is on the face too (the cell lies
/// inside the face or outside it, where no triangle is); in a cell a trim crosses it may be outside
/// the face (screw.step's head cone beside its slot: 0.042 mm from the face against a bound of
/// 0.032). Such cells keep the bounds that pair with the point's own parameters.
struct TrimZones {
    std::vector<Eigen::AlignedBox2d> boxes;
    /// Whether a trim may run through the open cell (u0, u1) x (v0, v1).
    bool meets(double u0, double u1, double v0, double v1) const;
    TrimZones transposed() const;
};

/// The certified bound of the patch's nu x nv grid: the smaller of the whole net's bound and the
/// cells' own (`local`: on a weighted patch).
double gridBound(const RationalPatch& p, int nu, int nv, bool local, const TrimZones& zones);
/// Where the grid searches of one face start on a patch like one searched before (the patches of
/// a surface of revolution repeat along its turn): per patch searched, its shape (degrees, weights,
/// the distances between its corners) and the answers its searches confirmed. Only a start: each
/// answer is confirmed as bisection confirms it (it passes, one fewer fails), so a patch that only
/// looks alike costs a probe or two, never a different grid.
struct SearchHints {
    struct Answers {
        std::vector<int> ruled; // fewestRuled: the fewest columns per count of rows (0: none)
        std::vector<int> sides; // patchSegments: the fewest along the longer side per count along the shorter
    };
    /// The answers of a patch like p, or nullptr.
    const Answers* like(const RationalPatch& p) const;
    void add(const RationalPatch& p, Answers answers);

private:
    struct Seen {
        int degreeU, degreeV;
        std::vector<double> weights;
        std::array<double, 6> corners; // the six distances between the control net's corners
        Answers answers;
    };
    static std::array<double, 6> cornerDistances(const RationalPatch& p);
    std::vector<Seen> seen_;
};
/// The grid with the fewest cells whose bound is at most target (`hints`: the face's searches so far).
std::array<int, 2> patchSegments(const RationalPatch& p, double target, const TrimZones& zones, SearchHints* hints = nullptr);
/// Columns of uneven widths across one knot span in u (its patches, one per span in v, each cut
/// into rows[b] even rows), each as wide as its cells' bounds allow within target, from left to
/// right: narrow beside a trim that keeps a cell to its parametric bound, wide elsewhere. The
/// breaks in [0, 1] (0 and 1 included) and, in `bound`, the largest cell bound; empty when they
/// are not fewer than `even` columns.
std::vector<double> unevenColumns(const std::vector<const RationalPatch*>& patches, const std::vector<int>& rows,
                                  const std::vector<const TrimZones*>& zones, double target, int even, double& bound);

// ---- cell bounds from a patch's curves (part_mesh_bounds.cpp; docs/cad.md "Tessellation") ------
// Each bounds, for every triangle whose corners lie in the cell and every point T of it, the
// distance from T to some point of the surface over the cell (one way: the mesh near the part).
// kInf where the patch is not of the form asked for.

/// The rational curve bound of control points x_0..x_m with weights w_i: any convex combination
/// of curve points lies within it of the curve at the same combination of their parameters.
/// (E_h + rho E_w) / w_min for the weight-scaled combination (docs/surfaces.md, "Rational
/// patches"; E the second differences times m (m - 1) / 8, about the box centre), plus q rho for
/// the plain one (q = (w_max - w_min) / w_min, rho the points' box half diagonal).
template <int D>
double curveBound(const Eigen::Matrix<double, D, 1>* x, const double* w, int m);
/// The same curve's weights with equal ends (w_i r^i, r = (w_0 / w_m)^(1/m): a Moebius change of
/// its parameter, the same points and curve). Where a bound needs only *some* curve point, not
/// the one at the combination's parameter, curveBound may take these: a narrow cell of an arc
/// has end weights that differ by its width (where the parameter speeds up), which adds a q rho
/// as large as the chord's own error; in this form only the middle weight's difference is left.
void endWeightsEqual(double* w, int m);

/// A cell of a surface of revolution whose circles run along u (degree 2 in u): P_ij = A + z_j a
/// + r_j c_i (+ eps_ij) with weights alpha_i beta_j (1 + eta_ij), so S(u, v) = A + z(v) a +
/// r(v) C(u) with C the arc of the c_i (weights alpha_i) orthogonal to the axis a and (r, z)(v)
/// the profile curve of the (r_j, z_j) (weights beta_j, r_j >= 0). A triangle point with
/// barycentrics l_k is A + Z a + R sum mu_k C(u_k), (R, Z) = sum l_k (r, z)(v_k), mu_k = l_k
/// r(v_k) / R (convex): within R_max E_C + c_max E_P of S(sum mu_k u_k, sum l_k v_k), E_C and E_P
/// the curveBound of the arc and of the profile, c_max = max |c_i| >= |C(u)|, plus 2 max |eps| +
/// 5 max eta rho_net for what the fit leaves. No twist term: a torus's cells need the chords of
/// its two circles and no more.
double revolutionCellBound(const RationalPatch& cell);

/// The cell [va, vb] (fractions of v) of a column of degree 1 in v with weights constant along v
/// whose rulings meet in one point (a cone): with P_i0 = A + lambda D_i + r_i (D_i = P_i1 - P_i0,
/// A and lambda by least squares), S(u, v) = A + t D(u) + r(u), t = lambda + v. With the apex
/// outside the cell (t of one sign), a triangle point is A + tau sum mu_k D(u_k) + sum l_k r(u_k),
/// tau = sum l_k t_k, mu_k = l_k t_k / tau: within max |t| E_D + 2 max |r_i| of S(sum mu_k u_k,
/// tau - lambda). The far end's circle is all that counts, not the column's width times its height.
double conicalCellBound(const RationalPatch& column, double va, double vb);

} // namespace freeform::part_mesh
