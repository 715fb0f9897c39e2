// Explicit instantiations: template errors surface when the library builds, not in a user's code.

#include "freeform/volume/bezier_volume.h"

namespace freeform {
template class BezierVolume<double>;
#ifndef FREEFORM_DOUBLE_ONLY_INSTANTIATIONS // float and long double (docs/development.md)
template class BezierVolume<float>;
template class BezierVolume<long double>;
#endif
} // namespace freeform
