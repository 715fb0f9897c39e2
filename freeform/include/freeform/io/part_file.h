#pragma once
// Which files are CAD parts: the one list of their extensions, for every front end and for the
// reader and writer (freeform/cad/cad_file.h), which builds without Open CASCADE lack
// (docs/cad.md, "Reading").

#include <string>

namespace freeform {

/// The part files' extensions as help texts and messages list them.
inline constexpr const char* kPartFileExtensions = ".step .stp .iges .igs .brep";

/// Whether the path names a part file by its extension, in any case: STEP (.step .stp), IGES
/// (.iges .igs) or Open CASCADE's own BRep (.brep).
bool isPartFileName(const std::string& path);

} // namespace freeform
