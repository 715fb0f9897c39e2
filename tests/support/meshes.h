#pragma once
// Hand-built and procedural meshes with known topology, for the mesh tests. Each builder states the
// numbers a test can rely on; none of them comes from the code under test.

#include <freeform/mesh/polygon_mesh.h>

#include <array>
#include <cmath>
#include <map>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

namespace freeform::test {

inline PolygonMesh meshFrom(const std::vector<Eigen::Vector3d>& points, const std::vector<std::vector<int>>& faces)
{
    PolygonMesh m;
    m.positions.resize(3, static_cast<Eigen::Index>(points.size()));
    for (std::size_t i = 0; i < points.size(); ++i) m.positions.col(static_cast<Eigen::Index>(i)) = points[i];
    for (const auto& f : faces) m.addFace(f.begin(), f.end());
    return m;
}

/// Regular-ish tetrahedron, outward faces: V 4, E 6, F 4, chi 2.
inline PolygonMesh tetrahedron()
{
    return meshFrom({{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}}, {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}});
}

/// Unit cube [0,1]^3 with outward quads: V 8, E 12, F 6, chi 2.
inline PolygonMesh cube()
{
    std::vector<Eigen::Vector3d> p;
    for (int i = 0; i < 8; ++i) p.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    return meshFrom(p, {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}});
}

/// Quad torus, n around the axis and m around the tube (n, m >= 3): V nm, E 2nm, F nm, chi 0.
inline PolygonMesh quadTorus(int n, int m, double major = 2, double minor = 0.5)
{
    std::vector<Eigen::Vector3d> p;
    std::vector<std::vector<int>> faces;
    const double tau = 6.283185307179586;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < m; ++j) {
            const double a = tau * i / n, b = tau * j / m;
            p.emplace_back((major + minor * std::cos(b)) * std::cos(a), (major + minor * std::cos(b)) * std::sin(a),
                           minor * std::sin(b));
        }
    auto id = [&](int i, int j) { return (i % n) * m + (j % m); };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < m; ++j) faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
    return meshFrom(p, faces);
}

/// Every quad split along the same diagonal into two triangles (same vertices, F doubles, E + F).
inline PolygonMesh splitQuads(const PolygonMesh& quads)
{
    PolygonMesh m;
    m.positions = quads.positions;
    for (int f = 0; f < quads.faceCount(); ++f) {
        const int* q = quads.face(f);
        m.addFace({q[0], q[1], q[2]});
        m.addFace({q[0], q[2], q[3]});
    }
    return m;
}

/// The boundary surface of a set of unit voxels (x, y, z), as outward quads sharing the lattice
/// vertices. Manifold when no two voxels touch along only an edge or a corner.
inline PolygonMesh voxelSurface(const std::set<std::array<int, 3>>& voxels)
{
    std::map<std::array<int, 3>, int> index;
    std::vector<Eigen::Vector3d> p;
    std::vector<std::vector<int>> faces;
    auto vertex = [&](std::array<int, 3> c) {
        const auto it = index.find(c);
        if (it != index.end()) return it->second;
        index[c] = static_cast<int>(p.size());
        p.emplace_back(c[0], c[1], c[2]);
        return static_cast<int>(p.size()) - 1;
    };
    for (const auto& v : voxels) {
        for (int axis = 0; axis < 3; ++axis) {
            for (int dir : {-1, 1}) {
                std::array<int, 3> n = v;
                n[axis] += dir;
                if (voxels.count(n)) continue;
                // The face of the voxel on side (axis, dir): corners counter-clockwise seen from outside.
                const int u = (axis + 1) % 3, w = (axis + 2) % 3;
                std::array<int, 3> base = v;
                if (dir > 0) base[axis] += 1;
                std::array<std::array<int, 2>, 4> square{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
                if (dir < 0) std::swap(square[1], square[3]);
                std::vector<int> face;
                for (const auto& s : square) {
                    std::array<int, 3> c = base;
                    c[u] += s[0];
                    c[w] += s[1];
                    face.push_back(vertex(c));
                }
                faces.push_back(face);
            }
        }
    }
    return meshFrom(p, faces);
}

/// A slab of 3 x (2h + 1) voxels with h square holes through it: a closed surface of genus h.
inline PolygonMesh holedSlab(int holes)
{
    std::set<std::array<int, 3>> voxels;
    for (int x = 0; x < 3; ++x)
        for (int y = 0; y < 2 * holes + 1; ++y)
            if (!(x == 1 && y % 2 == 1)) voxels.insert({x, y, 0});
    return voxelSurface(voxels);
}

/// Fan disk: centre 0 and n rim vertices: V n + 1, E 2n, F n, one boundary loop of n edges, chi 1.
inline PolygonMesh fanDisk(int n)
{
    std::vector<Eigen::Vector3d> p{{0, 0, 0}};
    std::vector<std::vector<int>> faces;
    for (int i = 0; i < n; ++i) {
        const double a = 6.283185307179586 * i / n;
        p.emplace_back(std::cos(a), std::sin(a), 0);
        faces.push_back({0, 1 + i, 1 + (i + 1) % n});
    }
    return meshFrom(p, faces);
}

/// Quad grid on [0, nx] x [0, ny]: a disk with V (nx+1)(ny+1), F nx ny, one boundary loop of 2(nx+ny).
inline PolygonMesh grid(int nx, int ny)
{
    std::vector<Eigen::Vector3d> p;
    std::vector<std::vector<int>> faces;
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) p.emplace_back(i, j, 0);
    auto id = [&](int i, int j) { return j * (nx + 1) + i; };
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
    return meshFrom(p, faces);
}

