#pragma once
// Certified watertight tessellation of a part (docs/cad.md, "Tessellation").
//
// Every edge is sampled once and its samples are the mesh vertices of both faces that share it,
// so a closed shell gives a closed mesh (every mesh edge in exactly two triangles). Each face is
// meshed in the parameter plane of its NURBS surface: a grid whose cells carry the certified
// bound of the rational patch tessellation (tessellate/tessellate_rational.h) is clipped by the
// face's trim polygon (the edge samples, in the face's parameters), and each clipped cell is cut
// into triangles by ear clipping, so every triangle has its corners in one cell. The edge samples
// include every point where a trim crosses a grid line, and are dense enough that the trim
// polygon stays near the trims. The bound of a face is then
//
//     bound = e + delta + T
//
// e      the largest certified bound of a grid cell of the face (the triangle's points against the
//        surface points at the same parameters);
// delta  the largest distance between a mesh vertex on the face's edges (the edge's own 3D curve,
//        or the part's vertex) and the face's surface at that vertex's parameters: the gaps that
//        the edge tolerances allow, measured at every such vertex;
// T      the trims' term: a certified bound on how far the surface at parameters between a
//        polygon side and its trim lies from the trim (each trim point paired continuously with
//        a side point, the pair's parameters apart by (du, dv), the surface points by at most
//        |S_u| |du| + |S_v| |dv| with the slopes of the side's own cell): triangle points whose
//        parameters lie just outside the trims are within T of the face's boundary.
//
// So every point of every triangle lies within `bound` of its face (one way: the mesh near the
// part, not every point of the part near the mesh). The grid aims at e <= 86/100 of the tolerance
// (9/10 on a face trimmed along iso lines only) and the samples at what the grid and the gaps
// leave; `certified` says the largest bound is within the tolerance (a part whose gaps exceed
// part of it may not be).
#include <vector>

#include "freeform/brep/part.h"
#include "freeform/mesh/polygon_mesh.h"

namespace freeform {

struct PartMeshOptions {
    double tolerance = 0;                 // > 0: the distance bound to aim for (the part's units)
    long long maxTriangles = 10'000'000;  // refuse (Error, with the estimate) a larger mesh; 0: no limit
    int maxEdgeSamples = 200'000;         // per edge; where it stops halvings the bound grows instead,
                                          // where it stops a grid crossing: Error
};

struct PartMeshReport {
    int faces = 0;                        // faces meshed
    int closedShells = 0;                 // shells whose edges are each used twice by its faces
    bool watertight = false;              // there is a closed shell and every mesh edge of every closed shell is in two triangles
    int openMeshEdges = 0;                // mesh edges of closed shells in fewer or more than two triangles
    double errorBound = 0;                // the largest face bound
    bool certified = false;               // errorBound <= tolerance
    double maxVertexGap = 0;              // the largest delta
    double maxTrimDeviation = 0;          // the largest T (the trims' term)
    std::vector<double> faceBound;        // per face of the part
};

struct PartMesh {
    PolygonMesh mesh;                     // triangles, counter-clockwise seen from outside the face
    std::vector<int> triangleFace;        // the part's face of each triangle
    PartMeshReport report;
};

/// The certified watertight mesh of the part (see above). Error naming the face on a face that
/// cannot be meshed (a surface whose parameter box straddles the start of its period, a trim
/// polygon the grid cannot clip), and on a mesh over options.maxTriangles.
PartMesh tessellatePart(const Part& part, const PartMeshOptions& options);

} // namespace freeform
