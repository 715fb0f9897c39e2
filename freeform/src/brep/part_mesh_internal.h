#pragma once
// Internals of the part tessellation (brep/part_mesh.h), shared by part_mesh.cpp (grids, edge
// samples, the whole part), part_mesh_bounds.cpp (the grids' certified bounds and their search)
// and part_mesh_cells.cpp (one face's trim polygon cut by its grid cells).

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "freeform/brep/part.h"
#include "freeform/tessellate/tessellate_rational.h"

namespace freeform::part_mesh {

constexpr double kInf = std::numeric_limits<double>::infinity();

inline std::string faceName(std::size_t f) { return "face " + std::to_string(f); }

/// A face's file parameter to its NURBS parameter in one direction; a periodic direction is
/// unrolled next to `centre` so that the face's box stays in one piece.
struct AxisMap {
    ParameterMap map;
    double centre = 0;
    double lo = 0, hi = 0; // a periodic direction: the face's box, unrolled

    double operator()(double u) const
    {
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
    double lipschitz = 0; // bound on |grad S| in NURBS parameters

    Eigen::Vector2d toS(const Eigen::Vector2d& uv) const { return {mu(uv.x()), mv(uv.y())}; }

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

    /// A grid line strictly between a and b: (axis, value), axis -1 when there is none.
    std::pair<int, double> crossing(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const
    {
        for (int axis = 0; axis < 2; ++axis) {
            const std::vector<double>& lines = axis == 0 ? gu : gv;
            const double lo = std::min(a[axis], b[axis]), hi = std::max(a[axis], b[axis]);
            const auto it = std::upper_bound(lines.begin(), lines.end(), lo);
            if (it != lines.end() && *it < hi) return {axis, *it};
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

/// Meshes one face: its loops (in NURBS parameters, with the vertices of the edge samples) clipped
/// by the grid cells, each clipped cell cut by ear clipping. Returns the largest distance between a
/// polygon vertex and the surface.
double meshFace(const PartFace& face, std::size_t f, const FaceGrid& g, std::vector<std::vector<PolyPoint>> loops,
                Builder& out);

/// Bounds on |S_u| and |S_v| of a rational patch over [0, 1]^2 (part_mesh_bounds.cpp).
std::pair<double, double> patchSlopes(const RationalPatch& patch);
/// A patch whose weights differ (where the cells' own bounds beat the whole net's).
bool weighted(const RationalPatch& p);
/// The certified bound of the patch's nu x nv grid: the smaller of the whole net's bound and the
/// cells' own (`local`: on a weighted patch).
double gridBound(const RationalPatch& p, int nu, int nv, bool local);
/// The grid with the fewest cells whose bound is at most target.
std::array<int, 2> patchSegments(const RationalPatch& p, double target);

} // namespace freeform::part_mesh
