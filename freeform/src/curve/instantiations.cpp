// Explicit instantiations: template errors surface when the library builds, not in a user's code.

#include "freeform/curve/bezier_curve.h"

namespace freeform {
template class BezierCurve<double, 2>;
template class BezierCurve<double, 3>;
#ifndef FREEFORM_DOUBLE_ONLY_INSTANTIATIONS // float and long double (docs/development.md)
template class BezierCurve<float, 2>;
template class BezierCurve<float, 3>;
template class BezierCurve<long double, 2>;
template class BezierCurve<long double, 3>;
#endif
} // namespace freeform
