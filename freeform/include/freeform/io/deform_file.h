#pragma once
// Free-form deformation of a mesh file in place, losing nothing (docs/ffd.md, docs/mesh-io.md; in
// io/ since it works on files, moved from volume/):
// the file's vertex positions move through the lattice; its normals and tangents, each anchored to
// a position, follow the map there; every other part of the file (faces, texture coordinates,
// groups, materials, colours, the order of everything) stays as read. `freeform ffd` and the
// editor's export both write through this.

#include <vector>

#include "freeform/io/mesh_io.h"
#include "freeform/volume/deform.h"

namespace freeform {

struct MeshFileDeformation {
    DeformReport report;          ///< over the file's positions
    std::vector<int> outside;     ///< positions outside the lattice box, ascending
};

/// Deforms `file` through `lattice`: positions by the lattice map; normals by cof(J) n renormalised
/// (NormalMode::Jacobian) or as the area-weighted normals of the deformed faces at their anchor
/// (NormalMode::Recompute; an anchor without faces keeps its normal); tangents by J t renormalised,
/// w kept. Where J is exactly the identity (outside the box under `keep`), normals and tangents
/// stay bit for bit. Error (from the lattice) when the options are invalid.
MeshFileDeformation deformMeshFile(const Lattice& lattice, MeshFile& file, const DeformOptions& options = {},
                                   NormalMode normals = NormalMode::Jacobian);

} // namespace freeform
