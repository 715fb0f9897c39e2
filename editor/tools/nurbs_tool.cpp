#include "tools/nurbs_tool.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <limits>
#include <type_traits>

#include "freeform/core/error.h"
#include "freeform/curve/nurbs_curve.h"
#include "freeform/document/document.h"
#include "freeform/surface/nurbs_surface.h"
#include "interaction/picking.h"
#include "tools/tool_util.h"

namespace freeform::editor {

using namespace tool_util;

namespace {

/// A number for the status bar: up to ten significant digits.
std::string shortNumber(double v)
{
    char text[32];
    std::snprintf(text, sizeof text, "%.10g", v);
    return text;
}

constexpr double kPi = 3.14159265358979323846;

std::vector<double>* weightsField(ObjectData& data, Eigen::Index& count)
{
    if (auto* d = std::get_if<RationalBezierCurveData>(&data)) return count = d->points.cols(), &d->weights;
    if (auto* d = std::get_if<RationalBezierSurfaceData>(&data)) return count = d->points.cols(), &d->weights;
    if (auto* d = std::get_if<NurbsCurveData>(&data)) return count = d->points.cols(), &d->weights;
    if (auto* d = std::get_if<NurbsSurfaceData>(&data)) return count = d->points.cols(), &d->weights;
    return nullptr;
}

/// A rational curve object's geometry (the scene's typed object) as a 3D NURBS: a 2D one with
/// z = 0, a rational Bézier curve on clamped knots over [0, 1].
/// The jets (point, C', C'') of a curve for its curvature comb: `perSpan` + 1 samples of every
/// knot span, each from the span's own rational Bézier piece, so both sides of a knot are drawn
/// and a jump of the curvature there shows as a step of the comb.
std::vector<Eigen::Matrix3d> combJets(const NurbsCurve<double, 3>& c, int perSpan)
{
    std::vector<Eigen::Matrix3d> jets;
    const auto pieces = c.bezierPieces();
    const std::vector<double>& breaks = c.breakpoints();
    for (std::size_t k = 0; k < pieces.size(); ++k) {
        const double h = breaks[k + 1] - breaks[k];
        for (int i = 0; i <= perSpan; ++i) {
            Eigen::Matrix3d j = pieces[k].derivatives(double(i) / perSpan, 2);
            j.col(1) /= h; // derivatives with respect to the curve's parameter
            j.col(2) /= h * h;
            jets.push_back(j);
        }
    }
    return jets;
}

std::optional<NurbsCurve<double, 3>> curve3(const Geometry& g)
{
    const auto lift = [](const NurbsCurve<double, 2>& c) {
        Eigen::Matrix<double, 4, Eigen::Dynamic> h = Eigen::Matrix<double, 4, Eigen::Dynamic>::Zero(4, c.homogeneousPoints().cols());
        h.topRows<2>() = c.homogeneousPoints().topRows<2>();
        h.row(3) = c.homogeneousPoints().row(2);
        return NurbsCurve<double, 3>(c.knotVector(), std::move(h));
    };
    if (const auto* c = std::get_if<NurbsCurve<double, 3>>(&g)) return *c;
    if (const auto* c = std::get_if<NurbsCurve<double, 2>>(&g)) return lift(*c);
    if (const auto* r = std::get_if<RationalBezierCurve<double, 3>>(&g)) return NurbsCurve<double, 3>::fromRationalBezier(*r);
    if (const auto* r = std::get_if<RationalBezierCurve<double, 2>>(&g)) return lift(NurbsCurve<double, 2>::fromRationalBezier(*r));
    return std::nullopt;
}

/// The levels of the de Boor construction at u (The NURBS Book A3.1 on the homogeneous points):
/// level 0 the p + 1 points of the span, level r the p + 1 - r affine combinations, each point
/// projected (divided by its weight).
std::vector<Points3> deBoorLevels(const NurbsCurve<double, 3>& c, double u)
{
    const int p = c.degree();
    u = c.clampToDomain(u);
    const int k = c.knotVector().findSpan(u);
    const std::vector<double>& U = c.knots();
    const auto& H = c.homogeneousPoints();
    Eigen::Matrix<double, 4, Eigen::Dynamic> d(4, p + 1);
    for (int j = 0; j <= p; ++j) d.col(j) = H.col(k - p + j);
    std::vector<Points3> levels;
    auto project = [&](int count, int first) {
        Points3 out(3, count);
        for (int j = 0; j < count; ++j) out.col(j) = d.col(first + j).head<3>() / d(3, first + j);
        levels.push_back(out);
    };
    project(p + 1, 0);
    for (int r = 1; r <= p; ++r) {
        for (int j = p; j >= r; --j) {
            const std::size_t i = static_cast<std::size_t>(k - p + j);
            const double a = (u - U[i]) / (U[i + static_cast<std::size_t>(p + 1 - r)] - U[i]);
            d.col(j) = (1 - a) * d.col(j - 1) + a * d.col(j);
        }
        project(p + 1 - r, r);
    }
    return levels;
}

Vec3f multiplicityColor(int m, int p)
{
    if (m >= p) return {1.0f, 0.35f, 0.3f};   // a break of the curve's smoothness down to C0 (or C-1)
    if (m > 1) return {1.0f, 0.8f, 0.25f};
    return {0.95f, 0.95f, 0.95f};
}

template <int Dim>
NurbsCurveData curveData(const NurbsCurve<double, Dim>& c, bool keepWeights)
{
    NurbsCurveData out;
    out.degree = c.degree();
    out.knots = c.knots();
    out.points = c.controlPoints();
    if (keepWeights) {
        const auto w = c.weights();
        out.weights.assign(w.data(), w.data() + w.size());
    }
    return out;
}

} // namespace

// ------------------------------------------------------------------ circles and arcs

NurbsCurveData circleData(const Eigen::Vector3d& c, double r, const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
    const NurbsCurve<double, 2> unit = NurbsCurve<double, 2>::circle(Eigen::Vector2d::Zero(), 1.0);
    NurbsCurveData d;
    d.degree = unit.degree();
    d.knots = unit.knots();
    const auto p = unit.controlPoints();
    d.points.resize(3, p.cols());
    for (Eigen::Index i = 0; i < p.cols(); ++i) d.points.col(i) = c + (r * p(0, i)) * a + (r * p(1, i)) * b;
    const auto w = unit.weights();
    d.weights.assign(w.data(), w.data() + w.size());
    return d;
}

ObjectData arcData(const Eigen::Vector3d& c, double r, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double sweep)
{
    if (!(sweep > 0 && sweep < 2 * kPi)) throw Error("arc: the sweep must lie in (0, 360) degrees");
    const int n = std::max(1, static_cast<int>(std::ceil(sweep / (kPi / 2) - 1e-12)));
    const double step = sweep / n, w = std::cos(step / 2);
    auto at = [&](double phi, double radius) -> Eigen::Vector3d { return c + (radius * std::cos(phi)) * a + (radius * std::sin(phi)) * b; };
    PointColumns points(3, 2 * n + 1);
    std::vector<double> weights;
    for (int j = 0; j <= 2 * n; ++j) {
        const double phi = j * step / 2;
        points.col(j) = j % 2 ? at(phi, r / w) : at(phi, r);
        weights.push_back(j % 2 ? w : 1.0);
    }
    if (n == 1) return RationalBezierCurveData{points, weights};
    NurbsCurveData d;
    d.degree = 2;
    d.knots = {0, 0, 0};
    for (int j = 1; j < n; ++j) d.knots.insert(d.knots.end(), 2, double(j));
    d.knots.insert(d.knots.end(), 3, double(n));
    d.points = points;
    d.weights = weights;
    return d;
}

// ------------------------------------------------------------------ queries

bool NurbsTool::handles(const KindInfo* kind) { return kind && kind->rational; }

std::vector<double> NurbsTool::weightsOf(const Scene& scene, int item)
{
    if (item < 0 || item >= scene.itemCount() || scene.item(item).kind != SceneItem::Kind::DocumentObject) return {};
    ObjectData data = scene.object(item).data;
    Eigen::Index count = 0;
    const std::vector<double>* w = weightsField(data, count);
    if (!w) return {};
    if (w->empty()) return std::vector<double>(static_cast<std::size_t>(count), 1.0);
    return *w;
}

double NurbsTool::sliderParameter(const ToolContext& c) const
{
    const int item = c.selection.item;
    if (item < 0 || item >= c.scene.itemCount() || c.scene.item(item).kind != SceneItem::Kind::DocumentObject) return 0;
    const ObjectData& data = c.scene.object(item).data;
    double a = 0, b = 1;
    if (const auto* d = std::get_if<NurbsCurveData>(&data)) {
        const std::size_t n = static_cast<std::size_t>(d->points.cols());
        if (d->knots.size() != n + static_cast<std::size_t>(d->degree) + 1) return 0;
        a = d->knots[static_cast<std::size_t>(d->degree)], b = d->knots[n];
    } else if (const auto* s = std::get_if<NurbsSurfaceData>(&data)) {
        const int dir = direction == 1 ? 1 : 0;
        const auto& k = s->knots[static_cast<std::size_t>(dir)];
        const std::size_t n = static_cast<std::size_t>(dir == 0 ? s->rows : s->cols);
        if (k.size() != n + static_cast<std::size_t>(s->degree[static_cast<std::size_t>(dir)]) + 1) return 0;
        a = k[static_cast<std::size_t>(s->degree[static_cast<std::size_t>(dir)])], b = k[n];
    }
    return a + t * (b - a);
}

// ------------------------------------------------------------------ keys and pointer

bool NurbsTool::onKey(ToolContext& c, KeyAction action)
{
    const int item = c.selection.item;
    const KindInfo* kind = item >= 0 && item < c.scene.itemCount() ? c.scene.item(item).info() : nullptr;
    switch (action) {
    case KeyAction::CreateCircle:
    case KeyAction::CreateArc:
        if (creating_) cancelCreating();
        else startCreating(action == KeyAction::CreateArc);
        return true;
    case KeyAction::CircleCancel:
        if (!creating_) return false;
        cancelCreating();
        return true;
    case KeyAction::InsertKnot:
        if (!kind || !kind->knots) return false;
        insertKnot(c, sliderParameter(c), direction);
        return true;
    case KeyAction::DeBoorConstruction:
        if (!handles(kind) || !kind->isCurve()) return false;
        construction = !construction;
        return true;
    case KeyAction::Comb:
        if (!handles(kind) || !kind->isCurve()) return false;
        comb = !comb;
        return true;
    default: return false;
    }
}

bool NurbsTool::onPointer(ToolContext& c, const PointerEvent& e)
{
    Scene& scene = c.scene;
    if (dragItem_ >= 0) {
        if (e.type == PointerEvent::Type::Release) {
            dragItem_ = -1;
            scene.endMerge();
            return true;
        }
        if (e.type == PointerEvent::Type::Move) scaleWeights(c, dragItem_, dragPoints_, dragStart_, std::exp(-(e.y - dragY_) / 100.0));
        return true;
    }
    if (creating_) {
        const auto hit = rayPlane(e, scene.bounds().center(), scene.camera.back());
        if (e.type == PointerEvent::Type::Move) {
            hasHover_ = hit.has_value();
            if (hit) hover_ = *hit;
            return e.button == 0;
        }
        if (e.type == PointerEvent::Type::Press && e.button == 1) return cancelCreating(), true;
        if (e.type == PointerEvent::Type::Press && e.button == 0) {
            if (hit) creationClick(c, *hit, scene.camera.back());
            return true;
        }
        return e.button == 0;
    }
    // Alt + press on a control point of a rational or NURBS object: the weight drag.
    if (e.type != PointerEvent::Type::Press || e.button != 0 || (e.mods & GLFW_MOD_ALT) == 0) return false;
    const ViewTransform view(c.viewProjection, -scene.camera.back(), c.viewWidth, c.viewHeight);
    int bestItem = -1, bestPoint = -1;
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i < scene.itemCount(); ++i) {
        const SceneItem& it = scene.item(i);
        if (!handles(it.info()) || !it.settings.visible) continue;
        const Eigen::Matrix3Xd points = scene.controlPoints(i);
        const auto k = pickPoint(view, points, e.x, e.y, 10);
        if (!k) continue;
        const auto px = view.toPixel(points.col(*k));
        const double d = px ? std::hypot(px->x() - e.x, px->y() - e.y) - (i == c.selection.item ? 0.5 : 0) : 1e9;
        if (d < best) best = d, bestItem = i, bestPoint = *k;
    }
    if (bestItem < 0) return false;
    c.selection.selectItem(bestItem);
    if (!c.selection.has(bestPoint)) c.selection.setPoints({bestPoint});
    dragItem_ = bestItem;
    dragPoints_ = c.selection.points;
    dragStart_.clear();
    const std::vector<double> w = weightsOf(scene, bestItem);
    for (int k : dragPoints_) dragStart_.push_back(w.at(static_cast<std::size_t>(k)));
    dragY_ = e.y;
    scene.beginMerge();
    return true;
}

