#pragma once
// The undirected edges of a PolygonMesh and the face sides on each (private to src/mesh).
//
// A side is one corner-to-next-corner step of a face: side s of face f runs from
// faceVertices[s] to faceVertices[sideNext[s]]. Sides are grouped by their unordered vertex pair;
// edge e owns sides order[groupStart[e] .. groupStart[e+1]), in increasing side index, and the
// edges are sorted by (smaller vertex, larger vertex).

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

#include "freeform/mesh/polygon_mesh.h"

namespace freeform::detail {

struct EdgeGroups {
    std::vector<int> sideNext;   // S: the next side of the same face
    std::vector<int> sideFace;   // S
    std::vector<int> order;      // S: sides grouped by edge
    std::vector<int> groupStart; // E + 1
    std::vector<int> sideEdge;   // S: the edge of each side

    int edgeCount() const { return static_cast<int>(groupStart.size()) - 1; }
    int sideCount(int e) const { return groupStart[e + 1] - groupStart[e]; }
};

inline EdgeGroups groupEdges(const PolygonMesh& mesh)
{
    EdgeGroups g;
    const int sides = static_cast<int>(mesh.faceVertices.size());
    const std::vector<int>& fv = mesh.faceVertices;
    g.sideNext.resize(sides);
    g.sideFace.resize(sides);
    for (int f = 0; f < mesh.faceCount(); ++f) {
        const int start = mesh.faceStart[f], end = mesh.faceStart[f + 1];
        for (int s = start; s < end; ++s) {
            g.sideNext[s] = s + 1 < end ? s + 1 : start;
            g.sideFace[s] = f;
        }
    }
    // Sort (edge key, side) pairs: contiguous, so the sort streams through memory.
    std::vector<std::pair<std::uint64_t, int>> keyed(sides);
    for (int s = 0; s < sides; ++s) {
        const auto a = static_cast<std::uint32_t>(fv[s]), b = static_cast<std::uint32_t>(fv[g.sideNext[s]]);
        keyed[s] = {(std::uint64_t(std::min(a, b)) << 32) | std::max(a, b), s};
    }
    std::sort(keyed.begin(), keyed.end());
    g.order.resize(sides);
    for (int i = 0; i < sides; ++i) g.order[i] = keyed[i].second;
    g.sideEdge.resize(sides);
    g.groupStart.push_back(0);
    for (int i = 0; i < sides; ++i) {
        if (i > 0 && keyed[i].first != keyed[i - 1].first) g.groupStart.push_back(i);
        g.sideEdge[g.order[i]] = static_cast<int>(g.groupStart.size()) - 1;
    }
    if (sides > 0) g.groupStart.push_back(sides);
    return g;
}

/// Union-find with path halving.
struct DisjointSets {
    std::vector<int> parent;
    explicit DisjointSets(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
    int find(int x)
    {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    }
    void unite(int a, int b)
    {
        a = find(a);
        b = find(b);
        if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
};

} // namespace freeform::detail
