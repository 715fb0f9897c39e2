#pragma once
// The document's plain data of geometry: toData, the inverse of buildGeometry for every kind (the
// fields as docs/format.md spells them), what every front end writes back into a document after
// an edit, a conversion or a deformation, said once here.

#include "freeform/brep/part.h"
#include "freeform/curve/nurbs_curve.h"
#include "freeform/curve/rational_bezier_curve.h"
#include "freeform/document/model.h"
#include "freeform/io/document.h"
#include "freeform/surface/nurbs_surface.h"
#include "freeform/surface/rational_bezier_surface.h"

namespace freeform {

/// The data of any geometry, so that buildGeometry(toData(g)) is g again (a spline's intervals as
/// it holds them; a subdivision cage written inline, its file's crease tags as the object's creases
/// and corners). Error when the format cannot hold it: a cage with holes, `creasemethod chaikin` or
/// `smoothtriangles` from its mesh file (the inline form has no field for them).
BezierCurveData toData(const BezierCurve<double, 2>& curve);
BezierCurveData toData(const BezierCurve<double, 3>& curve);
BezierSplineData toData(const BezierSpline<double, 2>& spline);
BezierSplineData toData(const BezierSpline<double, 3>& spline);
/// A nurbs_curve: degree, knots, points; the weights only when the curve is rational (empty
/// weights mean all 1 and are not written).
NurbsCurveData toData(const NurbsCurve<double, 2>& curve);
NurbsCurveData toData(const NurbsCurve<double, 3>& curve);
/// A nurbs_surface: degrees, both knot vectors, the rows x cols grid (rows along u); the weights
/// only when the surface is rational.
NurbsSurfaceData toData(const NurbsSurface<double, 3>& surface);
/// A rational_bezier_curve: points and weights (always written).
RationalBezierCurveData toData(const RationalBezierCurve<double, 2>& curve);
RationalBezierCurveData toData(const RationalBezierCurve<double, 3>& curve);
/// A rational_bezier_surface: degrees, points at i*(n+1) + j and their weights (always written).
RationalBezierSurfaceData toData(const RationalBezierSurface<double, 3>& surface);
DeBoorSplineData toData(const DeBoorSpline<2>& spline);
DeBoorSplineData toData(const DeBoorSpline<3>& spline);
BezierSurfaceData toData(const BezierSurface<double, 3>& surface);
DeBoorSurfaceData toData(const DeBoorSurface& surface);
LatticeData toData(const Lattice& lattice);
/// A trimmed_surface: its NURBS, parameter maps, parameter box and loops (src/document/part_data.cpp).
TrimmedSurfaceData toData(const TrimmedSurface& surface);
/// A part: every face, edge and vertex, the shells and solids, the units.
PartData toData(const Part& part);
SubdivisionSurfaceData toData(const SubdivisionObject& surface);
ObjectData toData(const Geometry& geometry);

/// The control points of an object as its data holds them (dim x count): a curve's, surface's or
/// lattice's points, a subdivision cage's inline vertices (empty when its mesh is a file), a
/// trimmed surface's NURBS grid; nullptr for a part (its faces are not edited point by point).
const PointColumns* dataPoints(const ObjectData& data);
PointColumns* dataPoints(ObjectData& data);

} // namespace freeform