void NurbsTool::startCreating(bool arc)
{
    creating_ = true;
    arc_ = arc;
    clicks_.clear();
    hasHover_ = false;
    status() = arc ? "arc: click the centre, then the start (radius), then the end (counter-clockwise); Escape cancels"
                   : "circle: click the centre, then a point of the circle; Escape cancels";
}

void NurbsTool::cancelCreating()
{
    creating_ = false;
    clicks_.clear();
    status().clear();
}

bool NurbsTool::creationClick(ToolContext& c, const Eigen::Vector3d& p, const Eigen::Vector3d& normal)
{
    if (clicks_.empty()) normal_ = normal.normalized();
    clicks_.push_back(p);
    const std::size_t needed = arc_ ? 3 : 2;
    if (clicks_.size() < needed) return true;
    const Eigen::Vector3d centre = clicks_[0];
    const Eigen::Vector3d toStart = clicks_[1] - centre;
    const double radius = toStart.norm();
    const bool arc = arc_;
    const std::vector<Eigen::Vector3d> clicks = clicks_;
    creating_ = false;
    clicks_.clear();
    if (!(radius > 0)) {
        status() = "the radius is zero: click a second point away from the centre";
        return false;
    }
    const Eigen::Vector3d a = toStart / radius, b = normal_.cross(a).normalized();
    try {
        ObjectData data;
        std::string name;
        if (arc) {
            const Eigen::Vector3d e = clicks[2] - centre;
            double sweep = std::atan2(e.dot(b), e.dot(a));
            if (sweep <= 0) sweep += 2 * kPi;
            data = arcData(centre, radius, a, b, sweep);
            name = "arc";
        } else {
            data = circleData(centre, radius, a, b);
            name = "circle";
        }
        const int i = c.scene.addObject({name, data, ""}, arc ? "create arc" : "create circle");
        c.selection.selectItem(i);
        status().clear();
        return true;
    } catch (const Error& err) {
        status() = err.what();
        return false;
    }
}

