#pragma once
// Internal to src/document: the operations on trimmed_surface and part objects (part_ops.cpp),
// called from the per-operation files.

#include <optional>
#include <string>
#include <vector>

#include "freeform/document/operations.h"

namespace freeform::detail {

/// nullopt when the object is neither a trimmed_surface nor a part.
std::optional<Evaluation> evaluatePartObject(const std::string& what, const TypedObject& object,
                                             const std::vector<double>& at, int order);
std::optional<std::vector<double>> partDomain(const TypedObject& object);
std::optional<PolygonMesh> tessellatePartObject(const TypedObject& object, const ObjectTessellation& options,
                                                TessellationReport* report);

} // namespace freeform::detail
