#pragma once
// The up axis of a mesh file. The library's world, like the editor's, is Z-up; many files are
// Y-up (every glTF: the glTF 2.0 specification says +Y is up; most OBJ files from other tools).
// A Y-up file is brought into the world by the quarter turn about +x, (x, y, z) -> (x, -z, y),
// whose entries are 0 and +-1, so the rotation and its inverse are exact in floating point and a
// file written back in its own convention has its original coordinates (docs/format.md, the
// editor's `meshes[].up`).

#include <optional>
#include <string>

#include <Eigen/Core>

#include "freeform/io/document.h"
#include "freeform/mesh/polygon_mesh.h"
#include "freeform/volume/lattice.h"

namespace freeform {

enum class UpAxis { Z, Y };

/// "z" or "y"; freeform::Error "WHERE: expected \"z\" or \"y\"" otherwise.
UpAxis parseUpAxis(const std::string& text, const std::string& where);
const char* toString(UpAxis up);

/// The convention a file's format prescribes: Y for .gltf and .glb (glTF 2.0, section 3.4), none
/// for the formats that have none (.obj, .ply, .stl, .off: the caller asks or remembers).
std::optional<UpAxis> formatUpAxis(const std::string& path);

/// The rotation from a file's coordinates into the Z-up world: the identity for Z, for Y the
/// quarter turn about +x (columns (1,0,0), (0,0,1), (0,-1,0)).
Eigen::Matrix3d upAxisToWorld(UpAxis up);

/// Rotates a mesh's positions and normals from its file's convention into the Z-up world.
void meshToWorld(PolygonMesh& mesh, UpAxis up);

/// A lattice given in world coordinates, expressed in a Y-up (or Z-up: unchanged) file's own
/// coordinates: origin, axes and points rotated back. Deforming the file's vertices with it equals
/// rotating them into the world, deforming there and rotating back (the lattice map commutes with
/// rotations of its frame), so a deformed file keeps its convention.
LatticeData latticeToFile(const LatticeData& lattice, UpAxis up);
/// The same for a built lattice (its degrees and outside policy kept).
Lattice latticeToFile(const Lattice& lattice, UpAxis up);

} // namespace freeform
