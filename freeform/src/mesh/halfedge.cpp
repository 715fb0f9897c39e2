// HalfedgeMesh: construction with non-manifold splitting, queries, local operators, self-check.

#include "freeform/mesh/halfedge.h"

#include <algorithm>
#include <set>
#include <utility>

#include "edge_groups.h"

namespace freeform {

namespace {

std::string edgeName(int a, int b)
{
    std::string text(1, '('); // built by appending: GCC 12 warns falsely on "(" + std::string
    text += std::to_string(a);
    text += ", ";
    text += std::to_string(b);
    text += ')';
    return text;
}

} // namespace

std::string HalfedgeMesh::BuildReport::describe() const
{
    if (!nonManifoldEdges.empty()) {
        const auto& e = nonManifoldEdges.front();
        return "edge " + edgeName(e.from, e.to) + " has " + std::to_string(e.faceCount) + " faces";
    }
    if (!nonManifoldVertices.empty()) {
        const auto& v = nonManifoldVertices.front();
        return "vertex " + std::to_string(v.vertex) + " has " + std::to_string(v.fanCount) +
               " fans of faces (its neighbourhood is not one disk)";
    }
    if (!inconsistentEdges.empty()) {
        const auto& e = inconsistentEdges.front();
        return "edge " + edgeName(e[0], e[1]) + " is run in the same direction by both its faces (inconsistent orientation)";
    }
    return {};
}

void HalfedgeMesh::requireClean(const std::string& what) const
{
    if (!report_.clean()) throw Error(what + ": " + report_.describe());
}

// ---------------------------------------------------------------------------------------------------
// Construction

HalfedgeMesh::HalfedgeMesh(const PolygonMesh& mesh)
{
    mesh.validate("mesh");
    const int vertices = mesh.vertexCount();
    const std::vector<int>& fv = mesh.faceVertices;
    const detail::EdgeGroups groups = detail::groupEdges(mesh);

    positions_.resize(vertices);
    for (int v = 0; v < vertices; ++v) positions_[v] = mesh.positions.col(v);
    outgoing_.assign(vertices, -1);
    original_.resize(vertices);
    for (int v = 0; v < vertices; ++v) original_[v] = v;
    faceHalfedge_.assign(mesh.faceCount(), -1);

    const int sides = static_cast<int>(fv.size());
    to_.reserve(2 * sides);
    next_.reserve(2 * sides);
    prev_.reserve(2 * sides);
    face_.reserve(2 * sides);

    // 1. Pair the sides of each edge: as many a->b with b->a as there are; every other side gets
    //    a boundary halfedge of its own (this is where non-manifold and inconsistent edges split).
    std::vector<int> sideHalfedge(sides);
    std::vector<int> forward, backward;
    for (int e = 0; e < groups.edgeCount(); ++e) {
        forward.clear();
        backward.clear();
        const int first = groups.order[groups.groupStart[e]];
        const int a = std::min(fv[first], fv[groups.sideNext[first]]);
        const int b = std::max(fv[first], fv[groups.sideNext[first]]);
        for (int i = groups.groupStart[e]; i < groups.groupStart[e + 1]; ++i) {
            const int s = groups.order[i];
            (fv[s] == a ? forward : backward).push_back(s);
        }
        const int count = groups.sideCount(e);
        if (count > 2) {
            report_.nonManifoldEdges.push_back({a, b, count});
        } else if (count == 2 && forward.size() != 1) {
            const int s = groups.order[groups.groupStart[e]];
            report_.inconsistentEdges.push_back({fv[s], fv[groups.sideNext[s]]});
        }
        const std::size_t pairs = std::min(forward.size(), backward.size());
        auto place = [&](int s, int h) {
            sideHalfedge[s] = h;
            to_[h] = fv[groups.sideNext[s]];
            face_[h] = groups.sideFace[s];
        };
        for (std::size_t i = 0; i < pairs; ++i) {
            const int ne = addEdge();
            place(forward[i], 2 * ne);
            place(backward[i], 2 * ne + 1);
        }
        auto single = [&](int s) {
            const int ne = addEdge();
            place(s, 2 * ne);
            to_[2 * ne + 1] = fv[s];
        };
        for (std::size_t i = pairs; i < forward.size(); ++i) single(forward[i]);
        for (std::size_t i = pairs; i < backward.size(); ++i) single(backward[i]);
    }

    // 2. Face cycles.
    for (int s = 0; s < sides; ++s) link(sideHalfedge[s], sideHalfedge[groups.sideNext[s]]);
    for (int f = 0; f < mesh.faceCount(); ++f) faceHalfedge_[f] = sideHalfedge[mesh.faceStart[f]];

    // 3. Fans. Around each vertex, the outgoing halfedges chain through h -> next(opposite(h)) as far
    //    as face halfedges reach: open fans run from an outgoing boundary halfedge to an incoming one,
    //    the rest are closed cycles. Each open fan's boundary halfedges are linked to each other, and
    //    every fan after the first gets its own copy of the vertex.
    const int halfedges = halfedgeCount();
    std::vector<int> outStart(vertices + 1, 0), outList(halfedges);
    for (int h = 0; h < halfedges; ++h) ++outStart[fromVertex(h) + 1];
    for (int v = 0; v < vertices; ++v) outStart[v + 1] += outStart[v];
    {
        std::vector<int> fill(outStart.begin(), outStart.end() - 1);
        for (int h = 0; h < halfedges; ++h) outList[fill[fromVertex(h)]++] = h;
    }
    std::vector<char> seen(halfedges, 0);
    std::vector<int> fanHalfedges, fanStart; // the fans of one vertex, flattened
    for (int v = 0; v < vertices; ++v) {
        fanHalfedges.clear();
        fanStart.assign(1, 0);
        for (int i = outStart[v]; i < outStart[v + 1]; ++i) {
            const int h0 = outList[i];
            if (face_[h0] >= 0) continue;
            seen[h0] = 1;
            fanHalfedges.push_back(h0);
            int h = h0;
            while (face_[h ^ 1] >= 0) {
                h = next_[h ^ 1];
                seen[h] = 1;
                fanHalfedges.push_back(h);
            }
            link(h ^ 1, h0);
            fanStart.push_back(static_cast<int>(fanHalfedges.size()));
        }
        for (int i = outStart[v]; i < outStart[v + 1]; ++i) {
            const int h0 = outList[i];
            if (seen[h0]) continue;
            int h = h0;
            do {
                seen[h] = 1;
                fanHalfedges.push_back(h);
                h = next_[h ^ 1];
            } while (h != h0);
            fanStart.push_back(static_cast<int>(fanHalfedges.size()));
        }
        const int fans = static_cast<int>(fanStart.size()) - 1;
        if (fans == 0) continue;
        outgoing_[v] = fanHalfedges.front();
        if (fans > 1) report_.splitVertices.push_back(v);
        for (int k = 1; k < fans; ++k) {
            const int copy = addVertex(positions_[v], v);
            outgoing_[copy] = fanHalfedges[fanStart[k]];
            for (int i = fanStart[k]; i < fanStart[k + 1]; ++i) to_[fanHalfedges[i] ^ 1] = copy;
        }
    }

    // 4. Non-manifold vertices of the input, orientation aside: corners at a vertex are in one fan
    //    when a chain of edges with exactly two faces joins them.
    detail::DisjointSets corners(sides);
    for (int e = 0; e < groups.edgeCount(); ++e) {
        if (groups.sideCount(e) != 2) continue;
        const int s1 = groups.order[groups.groupStart[e]], s2 = groups.order[groups.groupStart[e] + 1];
        // The corner of side s at vertex x: s itself when s starts at x, else the next side.
        auto cornerAt = [&](int s, int x) { return fv[s] == x ? s : groups.sideNext[s]; };
        for (int x : {fv[s1], fv[groups.sideNext[s1]]}) corners.unite(cornerAt(s1, x), cornerAt(s2, x));
    }
    std::vector<std::pair<int, int>> vertexFan(sides);
    for (int s = 0; s < sides; ++s) vertexFan[s] = {fv[s], corners.find(s)};
    std::sort(vertexFan.begin(), vertexFan.end());
    vertexFan.erase(std::unique(vertexFan.begin(), vertexFan.end()), vertexFan.end());
    for (std::size_t i = 0; i < vertexFan.size();) {
        std::size_t j = i;
        while (j < vertexFan.size() && vertexFan[j].first == vertexFan[i].first) ++j;
        if (j - i > 1) report_.nonManifoldVertices.push_back({vertexFan[i].first, static_cast<int>(j - i)});
        i = j;
    }
}

int HalfedgeMesh::addVertex(const Eigen::Vector3d& p, int original)
{
    positions_.push_back(p);
    original_.push_back(original);
    outgoing_.push_back(-1);
    return vertexCount() - 1;
}

int HalfedgeMesh::addEdge()
{
    for (auto* a : {&to_, &next_, &prev_, &face_}) a->insert(a->end(), 2, -1);
    return edgeCount() - 1;
}

int HalfedgeMesh::addFace()
{
    faceHalfedge_.push_back(-1);
    return faceCount() - 1;
}

// ---------------------------------------------------------------------------------------------------
// Queries

int HalfedgeMesh::valence(int v) const
{
    int n = 0;
    forEachOutgoing(v, [&](int) { ++n; });
    return n;
}

std::vector<int> HalfedgeMesh::vertexNeighbors(int v) const
{
    std::vector<int> out;
    forEachOutgoing(v, [&](int h) { out.push_back(to_[h]); });
    return out;
}

std::vector<int> HalfedgeMesh::vertexFaces(int v) const
{
    std::vector<int> out;
    forEachOutgoing(v, [&](int h) {
        if (face_[h] >= 0) out.push_back(face_[h]);
    });
    return out;
}

std::vector<int> HalfedgeMesh::faceVertices(int f) const
{
    std::vector<int> out;
    forEachFaceHalfedge(f, [&](int h) { out.push_back(fromVertex(h)); });
    return out;
}

int HalfedgeMesh::faceSize(int f) const
{
    int n = 0;
    forEachFaceHalfedge(f, [&](int) { ++n; });
    return n;
}

int HalfedgeMesh::findHalfedge(int a, int b) const
{
    int found = -1;
    forEachOutgoing(a, [&](int h) {
        if (found < 0 && to_[h] == b) found = h;
    });
    return found;
}

bool HalfedgeMesh::isClosed() const
{
    return std::none_of(face_.begin(), face_.end(), [](int f) { return f < 0; });
}

std::vector<std::vector<int>> HalfedgeMesh::boundaryLoops() const
{
    std::vector<std::vector<int>> loops;
    std::vector<char> seen(halfedgeCount(), 0);
    for (int h0 = 0; h0 < halfedgeCount(); ++h0) {
        if (face_[h0] >= 0 || seen[h0]) continue;
        std::vector<int> loop;
        int h = h0;
        do {
            seen[h] = 1;
            loop.push_back(h);
            h = next_[h];
        } while (h != h0);
        loops.push_back(std::move(loop));
    }
    return loops;
}

HalfedgeMesh::Components HalfedgeMesh::components() const
{
    Components c;
    c.ofFace.assign(faceCount(), -1);
    c.ofVertex.assign(vertexCount(), -1);
    std::vector<int> stack;
    for (int f0 = 0; f0 < faceCount(); ++f0) {
        if (c.ofFace[f0] >= 0) continue;
        const int id = c.count++;
        c.ofFace[f0] = id;
        stack.push_back(f0);
        while (!stack.empty()) {
            const int f = stack.back();
            stack.pop_back();
            forEachFaceHalfedge(f, [&](int h) {
                c.ofVertex[to_[h]] = id;
                const int g = face_[h ^ 1];
                if (g >= 0 && c.ofFace[g] < 0) {
                    c.ofFace[g] = id;
                    stack.push_back(g);
                }
            });
        }
    }
    return c;
}

// ---------------------------------------------------------------------------------------------------
// Local operators

namespace {

std::string outOfRange(const std::string& kind, int id, int count)
{
    return "there is no " + kind + " " + std::to_string(id) + " (the mesh has " + std::to_string(count) + ")";
}

bool refuse(std::string* reason, const std::string& why)
{
    if (reason) *reason = why;
    return false;
}

} // namespace

int HalfedgeMesh::insertDiagonal(int ha, int hb)
{
    // Splits the face of ha and hb by an edge from toVertex(ha) to toVertex(hb): the old face keeps
    // ha, the new one gets hb.
    const int f = face_[ha];
    const int na = next_[ha], nb = next_[hb];
    const int ne = addEdge();
    const int d = 2 * ne, d2 = 2 * ne + 1;
    to_[d] = to_[hb];
    to_[d2] = to_[ha];
    const int g = addFace();
    link(ha, d);
    link(d, nb);
    link(hb, d2);
    link(d2, na);
    face_[d] = f;
    faceHalfedge_[f] = ha;
    faceHalfedge_[g] = hb;
    int h = d2;
    do {
        face_[h] = g;
        h = next_[h];
    } while (h != d2);
    return ne;
}

bool HalfedgeMesh::canFlip(int e, std::string* reason) const
{
    if (e < 0 || e >= edgeCount()) return refuse(reason, outOfRange("edge", e, edgeCount()));
    const int h = 2 * e, t = 2 * e + 1;
    if (face_[h] < 0 || face_[t] < 0) return refuse(reason, "it is a boundary edge");
    if (faceSize(face_[h]) != 3 || faceSize(face_[t]) != 3) return refuse(reason, "its faces are not both triangles");
    const int c = to_[next_[h]], d = to_[next_[t]];
    if (c == d) return refuse(reason, "both triangles have the same third corner " + std::to_string(c));
    if (findHalfedge(c, d) >= 0)
        return refuse(reason, "the new edge " + edgeName(c, d) + " exists already");
    return true;
}

void HalfedgeMesh::flip(int e)
{
    std::string why;
    if (!canFlip(e, &why)) throw Error("flip of edge " + std::to_string(e) + ": " + why);
    const int h = 2 * e, t = 2 * e + 1;
    const int f = face_[h], g = face_[t];
    const int hn = next_[h], hp = prev_[h], tn = next_[t], tp = prev_[t];
    const int a = to_[t], b = to_[h], c = to_[hn], d = to_[tn];
    // f = (a, b, c) as h, hn, hp; g = (b, a, d) as t, tn, tp. After: f = (d, c, a), g = (c, d, b).
    to_[h] = c;
    to_[t] = d;
    link(h, hp);
    link(hp, tn);
    link(tn, h);
    link(t, tp);
    link(tp, hn);
    link(hn, t);
    face_[tn] = f;
    face_[hn] = g;
    faceHalfedge_[f] = h;
    faceHalfedge_[g] = t;
    if (outgoing_[a] == h) outgoing_[a] = tn;
    if (outgoing_[b] == t) outgoing_[b] = hn;
}

int HalfedgeMesh::splitEdge(int e, const Eigen::Vector3d& p)
{
    if (e < 0 || e >= edgeCount()) throw Error("split of edge " + std::to_string(e) + ": " + outOfRange("edge", e, edgeCount()));
    if (!p.allFinite()) throw Error("split of edge " + std::to_string(e) + ": the new position is not finite");
    const int h = 2 * e, t = 2 * e + 1;
    const bool triangleH = face_[h] >= 0 && faceSize(face_[h]) == 3;
    const bool triangleT = face_[t] >= 0 && faceSize(face_[t]) == 3;
    const int b = to_[h];
    const int m = addVertex(p, -1);
    const int ne = addEdge();
    const int hh = 2 * ne, tt = 2 * ne + 1;
    // h: a -> m, hh: m -> b (face of h); tt: b -> m, t: m -> a (face of t).
    const int hn = next_[h], tp = prev_[t];
    to_[h] = m;
    to_[hh] = b;
    to_[tt] = m;
    face_[hh] = face_[h];
    face_[tt] = face_[t];
    link(h, hh);
    link(hh, hn);
    link(tp, tt);
    link(tt, t);
    outgoing_[m] = face_[t] < 0 ? t : hh;
    if (outgoing_[b] == t) outgoing_[b] = tt;
    if (triangleH) insertDiagonal(h, hn);
    if (triangleT) insertDiagonal(tt, next_[t]);
    return m;
}

int HalfedgeMesh::splitFace(int f, const Eigen::Vector3d& p)
{
    if (f < 0 || f >= faceCount()) throw Error("split of face " + std::to_string(f) + ": " + outOfRange("face", f, faceCount()));
    if (!p.allFinite()) throw Error("split of face " + std::to_string(f) + ": the new position is not finite");
    std::vector<int> ring;
    forEachFaceHalfedge(f, [&](int h) { ring.push_back(h); });
    const int n = static_cast<int>(ring.size());
    const int m = addVertex(p, -1);
    // Spoke i joins m and corner v_i = fromVertex(ring[i]): halfedge 2k (m -> v_i), 2k + 1 (v_i -> m).
    std::vector<int> spoke(n);
    for (int i = 0; i < n; ++i) {
        spoke[i] = addEdge();
        to_[2 * spoke[i]] = fromVertex(ring[i]);
        to_[2 * spoke[i] + 1] = m;
    }
    // Triangle i: ring[i] (v_i -> v_i+1), (v_i+1 -> m), (m -> v_i).
    for (int i = 0; i < n; ++i) {
        const int tri = i == 0 ? f : addFace();
        const int in = 2 * spoke[(i + 1) % n] + 1, out = 2 * spoke[i];
        link(ring[i], in);
        link(in, out);
        link(out, ring[i]);
        face_[ring[i]] = face_[in] = face_[out] = tri;
        faceHalfedge_[tri] = ring[i];
    }
    outgoing_[m] = 2 * spoke[0];
    return m;
}

bool HalfedgeMesh::canCollapse(int h, std::string* reason) const
{
    if (h < 0 || h >= halfedgeCount()) return refuse(reason, outOfRange("halfedge", h, halfedgeCount()));
    const int t = h ^ 1, u = to_[t], v = to_[h];
    bool triangles = true;
    for (int x : {u, v}) forEachOutgoing(x, [&](int o) { triangles = triangles && (face_[o] < 0 || faceSize(face_[o]) == 3); });
    if (!triangles) return refuse(reason, "the faces around its ends are not all triangles");
    const int c = face_[h] >= 0 ? to_[next_[h]] : -1;
    const int d = face_[t] >= 0 ? to_[next_[t]] : -1;
    if (c >= 0 && c == d) return refuse(reason, "both triangles at the edge have the third corner " + std::to_string(c));

    // Links, with the boundary as the extra vertex -2 joined to every boundary vertex and edge.
    constexpr int kOutside = -2;
    auto vertexLink = [&](int x) {
        std::set<int> link;
        forEachOutgoing(x, [&](int o) {
            link.insert(to_[o]);
            if (face_[o] < 0 || face_[o ^ 1] < 0) link.insert(kOutside);
        });
        return link;
    };
    auto edgeLink = [&](int x) {
        std::set<std::pair<int, int>> link;
        forEachOutgoing(x, [&](int o) {
            if (face_[o] >= 0) {
                const int y = to_[o], z = to_[next_[o]];
                link.insert({std::min(y, z), std::max(y, z)});
            }
            if (face_[o] < 0 || face_[o ^ 1] < 0) link.insert({kOutside, to_[o]});
        });
        return link;
    };
    const std::set<int> lu = vertexLink(u), lv = vertexLink(v);
    std::set<int> common;
    std::set_intersection(lu.begin(), lu.end(), lv.begin(), lv.end(), std::inserter(common, common.end()));
    std::set<int> edgeLinkVertices;
    if (c >= 0) edgeLinkVertices.insert(c);
    if (d >= 0) edgeLinkVertices.insert(d);
    if (c < 0 || d < 0) edgeLinkVertices.insert(kOutside);
    if (common != edgeLinkVertices) {
        for (int x : common) {
            if (edgeLinkVertices.count(x)) continue;
            if (x == kOutside)
                return refuse(reason, "link condition: both ends lie on the boundary but the edge does not");
            return refuse(reason, "link condition: the ends have the common neighbour " + std::to_string(x) +
                                      " outside the edge's triangles");
        }
    }
    const auto eu = edgeLink(u), ev = edgeLink(v);
    for (const auto& pair : eu) {
        if (!ev.count(pair)) continue;
        if (pair.first == kOutside)
            return refuse(reason, "link condition: the edge's triangle with corner " + std::to_string(pair.second) +
                                      " would fold onto the boundary");
        return refuse(reason, "link condition: both ends form a triangle with edge " + edgeName(pair.first, pair.second));
    }
    return true;
}

void HalfedgeMesh::takePlace(int dead, int heir)
{
    // heir takes over dead's position in its face (or boundary) cycle.
    face_[heir] = face_[dead];
    next_[heir] = next_[dead];
    prev_[heir] = prev_[dead];
    next_[prev_[heir]] = heir;
    prev_[next_[heir]] = heir;
    if (face_[heir] >= 0 && faceHalfedge_[face_[heir]] == dead) faceHalfedge_[face_[heir]] = heir;
}

void HalfedgeMesh::preferBoundaryOutgoing(int v)
{
    forEachOutgoing(v, [&](int h) {
        if (face_[h] < 0) outgoing_[v] = h;
    });
}

int HalfedgeMesh::collapse(int h, const Eigen::Vector3d& p)
{
    std::string why;
    if (!canCollapse(h, &why)) throw Error("collapse of halfedge " + std::to_string(h) + ": " + why);
    if (!p.allFinite()) throw Error("collapse of halfedge " + std::to_string(h) + ": the new position is not finite");
    const int t = h ^ 1, u = to_[t];
    int v = to_[h];
    std::vector<int> incoming;
    forEachOutgoing(u, [&](int o) { incoming.push_back(o ^ 1); });
    std::vector<int> deadEdges{h >> 1}, deadFaces;
    std::vector<int> touched{v};

    if (face_[h] >= 0) {
        // Triangle (u, v, c) = h, hn, hp: hn (v -> c) takes the place of opposite(hp) (u -> c).
        const int hn = next_[h], hp = prev_[h], c = to_[hn];
        takePlace(hp ^ 1, hn);
        outgoing_[c] = hn ^ 1;
        outgoing_[v] = hn;
        deadEdges.push_back(hp >> 1);
        deadFaces.push_back(face_[h]);
        touched.push_back(c);
    }
    if (face_[t] >= 0) {
        // Triangle (v, u, d) = t, tn, tp: tp (d -> v) takes the place of opposite(tn) (d -> u).
        const int tn = next_[t], tp = prev_[t], d = to_[tn];
        takePlace(tn ^ 1, tp);
        outgoing_[d] = tp;
        outgoing_[v] = tp ^ 1;
        deadEdges.push_back(tn >> 1);
        deadFaces.push_back(face_[t]);
        touched.push_back(d);
    }
    if (face_[h] < 0) link(prev_[h], next_[h]);
    if (face_[t] < 0) link(prev_[t], next_[t]);
    for (int x : incoming) to_[x] = v;
    positions_[v] = p;
    for (int x : touched) preferBoundaryOutgoing(x);

    std::sort(deadEdges.rbegin(), deadEdges.rend());
    for (int e : deadEdges) removeEdge(e);
    std::sort(deadFaces.rbegin(), deadFaces.rend());
    for (int f : deadFaces) removeFace(f);
    if (v == vertexCount() - 1) v = u;
    removeVertex(u);
    return v;
}

void HalfedgeMesh::removeEdge(int e)
{
    const int last = edgeCount() - 1;
    if (e != last) {
        auto remap = [&](int x) { return (x >> 1) == last ? 2 * e + (x & 1) : x; };
        for (int side = 0; side < 2; ++side) {
            const int x = 2 * last + side, y = 2 * e + side;
            to_[y] = to_[x];
            face_[y] = face_[x];
            next_[y] = remap(next_[x]);
            prev_[y] = remap(prev_[x]);
        }
        for (int side = 0; side < 2; ++side) {
            const int x = 2 * last + side, y = 2 * e + side;
            next_[prev_[y]] = y;
            prev_[next_[y]] = y;
            if (face_[y] >= 0 && faceHalfedge_[face_[y]] == x) faceHalfedge_[face_[y]] = y;
            if (outgoing_[to_[y ^ 1]] == x) outgoing_[to_[y ^ 1]] = y;
        }
    }
    for (auto* a : {&to_, &next_, &prev_, &face_}) a->resize(a->size() - 2);
}

void HalfedgeMesh::removeFace(int f)
{
    const int last = faceCount() - 1;
    if (f != last) {
        faceHalfedge_[f] = faceHalfedge_[last];
        forEachFaceHalfedge(f, [&](int h) { face_[h] = f; });
    }
    faceHalfedge_.pop_back();
}

void HalfedgeMesh::removeVertex(int v)
{
    const int last = vertexCount() - 1;
    if (v != last) {
        positions_[v] = positions_[last];
        original_[v] = original_[last];
        outgoing_[v] = outgoing_[last];
        forEachOutgoing(v, [&](int h) { to_[h ^ 1] = v; });
    }
    positions_.pop_back();
    original_.pop_back();
    outgoing_.pop_back();
}

// ---------------------------------------------------------------------------------------------------
// Conversion and self-check

PolygonMesh HalfedgeMesh::toPolygonMesh() const
{
    PolygonMesh mesh;
    mesh.positions.resize(3, vertexCount());
    for (int v = 0; v < vertexCount(); ++v) mesh.positions.col(v) = positions_[v];
    mesh.faceVertices.reserve(halfedgeCount());
    for (int f = 0; f < faceCount(); ++f) {
        forEachFaceHalfedge(f, [&](int h) { mesh.faceVertices.push_back(fromVertex(h)); });
        mesh.faceStart.push_back(static_cast<int>(mesh.faceVertices.size()));
    }
    return mesh;
}

std::string HalfedgeMesh::checkInvariants() const
{
    const int hc = halfedgeCount(), vc = vertexCount(), fc = faceCount();
    const auto H = [](int h) { return "halfedge " + std::to_string(h); };
    if (hc % 2 != 0) return "odd number of halfedges";
    for (const auto* a : {&next_, &prev_, &face_}) {
        if (static_cast<int>(a->size()) != hc) return "halfedge arrays of different lengths";
    }
    if (static_cast<int>(original_.size()) != vc || static_cast<int>(positions_.size()) != vc)
        return "vertex arrays of different lengths";
    for (int h = 0; h < hc; ++h) {
        if (next_[h] < 0 || next_[h] >= hc || prev_[h] < 0 || prev_[h] >= hc) return H(h) + ": next/prev out of range";
        if (prev_[next_[h]] != h) return H(h) + ": prev(next(h)) != h";
        if (to_[h] < 0 || to_[h] >= vc) return H(h) + ": vertex out of range";
        if (face_[h] < -1 || face_[h] >= fc) return H(h) + ": face out of range";
        if (face_[next_[h]] != face_[h]) return H(h) + ": next(h) lies in another face";
        if (fromVertex(next_[h]) != to_[h]) return H(h) + ": next(h) does not start where h ends";
        if (to_[h] == to_[h ^ 1]) return H(h) + ": both ends of its edge are vertex " + std::to_string(to_[h]);
        if (face_[h] < 0 && face_[h ^ 1] < 0) return H(h) + ": both halves of its edge are boundary";
    }
    std::vector<int> perFace(fc, 0);
    for (int h = 0; h < hc; ++h)
        if (face_[h] >= 0) ++perFace[face_[h]];
    for (int f = 0; f < fc; ++f) {
        const int start = faceHalfedge_[f];
        if (start < 0 || start >= hc || face_[start] != f) return "face " + std::to_string(f) + ": its halfedge is not in it";
        if (faceSize(f) != perFace[f]) return "face " + std::to_string(f) + ": its halfedges form more than one cycle";
        if (perFace[f] < 3) return "face " + std::to_string(f) + ": fewer than three sides";
    }
    std::vector<int> perVertex(vc, 0);
    for (int h = 0; h < hc; ++h) ++perVertex[fromVertex(h)];
    for (int v = 0; v < vc; ++v) {
        const std::string V = "vertex " + std::to_string(v);
        const int o = outgoing_[v];
        if (o < 0) {
            if (perVertex[v] != 0) return V + ": has halfedges but no outgoing one";
            continue;
        }
        if (o >= hc || fromVertex(o) != v) return V + ": its outgoing halfedge does not start at it";
        int count = 0, boundary = 0;
        forEachOutgoing(v, [&](int x) {
            ++count;
            if (face_[x] < 0) ++boundary;
        });
        if (count != perVertex[v]) return V + ": its halfedges form more than one fan";
        if (boundary > 1) return V + ": more than one boundary halfedge leaves it";
        if (boundary == 1 && face_[o] >= 0) return V + ": boundary vertex whose outgoing halfedge is not the boundary one";
        if (!positions_[v].allFinite()) return V + ": position is not finite";
    }
    return {};
}

} // namespace freeform