// ------------------------------------------------------------------ operations

bool NurbsTool::setWeights(ToolContext& c, int item, const std::vector<int>& ks, double w)
{
    std::vector<double> start;
    const std::vector<double> current = weightsOf(c.scene, item);
    for (int k : ks) {
        if (k < 0 || k >= static_cast<int>(current.size())) {
            status() = "weight: no control point " + std::to_string(k);
            return false;
        }
        start.push_back(1.0);
    }
    return scaleWeights(c, item, ks, start, w);
}

bool NurbsTool::scaleWeights(ToolContext& c, int item, const std::vector<int>& ks, const std::vector<double>& start, double factor)
{
    try {
        if (item < 0 || item >= c.scene.itemCount() || !handles(c.scene.item(item).info()))
            throw Error("weights: select a rational Bézier or NURBS object first");
        if (ks.empty()) throw Error("weights: select control points first");
        DocumentObject next = c.scene.object(item);
        Eigen::Index count = 0;
        std::vector<double>* w = weightsField(next.data, count);
        if (w->empty()) w->assign(static_cast<std::size_t>(count), 1.0);
        if (!std::isfinite(factor) || !(factor > 0)) throw Error("weights: a weight must be a positive finite number");
        for (std::size_t j = 0; j < ks.size(); ++j) {
            if (ks[j] < 0 || ks[j] >= count) throw Error("weights: no control point " + std::to_string(ks[j]));
            const double value = std::clamp(start.at(j) * factor, 1e-12, 1e12);
            w->at(static_cast<std::size_t>(ks[j])) = value;
        }
        c.scene.replaceObject(item, next, "weight");
        const double first = w->at(static_cast<std::size_t>(ks.front()));
        status() = ks.size() == 1 ? "weight of point " + std::to_string(ks.front()) + " set to " + shortNumber(first)
                                  : "weights of " + std::to_string(ks.size()) + " points set (point " + std::to_string(ks.front()) + ": " +
                                        shortNumber(first) + ")";
        return true;
    } catch (const Error& e) {
        status() = e.what();
        return false;
    }
}

