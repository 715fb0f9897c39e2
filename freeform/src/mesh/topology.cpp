// meshReport: counts on the input, boundary loops on the halfedge structure, orientability by
// propagating face orientations over the manifold edges.

#include "freeform/mesh/topology.h"

#include <algorithm>

#include "edge_groups.h"

namespace freeform {

namespace {

std::string plural(int n, const std::string& word)
{
    return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

} // namespace

MeshReport meshReport(const PolygonMesh& mesh)
{
    const HalfedgeMesh structure(mesh); // validates
    const HalfedgeMesh::BuildReport& build = structure.buildReport();
    const detail::EdgeGroups groups = detail::groupEdges(mesh);
    const std::vector<int>& fv = mesh.faceVertices;
    const int vertexCount = mesh.vertexCount(), faceCount = mesh.faceCount();

    MeshReport r;
    r.vertices = vertexCount;
    r.edges = groups.edgeCount();
    r.faces = faceCount;
    r.nonManifoldEdges = build.nonManifoldEdges;
    r.nonManifoldVertices = build.nonManifoldVertices;
    r.inconsistentEdges = build.inconsistentEdges;
    r.manifold = build.manifold();
    r.oriented = build.inconsistentEdges.empty();
    r.euler = r.vertices - r.edges + r.faces;

    // Components: faces joined through shared vertices.
    detail::DisjointSets sets(vertexCount);
    std::vector<char> used(vertexCount, 0);
    for (int f = 0; f < faceCount; ++f) {
        const int* corners = mesh.face(f);
        for (int k = 0; k < mesh.faceSize(f); ++k) {
            used[corners[k]] = 1;
            sets.unite(corners[0], corners[k]);
        }
    }
    std::vector<int> rootComponent(vertexCount, -1), faceComponent(faceCount);
    for (int f = 0; f < faceCount; ++f) {
        int& id = rootComponent[sets.find(mesh.face(f)[0])];
        if (id < 0) id = r.components++;
        faceComponent[f] = id;
    }
    auto vertexComponent = [&](int v) { return rootComponent[sets.find(v)]; };
    r.isolatedVertices = static_cast<int>(std::count(used.begin(), used.end(), 0));
    std::vector<ComponentReport>& parts = r.componentReports;
    parts.resize(r.components);
    for (int v = 0; v < vertexCount; ++v)
        if (used[v]) ++parts[vertexComponent(v)].vertices;
    for (int f = 0; f < faceCount; ++f) ++parts[faceComponent[f]].faces;
    for (int e = 0; e < groups.edgeCount(); ++e) {
        ComponentReport& part = parts[faceComponent[groups.sideFace[groups.order[groups.groupStart[e]]]]];
        ++part.edges;
        if (groups.sideCount(e) == 1) {
            ++part.boundaryEdges;
            ++r.boundaryEdges;
        }
    }
    for (const auto& edge : build.nonManifoldEdges) parts[vertexComponent(edge.from)].manifold = false;
    for (const auto& vertex : build.nonManifoldVertices) parts[vertexComponent(vertex.vertex)].manifold = false;
    for (const auto& edge : build.inconsistentEdges) parts[vertexComponent(edge[0])].oriented = false;
    for (const auto& loop : structure.boundaryLoops()) {
        ++r.boundaryLoops;
        ++parts[faceComponent[structure.face(HalfedgeMesh::opposite(loop.front()))]].boundaryLoops;
    }

    // Orientability: give each face a sign so that the two faces of every manifold edge induce
    // opposite directions on it; a contradiction means no consistent orientation exists.
    std::vector<int> sign(faceCount, 0), stack;
    std::vector<std::vector<std::pair<int, bool>>> neighbours(faceCount); // (face, runs the same way)
    for (int e = 0; e < groups.edgeCount(); ++e) {
        if (groups.sideCount(e) != 2) continue;
        const int s1 = groups.order[groups.groupStart[e]], s2 = groups.order[groups.groupStart[e] + 1];
        const bool same = fv[s1] == fv[s2];
        neighbours[groups.sideFace[s1]].push_back({groups.sideFace[s2], same});
        neighbours[groups.sideFace[s2]].push_back({groups.sideFace[s1], same});
    }
    for (int f0 = 0; f0 < faceCount; ++f0) {
        if (sign[f0] != 0) continue;
        sign[f0] = 1;
        stack.push_back(f0);
        while (!stack.empty()) {
            const int f = stack.back();
            stack.pop_back();
            for (const auto& [g, same] : neighbours[f]) {
                const int want = same ? -sign[f] : sign[f];
                if (sign[g] == 0) {
                    sign[g] = want;
                    stack.push_back(g);
                } else if (sign[g] != want) {
                    parts[faceComponent[f]].orientable = false;
                }
            }
        }
    }

    for (int c = 0; c < r.components; ++c) {
        ComponentReport& part = parts[c];
        part.closed = part.boundaryEdges == 0;
        part.euler = part.vertices - part.edges + part.faces;
        r.orientable = r.orientable && part.orientable;
        if (!part.manifold) {
            part.genusNote = "not a manifold (it has an edge with more than two faces or a vertex with more than one fan "
                             "of faces)";
        } else if (!part.closed) {
            part.genusNote = "it has " + plural(part.boundaryLoops, "boundary loop") +
                             "; the genus is given for closed surfaces only";
        } else if (!part.orientable) {
            part.genusNote = "not orientable (a closed non-orientable surface with Euler characteristic " +
                             std::to_string(part.euler) + " is a sum of " + std::to_string(2 - part.euler) +
                             " projective planes)";
        } else {
            part.genus = (2 - part.euler) / 2;
        }
    }
    r.closed = r.boundaryEdges == 0;
    if (r.components == 0) {
        r.genusNote = "the mesh has no faces";
    } else {
        int sum = 0;
        for (int c = 0; c < r.components && r.genusNote.empty(); ++c) {
            if (parts[c].genus) {
                sum += *parts[c].genus;
            } else {
                r.genusNote = r.components == 1 ? parts[c].genusNote : "component " + std::to_string(c) + ": " + parts[c].genusNote;
            }
        }
        if (r.genusNote.empty()) r.genus = sum;
    }
    return r;
}

} // namespace freeform
