#include "interaction/manipulation.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

#include "scene/overlay.h"

namespace freeform::editor {

namespace {

Eigen::Vector3d unit(int axis)
{
    return Eigen::Vector3d::Unit(axis);
}

/// The parameter s of the point g + s a (a unit) nearest to the ray o + t d (d unit).
std::optional<double> nearestOnLine(const Eigen::Vector3d& g, const Eigen::Vector3d& a, const Eigen::Vector3d& o,
                                    const Eigen::Vector3d& d)
{
    const double b = a.dot(d);
    const double denominator = 1 - b * b;
    if (denominator < 1e-9) return std::nullopt; // the axis points at the eye
    const Eigen::Vector3d w0 = g - o;
    return (b * d.dot(w0) - a.dot(w0)) / denominator;
}

/// The hit of the ray o + t d on the plane through g with normal n.
std::optional<Eigen::Vector3d> hitPlane(const Eigen::Vector3d& g, const Eigen::Vector3d& n, const Eigen::Vector3d& o,
                                        const Eigen::Vector3d& d)
{
    const double dn = d.dot(n);
    if (std::abs(dn) < 1e-9) return std::nullopt;
    return o + ((g - o).dot(n) / dn) * d;
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b)
{
    return a.x() * b.y() - a.y() * b.x();
}

} // namespace

int constraintAxis(Constraint c)
{
    switch (c) {
    case Constraint::AxisX: case Constraint::PlaneX: return 0;
    case Constraint::AxisY: case Constraint::PlaneY: return 1;
    case Constraint::AxisZ: case Constraint::PlaneZ: return 2;
    default: return -1;
    }
}

bool isPlane(Constraint c)
{
    return c == Constraint::PlaneX || c == Constraint::PlaneY || c == Constraint::PlaneZ;
}

Eigen::Vector3d dragDelta(const ViewTransform& view, Constraint constraint, const Eigen::Vector3d& grab, double x0, double y0,
                          double x, double y)
{
    Eigen::Vector3d o0, d0, o1, d1;
    view.ray(x0, y0, o0, d0);
    view.ray(x, y, o1, d1);
    const int axis = constraintAxis(constraint);
    if (constraint == Constraint::View || isPlane(constraint)) {
        const Eigen::Vector3d n = constraint == Constraint::View ? view.viewDirection : unit(axis);
        const auto a = hitPlane(grab, n, o0, d0), b = hitPlane(grab, n, o1, d1);
        if (!a || !b) return Eigen::Vector3d::Zero();
        Eigen::Vector3d delta = *b - *a;
        if (constraint != Constraint::View) delta[axis] = 0; // exactly in the plane
        // A view along a world axis (front, top, ... ): the move is exactly in that axis's plane,
        // not off it by the rounding of the view's matrices (a flat curve drawn in the top view
        // would get z values like 1e-34).
        for (int r = 0; r < 3; ++r)
            if (constraint == Constraint::View && std::abs(n[(r + 1) % 3]) < 1e-9 && std::abs(n[(r + 2) % 3]) < 1e-9) delta[r] = 0;
        return delta;
    }
    const auto s0 = nearestOnLine(grab, unit(axis), o0, d0), s1 = nearestOnLine(grab, unit(axis), o1, d1);
    if (!s0 || !s1) return Eigen::Vector3d::Zero();
    return (*s1 - *s0) * unit(axis);
}

Eigen::Vector3d snapDelta(const Eigen::Vector3d& grab, const Eigen::Vector3d& delta, Constraint constraint, double step)
{
    if (!(step > 0)) return delta;
    Eigen::Vector3d target = grab + delta;
    const int axis = constraintAxis(constraint);
    for (int r = 0; r < 3; ++r) {
        const bool moves = constraint == Constraint::View || (isPlane(constraint) ? r != axis : r == axis);
        if (moves) target[r] = std::round(target[r] / step) * step;
    }
    return target - grab;
}

double falloff(double d, double radius)
{
    if (!(radius > 0) || d >= radius) return 0;
    const double t = d / radius;
    return 1 - t * t * (3 - 2 * t);
}

std::vector<double> softWeights(const Eigen::Matrix3Xd& points, const std::vector<int>& selected, double radius)
{
    std::vector<double> w(static_cast<std::size_t>(points.cols()), 0.0);
    for (int k : selected) w[static_cast<std::size_t>(k)] = 1;
    if (!(radius > 0)) return w;
    for (Eigen::Index k = 0; k < points.cols(); ++k) {
        if (w[static_cast<std::size_t>(k)] == 1) continue;
        double nearest = std::numeric_limits<double>::infinity();
        for (int s : selected) nearest = std::min(nearest, (points.col(k) - points.col(s)).norm());
        w[static_cast<std::size_t>(k)] = falloff(nearest, radius);
    }
    return w;
}

std::optional<Constraint> Gizmo::pick(const ViewTransform& view, double x, double y) const
{
    const std::optional<Eigen::Vector3d> c = view.toPixel(centre);
    if (!c) return std::nullopt;
    const double length = axisPixels * view.worldPerPixel(centre);
    const Eigen::Vector2d p(x, y);
    std::optional<Constraint> best;
    double bestDistance = pickPixels;
    const Constraint axes[3] = {Constraint::AxisX, Constraint::AxisY, Constraint::AxisZ};
    const Constraint planes[3] = {Constraint::PlaneX, Constraint::PlaneY, Constraint::PlaneZ};
    for (int a = 0; a < 3; ++a) {
        const std::optional<Eigen::Vector3d> e = view.toPixel(centre + length * unit(a));
        if (!e) continue;
        const Eigen::Vector2d s = c->head<2>(), t = e->head<2>();
        const double len2 = (t - s).squaredNorm();
        if (len2 < 4) continue; // seen end on
        const double u = std::clamp((p - s).dot(t - s) / len2, 0.0, 1.0);
        const double d = (s + u * (t - s) - p).norm();
        if (u > squareTo * 0.5 && d < bestDistance) { // the arrow, beyond the centre's crowd
            bestDistance = d;
            best = axes[a];
        }
    }
    if (best) return best;
    for (int a = 0; a < 3; ++a) {
        const Eigen::Vector3d u = unit((a + 1) % 3), v = unit((a + 2) % 3);
        Eigen::Vector2d q[4];
        bool ok = true;
        const double f[4][2] = {{squareFrom, squareFrom}, {squareTo, squareFrom}, {squareTo, squareTo}, {squareFrom, squareTo}};
        for (int k = 0; k < 4 && ok; ++k) {
            const auto pk = view.toPixel(centre + length * (f[k][0] * u + f[k][1] * v));
            if (!pk) ok = false;
            else q[k] = pk->head<2>();
        }
        if (!ok) continue;
        // Seen edge on, a square has no area and cannot be picked (its plane would not move).
        const double area = 0.5 * std::abs(cross2(q[2] - q[0], q[3] - q[1]));
        if (area < 16) continue;
        int positive = 0, negative = 0;
        for (int k = 0; k < 4; ++k) {
            const double s = cross2(q[(k + 1) % 4] - q[k], p - q[k]);
            positive += s > 0;
            negative += s < 0;
        }
        if (positive == 4 || negative == 4) return planes[a];
    }
    return std::nullopt;
}

void Gizmo::draw(const ViewTransform& view, Overlay& overlay, std::optional<Constraint> highlight) const
{
    const double length = axisPixels * view.worldPerPixel(centre);
    if (!(length > 0)) return;
    const Vec3f colors[3] = {Vec3f(0.95f, 0.3f, 0.3f), Vec3f(0.35f, 0.9f, 0.35f), Vec3f(0.35f, 0.55f, 1.0f)};
    const Vec3f bright(1.0f, 0.95f, 0.4f);
    const Constraint axes[3] = {Constraint::AxisX, Constraint::AxisY, Constraint::AxisZ};
    const Constraint planes[3] = {Constraint::PlaneX, Constraint::PlaneY, Constraint::PlaneZ};
    const Eigen::Vector3d back = -view.viewDirection;
    for (int a = 0; a < 3; ++a) {
        const Vec3f color = highlight == axes[a] ? bright : colors[a];
        const Eigen::Vector3d tip = centre + length * unit(a);
        overlay.addLine(centre.cast<float>(), tip.cast<float>(), color, true);
        // Arrow head: two short strokes in the plane of the axis and the view direction.
        Eigen::Vector3d side = unit(a).cross(back);
        if (side.norm() < 1e-6) side = unit((a + 1) % 3);
        side.normalize();
        const Eigen::Vector3d base = tip - 0.14 * length * unit(a);
        overlay.addLine(tip.cast<float>(), (base + 0.06 * length * side).cast<float>(), color, true);
        overlay.addLine(tip.cast<float>(), (base - 0.06 * length * side).cast<float>(), color, true);
        // The plane square with this axis as its normal, in the colour of the normal.
        const Vec3f squareColor = highlight == planes[a] ? bright : colors[a];
        const Eigen::Vector3d u = unit((a + 1) % 3), v = unit((a + 2) % 3);
        const Eigen::Vector3d q[4] = {centre + length * (squareFrom * u + squareFrom * v), centre + length * (squareTo * u + squareFrom * v),
                                      centre + length * (squareTo * u + squareTo * v), centre + length * (squareFrom * u + squareTo * v)};
        for (int k = 0; k < 4; ++k) overlay.addLine(q[k].cast<float>(), q[(k + 1) % 4].cast<float>(), squareColor, true);
    }
    (void)view;
}

} // namespace freeform::editor
