#pragma once
// Tessellation of a patch complex into an indexed triangle mesh (PolygonMesh) with per-vertex
// surface normals (analytic, from the patch's derivatives, not averaged face normals) and texture
// coordinates (u, v).
//
// Guarantees (derivations in docs/surfaces.md, "Tessellation"):
//   - certified accuracy (adaptive mode, tolerance > 0): every point of every triangle lies within
//     the tolerance of the surface point with the same (u, v), and every surface point within the
//     tolerance of the triangle point with the same (u, v) (a parametric bound; it bounds the
//     geometric distance in both directions too; with TessellationMeasure::Geometric only the
//     distance from every triangle point to the surface is bounded, by a bound that leaves out
//     the tangential part of the error, so fewer triangles; at a patch's sides only the part along
//     the side is left out). Refinement::Local (the default) splits each
//     patch's control net by de Casteljau into a tree of dyadic sub-rectangles until the bound of
//     each leaf, from the second differences of its own sub-net,
//         (m(m-1) max|D_uu b| + 2 m n max|D_uv b| + n(n-1) max|D_vv b|) / 8,
//     is at most the tolerance (with the geometric measure, or a pointwise geometric bound over
//     the leaf is); leaves next to finer leaves are fanned from a corner or cut by ear clipping
//     (every triangle has its corners in the leaf, which keeps the leaf's bound) so that no vertex
//     lies inside another triangle's edge. Refinement::PatchGrid is the
//     older global bound: one nu x nv grid per patch,
//         tessellationErrorBound(patch, nu, nv) = M_uu/(8 nu^2) + M_uv/(4 nu nv) + M_vv/(8 nv^2);
//   - conforming and crack-free: the samples on a patch side are the union of the leaf corners of
//     every patch sharing it (sides with identical control points, in either order; sharedEdges with
//     tolerance 0), at the same dyadic parameters, evaluated from the same curve in one canonical
//     orientation, so the resulting vertices are one vertex of the mesh (PatchGrid: the counts are
//     made equal by taking the maximum over every chain of shared sides). A closed complex
//     therefore gives a closed mesh. Collapsed sides become one vertex and the degenerate
//     triangles next to them are left out;
//   - orientation: triangles run counter-clockwise in (u, v), so their normals and the vertex
//     normals point along f_u x f_v; flipNormals reverses both (teapot.bpt: f_u x f_v points
//     into the teapot, flipNormals gives outward normals). A vertex shared by several patches
//     gets the normalised sum of their unit normals (equal across G1 edges) and the (u, v) of
//     the first patch that produced it;
//   - size: a mesh of more than maxTriangles triangles is refused with an Error that gives the
//     estimate, before the mesh is built.

#include <array>
#include <vector>

#include "freeform/mesh/polygon_mesh.h"
#include "freeform/surface/patch_complex.h"

