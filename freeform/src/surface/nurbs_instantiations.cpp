// Explicit instantiations of the rational Bézier and NURBS surfaces (docs/nurbs.md).

#include "freeform/surface/nurbs_surface.h"

namespace freeform {
template class RationalBezierSurface<double, 3>;
template class NurbsSurface<double, 3>;
#ifndef FREEFORM_DOUBLE_ONLY_INSTANTIATIONS // float and long double (docs/development.md)
template class RationalBezierSurface<float, 3>;
template class RationalBezierSurface<long double, 3>;
template class NurbsSurface<float, 3>;
template class NurbsSurface<long double, 3>;
#endif
} // namespace freeform
