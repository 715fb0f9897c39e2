#pragma once
// The math of moving control points with the pointer: the drag through the grab point (in the view
// plane, along an axis, or in an axis plane), snapping to the grid, the proportional ("soft")
// falloff, and the translate gizmo's screen-space geometry. Pure functions: no GL, no ImGui.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <optional>
#include <vector>

#include "interaction/picking.h"
#include "scene/grid.h" // gridStep: the step snapping uses

namespace freeform::editor {

struct Overlay;

/// How a drag moves the points. Axis*: along a world axis through the grab point; Plane*: in the
/// world plane through the grab point whose normal is the named axis (PlaneX: the y-z plane).
enum class Constraint { View, AxisX, AxisY, AxisZ, PlaneX, PlaneY, PlaneZ };

/// The axis (0, 1, 2) of an Axis* or Plane* constraint, -1 for View.
int constraintAxis(Constraint c);
bool isPlane(Constraint c);

/// The world displacement of a drag from pixel (x0, y0) to (x, y) that starts at `grab`:
/// View: the difference of the two cursor rays' hits on the plane through grab orthogonal to the
/// view direction; Axis: the difference of the points on the axis line through grab nearest to the
/// two rays; Plane: the difference of the rays' hits on the axis plane through grab. Zero when a
/// ray is parallel to the plane (or to the axis, seen end on).
Eigen::Vector3d dragDelta(const ViewTransform& view, Constraint constraint, const Eigen::Vector3d& grab, double x0, double y0,
                          double x, double y);

/// The delta that puts grab + delta on the grid of spacing `step` in the coordinates the
/// constraint moves (all three for View, one for an axis, two for a plane); the others keep
/// grab + delta's value. step <= 0: delta unchanged.
Eigen::Vector3d snapDelta(const Eigen::Vector3d& grab, const Eigen::Vector3d& delta, Constraint constraint, double step);

/// The proportional-editing weight at distance d from the nearest selected point: 1 - 3 t^2 +
/// 2 t^3 with t = d / radius (1 at the point, 0 with zero slope at the radius), 0 beyond.
double falloff(double d, double radius);

/// Weights of every point (3 x N): 1 for the selected ones, falloff of the distance to the nearest
/// selected point for the others (radius <= 0: 0 for all others).
std::vector<double> softWeights(const Eigen::Matrix3Xd& points, const std::vector<int>& selected, double radius);

/// The translate gizmo: three axis arrows and three plane squares at `centre`, sized in pixels.
struct Gizmo {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    double axisPixels = 90;        // arrow length on screen
    double pickPixels = 7;         // distance to an arrow that still picks it
    double squareFrom = 0.22, squareTo = 0.42; // plane squares, as fractions of the arrow length

    /// The handle under pixel (x, y): an Axis* or Plane* constraint, or nothing.
    std::optional<Constraint> pick(const ViewTransform& view, double x, double y) const;
    /// Adds the arrows and squares to the overlay (on top), `highlight` drawn brighter.
    void draw(const ViewTransform& view, Overlay& overlay, std::optional<Constraint> highlight) const;
};

} // namespace freeform::editor
