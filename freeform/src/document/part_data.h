#pragma once
// Trimmed surfaces and parts from their document data (the inverse of toData, object_data.h).
// Private to the document layer: buildGeometry (model.cpp) calls them.

#include "freeform/brep/part.h"
#include "freeform/io/document.h"

namespace freeform::detail {

TrimmedSurface trimmedSurfaceFromData(const TrimmedSurfaceData& data);
/// Error naming the face (`faces[3]: ...`) whose surface or trims cannot be built.
Part partFromData(const PartData& data);

} // namespace freeform::detail
