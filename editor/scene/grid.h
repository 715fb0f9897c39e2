#pragma once
// The ground grid's line spacing, shared by the scene drawer (the grid it draws) and the
// interaction layer (the step snapping uses): it lives in the scene layer, which the interaction
// layer may include but not the other way round.

#include <Eigen/Geometry>

namespace freeform::editor {

/// 1, 2 or 5 times a power of ten, the nearest at or above x (x > 0).
double niceStep(double x);

/// The grid spacing for a scene of these bounds: the display grid's line spacing (1, 2 or 5 times
/// a power of ten, at or above an eighth of the scene's extent); snapping uses the same step.
double gridStep(const Eigen::AlignedBox3d& bounds);

} // namespace freeform::editor
