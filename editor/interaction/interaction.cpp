#include "interaction/interaction.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "interaction/keymap.h"

namespace freeform::editor {

namespace {

const Vec3f kSelectedColor(0.3f, 0.95f, 1.0f);
const Vec3f kHoverColor(1.0f, 1.0f, 1.0f);
const Vec3f kActiveColor(0.55f, 1.0f, 0.55f);
const Vec3f kSoftColor(0.85f, 0.5f, 1.0f);
const Vec3f kBoxColor(0.9f, 0.9f, 0.9f);

bool pickable(const Scene& scene, int i)
{
    const SceneItem& it = scene.item(i);
    return it.settings.visible && it.kind == SceneItem::Kind::DocumentObject;
}

/// Unit vectors of the view plane at p (pixels right and up) and the world length of a pixel.
void viewPlane(const ViewTransform& view, const Eigen::Vector3d& p, Eigen::Vector3d& right, Eigen::Vector3d& up)
{
    const auto q = view.toPixel(p);
    if (!q) {
        right = Eigen::Vector3d::UnitX();
        up = Eigen::Vector3d::UnitY();
        return;
    }
    right = (view.unproject(q->x() + 1, q->y(), q->z()) - view.unproject(q->x(), q->y(), q->z())).normalized();
    up = (view.unproject(q->x(), q->y() - 1, q->z()) - view.unproject(q->x(), q->y(), q->z())).normalized();
}

} // namespace

double Interaction::pickRadius(const Scene& scene) const
{
    return 0.5 * scene.display.pointSize + settings_.pickSlack;
}

double Interaction::softRadius(const Scene& scene) const
{
    if (settings_.softRadius > 0) return settings_.softRadius;
    return 0.25 * scene.bounds().diagonal().norm();
}

std::optional<std::pair<int, int>> Interaction::pickControlPoint(const Scene& scene, const Selection& selection,
                                                                 const ViewTransform& view, double x, double y) const
{
    const double radius = pickRadius(scene);
    if (selection.item >= 0 && selection.item < scene.itemCount() && pickable(scene, selection.item))
        if (const auto k = pickPoint(view, scene.controlPoints(selection.item), x, y, radius)) return std::pair{selection.item, *k};
    if (!scene.display.controlPoints) return std::nullopt;
    std::optional<std::pair<int, int>> best;
    double bestDistance = radius;
    for (int i = 0; i < scene.itemCount(); ++i) {
        if (i == selection.item || !pickable(scene, i)) continue;
        const Eigen::Matrix3Xd points = scene.controlPoints(i);
        const auto k = pickPoint(view, points, x, y, radius);
        if (!k) continue;
        const auto q = view.toPixel(points.col(*k));
        const double d = std::hypot(q->x() - x, q->y() - y);
        if (!best || d < bestDistance) {
            best = std::pair{i, *k};
            bestDistance = d;
        }
    }
    return best;
}

std::optional<int> Interaction::pickItem(const Scene& scene, const ViewTransform& view, double x, double y) const
{
    // Curves within the pick radius on screen win over surfaces (they lie on them, often).
    std::optional<int> curve;
    double curveDistance = pickRadius(scene);
    for (int i = 0; i < scene.itemCount(); ++i) {
        const SceneItem& it = scene.item(i);
        if (!it.settings.visible || it.geometry.curve.cols() == 0) continue;
        const auto d = pixelDistanceToPolyline(view, it.geometry.curve, x, y);
        if (d && *d <= curveDistance) {
            curve = i;
            curveDistance = *d;
        }
    }
    if (curve) return curve;
    Eigen::Vector3d origin, direction;
    view.ray(x, y, origin, direction);
    std::optional<int> surface;
    double nearest = std::numeric_limits<double>::infinity();
    for (int i = 0; i < scene.itemCount(); ++i) {
        const SceneItem& it = scene.item(i);
        if (!it.settings.visible || !it.geometry.surface) continue;
        if (!it.geometry.bounds.isEmpty()) {
            // Slab test against the item's box first: most items are not under the pointer.
            const Eigen::AlignedBox3d& b = it.geometry.bounds;
            double t0 = -std::numeric_limits<double>::infinity(), t1 = std::numeric_limits<double>::infinity();
            for (int r = 0; r < 3; ++r) {
                if (direction[r] == 0) {
                    if (origin[r] < b.min()[r] || origin[r] > b.max()[r]) t0 = 1, t1 = 0;
                    continue;
                }
                double a = (b.min()[r] - origin[r]) / direction[r], c = (b.max()[r] - origin[r]) / direction[r];
                if (a > c) std::swap(a, c);
                t0 = std::max(t0, a);
                t1 = std::min(t1, c);
            }
            if (t0 > t1 || t1 < 0 || t0 > nearest) continue;
        }
        const auto t = rayMesh(origin, direction, *it.geometry.surface);
        if (t && *t < nearest) {
            nearest = *t;
            surface = i;
        }
    }
    return surface;
}

std::optional<Eigen::Vector3d> Interaction::selectionCentre(const Scene& scene, const Selection& selection) const
{
    if (selection.item < 0 || selection.item >= scene.itemCount() || selection.points.empty()) return std::nullopt;
    const Eigen::Matrix3Xd points = scene.controlPoints(selection.item);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int n = 0;
    for (int k : selection.points)
        if (k < points.cols()) sum += points.col(k), ++n;
    if (n == 0) return std::nullopt;
    return sum / n;
}

void Interaction::startMove(Scene& scene, const Selection& selection, Constraint constraint, int grabPoint, double x, double y)
{
    item_ = selection.item;
    const Eigen::Matrix3Xd points = scene.controlPoints(item_);
    std::vector<int> selected;
    for (int k : selection.points)
        if (k < points.cols()) selected.push_back(k);
    const std::vector<double> w = softWeights(points, selected, settings_.soft ? softRadius(scene) : 0.0);
    moving_.clear();
    weights_.clear();
    for (std::size_t k = 0; k < w.size(); ++k)
        if (w[k] > 0) moving_.push_back(static_cast<int>(k)), weights_.push_back(w[k]);
    start_.resize(3, static_cast<Eigen::Index>(moving_.size()));
    grabIndex_ = -1;
    for (std::size_t j = 0; j < moving_.size(); ++j) {
        start_.col(static_cast<Eigen::Index>(j)) = points.col(moving_[j]);
        if (moving_[j] == grabPoint) grabIndex_ = static_cast<int>(j);
    }
    if (grabIndex_ >= 0) grab_ = points.col(grabPoint);
    else if (const auto c = selectionCentre(scene, selection)) grab_ = *c;
    constraint_ = constraint;
    startX_ = x_ = x;
    startY_ = y_ = y;
    step_ = gridStep(scene.bounds());
    lastDelta_ = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
    moved_ = false;
    scene.beginMerge();
}

void Interaction::applyMove(Scene& scene, const ViewTransform& view, double x, double y)
{
    x_ = x;
    y_ = y;
    Eigen::Vector3d delta = dragDelta(view, constraint_, grab_, startX_, startY_, x, y);
    if (settings_.snap) delta = snapDelta(grab_, delta, constraint_, step_);
    if (delta == lastDelta_ || moving_.empty() || (!moved_ && delta.isZero(0))) return;
    lastDelta_ = delta;
    moved_ = true;
    Eigen::Matrix3Xd p(3, start_.cols());
    for (Eigen::Index j = 0; j < start_.cols(); ++j) p.col(j) = start_.col(j) + weights_[static_cast<std::size_t>(j)] * delta;
    if (grabIndex_ >= 0) p.col(grabIndex_) = grab_ + delta; // with snapping: exactly the grid node
    if (settings_.snap && grabIndex_ >= 0) {
        const Eigen::Vector3d target = snapDelta(Eigen::Vector3d::Zero(), grab_ + delta, constraint_, step_);
        const int axis = constraintAxis(constraint_);
        for (int r = 0; r < 3; ++r) {
            const bool moves = constraint_ == Constraint::View || (isPlane(constraint_) ? r != axis : r == axis);
            if (moves) p(r, grabIndex_) = target[r];
        }
    }
    scene.setControlPoints(item_, moving_, p, mode_ == Mode::Grab ? "grab points" : "move points");
}

void Interaction::setConstraint(Scene& scene, const ViewTransform& view, Constraint c)
{
    constraint_ = constraint_ == c ? Constraint::View : c;
    lastDelta_ = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
    applyMove(scene, view, x_, y_);
}

bool Interaction::press(Scene& scene, Selection& selection, const ViewTransform& view, int button, int mods, double x, double y)
{
    if (mode_ == Mode::Grab) {
        if (button == GLFW_MOUSE_BUTTON_LEFT) finish(scene);
        else cancel(scene);
        return true;
    }
    if (mode_ != Mode::None) return true;
    if (button != GLFW_MOUSE_BUTTON_LEFT) return false;
    const bool shift = mods & GLFW_MOD_SHIFT, ctrl = mods & GLFW_MOD_CONTROL;
    // A control point of the selected object under the pointer wins over a gizmo handle drawn
    // across it (docs/editor.md, "Gizmo"): the point is what the user aims at, and the handle can
    // be taken anywhere else along its length.
    const auto pointHit = pickControlPoint(scene, selection, view, x, y);
    const bool pointOfSelected = pointHit && pointHit->first == selection.item;
    if (!ctrl && !shift && !pointOfSelected && settings_.gizmo && selection.item >= 0 && selection.item < scene.itemCount()) {
        if (const auto centre = selectionCentre(scene, selection)) {
            Gizmo g;
            g.centre = *centre;
            if (const auto c = g.pick(view, x, y)) {
                // The point clicked last (if still selected) is the one that snaps exactly.
                mode_ = Mode::Drag;
                startMove(scene, selection, *c, selection.has(activePoint_) ? activePoint_ : -1, x, y);
                return true;
            }
        }
    }
    if (!ctrl) {
        if (const auto& hit = pointHit) {
            const auto [item, k] = *hit;
            if (shift) {
                if (item != selection.item) {
                    selection.selectItem(item);
                    selection.setPoints({k});
                } else {
                    selection.togglePoint(k);
                }
                activePoint_ = selection.has(k) ? k : -1;
                return true;
            }
            if (item != selection.item || !selection.has(k)) {
                selection.selectItem(item);
                selection.setPoints({k});
            }
            activePoint_ = k;
            mode_ = Mode::Drag;
            startMove(scene, selection, Constraint::View, k, x, y);
            return true;
        }
        return false;
    }
    mode_ = Mode::Box;
    boxAdd_ = shift;
    startX_ = x_ = x;
    startY_ = y_ = y;
    return true;
}

void Interaction::move(Scene& scene, Selection& selection, const ViewTransform& view, double x, double y)
{
    if (mode_ == Mode::Drag || mode_ == Mode::Grab) {
        applyMove(scene, view, x, y);
        return;
    }
    if (mode_ == Mode::Box) {
        x_ = x;
        y_ = y;
        return;
    }
    const auto hit = pickControlPoint(scene, selection, view, x, y);
    selection.hoverItem = hit ? hit->first : -1;
    selection.hoverPoint = hit ? hit->second : -1;
    gizmoHover_.reset();
    if (settings_.gizmo && !(hit && hit->first == selection.item)) // a point of the selection wins (press)
        if (const auto centre = selectionCentre(scene, selection)) {
            Gizmo g;
            g.centre = *centre;
            gizmoHover_ = g.pick(view, x, y);
        }
}

void Interaction::release(Scene& scene, Selection& selection, const ViewTransform& view, int button, int mods, double x, double y)
{
    (void)mods;
    if (button != GLFW_MOUSE_BUTTON_LEFT) return;
    if (mode_ == Mode::Drag) {
        applyMove(scene, view, x, y);
        finish(scene);
    } else if (mode_ == Mode::Box) {
        mode_ = Mode::None;
        std::vector<int> items;
        if (selection.item >= 0 && selection.item < scene.itemCount()) items.push_back(selection.item);
        if (scene.display.controlPoints || items.empty())
            for (int i = 0; i < scene.itemCount(); ++i)
                if (i != selection.item) items.push_back(i);
        for (int i : items) {
            if (!pickable(scene, i)) continue;
            const std::vector<int> inside = pointsInBox(view, scene.controlPoints(i), startX_, startY_, x, y);
            if (inside.empty()) continue;
            if (i != selection.item) {
                selection.selectItem(i);
                selection.setPoints(inside);
            } else {
                std::vector<int> all = boxAdd_ ? selection.points : std::vector<int>{};
                all.insert(all.end(), inside.begin(), inside.end());
                selection.setPoints(all);
            }
            return;
        }
        if (!boxAdd_) selection.points.clear();
    }
}

void Interaction::click(Scene& scene, Selection& selection, const ViewTransform& view, int mods, double x, double y)
{
    if (const auto i = pickItem(scene, view, x, y)) {
        if (*i != selection.item) selection.selectItem(*i);
        else if (!(mods & GLFW_MOD_SHIFT)) selection.points.clear();
        // A part: the face under the pointer (its triangles' vertices know their face).
        const ItemGeometry& g = scene.item(*i).geometry;
        selection.face = -1;
        if (g.surface && g.vertexFace.size() == static_cast<std::size_t>(g.surface->vertexCount())) {
            Eigen::Vector3d origin, direction;
            view.ray(x, y, origin, direction);
            if (const auto hit = rayMeshHit(origin, direction, *g.surface))
                selection.face = g.vertexFace[static_cast<std::size_t>(g.surface->face(hit->face)[0])];
        }
        return;
    }
    if (mods & GLFW_MOD_SHIFT) return;
    if (!selection.points.empty()) selection.points.clear();
    else selection.clear();
}

bool Interaction::key(Scene& scene, Selection& selection, const ViewTransform& view, int key, int mods, double x, double y)
{
    if (busy()) {
        if (const KeyBinding* b = findBinding(KeyContext::Gesture, key, mods)) {
            switch (b->action) {
            case KeyAction::GestureCancel: cancel(scene); break;
            case KeyAction::GestureConfirm: finish(scene); break;
            case KeyAction::AxisX: setConstraint(scene, view, Constraint::AxisX); break;
            case KeyAction::AxisY: setConstraint(scene, view, Constraint::AxisY); break;
            case KeyAction::AxisZ: setConstraint(scene, view, Constraint::AxisZ); break;
            case KeyAction::PlaneX: setConstraint(scene, view, Constraint::PlaneX); break;
            case KeyAction::PlaneY: setConstraint(scene, view, Constraint::PlaneY); break;
            case KeyAction::PlaneZ: setConstraint(scene, view, Constraint::PlaneZ); break;
            default: break;
            }
        }
        return true; // everything else waits until the gesture ends
    }
    const KeyBinding* b = findBinding(KeyContext::Edit, key, mods);
    if (!b) return false;
    const bool hasItem = selection.item >= 0 && selection.item < scene.itemCount();
    switch (b->action) {
    case KeyAction::SelectNone:
        selection.points.clear();
        return true;
    case KeyAction::SelectAll: {
        if (!hasItem) return false;
        std::vector<int> all(static_cast<std::size_t>(scene.controlPointCount(selection.item)));
        std::iota(all.begin(), all.end(), 0);
        selection.setPoints(std::move(all));
        return true;
    }
    case KeyAction::Deselect:
        if (!selection.points.empty()) selection.points.clear();
        else if (hasItem) selection.clear();
        else return false;
        return true;
    case KeyAction::ToggleGizmo:
        settings_.gizmo = !settings_.gizmo;
        return true;
    case KeyAction::Grab:
        if (!hasItem || selection.points.empty()) return false;
        mode_ = Mode::Grab;
        startMove(scene, selection, Constraint::View, selection.has(activePoint_) ? activePoint_ : selection.points.front(), x, y);
        return true;
    case KeyAction::ToggleSoft:
        settings_.soft = !settings_.soft;
        if (settings_.soft && !(settings_.softRadius > 0)) settings_.softRadius = softRadius(scene);
        return true;
    case KeyAction::ToggleSnap:
        settings_.snap = !settings_.snap;
        return true;
    case KeyAction::SoftLarger:
        if (!settings_.soft) return false;
        settings_.softRadius = softRadius(scene) * 1.25;
        return true;
    case KeyAction::SoftSmaller:
        if (!settings_.soft) return false;
        settings_.softRadius = softRadius(scene) / 1.25;
        return true;
    default: return false;
    }
}

void Interaction::finish(Scene& scene)
{
    if (mode_ == Mode::Drag || mode_ == Mode::Grab) scene.endMerge();
    mode_ = Mode::None;
    moving_.clear();
}

void Interaction::cancel(Scene& scene)
{
    if (mode_ == Mode::Drag || mode_ == Mode::Grab) scene.cancelMerge();
    mode_ = Mode::None;
    moving_.clear();
}

void Interaction::fillOverlay(const Scene& scene, const Selection& selection, const ViewTransform& view, Overlay& overlay) const
{
    overlay.pointDiameter = scene.display.pointSize + 3;
    if (selection.item >= 0 && selection.item < scene.itemCount() && scene.item(selection.item).settings.visible) {
        const Eigen::Matrix3Xd points = scene.controlPoints(selection.item);
        for (int k : selection.points)
            if (k < points.cols()) overlay.addPoint(points.col(k).cast<float>(), k == activePoint_ ? kActiveColor : kSelectedColor);
        if (const auto centre = selectionCentre(scene, selection)) {
            if (settings_.gizmo && mode_ != Mode::Box && mode_ != Mode::Grab) {
                Gizmo g;
                g.centre = *centre;
                std::optional<Constraint> highlight = gizmoHover_;
                if (mode_ == Mode::Drag && constraint_ != Constraint::View) highlight = constraint_;
                g.draw(view, overlay, highlight);
            }
            if (settings_.soft) {
                Eigen::Vector3d right, up;
                const Eigen::Vector3d c = busy() ? grab_ : *centre;
                viewPlane(view, c, right, up);
                const double r = softRadius(scene);
                const int n = 64;
                for (int k = 0; k < n; ++k) {
                    const double a = 2 * M_PI * k / n, b = 2 * M_PI * (k + 1) / n;
                    overlay.addLine((c + r * (std::cos(a) * right + std::sin(a) * up)).cast<float>(),
                                    (c + r * (std::cos(b) * right + std::sin(b) * up)).cast<float>(), kSoftColor, true);
                }
            }
        }
        if (busy() && constraint_ != Constraint::View) {
            // The constraint line or plane through the grab point, long enough to cross the view.
            const double length = 2000 * view.worldPerPixel(grab_);
            const int axis = constraintAxis(constraint_);
            const Vec3f colors[3] = {Vec3f(0.95f, 0.3f, 0.3f), Vec3f(0.35f, 0.9f, 0.35f), Vec3f(0.35f, 0.55f, 1.0f)};
            for (int r = 0; r < 3; ++r) {
                if (isPlane(constraint_) ? r == axis : r != axis) continue;
                const Eigen::Vector3d u = length * Eigen::Vector3d::Unit(r);
                overlay.addLine((grab_ - u).cast<float>(), (grab_ + u).cast<float>(), colors[r], false);
            }
        }
    }
    if (selection.hoverItem >= 0 && selection.hoverItem < scene.itemCount() && selection.hoverPoint >= 0 && mode_ == Mode::None) {
        const Eigen::Matrix3Xd points = scene.controlPoints(selection.hoverItem);
        if (selection.hoverPoint < points.cols()) overlay.addPoint(points.col(selection.hoverPoint).cast<float>(), kHoverColor);
    }
    if (mode_ == Mode::Box) {
        const Eigen::Vector3d a = view.unproject(startX_, startY_, 0), b = view.unproject(x_, startY_, 0),
                              c = view.unproject(x_, y_, 0), d = view.unproject(startX_, y_, 0);
        overlay.addLine(a.cast<float>(), b.cast<float>(), kBoxColor, true);
        overlay.addLine(b.cast<float>(), c.cast<float>(), kBoxColor, true);
        overlay.addLine(c.cast<float>(), d.cast<float>(), kBoxColor, true);
        overlay.addLine(d.cast<float>(), a.cast<float>(), kBoxColor, true);
    }
}

} // namespace freeform::editor
