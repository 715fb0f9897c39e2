#pragma once
// The FFD of an imported mesh in the editor (no scene, no ImGui): an FfdSession binds the rest
// mesh to a lattice's frame once (FfdBinding: lattice coordinates computed once per fit) and then
// deforms positions AND normals for any control points of that frame, without recomputing the
// lattice coordinates. The live view computes in float, the precision the GPU draws in (about twice
// as fast as double for positions + normals: docs/performance.md); exports and the exact
// composition with curves and patches compute in double. Exports write the deformed mesh through MeshFile into the input's own file
// format (only positions, normals and tangents change; docs/mesh-io.md), exactly as `freeform ffd`
// does. The lattice also applies exactly to the document's Bézier curves, splines and patches
// (deformCurve / deformSurface) and to the inline cage vertices of subdivision surfaces.
//
// Invariant of FfdSession: rest() and the binding describe the same vertices in the same order;
// deform() writes every vertex (3 x V positions and normals) of that mesh.

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "freeform/io/document.h"
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

/// The mesh file `input` deformed through the lattice into `output` (format by its extension;
/// the input's format keeps everything the file had): positions, normals (cof(J) n) and tangents
/// (J t) as `freeform ffd` writes them. Returns the deformation report.
DeformReport exportDeformedMesh(const std::string& input, const Lattice& lattice, double strength,
                                const std::string& output);

/// The object deformed exactly through the lattice, when the library can: 3D bezier_curve and
/// bezier_spline (degree d (l+m+n) per segment), bezier_surface (deformSurface), and the inline
/// vertices of a subdivision_surface (point-wise, which is exact for a cage). Curves and patches
/// must lie inside the lattice box (their control points do) unless the policy is extrapolate;
/// nullopt with `why` set when the object is left as it is.
std::optional<ObjectData> deformObject(const Lattice& lattice, const ObjectData& object, double strength, std::string& why);

} // namespace freeform::editor
