// freeform tessellate on a STEP or IGES part: the certified watertight mesh (docs/cli.md,
// docs/cad.md "Tessellation").

#include "command.h"
#include "freeform/brep/part_mesh.h"
#include "freeform/cad/cad_file.h"
#include "freeform/io/mesh_io.h"

namespace freeform::cli {

Json partTessellate(const std::string& path, const std::string& output, double tolerance, long long maxTriangles)
{
    return partMeshCommand(readCadFile(path), output, tolerance, maxTriangles);
}

Json partMeshCommand(const Part& part, const std::string& output, double tolerance, long long maxTriangles)
{
    PartMeshOptions options;
    options.tolerance = tolerance;
    options.maxTriangles = maxTriangles;
    const PartMesh result = tessellatePart(part, options);
    writePolygonMesh(result.mesh, output);
    const PartMeshReport& r = result.report;
    Json j;
    j["output"] = output;
    j["faces"] = r.faces;
    j["triangles"] = result.mesh.faceCount();
    j["vertices"] = result.mesh.vertexCount();
    j["watertight"] = r.watertight;
    j["error_bound"] = r.errorBound;
    j["certified"] = r.certified;
    j["tolerance"] = tolerance;
    j["closed_shells"] = r.closedShells;
    j["open_mesh_edges"] = r.openMeshEdges;
    j["max_vertex_gap"] = r.maxVertexGap;
    j["max_trim_deviation"] = r.maxTrimDeviation;
    return j;
}

} // namespace freeform::cli
