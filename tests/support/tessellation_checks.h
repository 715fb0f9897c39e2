#pragma once
// Independent checks of tessellated meshes, shared by the tessellation tests: topology counted from
// the face list alone, point-triangle distances (Ericson), and the deviation of a one-patch mesh
// from its patch in both directions (de Casteljau evaluation, Gauss-Newton foot points). Nothing
// here calls the tessellator.

#include <freeform/mesh/polygon_mesh.h>
#include <freeform/surface/patch_complex.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_map>
#include <utility>
#include <vector>

namespace freeform::test {

using V3 = Eigen::Vector3d;
using V2 = Eigen::Vector2d;

/// Topology counted from the face list alone (independent of the library's mesh code).
struct Topology {
    long vertices = 0, edges = 0, faces = 0;
    long boundaryEdges = 0, nonManifoldEdges = 0;
    std::vector<std::pair<int, int>> boundary;
    long euler() const { return vertices - edges + faces; }
};

inline Topology topology(const PolygonMesh& mesh)
{
    std::map<std::pair<int, int>, int> incidence;
    std::vector<bool> used(static_cast<std::size_t>(mesh.vertexCount()), false);
    for (int f = 0; f < mesh.faceCount(); ++f) {
        const int* v = mesh.face(f);
        for (int k = 0; k < mesh.faceSize(f); ++k) {
            const int a = v[k], b = v[(k + 1) % mesh.faceSize(f)];
            ++incidence[{std::min(a, b), std::max(a, b)}];
            used[static_cast<std::size_t>(a)] = true;
        }
    }
    Topology t;
    t.vertices = std::count(used.begin(), used.end(), true);
    t.faces = mesh.faceCount();
    t.edges = static_cast<long>(incidence.size());
    for (const auto& [e, n] : incidence) {
        if (n == 1) {
            ++t.boundaryEdges;
            t.boundary.push_back(e);
        }
        if (n > 2) ++t.nonManifoldEdges;
    }
    return t;
}

/// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
inline V3 closestOnTriangle(const V3& p, const V3& a, const V3& b, const V3& c)
{
    const V3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const V3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
    const V3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
    const double denom = 1 / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

/// Triangles bucketed in a uniform grid of cells, for distance queries up to a radius.
class TriangleGrid {
public:
    TriangleGrid(const PolygonMesh& mesh, double cell) : mesh_(mesh), cell_(cell)
    {
        for (int f = 0; f < mesh.faceCount(); ++f) {
            Eigen::AlignedBox3d box;
            for (int k = 0; k < 3; ++k) box.extend(V3(mesh.positions.col(mesh.face(f)[k])));
            const auto lo = key(box.min()), hi = key(box.max());
            for (long x = lo[0]; x <= hi[0]; ++x)
                for (long y = lo[1]; y <= hi[1]; ++y)
                    for (long z = lo[2]; z <= hi[2]; ++z) cells_[pack(x, y, z)].push_back(f);
        }
    }
    /// Distance from p to the nearest triangle, or infinity when none is within radius.
    double distance(const V3& p, double radius) const
    {
        double best = std::numeric_limits<double>::infinity();
        const auto lo = key(p - V3::Constant(radius)), hi = key(p + V3::Constant(radius));
        for (long x = lo[0]; x <= hi[0]; ++x)
            for (long y = lo[1]; y <= hi[1]; ++y)
                for (long z = lo[2]; z <= hi[2]; ++z) {
                    const auto it = cells_.find(pack(x, y, z));
                    if (it == cells_.end()) continue;
                    for (int f : it->second) {
                        const int* v = mesh_.face(f);
                        const V3 q = closestOnTriangle(p, mesh_.positions.col(v[0]), mesh_.positions.col(v[1]),
                                                       mesh_.positions.col(v[2]));
                        best = std::min(best, (q - p).norm());
                    }
                }
        return best;
    }

private:
    std::array<long, 3> key(const V3& p) const
    {
        return {static_cast<long>(std::floor(p.x() / cell_)), static_cast<long>(std::floor(p.y() / cell_)),
                static_cast<long>(std::floor(p.z() / cell_))};
    }
    static long pack(long x, long y, long z) { return ((x + 4096) * 8192 + (y + 4096)) * 8192 + (z + 4096); }
    const PolygonMesh& mesh_;
    double cell_;
    std::unordered_map<long, std::vector<int>> cells_;
};

/// Largest |T(x) - f(x)| over the points (i, j, k)/6 of every triangle of a one-patch mesh (its
/// texcoords are the patch's (u, v)), f by the patch's de Casteljau evaluate.
inline double parametricDeviation(const Patch& patch, const PolygonMesh& mesh)
{
    double worst = 0;
    for (int f = 0; f < mesh.faceCount(); ++f) {
        const int* v = mesh.face(f);
        for (int i = 0; i <= 6; ++i)
            for (int j = 0; i + j <= 6; ++j) {
                const double a = i / 6.0, b = j / 6.0, c = 1 - a - b;
                const V2 uv = a * V2(mesh.texcoords.col(v[0])) + b * V2(mesh.texcoords.col(v[1])) + c * V2(mesh.texcoords.col(v[2]));
                const V3 t = a * V3(mesh.positions.col(v[0])) + b * V3(mesh.positions.col(v[1])) + c * V3(mesh.positions.col(v[2]));
                worst = std::max(worst, (t - patch.evaluate(uv.x(), uv.y())).norm());
            }
    }
    return worst;
}

/// Largest distance from the points (i, j, k)/4 of every triangle of a one-patch mesh to the patch,
/// each by Gauss-Newton on |p - f(y)|^2 from the point's own (u, v) with the patch's jet (y kept in
/// [0, 1]^2), so at most the distance to the point found: an upper bound of the true distance.
inline double meshToSurface(const Patch& patch, const PolygonMesh& mesh)
{
    double worst = 0;
    for (int f = 0; f < mesh.faceCount(); ++f) {
        const int* v = mesh.face(f);
        for (int i = 0; i <= 4; ++i)
            for (int j = 0; i + j <= 4; ++j) {
                const double a = i / 4.0, b = j / 4.0, c = 1 - a - b;
                V2 y = a * V2(mesh.texcoords.col(v[0])) + b * V2(mesh.texcoords.col(v[1])) + c * V2(mesh.texcoords.col(v[2]));
                const V3 p = a * V3(mesh.positions.col(v[0])) + b * V3(mesh.positions.col(v[1])) + c * V3(mesh.positions.col(v[2]));
                double best = (p - patch.evaluate(y.x(), y.y())).norm();
                for (int it = 0; it < 8; ++it) {
                    const auto jet = patch.jet(y.x(), y.y(), 1);
                    const V3 r = V3(jet.col(0)) - p, fu = jet.col(1), fv = jet.col(2);
                    Eigen::Matrix2d h;
                    h << fu.dot(fu), fu.dot(fv), fu.dot(fv), fv.dot(fv);
                    if (!(std::abs(h.determinant()) > 0)) break;
                    y = (y - h.inverse() * V2(fu.dot(r), fv.dot(r))).cwiseMax(0.0).cwiseMin(1.0);
                    best = std::min(best, (p - patch.evaluate(y.x(), y.y())).norm());
                }
                worst = std::max(worst, best);
            }
    }
    return worst;
}

/// Largest distance from f(u, v) on an irregular n x n grid (and the sides) to the mesh of the grid
/// tri (up to radius).
inline double surfaceToMesh(const Patch& patch, const TriangleGrid& tri, int n, double radius)
{
    double worst = 0;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
            const double u = i == n ? 1.0 : std::fmod(i * 0.6180339887 / n * 1.7 + 0.0013, 1.0);
            const double v = j == n ? 1.0 : std::fmod(j * 0.7071067811 / n * 1.9 + 0.0007, 1.0);
            worst = std::max(worst, tri.distance(patch.evaluate(u, v), radius));
        }
    return worst;
}

/// The same with the mesh's grid built here (cell: the bucket size, about the triangles' size). For
/// several patches of one mesh, build the grid once and pass it.
inline double surfaceToMesh(const Patch& patch, const PolygonMesh& mesh, int n, double radius, double cell = 0.02)
{
    return surfaceToMesh(patch, TriangleGrid(mesh, cell), n, radius);
}

} // namespace freeform::test
