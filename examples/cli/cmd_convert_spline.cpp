// Placeholder until the spline conversion lands (replaced by its implementation).
#include "command.h"
#include "freeform/core/error.h"
namespace freeform::cli {
int convertSpline(const Args&) { throw Error("convert: this conversion is not available in this build"); }
} // namespace freeform::cli
