#pragma once
// Open CASCADE's curves and surfaces in their exact NURBS forms, in their own parameters
// (brep/exact_forms.h). Private to freeform_cad.

#include <string>
#include <utility>

#include <Geom2d_Curve.hxx>
#include <Geom_Curve.hxx>
#include <Geom_Surface.hxx>

#include "freeform/brep/exact_forms.h"

namespace freeform::occt {

/// The curve on [f, l]; Error for kinds without an exact rational form (offset curves).
MappedCurve<3> exactCurve(const Handle(Geom_Curve)& curve, double f, double l);
MappedCurve<2> exactCurve2d(const Handle(Geom2d_Curve)& curve, double f, double l);
/// The surface over the face's parameter box, and its kind as the file gave it ("plane",
/// "cylinder", "cone", "sphere", "torus", "revolution", "extrusion", "bspline", "bezier").
std::pair<MappedSurface, std::string> exactSurface(const Handle(Geom_Surface)& surface, double u0, double u1, double v0,
                                                   double v1);

} // namespace freeform::occt
