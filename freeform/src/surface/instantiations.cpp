// Explicit instantiations: template errors surface when the library builds, not in a user's code.

#include "freeform/surface/bezier_surface.h"

namespace freeform {
template class BezierSurface<float, 2>;
template class BezierSurface<float, 3>;
template class BezierSurface<double, 2>;
template class BezierSurface<double, 3>;
template class BezierSurface<long double, 2>;
template class BezierSurface<long double, 3>;
} // namespace freeform
