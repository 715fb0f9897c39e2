#pragma once
// Exact free-form deformation of a part (docs/cad.md, "Deformation").
//
// Every face's NURBS surface and every edge's 3D curve is composed with the lattice exactly
// (volume/deform_rational.h: Bézier piece by piece, the breakpoints kept; a face's surface first cut
// down to the face's parameter box where the file's surface is larger), so the deformed face is
// the lattice applied to the face, point for point, at the same parameters. The trims (pcurves)
// live in the faces' parameters and stay as they are; the parameter maps of the exact forms
// (brep/parameter_map.h) stay too; vertices are mapped. An affine lattice maps the control points
// and keeps every degree (affine maps commute with rational Bézier and NURBS forms).
//
// The composition is the lattice polynomial continued beyond the box: it equals the lattice's
// outside policy inside the box and under the extrapolate policy. A face or edge whose control net
// leaves the box under keep or clamp is still deformed (vertices too, by the same polynomial, so
// they stay on their faces) and counted in `outsideFaces`, not in `exactFaces`.
//
// Tolerances: where the part lies in the box, the lattice moves two points apart by at most its
// Lipschitz bound L (volume/deform.h, lipschitzBound), so every edge, vertex and face tolerance is
// multiplied by L (for a rational lattice, whose map has no such simple bound, L is the largest
// |J| sampled at 9^3 points of the box, and the report says it is not certified); an approximated face or edge adds its error to the tolerances of its edges.
// `maxGap` is checkPart's sampled largest gap after the deformation.
//
// Degree cap: the composed degree is d (l+m+n) (d (1+l+m+n) for a rational lattice), so a bicubic
// face under a cubic lattice has degree 27. A face or edge above the cap (maxDegree when it is
// set, and kMaxDegree = 67, the most the library's NURBS hold, in any case) is degree reduced
// (homogeneous least squares per Bézier piece, ends kept, so neighbouring pieces still meet), its
// knot spans halved until the certified error is within the tolerance (at most maxSplits times, and
// only while each halving at least halves the error). A composition above kMaxDegree is formed
// patch by patch at its own degree and reduced from there, never held as a NURBS. The error bound per reduction is the homogeneous one H of the
// library plus the weights: |A/W - B/V| <= H (1 + max|B_i/V_i|) / min W_i (convex hulls).

#include <vector>

#include "freeform/brep/part.h"
#include "freeform/volume/deform_rational.h"

namespace freeform {

struct PartDeformOptions {
    double strength = 1;
    /// 0: no cap but the library's kMaxDegree (67). Otherwise faces and edges of higher degree
    /// are approximated at this degree (at most 67).
    int maxDegree = 0;
    /// The largest error an approximation may have; <= 0: 1e-6 of the part's box diagonal.
    double tolerance = 0;
    /// How often the knot spans of one face or edge may be halved to reach the tolerance.
    int maxSplits = 3;
    int threads = 0; // faces and edges are composed in parallel (0: all cores)
};

struct PartDeformReport {
    int faces = 0;
    int exactFaces = 0;                 // composed exactly, inside the box (or extrapolate)
    std::vector<int> approximatedFaces; // degree reduced (indices)
    std::vector<double> faceErrors;     // per face: the certified approximation error (0 when exact)
    int approximatedEdges = 0;
    double maxApproximationError = 0;   // over faces and edges
    int maxDegree = 0;                  // the largest degree of a face or edge after
    int outsideFaces = 0;               // control net outside the box under keep or clamp
    bool affine = false;                // the lattice map is affine (degrees kept)
    double lipschitz = 1;               // the factor the tolerances grew by
    bool lipschitzCertified = true;     // lipschitzBound; false: a rational lattice, the largest |J| sampled
    double maxGap = 0;                  // checkPart after
    double maxTolerance = 0;            // the largest edge tolerance after
};

struct DeformedPart {
    Part part;
    PartDeformReport report;
};

/// The part through the lattice. Error naming the face or edge (counted from 1) whose composition
/// fails (numbers that overflow far outside the box) or whose approximation stays above the
/// tolerance after maxSplits halvings.
DeformedPart deformPart(const Part& part, const RationalLattice& lattice, const PartDeformOptions& options = {});

} // namespace freeform
