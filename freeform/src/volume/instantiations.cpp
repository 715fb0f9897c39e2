// Explicit instantiations: template errors surface when the library builds, not in a user's code.

#include "freeform/volume/bezier_volume.h"

namespace freeform {
template class BezierVolume<float>;
template class BezierVolume<double>;
template class BezierVolume<long double>;
} // namespace freeform
