#pragma once
// Tessellation of a patch complex into an indexed triangle mesh (PolygonMesh) with per-vertex
// surface normals (analytic, from BezierSurface::normal, not averaged face normals) and texture
// coordinates (u, v).
//
// Guarantees (derivation in docs/surfaces.md, "Tessellation"):
//   - certified accuracy: every patch is cut into an nu x nv grid of parameter cells, each split
//     into two triangles, and every surface point f(u, v) lies within
//         tessellationErrorBound(patch, nu, nv) = M_uu/(8 nu^2) + M_uv/(4 nu nv) + M_vv/(8 nv^2)
//     of the triangle point at the same (u, v), where M_uu = m(m-1) max |second u-difference of
//     the net|, M_uv = m n max |mixed difference|, M_vv likewise: bounds of |f_uu|, |f_uv|,
//     |f_vv| from the convex hull property. tessellate() with a tolerance picks for every patch
//     the cheapest grid whose bound is below it (and reports the bound actually reached);
//   - crack-free: sides whose control points are identical (in either order; sharedEdges with
//     tolerance 0) get the same number of samples, at the same parameters, evaluated from the
//     same curve, and the resulting vertices are one vertex of the mesh; counts are made equal
//     by taking the maximum over every chain of shared sides (which only lowers the bound).
//     A closed complex therefore gives a closed mesh. Collapsed sides become one vertex and the
//     degenerate triangles next to them are left out;
//   - orientation: triangles run counter-clockwise in (u, v), so their normals and the vertex
//     normals point along f_u x f_v; flipNormals reverses both (teapot.bpt: f_u x f_v points
//     into the teapot, flipNormals gives outward normals). A vertex shared by several patches
//     gets the normalised sum of their unit normals (equal across G1 edges) and the (u, v) of
//     the first patch that produced it.

#include <array>
#include <vector>

#include "freeform/mesh/polygon_mesh.h"
#include "freeform/surface/patch_complex.h"

namespace freeform {

struct TessellationOptions {
    /// > 0: adaptive to this distance (certified, see above); 0: the fixed counts below.
    double tolerance = 0;
    /// Segments per patch in u and v (uniform mode), at least 1.
    int segmentsU = 8, segmentsV = 8;
    /// Upper limit of segments per patch and direction in adaptive mode; where it binds, the
    /// bound in the report exceeds the tolerance.
    int maxSegments = 4096;
    /// Reverse the triangles and negate the normals.
    bool flipNormals = false;
};

struct TessellationReport {
    std::vector<std::array<int, 2>> required; // per patch: (nu, nv) its own bound asks for
    std::vector<std::array<int, 2>> segments; // per patch: (nu, nv) used (after matching shared sides)
    double errorBound = 0;                    // the largest certified bound over the patches
};

/// M_uu/(8 nu^2) + M_uv/(4 nu nv) + M_vv/(8 nv^2) for the patch on an nu x nv grid.
double tessellationErrorBound(const Patch& patch, int segmentsU, int segmentsV);

/// The grid with the fewest cells whose bound is at most tolerance (each count at most
/// maxSegments; where that binds, the counts are maxSegments).
std::array<int, 2> adaptiveSegments(const Patch& patch, double tolerance, int maxSegments = 4096);

/// The triangle mesh of the complex (see the guarantees above). Error on bad options.
PolygonMesh tessellate(const PatchComplex& complex, const TessellationOptions& options,
                       TessellationReport* report = nullptr);

/// segmentsU x segmentsV per patch (more on a patch whose shared sides need it to match).
PolygonMesh tessellateUniform(const PatchComplex& complex, int segmentsU, int segmentsV);

/// Adaptive to `tolerance` (certified).
PolygonMesh tessellateAdaptive(const PatchComplex& complex, double tolerance);

} // namespace freeform