bool NurbsTool::insertKnot(ToolContext& c, double u, int dir)
{
    int item = -1;
    const DocumentObject* object = selectedObject(c, item);
    try {
        if (!object) throw Error("insert knot: select a NURBS curve or surface first");
        DocumentObject next = *object;
        // The geometry as the document layer built it (Error: why the object is invalid).
        const Geometry& g = c.scene.typedObject(item).geometry();
        const bool weighted = std::visit(
            [](const auto& d) {
                if constexpr (std::is_same_v<std::decay_t<decltype(d)>, NurbsCurveData> ||
                              std::is_same_v<std::decay_t<decltype(d)>, NurbsSurfaceData>)
                    return !d.weights.empty();
                else return false;
            },
            object->data);
        if (const auto* c2 = std::get_if<NurbsCurve<double, 2>>(&g)) {
            next.data = curveData(c2->insertKnot(u), weighted);
        } else if (const auto* c3 = std::get_if<NurbsCurve<double, 3>>(&g)) {
            next.data = curveData(c3->insertKnot(u), weighted);
        } else if (const auto* surface = std::get_if<NurbsSurface<double, 3>>(&g)) {
            const auto* s = std::get_if<NurbsSurfaceData>(&object->data);
            const double a = dir == 0 ? surface->knotsU().front() : surface->knotsV().front();
            const double b = dir == 0 ? surface->knotsU().back() : surface->knotsV().back();
            if (!(u > a && u < b)) throw Error("insert knot: " + std::to_string(u) + " is not inside the domain (" + std::to_string(a) + ", " + std::to_string(b) + ")");
            const NurbsSurface<double, 3> refined = dir == 0 ? surface->refinedU({u}) : surface->refinedV({u});
            NurbsSurfaceData out;
            out.degree = s->degree;
            out.knots = {refined.knotsU().knots(), refined.knotsV().knots()};
            out.rows = refined.countU();
            out.cols = refined.countV();
            out.points = refined.controlPoints();
            if (weighted) {
                const auto w = refined.weights();
                out.weights.assign(w.data(), w.data() + w.size());
            }
            next.data = out;
        } else {
            throw Error("insert knot: for nurbs_curve and nurbs_surface objects");
        }
        c.scene.replaceObject(item, next, "insert knot");
        c.selection.points.clear();
        const char* along = std::holds_alternative<NurbsSurfaceData>(next.data) ? (dir == 0 ? " in u" : " in v") : "";
        status() = std::string("knot ") + shortNumber(u) + " inserted" + along + " (the shape unchanged; undo: Ctrl+Z)";
        return true;
    } catch (const Error& e) {
        status() = e.what();
        return false;
    }
}

