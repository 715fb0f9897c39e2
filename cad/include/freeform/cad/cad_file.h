#pragma once
// STEP and IGES parts through Open CASCADE's data exchange (docs/cad.md, "Reading").
//
// The freeform_cad library is the only code that includes Open CASCADE; its interface holds only
// freeform's own types (brep/part.h), so the CLI, the editor and Python link it without seeing
// Open CASCADE. Every face becomes a trimmed surface in its exact NURBS form, with its trims and
// edges in the file's own parameters (brep/parameter_map.h); coordinates stay in the file's length
// unit, which the part names. Open CASCADE's messages are collected, never printed.

#include <string>
#include <vector>

#include "freeform/brep/part.h"

namespace freeform {

/// Whether the path names a STEP (.step .stp) or IGES (.iges .igs) file (by its extension, in any
/// case).
bool isCadFile(const std::string& path);

/// Reads a STEP or IGES file into a part. Throws freeform::Error naming the file, and the face or
/// edge (by its index, counted from 1 as Open CASCADE's maps count them) whose geometry has no
/// exact rational form (offset curves and surfaces, and other kinds freeform does not read).
/// Open CASCADE's warnings are appended to `warnings` when it is given, else handed to
/// freeform::warn (core/warning.h) like every warning of the library.
Part readCadFile(const std::string& path, std::vector<std::string>* warnings = nullptr);

} // namespace freeform
