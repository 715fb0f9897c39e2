// Explicit instantiations of the curves' dense solves (curve/least_squares.h).

#include "freeform/curve/least_squares.h"

namespace freeform::detail {
FREEFORM_LEAST_SQUARES_FIXED(template, double)
#ifndef FREEFORM_DOUBLE_ONLY_INSTANTIATIONS // float and long double (docs/development.md)
FREEFORM_LEAST_SQUARES_FIXED(template, float)
FREEFORM_LEAST_SQUARES_FIXED(template, long double)
#endif
FREEFORM_LEAST_SQUARES_DYNAMIC(template, double)
} // namespace freeform::detail
