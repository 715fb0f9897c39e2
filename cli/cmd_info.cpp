// freeform info: the topology report of a mesh file.

#include <cctype>
#include <filesystem>
#include <memory>

#include "command.h"
#include "freeform/io/mesh_io.h"
#include "freeform/mesh/topology.h"

namespace freeform::cli {
namespace {

Json genusJson(const std::optional<int>& genus)
{
    return genus ? Json(*genus) : Json(nullptr);
}

Json componentJson(const ComponentReport& c)
{
    Json j;
    j["vertices"] = c.vertices;
    j["edges"] = c.edges;
    j["faces"] = c.faces;
    j["boundary_edges"] = c.boundaryEdges;
    j["boundary_loops"] = c.boundaryLoops;
    j["manifold"] = c.manifold;
    j["closed"] = c.closed;
    j["orientable"] = c.orientable;
    j["oriented"] = c.oriented;
    j["euler"] = c.euler;
    j["genus"] = genusJson(c.genus);
    if (!c.genus) j["genus_note"] = c.genusNote;
    return j;
}

struct InfoOptions {
    std::vector<std::string> positional;
    bool details = false;
};

Json info(const InfoOptions& o)
{
    expectPositional(o.positional, 1, "the mesh file (freeform info MESH)");
    const std::string& path = o.positional[0];
    if (lowerExtension(path) == ".json" || isPartFileName(path)) return partInfo(path, o.details); // a document's part, or a CAD file's
    const PolygonMesh mesh = readPolygonMesh(path);
    MeshReport r;
    try {
        r = meshReport(mesh);
    } catch (const Error& e) {
        throw Error(path + ": " + e.what()); // the topology's message names the face, this the file
    }
    Json j;
    // Only a file that went through Assimp says so ("assimp (not lossless)"); the lossless readers'
    // output stays exactly as docs/cli.md shows it.
    if (const std::string reader = meshReader(path); reader != "freeform (lossless)") j["reader"] = reader;
    j["vertices"] = r.vertices;
    j["edges"] = r.edges;
    j["faces"] = r.faces;
    j["boundary_edges"] = r.boundaryEdges;
    j["boundary_loops"] = r.boundaryLoops;
    j["components"] = r.components;
    j["manifold"] = r.manifold;
    j["closed"] = r.closed;
    j["euler"] = r.euler;
    j["genus"] = genusJson(r.genus);
    if (!r.genus) j["genus_note"] = r.genusNote;
    if (o.details) {
        j["orientable"] = r.orientable;
        j["oriented"] = r.oriented;
        j["isolated_vertices"] = r.isolatedVertices;
        j["non_manifold_edges"] = Json::array();
        for (const auto& e : r.nonManifoldEdges) j["non_manifold_edges"].push_back({e.from, e.to, e.faceCount});
        j["non_manifold_vertices"] = Json::array();
        for (const auto& v : r.nonManifoldVertices) j["non_manifold_vertices"].push_back({v.vertex, v.fanCount});
        j["inconsistent_edges"] = Json::array();
        for (const auto& e : r.inconsistentEdges) j["inconsistent_edges"].push_back({e[0], e[1]});
        j["component_reports"] = Json::array();
        for (const auto& c : r.componentReports) j["component_reports"].push_back(componentJson(c));
    }
    return j;
}

} // namespace

Action defineInfo(CLI::App& app)
{
    auto o = std::make_shared<InfoOptions>();
    app.footer("Reads a mesh file (.obj .ply .stl .off .gltf .glb) and prints one JSON object:\n"
               "  {\"vertices\": V, \"edges\": E, \"faces\": F, \"boundary_edges\": B,\n"
               "   \"boundary_loops\": L, \"components\": C, \"manifold\": true|false,\n"
               "   \"closed\": true|false, \"euler\": V - E + F, \"genus\": G}\n"
               "E counts distinct undirected edges, B the edges with exactly one face, C the pieces of\n"
               "faces connected through shared vertices. The genus is given only when every component\n"
               "is a closed orientable manifold (then it is the sum of (2 - chi) / 2 over the\n"
               "components); otherwise it is null and \"genus_note\" says why. docs/meshes.md explains\n"
               "every field.\n"
               "A STEP (.step .stp), IGES (.iges .igs) or BRep (.brep) part gives instead\n"
               "  {\"faces\": F, \"edges\": E, \"vertices\": V, \"shells\": S, \"solids\": N,\n"
               "   \"closed\": true|false, \"units\": \"mm\", \"bounds\": {\"min\": [...], \"max\": [...]}, ...}\n"
               "(docs/cad.md).\n"
               "Exit status: 0 ok, 1 bad input (missing, unreadable or malformed file), 2 bad usage.");
    addPositionals(app, "MESH", o->positional, "the mesh file");
    addFlag(app, "--details", o->details,
                 "also print \"orientable\", \"oriented\", \"isolated_vertices\", the lists "
                 "\"non_manifold_edges\" ([from, to, faces]), \"non_manifold_vertices\" ([vertex, fans]) and "
                 "\"inconsistent_edges\" ([a, b], run a -> b by both faces), and \"component_reports\" (the "
                 "same fields per component)");
    return [o] { return info(*o); };
}

} // namespace freeform::cli
