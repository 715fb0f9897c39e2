// Names of the interpolation options, and the explicit instantiations of the spline templates
// (BezierSpline, joins, continuity, interpolation) for float/double x 2D/3D.

#include "freeform/curve/bezier_spline.h"
#include "freeform/curve/continuity.h"
#include "freeform/curve/interpolation.h"
#include "freeform/curve/joins.h"

namespace freeform {

InterpolationEnd parseInterpolationEnd(const std::string& text, const std::string& what)
{
    if (text == "natural") return InterpolationEnd::Natural;
    if (text == "clamped") return InterpolationEnd::Clamped;
    if (text == "periodic") return InterpolationEnd::Periodic;
    throw Error(what + ": unknown end condition \"" + text + "\" (known: natural, clamped, periodic)");
}

std::string toString(InterpolationEnd end)
{
    switch (end) {
    case InterpolationEnd::Natural: return "natural";
    case InterpolationEnd::Clamped: return "clamped";
    case InterpolationEnd::Periodic: return "periodic";
    }
    return "natural";
}

Parametrization parseParametrization(const std::string& text, const std::string& what)
{
    if (text == "uniform") return Parametrization::Uniform;
    if (text == "chord") return Parametrization::Chord;
    if (text == "centripetal") return Parametrization::Centripetal;
    throw Error(what + ": unknown parametrization \"" + text + "\" (known: uniform, chord, centripetal)");
}

std::string toString(Parametrization param)
{
    switch (param) {
    case Parametrization::Uniform: return "uniform";
    case Parametrization::Chord: return "chord";
    case Parametrization::Centripetal: return "centripetal";
    }
    return "chord";
}

#define FREEFORM_SPLINE(S, D)                                                                                      \
    template class BezierSpline<S, D>;                                                                             \
    template BezierSpline<S, D> joinC1<S, D>(const BezierSpline<S, D>&, int, JoinMove);                             \
    template BezierSpline<S, D> joinG1<S, D>(const BezierSpline<S, D>&, int, JoinMove);                             \
    template BezierSpline<S, D> joinC2<S, D>(const BezierSpline<S, D>&, int, JoinMove);                             \
    template void joinC0<S, D>(PointMatrix<S, D>&, PointMatrix<S, D>&, JoinMove);                                   \
    template void joinC1<S, D>(PointMatrix<S, D>&, PointMatrix<S, D>&, S, S, JoinMove);                             \
    template void joinG1<S, D>(PointMatrix<S, D>&, PointMatrix<S, D>&, JoinMove);                                   \
    template void joinC2<S, D>(PointMatrix<S, D>&, PointMatrix<S, D>&, S, S, JoinMove);                             \
    template JointContinuity<S> jointContinuity<S, D>(const PointMatrix<S, D>&, const PointMatrix<S, D>&, S, S,    \
                                                      const ContinuityTolerances<S>&);                             \
    template std::vector<JointContinuity<S>> continuityReport<S, D>(const BezierSpline<S, D>&,                     \
                                                                    const ContinuityTolerances<S>&);               \
    template std::vector<S> parameterGaps<S, D>(const PointMatrix<S, D>&, Parametrization, bool);                  \
    template BezierSpline<S, D> interpolateCubic<S, D>(const PointMatrix<S, D>&, const InterpolationOptions<S, D>&);
FREEFORM_SPLINE(float, 2)
FREEFORM_SPLINE(float, 3)
FREEFORM_SPLINE(double, 2)
FREEFORM_SPLINE(double, 3)
#undef FREEFORM_SPLINE

} // namespace freeform
