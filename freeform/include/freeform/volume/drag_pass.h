#pragma once
// One frame of an interactive lattice drag over a bound mesh, straight from a base evaluation, in
// one pass over the vertices (the editor's FfdSession calls it; docs/ffd.md, "A lattice drag").
// While a set of lattice points moves by one common vector `delta` since the base, the
// displacement changes by w B delta and the Jacobian by u v^T, with u = w delta, B the sum of the
// set's Bernstein products at the vertex's lattice coordinates and v = dual^T grad B. Then
//   p = p0 + B u,   det J = det A + (cof(A) v) . u,   cof(J) n = cof(A) n + u x (A (n x v)),
// the last because cof(M) has the columns m1 x m2, m2 x m0, m0 x m1. The pass runs in float,
// sixteen vertices at a time, compiled for each CPU level as FfdBinding's kernel is (the shared
// src/volume/cpu_dispatch.h).

#include <array>
#include <cstddef>
#include <vector>

namespace freeform {

/// The pass's data layouts: vertices in blocks of kDragLanes.
///  - coordinates: kDragCoordFields floats per lane: s, t, u (the lattice coordinates with the
///    outside policy applied, outsideRule's `at`), then the rest normal x, y, z;
///  - base: kDragBaseFields floats per lane: p0 x, y, z, A (9, column-major), det A.
/// Padding lanes of the last block repeat the last vertex (finite; never written out).
constexpr int kDragLanes = 16, kDragCoordFields = 6, kDragBaseFields = 13;

/// What one drag frame reads and writes (runDragPass), and what it finds.
struct DragPass {
    std::size_t count = 0;
    const float* coords = nullptr;        // blocks: kDragCoordFields x kDragLanes
    /// Per vertex, only when some vertex lies outside the box under keep or clamp (else null):
    /// outsideRule's mask, bit a (a < 3) the axis adds its gradient, bit 3 the vertex moves.
    const unsigned char* masks = nullptr;
    const float* base = nullptr;          // blocks: kDragBaseFields x kDragLanes (Evaluated base)
    const double* rest = nullptr;         // 3 x count, the rest positions (identity base)
    int deg[3] = {3, 3, 3};               // the lattice's degrees
    const std::array<int, 3>* ijk = nullptr; // the moved points' lattice indices ...
    std::size_t moved = 0;                // ... and their number
    float dual[9] = {};                   // the lattice's dual frame, row-major
    float u[3] = {};                      // strength * delta
    double* pos = nullptr;                // out: 3 x count positions, normals (unit; 0 where the
    double* nor = nullptr;                // cofactor normal vanishes)
    float* fpos = nullptr;                // out, optional: the same in float (the upload's copies)
    float* fnor = nullptr;
    float* det = nullptr;                 // out, optional: det J per vertex
    // Found: det J's range, the folds (det J <= 0, ascending; appended), the box (in float).
    double lo = 1, hi = 1;
    std::vector<int>* folds = nullptr;
    float mn[3] = {}, mx[3] = {};
};

/// The pass over all f.count vertices on the calling thread. identityBase: the base is the rest
/// mesh (A = I, det A = 1; reads f.rest), else the evaluated base f.base.
void runDragPass(DragPass& f, bool identityBase);

} // namespace freeform
