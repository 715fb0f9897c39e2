// Explicit instantiations of the rational Bézier and NURBS curves (docs/nurbs.md).

#include "freeform/curve/nurbs_curve.h"

namespace freeform {
template class KnotVector<float>;
template class KnotVector<double>;
template class KnotVector<long double>;
template class RationalBezierCurve<float, 2>;
template class RationalBezierCurve<float, 3>;
template class RationalBezierCurve<double, 2>;
template class RationalBezierCurve<double, 3>;
template class RationalBezierCurve<long double, 2>;
template class RationalBezierCurve<long double, 3>;
template class NurbsCurve<float, 2>;
template class NurbsCurve<float, 3>;
template class NurbsCurve<double, 2>;
template class NurbsCurve<double, 3>;
template class NurbsCurve<long double, 2>;
template class NurbsCurve<long double, 3>;
} // namespace freeform
