#pragma once
// The document's plain data of rational and NURBS geometry (the inverse of buildGeometry for these
// four types; the fields as docs/format.md spells them): what every front end writes back into a
// document after an edit, a conversion or a deformation, said once here.

#include "freeform/curve/nurbs_curve.h"
#include "freeform/curve/rational_bezier_curve.h"
#include "freeform/io/document.h"
#include "freeform/surface/nurbs_surface.h"
#include "freeform/surface/rational_bezier_surface.h"

namespace freeform {

/// A nurbs_curve: degree, knots, points; the weights only when the curve is rational (empty
/// weights mean all 1 and are not written).
NurbsCurveData nurbsCurveData(const NurbsCurve<double, 2>& curve);
NurbsCurveData nurbsCurveData(const NurbsCurve<double, 3>& curve);

/// A nurbs_surface: degrees, both knot vectors, the rows x cols grid (rows along u); the weights
/// only when the surface is rational.
NurbsSurfaceData nurbsSurfaceData(const NurbsSurface<double, 3>& surface);

/// A rational_bezier_curve: points and weights (always written).
RationalBezierCurveData rationalCurveData(const RationalBezierCurve<double, 2>& curve);
RationalBezierCurveData rationalCurveData(const RationalBezierCurve<double, 3>& curve);

/// A rational_bezier_surface: degrees, points at i*(n+1) + j and their weights (always written).
RationalBezierSurfaceData rationalSurfaceData(const RationalBezierSurface<double, 3>& surface);

} // namespace freeform
