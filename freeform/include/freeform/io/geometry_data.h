#pragma once
// Geometry from the document's plain data and from files (io layer): the lattice object, the
// subdivision cage (inline or from a mesh file with OBJ crease tags). Moved here from
// volume/lattice.h and subdivision/subdivision_surface.h, which know no file format.

#include <string>

#include "freeform/io/document.h"
#include "freeform/subdivision/subdivision_surface.h"
#include "freeform/volume/lattice.h"

namespace freeform {

/// The document's lattice object as a Lattice (points, frame, outside policy); Error naming the
/// field when it is not valid.
Lattice latticeFromData(const LatticeData& data);
/// The lattice as the document's lattice object.
LatticeData latticeToData(const Lattice& lattice);

/// Reads a cage from any mesh file the library reads (io/mesh_io.h). In OBJ files the crease tags
/// of OpenSubdiv's shape format are read too, with 0-based vertex indices:
///   t crease 2/1 V0 V1 SHARPNESS      (several pairs: 2k/k V0 V1 V2 V3 ... S1 .. Sk, or 2k/1: one S)
///   t corner 1/1 V SHARPNESS          (likewise k/k or k/1)
/// Other tags are an Error naming the line. MeshFile keeps `t` lines verbatim, so a cage deformed
/// with `freeform ffd` keeps its creases.
SubdivisionCage readCage(const std::string& path);

/// Parses the `t` lines of an OBJ text into the cage's creases and corners (see readCage).
void parseCreaseTags(const std::string& objText, const std::string& source, SubdivisionCage& cage);

/// The cage of a document's subdivision_surface object: the mesh file (a relative path is taken
/// relative to documentDirectory; OBJ crease tags are read) or the inline vertices and faces, then
/// the object's own creases and corners appended. Error prefixed with `what`.
SubdivisionCage cageFromData(const SubdivisionSurfaceData& data, const std::string& documentDirectory,
                             const std::string& what);

/// A subdivision_surface whose cage is in a mesh file as inline vertices and faces, with the file's
/// crease tags (and the object's own creases and corners) as creases / corners; an inline one as it
/// is. Error prefixed with `what` when the file cannot be read, or when its cage has what the inline
/// form cannot hold (holes, `creasemethod chaikin`, `smoothtriangles`). Edits and deformations of a
/// file cage go through this, so the file itself is never rewritten.
SubdivisionSurfaceData inlineCage(const SubdivisionSurfaceData& data, const std::string& documentDirectory,
                                  const std::string& what);

/// The inline data of a cage (vertices, faces, creases, corners; scheme and boundary as given);
/// Error prefixed with `what` when it has holes, `creasemethod chaikin` or `smoothtriangles`.
SubdivisionSurfaceData cageToData(const SubdivisionCage& cage, const std::string& scheme, const std::string& boundary,
                                  const std::string& what);

/// The surface of a document's subdivision_surface object (cageFromData, its scheme and boundary).
SubdivisionSurface surfaceFromData(const SubdivisionSurfaceData& data, const std::string& documentDirectory,
                                   const std::string& what);

} // namespace freeform
