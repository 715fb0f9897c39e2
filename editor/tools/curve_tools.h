#pragma once
// Operations of the curve and spline tools on document data (no scene, no ImGui): each returns new
// data and leaves its input alone; Error (freeform::Error) when the operation does not apply, with
// nothing changed. Shape-preserving operations (degree elevation, splitting, inserting a spline
// joint) are exact in the sense of the library functions they call; inserting or deleting a
// Bézier curve's control point changes the curve (it changes the degree by one). Joint handle
// modes (JointMode) are applied to one joint by the library's joins (curve/joins.h): aligned =
// joinG1, mirrored = joinC1, C2 = joinC2 (cubics), each moving only the side opposite the kept
// handle; enforceJointModes keeps all of them after any edit.

#include <Eigen/Core>

#include <utility>
#include <vector>

#include "freeform/curve/aframe.h"
#include "freeform/curve/bezier_spline.h"
#include "freeform/curve/continuity.h"
#include "freeform/curve/joins.h"
#include "freeform/io/document.h"
#include "scene/settings.h"

namespace freeform::editor {

using Points3 = Eigen::Matrix<double, 3, Eigen::Dynamic>;

/// 2D or 3D columns as 3D (z = 0 for 2D) and back (rows = 2 drops z).
Points3 toPoints3(const PointColumns& points);
PointColumns fromPoints3(const Points3& points, Eigen::Index rows);

// ---------------------------------------------------------------- Bézier curves
/// The same curve one degree higher (BezierCurve::elevated).
BezierCurveData elevateCurve(const BezierCurveData& curve);
/// The pieces over [0, t] and [t, 1], t in (0, 1).
std::pair<BezierCurveData, BezierCurveData> splitCurve(const BezierCurveData& curve, double t);
/// A new control point p inserted at index `at` (0..n+1; n+1 appends): the degree grows by one.
BezierCurveData insertCurvePoint(const BezierCurveData& curve, int at, const Eigen::Vector3d& p);
/// Control point k removed (the degree drops by one); Error when it is the last one.
BezierCurveData deleteCurvePoint(const BezierCurveData& curve, int k);
/// The levels of the de Casteljau triangle at t: level r holds n + 1 - r points (level 0 the
/// control points, level n the curve point f(t)).
std::vector<Points3> deCasteljauLevels(const Points3& points, double t);

// ---------------------------------------------------------------- Bézier splines
BezierSpline<double, 3> toSpline(const BezierSplineData& data);
BezierSplineData fromSpline(const BezierSpline<double, 3>& spline, Eigen::Index rows);
/// Every segment one degree higher (the curve is unchanged).
BezierSplineData elevateSpline(const BezierSplineData& spline);
/// A C-infinity joint inserted at global parameter T (strictly inside a segment): shape unchanged.
BezierSplineData insertJoint(const BezierSplineData& spline, double T);
/// Joint j removed (BezierSpline::removeJoint: the neighbours' continuity is kept up to order
/// (n-1)/2); Error for an end joint of an open spline.
BezierSplineData deleteJoint(const BezierSplineData& spline, int joint);
/// An open spline cut at global parameter T (inside the domain) into the parts before and after.
std::pair<BezierSplineData, BezierSplineData> splitSpline(const BezierSplineData& spline, double T);
/// The joint a control point belongs to: itself for a joint, the nearer joint for a handle
/// (inner points of segments of degree >= 3 between two joints go to the nearer one).
int jointOfPoint(const BezierSplineData& spline, int point);
/// Which side of joint j the point is: -1 the left handle (or further left), +1 the right,
/// 0 the joint itself.
int sideOfPoint(const BezierSplineData& spline, int joint, int point);
/// Column of joint j (closed splines: j mod L).
int jointColumn(const BezierSplineData& spline, int joint);
/// Whether joint j has a segment on each side (interior joints of open splines, every joint of a
/// closed spline with at least two segments).
bool isInnerJoint(const BezierSplineData& spline, int joint);
/// Joint j given mode `mode` keeping the side `keepSide` (-1: keep the left handle and move the
/// right one; +1 the opposite). Free changes nothing. Error: C2 on a non-cubic spline, aligned with
/// a handle on the joint.
BezierSplineData applyJointMode(const BezierSplineData& spline, int joint, JointMode mode, int keepSide);
/// After control points `moved` changed (the old data `before`, whose joints keep their modes, and
/// the new `after`), every inner joint's mode is enforced again, whichever points moved
/// (docs/editor.md, "Joints of a bezier_spline"): a joint point moved without its handles carries
/// them along; the moved (and carried) points stay where they were put when the modes allow it.
/// Every inner joint C2 on a cubic: the de Boor polygon of `before` is changed least (minimum norm)
/// so that the moved Bézier points land where they were put (least squares when they cannot all),
/// and the result is C2 by construction. Otherwise (mixed modes): the mirrored (C1) and C2 joints'
/// conditions are linear and an aligned joint's is too once its direction is chosen (the moved
/// handle's when one of its two handles moved, else the bisector of both); the points not moved
/// change least so that all of them hold, with the joint points kept in place if possible.
BezierSplineData enforceJointModes(const BezierSplineData& before, const BezierSplineData& after,
                                   const std::vector<JointMode>& modes, const std::vector<int>& moved);
/// Continuity of every inner joint (continuity.h), in 3D.
std::vector<JointContinuity<double>> splineContinuity(const BezierSplineData& spline);

/// The de Boor points of a C2 cubic spline (clamped ends for open splines, periodic for closed),
/// and back: the Bézier points of de Boor points under the same end condition and intervals.
EndCondition deBoorEnd(const BezierSplineData& spline);
Points3 splineDeBoorPoints(const BezierSplineData& spline);
BezierSplineData splineFromDeBoor(const BezierSplineData& spline, const Points3& deboor);

/// The curvature comb of a 3D curve sampled at `ts` by `f` (position, first and second
/// derivative): pairs (point, point - scale * curvature vector) as columns 2i, 2i+1.
Points3 curvatureComb(const std::vector<Eigen::Matrix<double, 3, 3>>& derivatives, double scale);

} // namespace freeform::editor
