#pragma once
// The lattice tool's operations on data (no scene, no ImGui). The live FFD of an imported mesh
// (FfdSession, in float) is a derived result the scene evaluates (scene/ffd_session.h,
// scene/derived.h); exports and the exact composition with curves and patches compute in double. Exports write the deformed mesh through MeshFile into the input's own file
// format (only positions, normals and tangents change; docs/mesh-io.md), exactly as `freeform ffd`
// does. Applying the lattice to the document's objects is the document layer's deformDocument
// (freeform/document/operations.h; LatticeTool::applyLatticeToObjects), as in `freeform ffd DOC`.

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

} // namespace freeform::editor
