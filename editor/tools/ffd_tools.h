#pragma once
// The lattice tool's operations on data (no scene, no ImGui). The live FFD of an imported mesh
// (FfdSession, in float) is a derived result the scene evaluates (scene/ffd_session.h,
// scene/derived.h); exports and the exact composition with curves and patches compute in double. Exports write the deformed mesh through MeshFile into the input's own file
// format (only positions, normals and tangents change; docs/mesh-io.md), exactly as `freeform ffd`
// does. The lattice also applies exactly to the document's Bézier curves, splines and patches
// (deformCurve / deformSurface) and to the inline cage vertices of subdivision surfaces.

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "freeform/io/document.h"
#include "freeform/mesh/polygon_mesh.h"
#include "freeform/volume/deform.h"
#include "freeform/volume/lattice.h"
#include "scene/ffd_session.h"

namespace freeform::editor {



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