// ------------------------------------------------------------------ overlays

void NurbsTool::update(ToolContext& c, Overlay& o)
{
    if (creating_) {
        std::vector<Eigen::Vector3d> pts = clicks_;
        if (hasHover_) pts.push_back(hover_);
        for (const auto& p : clicks_) o.addPoint(f3(p), kCreate);
        if (pts.size() >= 2 && (pts[1] - pts[0]).norm() > 0) {
            const Eigen::Vector3d a = (pts[1] - pts[0]).normalized(), b = c.scene.camera.back().normalized().cross(a).normalized();
            const double r = (pts[1] - pts[0]).norm();
            double sweep = 2 * kPi;
            if (arc_ && pts.size() >= 3) {
                const Eigen::Vector3d e = pts[2] - pts[0];
                sweep = std::atan2(e.dot(b), e.dot(a));
                if (sweep <= 0) sweep += 2 * kPi;
            }
            Points3 preview(3, 97);
            for (Eigen::Index k = 0; k < preview.cols(); ++k) {
                const double phi = sweep * double(k) / 96.0;
                preview.col(k) = pts[0] + r * std::cos(phi) * a + r * std::sin(phi) * b;
            }
            drawPolyline(o, preview, kCreate);
            o.addLine(f3(pts[0]), f3(pts[1]), kConstruction, true);
        }
    }
    int item = -1;
    const DocumentObject* object = selectedObject(c, item);
    if (!object || !handles(c.scene.item(item).info())) return;
    try {
        const double size = sceneSize(c.scene);
        const TypedObject* typed = c.scene.typed(item);
        if (!typed) return; // an invalid object: its message is in the status line and Properties
        const auto* nurbsSurface = std::get_if<NurbsSurface<double, 3>>(&typed->geometry());
        if (const auto curve = curve3(typed->geometry())) {
            if (showKnots && std::holds_alternative<NurbsCurveData>(object->data)) {
                // A dot at every distinct knot of the domain, and one tick across the curve per unit
                // of its multiplicity (spaced along the curve).
                const int p = curve->degree();
                const Eigen::Vector3d back = c.scene.camera.back();
                for (double u : curve->knotVector().breakpoints()) {
                    const int m = curve->knotVector().multiplicity(u);
                    const Eigen::Matrix<double, 3, Eigen::Dynamic> jet = curve->derivatives(u, 1);
                    const Eigen::Vector3d point = jet.col(0);
                    Eigen::Vector3d tangent = jet.col(1);
                    tangent = tangent.norm() > 0 ? Eigen::Vector3d(tangent.normalized()) : Eigen::Vector3d::UnitX();
                    Eigen::Vector3d across = back.cross(tangent);
                    across = across.norm() > 0 ? Eigen::Vector3d(across.normalized()) : Eigen::Vector3d::UnitY();
                    const Vec3f colour = multiplicityColor(m, p);
                    o.addPoint(f3(point), colour);
                    const double h = 0.018 * size, gap = 0.009 * size;
                    for (int j = 0; j < m; ++j) {
                        const Eigen::Vector3d at = point + (j - 0.5 * (m - 1)) * gap * tangent;
                        o.addLine(f3(at - h * across), f3(at + h * across), colour, true);
                    }
                }
            }
            if (construction) drawConstructionLevels(o, deBoorLevels(*curve, curve->domainStart() + t * (curve->domainEnd() - curve->domainStart())));
            if (comb) drawComb(o, combJets(*curve, 48), size, combScale);
        } else if (const auto* surface = nurbsSurface; surface && showKnots) {
            // Isoparametric lines at the knots (the domain's edges included), 64 samples each,
            // lifted towards the eye by 0.4 % of the scene so that the depth test keeps them in
            // front of their own surface (and behind the rest).
            const int p = surface->degreeU(), q = surface->degreeV();
            const Eigen::Vector3d lift = 0.004 * size * c.scene.camera.back();
            const auto& ku = surface->knotsU();
            const auto& kv = surface->knotsV();
            const auto lineAt = [&](bool inU, double s, const Vec3f& colour) {
                const double a = inU ? kv.front() : ku.front(), b = inU ? kv.back() : ku.back();
                Eigen::Vector3d last = Eigen::Vector3d::Zero();
                for (int k = 0; k <= 64; ++k) {
                    const double x = a + (b - a) * k / 64.0;
                    const Eigen::Vector3d pt = (inU ? surface->evaluate(s, x) : surface->evaluate(x, s)) + lift;
                    if (k > 0) o.addLine(f3(last), f3(pt), colour, false);
                    last = pt;
                }
            };
            for (double u : ku.breakpoints()) lineAt(true, u, multiplicityColor(ku.multiplicity(u), p));
            for (double v : kv.breakpoints()) lineAt(false, v, multiplicityColor(kv.multiplicity(v), q));
        }
    } catch (const Error&) {
        // An object the library refuses shows no knots and no construction (its message is the
        // item's, in the Properties panel).
    }
}

void NurbsTool::reset()
{
    creating_ = arc_ = false;
    clicks_.clear();
    hasHover_ = false;
    if (dragItem_ >= 0) dragItem_ = -1;
    dragPoints_.clear();
    dragStart_.clear();
    t = 0.5;
    direction = 0;
    construction = comb = false;
    combScale = 1;
    showKnots = true;
    typedWeight = 1;
}

} // namespace freeform::editor
