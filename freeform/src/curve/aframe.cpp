// End conditions by name, and the explicit instantiations of the A-frame for float/double x 2D/3D.

#include "freeform/curve/aframe.h"

namespace freeform {

EndCondition parseEndCondition(const std::string& text, const std::string& what)
{
    if (text == "open") return EndCondition::Open;
    if (text == "clamped") return EndCondition::Clamped;
    if (text == "closed") return EndCondition::Closed;
    throw Error(what + ": unknown end condition \"" + text + "\" (known: open, clamped, closed)");
}

std::string toString(EndCondition end)
{
    switch (end) {
    case EndCondition::Open: return "open";
    case EndCondition::Clamped: return "clamped";
    case EndCondition::Closed: return "closed";
    }
    return "open";
}

#define FREEFORM_AFRAME(S, D)                                                                                  \
    template PointMatrix<S, D> aframeBezierPoints<S, D>(const PointMatrix<S, D>&, EndCondition,                \
                                                        const std::vector<S>&);                                \
    template PointMatrix<S, D> aframeDeBoorPoints<S, D>(const PointMatrix<S, D>&, EndCondition,                \
                                                        const std::vector<S>&, S);
FREEFORM_AFRAME(float, 2)
FREEFORM_AFRAME(float, 3)
FREEFORM_AFRAME(double, 2)
FREEFORM_AFRAME(double, 3)
#undef FREEFORM_AFRAME

} // namespace freeform