namespace freeform {

/// How adaptive mode refines: a tree of sub-nets per patch (local bounds), or one grid per patch
/// from the bound of the whole net (the method before issue 15, kept for comparison).
enum class TessellationRefinement { Local, PatchGrid };
enum class TessellationMeasure { Parametric, Geometric };

struct TessellationOptions {
    /// > 0: adaptive to this distance (certified, see above); 0: the fixed counts below.
    double tolerance = 0;
    /// Empty (the default): `tolerance` for every patch. Otherwise one tolerance per patch of the
    /// complex (each positive and finite; adaptive mode even where `tolerance` is 0): patch p is
    /// refined to patchTolerance[p], and the certificate is per patch (report.patchBound[p] <=
    /// patchTolerance[p] unless maxSegments binds; report.worstRatio is the largest bound/tolerance).
    /// Shared sides take the union of the samples of both patches, so the mesh stays conforming.
    /// (The editor's per-patch screen tolerance, docs/editor.md.) Patch complexes only: the
    /// rational and NURBS tessellators refuse it.
    std::vector<double> patchTolerance;
    TessellationRefinement refinement = TessellationRefinement::Local;
    /// Segments per patch in u and v (uniform mode), at least 1.
    int segmentsU = 8, segmentsV = 8;
    /// Upper limit of segments per patch and direction in adaptive mode (Local: no leaf is narrower
    /// than 1/maxSegments of the patch); where it binds, the bound in the report exceeds the
    /// tolerance.
    int maxSegments = 4096;
    /// Refuse (Error, with the estimate) a mesh of more triangles than this; 0: no limit.
    long long maxTriangles = 10'000'000;
    /// What the tolerance bounds (adaptive modes): Parametric (the default) |T(x) - f(x)| for the
    /// triangle point T(x) and the surface point with the same (u, v), which bounds the distance
    /// both ways (mesh to surface and surface to mesh); Geometric: the distance from every triangle
    /// point to the surface only (one way), a bound that ignores the tangential part of the error
    /// (Local refinement only; PatchGrid treats it as Parametric). docs/surfaces.md.
    TessellationMeasure measure = TessellationMeasure::Parametric;
    /// Sample every triangle against its patch and report the largest deviations found.
    bool sampleDeviation = false;
    /// Reverse the triangles and negate the normals.
    bool flipNormals = false;
};

struct TessellationReport {
    // Grid modes: per patch the (nu, nv) its own bound asks for, and the (nu, nv) used (after
    // matching shared sides). Local: both are the finest leaf's (1/width in u, 1/width in v).
    std::vector<std::array<int, 2>> required;
    std::vector<std::array<int, 2>> segments;
    double errorBound = 0;                    // the largest certified bound over the patches
    /// Adaptive modes: the certified bound of each patch, and the largest ratio of a patch's bound
    /// to its own tolerance (patchTolerance[p], or tolerance): at most 1 unless maxSegments binds.
    std::vector<double> patchBound;
    double worstRatio = 0;
    /// A part or trimmed surface (the document layer's tessellateObject): the face of each triangle.
    std::vector<int> triangleFace;
    long long leaves = 0;                     // Local: sub-rectangles (leaves of the trees)
    /// With options.sampleDeviation: the largest distances found at 12 points per triangle, from
    /// the triangle point at (u, v) to f(u, v) (parametric) and to its foot point on the patch
    /// found by Newton's method (geometric). Samples, so lower bounds of the true maxima; the
    /// geometric one is at most errorBound, the parametric one too with the parametric measure.
    double measuredParametric = 0, measuredGeometric = 0;
};

/// Largest deviations of triangle xyz[0..2] (with parameters uv[0..2] on the patch) from the patch
/// found at sample points (barycentric coordinates (i, j, k)/samples, i + j + k = samples, corners
/// left out): parametric |T(x) - f(x)| and geometric |T(x) - f(y)| with y the foot point from x
/// (Newton on |T(x) - f(y)|^2, y kept in [0, 1]^2). Both are 0 for a triangle of the surface.
struct TriangleDeviation {
    double parametric = 0, geometric = 0;
};
TriangleDeviation sampleTriangleDeviation(const Patch& patch, const std::array<Eigen::Vector2d, 3>& uv,
                                          const std::array<Eigen::Vector3d, 3>& xyz, int samples = 4);

/// M_uu/(8 nu^2) + M_uv/(4 nu nv) + M_vv/(8 nv^2) for the patch on an nu x nv grid.
double tessellationErrorBound(const Patch& patch, int segmentsU, int segmentsV);

/// The grid with the fewest cells whose bound is at most tolerance (each count at most
/// maxSegments; where that binds, the counts are maxSegments).
std::array<int, 2> adaptiveSegments(const Patch& patch, double tolerance, int maxSegments = 4096);

/// The triangle mesh of the complex (see the guarantees above). Error on bad options.
PolygonMesh tessellate(const PatchComplex& complex, const TessellationOptions& options,
                       TessellationReport* report = nullptr);

/// The local certified bound of the patch's own net (the bound of a leaf that is the whole patch):
/// (m(m-1) max|D_uu b| + 2 m n max|D_uv b| + n(n-1) max|D_vv b|) / 8 = tessellationErrorBound(p, 1, 1).
double netErrorBound(const Patch& patch);

/// segmentsU x segmentsV per patch (more on a patch whose shared sides need it to match).
PolygonMesh tessellateUniform(const PatchComplex& complex, int segmentsU, int segmentsV);

/// Adaptive to `tolerance` (certified).
PolygonMesh tessellateAdaptive(const PatchComplex& complex, double tolerance);

} // namespace freeform
