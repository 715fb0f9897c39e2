#pragma once
// The live FFD of an imported mesh (no ImGui, no tools): an FfdSession binds the rest mesh to a
// lattice's frame once (FfdBinding: lattice coordinates computed once per fit) and then deforms
// positions AND normals for any control points of that frame, without recomputing the lattice
// coordinates. It computes in float, the precision the GPU draws in (about twice as fast as double
// for positions + normals: docs/performance.md). The scene evaluates deformed meshes through it
// (scene/derived.h); exports compute in double (tools/ffd_tools.h).
//
// Invariant: rest() and the binding describe the same vertices in the same order; deform() writes
// every vertex (3 x V positions and normals) of that mesh.

#include <Eigen/Core>

#include <vector>

#include "freeform/mesh/polygon_mesh.h"
#include "freeform/volume/deform.h"
#include "freeform/volume/lattice.h"

namespace freeform::editor {

class FfdSession {
public:
    /// Binds `rest` (triangles with per-vertex normals, as the scene draws meshes) to the frame,
    /// degrees and outside policy of `lattice`.
    FfdSession(const Lattice& lattice, PolygonMesh rest);

    const PolygonMesh& rest() const { return rest_; }
    /// Whether `lattice` has the bound frame, degrees and outside policy (else bind again).
    bool matches(const Lattice& lattice) const;

    /// Deformed positions and normals (cof(J) n renormalised), computed in float, into `out`
    /// (resized to the rest mesh's vertex count; faces untouched), det J per vertex into detJ when
    /// given (the colour map's scalars).
    DeformReport deform(const Lattice& lattice, double strength, PolygonMesh& out, std::vector<float>* detJ = nullptr);

private:
    Lattice frame_;
    PolygonMesh rest_;
    FfdBinding<float> binding_;
    Eigen::Matrix<float, 3, Eigen::Dynamic> restNormals_;      // rest_.normals in float
    Eigen::Matrix<float, 3, Eigen::Dynamic> positions_, normals_; // kept between calls (no fresh pages)
};

} // namespace freeform::editor
