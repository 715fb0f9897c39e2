#include "tools/curve_tool.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>

#include "freeform/core/error.h"
#include "freeform/curve/interpolation.h"
#include "tools/tool_util.h"

namespace freeform::editor {

using namespace tool_util;

namespace {

void drawConstruction(Overlay& o, const Points3& control, double t)
{
    drawConstructionLevels(o, deCasteljauLevels(control, t));
}

std::vector<Eigen::Matrix3d> curveJets(const BezierCurve<double, 3>& c, int samples)
{
    std::vector<Eigen::Matrix3d> jets;
    for (int i = 0; i <= samples; ++i) jets.push_back(c.derivatives(static_cast<double>(i) / samples, 2));
    return jets;
}

bool curveLike(const ToolContext& c)
{
    const int item = c.selection.item;
    if (item < 0 || item >= c.scene.itemCount()) return false;
    const KindInfo* kind = c.scene.item(item).info();
    return kind && kind->isCurve() && !kind->rational;
}

/// Replaces the selected object's data by op(data); Error messages go to `status`.
template <typename Op>
bool editSelected(ToolContext& c, std::string& status, const char* label, Op op)
{
    int item = -1;
    const DocumentObject* object = selectedObject(c, item);
    if (!object) {
        status = "select a curve or spline first";
        return false;
    }
    // op may change the object's settings too (joint modes): one step with the object, and
    // nothing left of either when it fails.
    c.scene.beginMerge();
    try {
        DocumentObject next = *object;
        if (!op(next)) {
            c.scene.cancelMerge();
            status = std::string(label) + ": not for a " + c.scene.item(item).type;
            return false;
        }
        c.scene.replaceObject(item, next, label);
        c.scene.endMerge();
        status.clear();
        return true;
    } catch (const Error& e) {
        c.scene.cancelMerge();
        status = e.what();
        return false;
    }
}

} // namespace

// ------------------------------------------------------------------ keys and pointer

bool CurveTool::onCreateKey(ToolContext& c, KeyAction action)
{
    switch (action) {
    case KeyAction::CreateFinish: return createFromClicks(c), true;
    case KeyAction::CreateCancel:
        creating_ = false;
        newPoints_.resize(3, 0);
        return true;
    case KeyAction::CreateRemoveLast:
        if (newPoints_.cols() > 0) newPoints_.conservativeResize(3, newPoints_.cols() - 1);
        return true;
    default: return false;
    }
}

bool CurveTool::onKey(ToolContext& c, KeyAction action)
{
    if (creating_ && onCreateKey(c, action)) return true;
    switch (action) {
    case KeyAction::CreateCurve:
    case KeyAction::CreateSpline:
        creating_ = !creating_;
        creatingSpline_ = action == KeyAction::CreateSpline;
        newPoints_.resize(3, 0);
        status() = !creating_ ? ""
                   : creatingSpline_ ? "click the points the C2 spline passes through; Enter or right click ends, Escape cancels"
                                     : "click control points in the view; Enter or right click ends, Escape cancels";
        return true;
    case KeyAction::Elevate: return curveLike(c) && (elevateSelected(c), true);
    case KeyAction::Split: return curveLike(c) && (splitSelected(c), true);
    case KeyAction::InsertPoint: return curveLike(c) && (insertAtSelected(c), true);
    case KeyAction::DeletePoint:
        if (!curveLike(c) || c.selection.points.empty()) return false;
        return deleteSelected(c), true;
    case KeyAction::Construction:
        if (!curveLike(c)) return false;
        construction = !construction;
        return true;
    case KeyAction::Comb:
        if (!curveLike(c)) return false;
        comb = !comb;
        return true;
    default: return false;
    }
}

bool CurveTool::onPointer(ToolContext& c, const PointerEvent& e)
{
    if (!creating_) return false;
    if (e.type == PointerEvent::Type::Press && e.button == 1) return createFromClicks(c), true;
    if (e.type == PointerEvent::Type::Press && e.button == 0) {
        const auto p = rayPlane(e, c.scene.bounds().center(), c.scene.camera.back());
        if (p) {
            newPoints_.conservativeResize(3, newPoints_.cols() + 1);
            newPoints_.col(newPoints_.cols() - 1) = *p;
        }
        return true;
    }
    return e.type != PointerEvent::Type::Move || e.button == 0;
}

void CurveTool::startCreating(bool spline)
{
    creating_ = true;
    creatingSpline_ = spline;
}

// ------------------------------------------------------------------ overlays

void CurveTool::update(ToolContext& c, Overlay& o)
{
    if (creating_) {
        if (creatingSpline_ && newPoints_.cols() >= 2) {
            // The spline the clicks make so far (nothing while two clicks coincide).
            try {
                const BezierSpline<double, 3> preview = interpolateCubic<double, 3>(newPoints_);
                Points3 samples(3, 16 * preview.segmentCount() + 1);
                for (Eigen::Index k = 0; k < samples.cols(); ++k)
                    samples.col(k) = preview.evaluate(preview.domainEnd() * double(k) / double(samples.cols() - 1));
                drawPolyline(o, samples, kCreate);
            } catch (const Error&) {
            }
        } else {
            drawPolyline(o, newPoints_, kCreate);
        }
        for (Eigen::Index i = 0; i < newPoints_.cols(); ++i) o.addPoint(f3(newPoints_.col(i)), kCreate);
    }
    int item = -1;
    const DocumentObject* object = selectedObject(c, item);
    if (!object || !(construction || comb)) return;
    const double size = sceneSize(c.scene);
    // The curve as the scene's typed document holds it (none for an object the document layer
    // refuses: its message is in Properties); 2D curves lifted to z = 0.
    const TypedObject* typed = c.scene.typed(item);
    const std::optional<AnyCurve> curve = typed ? AnyCurve::of(*typed) : std::nullopt;
    // The polynomial curves only: a rational curve's overlays are the NURBS tool's.
    const std::optional<BezierSpline<double, 3>> polynomial = curve ? curve->spline3() : std::nullopt;
    if (!polynomial) return;
    const BezierSpline<double, 3>& spline = *polynomial;
    if (std::holds_alternative<BezierCurveData>(object->data)) {
        if (construction) drawConstruction(o, spline.segmentPoints(0), t);
        if (comb) drawComb(o, curveJets(spline.segment(0), 200), size, combScale);
    } else if (std::holds_alternative<BezierSplineData>(object->data)) {
        splineOverlays(o, spline, size);
    } else if (std::holds_alternative<DeBoorSplineData>(object->data) && construction) {
        const auto where = spline.locate(t * spline.domainEnd());
        drawConstruction(o, spline.segmentPoints(where.segment), where.t);
    }
}

void CurveTool::splineOverlays(Overlay& o, const BezierSpline<double, 3>& spline, double size) const
{
    if (construction) {
        const auto where = spline.locate(t * spline.domainEnd());
        drawConstruction(o, spline.segmentPoints(where.segment), where.t);
    }
    if (comb) {
        std::vector<Eigen::Matrix3d> jets;
        for (int i = 0; i < spline.segmentCount(); ++i) {
            const auto segment = curveJets(spline.segment(i), 60);
            const double h = spline.intervals()[static_cast<std::size_t>(i)];
            for (Eigen::Matrix3d j : segment) {
                j.col(1) /= h; // derivatives with respect to the global parameter
                j.col(2) /= h * h;
                jets.push_back(j);
            }
        }
        drawComb(o, jets, size, combScale);
    }
}

void CurveTool::reset()
{
    creating_ = creatingSpline_ = false;
    newPoints_.resize(3, 0);
    t = 0.5;
    construction = comb = false;
    combScale = 1;
}

// ------------------------------------------------------------------ operations

bool CurveTool::createFromClicks(ToolContext& c)
{
    creating_ = false;
    if (newPoints_.cols() < 2) {
        status() = "a curve needs at least two points";
        newPoints_.resize(3, 0);
        return false;
    }
    const Points3 clicked = newPoints_;
    newPoints_.resize(3, 0);
    try {
        if (creatingSpline_) {
            // Through the clicked points: the C2 cubic interpolant (natural ends, chord-length
            // intervals), every inner joint in mode C2, so dragging keeps it C2.
            const BezierSpline<double, 3> spline = interpolateCubic<double, 3>(clicked);
            BezierSplineData data;
            data.points = spline.controlPoints();
            data.intervals = spline.intervals();
            ObjectSettings settings;
            settings.joints.assign(static_cast<std::size_t>(spline.segmentCount() + 1), JointMode::C2);
            settings.joints.front() = settings.joints.back() = JointMode::Free;
            c.scene.beginMerge();
            const int i = c.scene.addObject({"spline", data, ""}, "create spline");
            c.scene.setSettings(i, settings, "create spline");
            c.scene.endMerge();
            c.selection.selectItem(i);
            status().clear();
            return true;
        }
        const int i = c.scene.addObject({"curve", BezierCurveData{clicked}, ""}, "create curve");
        c.selection.selectItem(i);
        status().clear();
        return true;
    } catch (const Error& e) {
        status() = e.what();
        return false;
    }
}

bool CurveTool::elevateSelected(ToolContext& c)
{
    return editSelected(c, status(), "elevate degree", [&](DocumentObject& o) {
        if (auto* d = std::get_if<BezierCurveData>(&o.data)) return o.data = elevateCurve(*d), true;
        if (auto* d = std::get_if<BezierSplineData>(&o.data)) {
            std::vector<JointMode> modes = jointModes(c.scene, c.selection.item);
            if (std::find(modes.begin(), modes.end(), JointMode::C2) != modes.end())
                throw Error("elevate degree: C2 handle modes need a cubic spline (set those joints free first)");
            return o.data = elevateSpline(*d), true;
        }
        return false;
    });
}

bool CurveTool::splitSelected(ToolContext& c)
{
    int item = -1;
    const DocumentObject* object = selectedObject(c, item);
    if (!object) {
        status() = "select a curve or an open spline first";
        return false;
    }
    try {
        DocumentObject first = *object, second = *object;
        if (const auto* d = std::get_if<BezierCurveData>(&object->data)) {
            auto halves = splitCurve(*d, t);
            first.data = halves.first;
            second.data = halves.second;
        } else if (const auto* d = std::get_if<BezierSplineData>(&object->data)) {
            auto halves = splitSpline(*d, t * toSpline(*d).domainEnd());
            first.data = halves.first;
            second.data = halves.second;
        } else {
            status() = "split: for bezier_curve and bezier_spline objects";
            return false;
        }
        // The handle modes do not carry over (the joints are renumbered): the halves start free.
        ObjectSettings settings = c.scene.item(item).settings;
        settings.joints.clear();
        c.scene.beginMerge();
        c.scene.replaceObject(item, first, "split");
        c.scene.setSettings(item, settings, "split");
        second.name = object->name;
        const int added = c.scene.addObject(second, "split");
        c.scene.setSettings(added, settings, "split");
        c.scene.endMerge();
        c.selection.selectItem(added);
        status().clear();
        return true;
    } catch (const Error& e) {
        c.scene.endMerge();
        status() = e.what();
        return false;
    }
}

bool CurveTool::insertAtSelected(ToolContext& c)
{
    const int k = selectedPoint(c);
    return editSelected(c, status(), "insert point", [&](DocumentObject& o) {
        if (auto* d = std::get_if<BezierCurveData>(&o.data)) {
            // After the selected point (midway to the next), else at the curve point f(t) before the end.
            const Points3 p = toPoints3(d->points);
            const auto n = static_cast<int>(p.cols());
            if (k >= 0 && k + 1 < n) o.data = insertCurvePoint(*d, k + 1, 0.5 * (p.col(k) + p.col(k + 1)));
            else if (k == n - 1) o.data = insertCurvePoint(*d, n, p.col(n - 1) + (p.col(n - 1) - p.col(n - 2)));
            else o.data = insertCurvePoint(*d, n - 1, BezierCurve<double, 3>(p).evaluate(t));
            return true;
        }
        if (auto* d = std::get_if<BezierSplineData>(&o.data)) {
            const BezierSpline<double, 3> spline = toSpline(*d);
            double T = t * spline.domainEnd();
            if (k >= 0) { // the middle of the segment after the selected point
                const int segment = std::min(k / d->degree, spline.segmentCount() - 1);
                T = 0.5 * (spline.knot(segment) + spline.knot(segment + 1));
            }
            const int segment = spline.locate(T).segment;
            o.data = insertJoint(*d, T);
            // The new joint gets mode free; the others keep theirs.
            ObjectSettings settings = c.scene.item(c.selection.item).settings;
            if (!settings.joints.empty()) {
                settings.joints = jointModes(c.scene, c.selection.item);
                settings.joints.insert(settings.joints.begin() + segment + 1, JointMode::Free);
                c.scene.setSettings(c.selection.item, settings, "insert point");
            }
            return true;
        }
        if (auto* d = std::get_if<DeBoorSplineData>(&o.data)) {
            const auto n = d->points.cols();
            const auto at = k >= 0 && k + 1 < n ? k : n - 2;
            PointColumns p(d->points.rows(), n + 1);
            p.leftCols(at + 1) = d->points.leftCols(at + 1);
            p.col(at + 1) = 0.5 * (d->points.col(at) + d->points.col(at + 1));
            p.rightCols(n - at - 1) = d->points.rightCols(n - at - 1);
            d->points = p;
            if (!d->intervals.empty()) d->intervals.push_back(1.0);
            return true;
        }
        return false;
    });
}

bool CurveTool::deleteSelected(ToolContext& c)
{
    const int k = selectedPoint(c);
    if (k < 0) {
        status() = "select a control point to delete";
        return false;
    }
    const bool ok = editSelected(c, status(), "delete point", [&](DocumentObject& o) {
        if (auto* d = std::get_if<BezierCurveData>(&o.data)) return o.data = deleteCurvePoint(*d, k), true;
        if (auto* d = std::get_if<BezierSplineData>(&o.data)) {
            const int joint = jointOfPoint(*d, k);
            o.data = deleteJoint(*d, joint);
            ObjectSettings settings = c.scene.item(c.selection.item).settings;
            if (!settings.joints.empty()) {
                settings.joints = jointModes(c.scene, c.selection.item);
                settings.joints.erase(settings.joints.begin() + joint);
                c.scene.setSettings(c.selection.item, settings, "delete point");
            }
            return true;
        }
        if (auto* d = std::get_if<DeBoorSplineData>(&o.data)) {
            const auto n = d->points.cols();
            PointColumns p(d->points.rows(), n - 1);
            p.leftCols(k) = d->points.leftCols(k);
            p.rightCols(n - 1 - k) = d->points.rightCols(n - 1 - k);
            d->points = p;
            if (!d->intervals.empty()) d->intervals.pop_back();
            return true;
        }
        return false;
    });
    if (ok) c.selection.points.clear();
    return ok;
}

} // namespace freeform::editor
