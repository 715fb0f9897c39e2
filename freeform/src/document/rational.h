#pragma once
// Internal to src/document: the operations on rational_bezier_curve, rational_bezier_surface,
// nurbs_curve and nurbs_surface objects (rational.cpp), called from the per-operation files.

#include <optional>
#include <string>
#include <vector>

#include "freeform/document/operations.h"

namespace freeform::detail {

/// nullopt when the object is not one of the four rational types.
std::optional<Evaluation> evaluateRational(const std::string& what, const TypedObject& object, const std::vector<double>& at,
                                           int order);
std::optional<std::vector<double>> rationalDomain(const TypedObject& object);
std::optional<Eigen::Matrix<double, 3, Eigen::Dynamic>> rationalPolyline(const TypedObject& object, double tolerance);
std::optional<PolygonMesh> tessellateRationalObject(const TypedObject& object, const ObjectTessellation& options,
                                                    TessellationReport* report);
/// Control net of the four types (points and polygon/grid edges); false for other types.
bool rationalControlNet(const TypedObject& object, ControlNet& net);

} // namespace freeform::detail
