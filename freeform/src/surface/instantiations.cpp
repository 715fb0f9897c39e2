// Explicit instantiations: template errors surface when the library builds, not in a user's code.
// Only the 3D patches: clang 14 instantiates the members constrained to Dim == 3 (normal,
// curvature) for an explicit instantiation of a 2D patch too and fails, so 2D patches are
// instantiated implicitly where they are used (the fuzz build uses clang, scripts/fuzz.sh).

#include "freeform/surface/bezier_surface.h"

namespace freeform {
template class BezierSurface<double, 3>;
#ifndef FREEFORM_DOUBLE_ONLY_INSTANTIATIONS // float and long double (docs/development.md)
template class BezierSurface<float, 3>;
template class BezierSurface<long double, 3>;
#endif
} // namespace freeform