/// Klein bottle: an n x m quad grid with (i + n, j) identified with (i, -j): closed, manifold,
/// non-orientable, V nm, E 2nm, F nm, chi 0. Positions are arbitrary (topology only).
inline PolygonMesh kleinBottle(int n, int m)
{
    std::vector<Eigen::Vector3d> p;
    std::vector<std::vector<int>> faces;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < m; ++j) p.emplace_back(i, j, (i * 7 + j * 3) % 5);
    auto id = [&](int i, int j) {
        if (i >= n) {
            i -= n;
            j = -j;
        }
        j = ((j % m) + m) % m;
        return i * m + j;
    };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < m; ++j) faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
    return meshFrom(p, faces);
}

/// Möbius band of n >= 3 quads: V 2n, E 3n, F n, one boundary loop of 2n edges, chi 0.
inline PolygonMesh mobius(int n)
{
    std::vector<Eigen::Vector3d> p;
    std::vector<std::vector<int>> faces;
    for (int i = 0; i < n; ++i)
        for (int k = 0; k < 2; ++k) p.emplace_back(i, k, 0);
    auto id = [&](int i, int k) { return i >= n ? 2 * (i - n) + (1 - k) : 2 * i + k; };
    for (int i = 0; i < n; ++i) faces.push_back({id(i, 0), id(i + 1, 0), id(i + 1, 1), id(i, 1)});
    return meshFrom(p, faces);
}

/// Disjoint union: b's vertex ids shifted by a's vertex count.
inline PolygonMesh disjointUnion(const PolygonMesh& a, const PolygonMesh& b)
{
    PolygonMesh m;
    m.positions.resize(3, a.vertexCount() + b.vertexCount());
    m.positions << a.positions, b.positions;
    m.faceVertices = a.faceVertices;
    m.faceStart = a.faceStart;
    for (int f = 0; f < b.faceCount(); ++f) {
        std::vector<int> face(b.face(f), b.face(f) + b.faceSize(f));
        for (int& v : face) v += a.vertexCount();
        m.addFace(face.begin(), face.end());
    }
    return m;
}

/// Distinct undirected edges counted by brute force (independent of the library).
inline int countEdges(const PolygonMesh& m)
{
    std::set<std::pair<int, int>> edges;
    for (int f = 0; f < m.faceCount(); ++f)
        for (int k = 0; k < m.faceSize(f); ++k) {
            const int a = m.face(f)[k], b = m.face(f)[(k + 1) % m.faceSize(f)];
            edges.insert({std::min(a, b), std::max(a, b)});
        }
    return static_cast<int>(edges.size());
}

} // namespace freeform::test
