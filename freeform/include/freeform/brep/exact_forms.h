#pragma once
// Exact NURBS forms of the curves and surfaces of CAD files, in the file's own parameters
// (docs/cad.md, "Exact forms"; brep/parameter_map.h says how the parameters relate).
//
// A MappedCurve is a NURBS curve with a parameter map and the file's parameter range
// [first, last]: point(t) = nurbs(map(t)). A MappedSurface is a NURBS surface with a map per
// direction. Lines, parabolas, B-splines, Bézier curves and planes keep their parameter; circles,
// ellipses and the angular directions of cylinders, cones, spheres, tori and surfaces of
// revolution become rational quadratic arcs (at most a quarter turn each) on a half-angle map;
// hyperbolas a rational quadratic on e^t. The constructions are exact: only the rounding of the
// control points (and of tan or exp in the map) separates point(t) from the analytic value.

#include <Eigen/Core>

#include "freeform/brep/parameter_map.h"
#include "freeform/curve/nurbs_curve.h"
#include "freeform/surface/nurbs_surface.h"

namespace freeform {

template <int Dim>
struct MappedCurve {
    using Vec = Eigen::Matrix<double, Dim, 1>;
    NurbsCurve<double, Dim> nurbs;
    ParameterMap map;
    double first = 0, last = 1; // the file's parameter range

    Vec point(double t) const { return nurbs.evaluate(map(t)); }
    /// The direction of dC/dt: the NURBS derivative at map(t) (the map is increasing, so only the
    /// length differs from the derivative in the file's parameter).
    Vec tangent(double t) const { return nurbs.derivatives(map(t), 1).col(1); }
};

struct MappedSurface {
    NurbsSurface<double, 3> nurbs;
    ParameterMap mapU, mapV;

    Eigen::Vector3d point(double u, double v) const { return nurbs.evaluate(mapU(u), mapV(v)); }
    /// The unit normal S_u x S_v (zero where the surface is degenerate, e.g. at a sphere's pole);
    /// the maps are increasing, so its direction is the NURBS surface's.
    Eigen::Vector3d normal(double u, double v) const { return nurbs.normal(mapU(u), mapV(v)); }
};

// ---- curves (Dim 2 and 3), each on the file's parameter range [t0, t1] -----------------------------

/// origin + t * direction.
template <int Dim>
MappedCurve<Dim> exactLine(const Eigen::Matrix<double, Dim, 1>& origin, const Eigen::Matrix<double, Dim, 1>& direction,
                           double t0, double t1);
/// center + a cos t X + b sin t Y (a circle when a = b).
template <int Dim>
MappedCurve<Dim> exactEllipse(const Eigen::Matrix<double, Dim, 1>& center, const Eigen::Matrix<double, Dim, 1>& X,
                              const Eigen::Matrix<double, Dim, 1>& Y, double a, double b, double t0, double t1);
/// center + a cosh t X + b sinh t Y.
template <int Dim>
MappedCurve<Dim> exactHyperbola(const Eigen::Matrix<double, Dim, 1>& center, const Eigen::Matrix<double, Dim, 1>& X,
                                const Eigen::Matrix<double, Dim, 1>& Y, double a, double b, double t0, double t1);
/// vertex + t^2 / (4 focal) X + t Y.
template <int Dim>
MappedCurve<Dim> exactParabola(const Eigen::Matrix<double, Dim, 1>& vertex, const Eigen::Matrix<double, Dim, 1>& X,
                               const Eigen::Matrix<double, Dim, 1>& Y, double focal, double t0, double t1);
/// A NURBS curve restricted to [t0, t1] of its domain (knot insertion: the parameter is kept).
template <int Dim>
MappedCurve<Dim> exactRestriction(const NurbsCurve<double, Dim>& curve, const ParameterMap& map, double t0, double t1);

// ---- surfaces -------------------------------------------------------------------------------------

/// origin + u X + v Y on [u0, u1] x [v0, v1].
MappedSurface exactPlane(const Eigen::Vector3d& origin, const Eigen::Vector3d& X, const Eigen::Vector3d& Y, double u0,
                         double u1, double v0, double v1);
/// The meridian turned about the axis (origin, unit axis) by the angle u in [u0, u1] (right-handed
/// about the axis): S(u, v) = rotation(u) meridian(v). v keeps the meridian's parameter and map.
MappedSurface exactRevolution(const MappedCurve<3>& meridian, const Eigen::Vector3d& origin, const Eigen::Vector3d& axis,
                              double u0, double u1);
/// base(u) + v direction for v in [v0, v1]; u keeps the base curve's parameter and map.
MappedSurface exactExtrusion(const MappedCurve<3>& base, const Eigen::Vector3d& direction, double v0, double v1);

} // namespace freeform
