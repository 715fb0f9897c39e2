// Explicit instantiations of the rational Bézier and NURBS curves (docs/nurbs.md).

#include "freeform/curve/nurbs_curve.h"

namespace freeform {
template class KnotVector<double>;
template class RationalBezierCurve<double, 2>;
template class RationalBezierCurve<double, 3>;
template class NurbsCurve<double, 2>;
template class NurbsCurve<double, 3>;
#ifndef FREEFORM_DOUBLE_ONLY_INSTANTIATIONS // float and long double (docs/development.md)
template class KnotVector<float>;
template class KnotVector<long double>;
template class RationalBezierCurve<float, 2>;
template class RationalBezierCurve<float, 3>;
template class RationalBezierCurve<long double, 2>;
template class RationalBezierCurve<long double, 3>;
template class NurbsCurve<float, 2>;
template class NurbsCurve<float, 3>;
template class NurbsCurve<long double, 2>;
template class NurbsCurve<long double, 3>;
#endif
} // namespace freeform
