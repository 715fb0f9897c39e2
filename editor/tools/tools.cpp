#include "tools/tools.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

#include "freeform/io/geometry_data.h"
#include "freeform/core/error.h"
#include "freeform/curve/interpolation.h"
#include "freeform/surface/bezier_surface.h"
#include "interaction/picking.h"
#include "tools/tool_state.h"

namespace freeform::editor {

namespace {

using State = Tools::State;

const Vec3f kConstruction(1.0f, 0.75f, 0.2f);
const Vec3f kCurvePoint(1.0f, 0.3f, 0.2f);
const Vec3f kDeBoor(0.3f, 0.85f, 1.0f);
const Vec3f kComb(0.6f, 0.9f, 0.4f);
const Vec3f kCreate(1.0f, 1.0f, 1.0f);

Vec3f f3(const Eigen::Vector3d& p) { return p.cast<float>(); }

/// The ray of a pointer event meets the plane (point, normal); nothing when parallel or behind.
std::optional<Eigen::Vector3d> rayPlane(const PointerEvent& e, const Eigen::Vector3d& point, const Eigen::Vector3d& normal)
{
    const double d = e.rayDirection.dot(normal);
    if (std::abs(d) < 1e-12) return std::nullopt;
    const double s = (point - e.rayOrigin).dot(normal) / d;
    if (s < 0) return std::nullopt;
    return Eigen::Vector3d(e.rayOrigin + s * e.rayDirection);
}

/// Pixel of a world point under the context's view-projection (nothing behind the eye).
std::optional<Eigen::Vector2d> toPixel(const ToolContext& c, const Eigen::Vector3d& p)
{
    const Eigen::Vector4d q = c.viewProjection * Eigen::Vector4d(p.x(), p.y(), p.z(), 1.0);
    if (q.w() <= 0) return std::nullopt;
    return Eigen::Vector2d((q.x() / q.w() * 0.5 + 0.5) * c.viewWidth, (0.5 - q.y() / q.w() * 0.5) * c.viewHeight);
}

const DocumentObject* selectedObject(const ToolContext& c, int& item)
{
    item = c.selection.item;
    if (item < 0 || item >= c.scene.itemCount() || c.scene.item(item).kind != SceneItem::Kind::DocumentObject) return nullptr;
    return &c.scene.object(item);
}

double sceneSize(const Scene& scene)
{
    const double d = scene.bounds().diagonal().norm();
    return d > 0 ? d : 1.0;
}

/// Whether every inner joint of a cubic spline is in C2 mode (then its de Boor points are edited).
bool allC2(const BezierSplineData& s, const std::vector<JointMode>& modes)
{
    if (s.degree != 3) return false;
    bool any = false;
    const int L = static_cast<int>(s.closed ? s.points.cols() / 3 : (s.points.cols() - 1) / 3);
    for (int j = 0; j <= L; ++j) {
        if (!isInnerJoint(s, j)) continue;
        any = true;
        if (j >= static_cast<int>(modes.size()) || modes[static_cast<std::size_t>(j)] != JointMode::C2) return false;
    }
    return any;
}

// ------------------------------------------------------------------ overlays

void drawPolyline(Overlay& o, const Points3& p, const Vec3f& color, bool closed = false)
{
    for (Eigen::Index i = 0; i + 1 < p.cols(); ++i) o.addLine(f3(p.col(i)), f3(p.col(i + 1)), color, true);
    if (closed && p.cols() > 2) o.addLine(f3(p.col(p.cols() - 1)), f3(p.col(0)), color, true);
}

void drawConstruction(Overlay& o, const Points3& control, double t)
{
    const std::vector<Points3> levels = deCasteljauLevels(control, t);
    for (std::size_t r = 1; r < levels.size(); ++r) {
        const float fade = 1.0f - 0.5f * static_cast<float>(r) / static_cast<float>(levels.size());
        drawPolyline(o, levels[r], kConstruction * fade);
        for (Eigen::Index i = 0; i < levels[r].cols(); ++i)
            o.addPoint(f3(levels[r].col(i)), r + 1 == levels.size() ? kCurvePoint : Vec3f(kConstruction * fade));
    }
}

void drawComb(Overlay& o, const std::vector<Eigen::Matrix3d>& jets, double size, double scale)
{
    double kmax = 0;
    for (const auto& j : jets) {
        const double s2 = j.col(1).squaredNorm();
        if (s2 > 0) kmax = std::max(kmax, j.col(1).cross(j.col(2)).norm() / (s2 * std::sqrt(s2)));
    }
    if (!(kmax > 0)) return;
    const Points3 comb = curvatureComb(jets, scale * 0.15 * size / kmax);
    for (Eigen::Index i = 0; i < comb.cols(); i += 2) {
        o.addLine(f3(comb.col(i)), f3(comb.col(i + 1)), kComb * 0.7f, true);
        if (i + 3 < comb.cols()) o.addLine(f3(comb.col(i + 1)), f3(comb.col(i + 3)), kComb, true);
    }
}

std::vector<Eigen::Matrix3d> curveJets(const BezierCurve<double, 3>& c, int samples)
{
    std::vector<Eigen::Matrix3d> jets;
    for (int i = 0; i <= samples; ++i) jets.push_back(c.derivatives(static_cast<double>(i) / samples, 2));
    return jets;
}

void curveOverlays(ToolContext& c, State& s, Overlay& o)
{
    int item = -1;
    const DocumentObject* object = selectedObject(c, item);
    if (!object) return;
    const double size = sceneSize(c.scene);
    if (const auto* d = std::get_if<BezierCurveData>(&object->data)) {
        const Points3 p = toPoints3(d->points);
        if (s.construction) drawConstruction(o, p, s.t);
        if (s.comb) drawComb(o, curveJets(BezierCurve<double, 3>(p), 200), size, s.combScale);
    } else if (const auto* d = std::get_if<BezierSplineData>(&object->data)) {
        try {
            const BezierSpline<double, 3> spline = toSpline(*d);
            if (s.construction) {
                const auto where = spline.locate(s.t * spline.domainEnd());
                drawConstruction(o, spline.segmentPoints(where.segment), where.t);
            }
            if (s.comb) {
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
                drawComb(o, jets, size, s.combScale);
            }
            if (allC2(*d, jointModes(c.scene, item))) {
                const Points3 deboor = splineDeBoorPoints(*d);
                drawPolyline(o, deboor, kDeBoor * 0.8f, d->closed);
                for (Eigen::Index i = 0; i < deboor.cols(); ++i) o.addPoint(f3(deboor.col(i)), kDeBoor);
            }
        } catch (const Error&) {
            // A spline that is not C2 within tolerance shows no de Boor points.
        }
    } else if (const auto* d = std::get_if<DeBoorSplineData>(&object->data)) {
        if (s.construction || s.comb) {
            const auto spline = BezierSpline<double, 3>::fromDeBoor(toPoints3(d->points), parseEndCondition(d->end, "end"), d->intervals);
            if (s.construction) {
                const auto where = spline.locate(s.t * spline.domainEnd());
                drawConstruction(o, spline.segmentPoints(where.segment), where.t);
            }
        }
    }
}

// ------------------------------------------------------------------ handle modes while dragging

void trackJointModes(ToolContext& c, State& s)
{
    int item = -1;
    const DocumentObject* object = selectedObject(c, item);
    const auto* d = object ? std::get_if<BezierSplineData>(&object->data) : nullptr;
    if (!d) {
        s.modeItem = -1;
        s.modeSnapshot.reset();
        return;
    }
    if (item != s.modeItem || !s.modeSnapshot) {
        s.modeItem = item;
        s.modeSnapshot = *d;
        return;
    }
    if (s.modeSnapshot->points.cols() != d->points.cols() || s.modeSnapshot->degree != d->degree) {
        s.modeSnapshot = *d;
        return;
    }
    std::vector<int> moved;
    for (Eigen::Index k = 0; k < d->points.cols(); ++k)
        if (d->points.col(k) != s.modeSnapshot->points.col(k)) moved.push_back(static_cast<int>(k));
    if (moved.empty()) return;
    // Undo and redo restore states of the document as they were: enforcing the modes on them would
    // be an edit of its own that clears the redo steps (a record always empties them, so a redo
    // step left means the last change was an undo or a redo).
    if (c.scene.history().canRedo()) {
        s.modeSnapshot = *d;
        return;
    }
    const std::vector<JointMode> modes = jointModes(c.scene, item);
    BezierSplineData enforced = enforceJointModes(*s.modeSnapshot, *d, modes, moved);
    // Re-enforcing a mode that already holds moves points by rounding only: no edit for that.
    const double scale = std::max(1.0, d->points.cwiseAbs().maxCoeff());
    if ((enforced.points - d->points).cwiseAbs().maxCoeff() > 1e-12 * scale) {
        DocumentObject next = *object;
        next.data = enforced;
        try {
            // One change since the last look (a typed coordinate, a frame of a drag): the modes
            // complete that change, in its undo step. Several: a step of their own.
            if (c.scene.changeCount() == s.lastChange + 1) c.scene.amendObject(item, next);
            else c.scene.replaceObject(item, next, "handle mode");
        } catch (const Error& e) {
            s.message = e.what();
        }
    }
    s.modeSnapshot = std::get<BezierSplineData>(c.scene.object(item).data);
}

// ------------------------------------------------------------------ FFD links

void restoreRest(Scene& scene, const FfdLink& link)
{
    const int m = findItem(scene, link.mesh);
    if (m < 0 || !link.session || scene.item(m).key != link.meshKey) return;
    SceneItem& it = scene.item(m);
    if (!it.geometry.surface || it.geometry.surface->positions.cols() != link.session->rest().positions.cols()) return;
    it.geometry.surface->positions = link.session->rest().positions;
    it.geometry.surface->normals = link.session->rest().normals;
    scene.setScalars(m, {});
}

void updateLinks(ToolContext& c, State& s)
{
    Scene& scene = c.scene;
    // Lattices that deform a mesh, by name.
    std::map<std::string, int> lattices;
    for (int i = 0; i < scene.itemCount(); ++i)
        if (scene.item(i).kind == SceneItem::Kind::DocumentObject && scene.item(i).type == "lattice" &&
            !scene.item(i).settings.ffd.mesh.empty())
            lattices[scene.item(i).name] = i;
    for (auto it = s.links.begin(); it != s.links.end();) {
        const auto found = lattices.find(it->first);
        if (found == lattices.end() || scene.item(found->second).settings.ffd.mesh != it->second.mesh) {
            restoreRest(scene, it->second);
            it = s.links.erase(it);
        } else {
            ++it;
        }
    }
    for (const auto& [name, li] : lattices) {
        const ObjectSettings& settings = scene.item(li).settings;
        const int m = findItem(scene, settings.ffd.mesh);
        if (m < 0 || scene.item(m).kind != SceneItem::Kind::ImportedMesh) continue;
        if (scene.item(m).geometryDirty) scene.updateGeometry();
        SceneItem& mesh = scene.item(m);
        if (!mesh.geometry.surface) continue;
        FfdLink& link = s.links[name];
        const auto& data = std::get<LatticeData>(scene.object(li).data);
        try {
            const Lattice lattice = latticeFromData(data);
            const bool rebind = !link.session || link.mesh != settings.ffd.mesh || link.meshKey != mesh.key ||
                                !link.session->matches(lattice);
            if (rebind) {
                // The rest mesh: the item's geometry as read, unless this link deformed it.
                PolygonMesh rest = *mesh.geometry.surface;
                if (link.session && link.meshKey == mesh.key && link.appliedRevision == mesh.revision) rest = link.session->rest();
                link = FfdLink{};
                link.mesh = settings.ffd.mesh;
                link.meshKey = mesh.key;
                link.session = std::make_unique<FfdSession>(lattice, std::move(rest));
            }
            const bool changed = rebind || link.appliedRevision != mesh.revision || link.appliedPoints != data.points ||
                                 link.appliedStrength != settings.ffd.strength;
            if (!changed) continue;
            const auto t0 = std::chrono::steady_clock::now();
            // det J straight into the colour scalars, in the last frame's memory (no fresh pages).
            std::vector<float> scalars = std::move(mesh.scalars);
            link.report = link.session->deform(lattice, settings.ffd.strength, *mesh.geometry.surface, &scalars);
            link.deformMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
            mesh.geometry.bounds.setEmpty();
            const auto& p = mesh.geometry.surface->positions;
            if (p.cols() > 0) mesh.geometry.bounds = Eigen::AlignedBox3d(p.rowwise().minCoeff(), p.rowwise().maxCoeff());
            scene.setScalars(m, std::move(scalars)); // also a new revision: the drawer uploads the mesh
            link.appliedRevision = scene.item(m).revision;
            link.appliedPoints = data.points;
            link.appliedStrength = settings.ffd.strength;
            link.certificate.reset();
        } catch (const Error& e) {
            s.message = e.what();
        }
    }
}

} // namespace

// ------------------------------------------------------------------ shared helpers

int findItem(const Scene& scene, const std::string& name)
{
    for (int i = 0; i < scene.itemCount(); ++i)
        if (scene.item(i).name == name) return i;
    return -1;
}

std::string meshFilePath(const Scene& scene, int meshItem)
{
    const std::filesystem::path p(scene.item(meshItem).meshPath);
    if (p.is_absolute() || scene.path().empty()) return p.string();
    return (std::filesystem::path(scene.path()).parent_path() / p).string();
}

std::vector<JointMode> jointModes(const Scene& scene, int item)
{
    std::vector<JointMode> modes = scene.item(item).settings.joints;
    if (const auto* d = std::get_if<BezierSplineData>(&scene.object(item).data)) {
        const auto L = d->closed ? d->points.cols() / d->degree : (d->points.cols() - 1) / d->degree;
        modes.resize(static_cast<std::size_t>(d->closed ? L : L + 1), JointMode::Free);
    }
    return modes;
}

// ------------------------------------------------------------------ operations

namespace {

/// The cubic spline with the joints of `d` (same intervals) that is C2 at every inner joint: the
/// C2 interpolant of the joints, with the end derivatives of `d` (open) or periodic (closed). Unlike
/// making joints C2 one after the other, no joint moves and the handles stay near the old ones.
BezierSplineData c2ThroughJoints(const BezierSplineData& d)
{
    const Eigen::Index L = d.closed ? d.points.cols() / 3 : (d.points.cols() - 1) / 3;
    Points3 joints(3, L + 1);
    for (Eigen::Index j = 0; j <= L; ++j) joints.col(j) = d.points.col((3 * j) % d.points.cols());
    InterpolationOptions<double, 3> options;
    options.params.assign(1, 0.0);
    for (Eigen::Index i = 0; i < L; ++i)
        options.params.push_back(options.params.back() + (d.intervals.empty() ? 1.0 : d.intervals[static_cast<std::size_t>(i)]));
    if (d.closed) {
        options.end = InterpolationEnd::Periodic;
    } else {
        const double h0 = options.params[1] - options.params[0], hL = options.params.back() - options.params[static_cast<std::size_t>(L - 1)];
        options.end = InterpolationEnd::Clamped;
        options.startDerivative = 3 * (d.points.col(1) - d.points.col(0)) / h0;
        options.endDerivative = 3 * (d.points.col(3 * L) - d.points.col(3 * L - 1)) / hL;
    }
    const BezierSpline<double, 3> spline = interpolateCubic<double, 3>(joints, options);
    BezierSplineData out = d;
    out.points = spline.controlPoints();
    return out;
}

} // namespace

bool createCurveFromClicks(ToolContext& c, State& s)
{
    s.creating = false;
    if (s.newPoints.cols() < 2) {
        s.message = "a curve needs at least two points";
        s.newPoints.resize(3, 0);
        return false;
    }
    const Points3 clicked = s.newPoints;
    s.newPoints.resize(3, 0);
    try {
        if (s.creatingSpline) {
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
            s.modeSnapshot = data;
            s.message.clear();
            return true;
        }
        const int i = c.scene.addObject({"curve", BezierCurveData{clicked}, ""}, "create curve");
        c.selection.selectItem(i);
        s.message.clear();
        return true;
    } catch (const Error& e) {
        s.message = e.what();
        return false;
    }
}

bool createPatch(ToolContext& c, State& s)
{
    const int m = std::clamp(s.patchDegree[0], 1, 20), n = std::clamp(s.patchDegree[1], 1, 20);
    const Eigen::AlignedBox3d box = c.scene.bounds();
    const Eigen::Vector3d centre = box.center();
    const double half = 0.25 * sceneSize(c.scene);
    const Eigen::Vector3d right = c.scene.camera.right(), up = c.scene.camera.up();
    BezierSurfaceData d;
    d.degree = {m, n};
    d.points.resize(3, (m + 1) * (n + 1));
    for (int i = 0; i <= m; ++i)
        for (int j = 0; j <= n; ++j)
            d.points.col(i * (n + 1) + j) = centre + half * ((2.0 * i / m - 1) * up + (2.0 * j / n - 1) * right);
    try {
        c.selection.selectItem(c.scene.addObject({"patch", d, ""}, "create patch"));
        return true;
    } catch (const Error& e) {
        s.message = e.what();
        return false;
    }
}

namespace {

/// Replaces the selected object's data by op(data); Error messages go to state.message.
template <typename Op>
bool editSelected(ToolContext& c, State& s, const char* label, Op op)
{
    int item = -1;
    const DocumentObject* object = selectedObject(c, item);
    if (!object) {
        s.message = "select a curve or spline first";
        return false;
    }
    // op may change the object's settings too (joint modes): one step with the object, and
    // nothing left of either when it fails.
    c.scene.beginMerge();
    try {
        DocumentObject next = *object;
        if (!op(next)) {
            c.scene.cancelMerge();
            s.message = std::string(label) + ": not for a " + c.scene.item(item).type;
            return false;
        }
        c.scene.replaceObject(item, next, label);
        c.scene.endMerge();
        s.message.clear();
        return true;
    } catch (const Error& e) {
        c.scene.cancelMerge();
        s.message = e.what();
        return false;
    }
}

int selectedPoint(const ToolContext& c) { return c.selection.points.empty() ? -1 : c.selection.points.back(); }

/// Error naming the item unless item i is a lattice object (the lattice operations' argument).
void requireLattice(const Scene& scene, int i)
{
    std::string why;
    if (i < 0 || i >= scene.itemCount()) {
        why = "there is no item ";
        why += std::to_string(i);
    } else if (scene.item(i).kind != SceneItem::Kind::DocumentObject || !std::holds_alternative<LatticeData>(scene.object(i).data)) {
        why = scene.item(i).name;
        why += " is not a lattice";
    }
    if (!why.empty()) throw Error(why);
}

} // namespace

bool elevateSelected(ToolContext& c, State& s)
{
    return editSelected(c, s, "elevate degree", [&](DocumentObject& o) {
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

bool splitSelected(ToolContext& c, State& s)
{
    int item = -1;
    const DocumentObject* object = selectedObject(c, item);
    if (!object) {
        s.message = "select a curve or an open spline first";
        return false;
    }
    try {
        DocumentObject first = *object, second = *object;
        if (const auto* d = std::get_if<BezierCurveData>(&object->data)) {
            auto halves = splitCurve(*d, s.t);
            first.data = halves.first;
            second.data = halves.second;
        } else if (const auto* d = std::get_if<BezierSplineData>(&object->data)) {
            auto halves = splitSpline(*d, s.t * toSpline(*d).domainEnd());
            first.data = halves.first;
            second.data = halves.second;
        } else {
            s.message = "split: for bezier_curve and bezier_spline objects";
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
        s.message.clear();
        return true;
    } catch (const Error& e) {
        c.scene.endMerge();
        s.message = e.what();
        return false;
    }
}

bool insertAtSelected(ToolContext& c, State& s)
{
    const int k = selectedPoint(c);
    return editSelected(c, s, "insert point", [&](DocumentObject& o) {
        if (auto* d = std::get_if<BezierCurveData>(&o.data)) {
            // After the selected point (midway to the next), else at the curve point f(t) before the end.
            const Points3 p = toPoints3(d->points);
            const auto n = static_cast<int>(p.cols());
            if (k >= 0 && k + 1 < n) o.data = insertCurvePoint(*d, k + 1, 0.5 * (p.col(k) + p.col(k + 1)));
            else if (k == n - 1) o.data = insertCurvePoint(*d, n, p.col(n - 1) + (p.col(n - 1) - p.col(n - 2)));
            else o.data = insertCurvePoint(*d, n - 1, BezierCurve<double, 3>(p).evaluate(s.t));
            return true;
        }
        if (auto* d = std::get_if<BezierSplineData>(&o.data)) {
            const BezierSpline<double, 3> spline = toSpline(*d);
            double T = s.t * spline.domainEnd();
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

bool deleteSelected(ToolContext& c, State& s)
{
    const int k = selectedPoint(c);
    if (k < 0) {
        s.message = "select a control point to delete";
        return false;
    }
    const bool ok = editSelected(c, s, "delete point", [&](DocumentObject& o) {
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

bool setJointMode(ToolContext& c, State& s, JointMode mode, int joint)
{
    int item = -1;
    const DocumentObject* object = selectedObject(c, item);
    const auto* d = object ? std::get_if<BezierSplineData>(&object->data) : nullptr;
    if (!d) {
        s.message = "handle modes are for bezier_spline joints";
        return false;
    }
    const int k = selectedPoint(c);
    if (joint < 0) {
        if (k < 0) {
            s.message = "select a joint or a handle of the spline";
            return false;
        }
        joint = jointOfPoint(*d, k);
    }
    if (!isInnerJoint(*d, joint)) {
        s.message = "joint " + std::to_string(joint) + " is an end of the spline: it has no handle mode";
        return false;
    }
    // Keep the selected handle (or the left one) and adjust the opposite one.
    const int side = k >= 0 ? sideOfPoint(*d, joint, k) : -1;
    try {
        DocumentObject next = *object;
        next.data = applyJointMode(*d, joint, mode, side > 0 ? +1 : -1);
        ObjectSettings settings = c.scene.item(item).settings;
        settings.joints = jointModes(c.scene, item);
        settings.joints[static_cast<std::size_t>(joint)] = mode;
        c.scene.beginMerge();
        c.scene.setSettings(item, settings, "handle mode");
        c.scene.replaceObject(item, next, "handle mode");
        c.scene.endMerge();
        s.modeSnapshot = std::get<BezierSplineData>(c.scene.object(item).data);
        s.message = std::string("joint ") + std::to_string(joint) + ": " + toString(mode);
        return true;
    } catch (const Error& e) {
        c.scene.endMerge();
        s.message = e.what();
        return false;
    }
}

bool setAllJointModes(ToolContext& c, State& s, JointMode mode)
{
    int item = -1;
    const DocumentObject* object = selectedObject(c, item);
    const auto* d = object ? std::get_if<BezierSplineData>(&object->data) : nullptr;
    if (!d) {
        s.message = "handle modes are for bezier_spline joints";
        return false;
    }
    try {
        BezierSplineData data = *d;
        ObjectSettings settings = c.scene.item(item).settings;
        settings.joints = jointModes(c.scene, item);
        const bool c2Cubic = mode == JointMode::C2 && data.degree == 3;
        if (c2Cubic) data = c2ThroughJoints(data);
        for (int j = 0; j < static_cast<int>(settings.joints.size()); ++j) {
            if (!isInnerJoint(data, j)) continue;
            if (!c2Cubic) data = applyJointMode(data, j, mode, -1); // left to right: each joint keeps its left side
            settings.joints[static_cast<std::size_t>(j)] = mode;
        }
        DocumentObject next = *object;
        next.data = data;
        c.scene.beginMerge();
        c.scene.setSettings(item, settings, "handle modes");
        c.scene.replaceObject(item, next, "handle modes");
        c.scene.endMerge();
        s.modeSnapshot = data;
        s.message.clear();
        return true;
    } catch (const Error& e) {
        c.scene.endMerge();
        s.message = e.what();
        return false;
    }
}

bool fitLattice(ToolContext& c, State& s, int meshItem)
{
    if (meshItem < 0 || meshItem >= c.scene.itemCount() || c.scene.item(meshItem).kind != SceneItem::Kind::ImportedMesh) {
        s.message = "select an imported mesh to fit a lattice to";
        return false;
    }
    c.scene.updateGeometry();
    const SceneItem& mesh = c.scene.item(meshItem);
    if (!mesh.geometry.surface) {
        s.message = "the mesh has no geometry";
        return false;
    }
    // Fit to the rest mesh (a mesh already deformed by a lattice is fitted as it was read).
    const PolygonMesh* rest = &*mesh.geometry.surface;
    for (const auto& [name, link] : s.links)
        if (link.mesh == mesh.name && link.session && link.meshKey == mesh.key) rest = &link.session->rest();
    try {
        std::array<int, 3> degree{};
        for (int a = 0; a < 3; ++a) degree[static_cast<std::size_t>(a)] = std::clamp(s.latticeDegree[a], 1, 20);
        const Lattice lattice = Lattice::fit(rest->positions, degree, s.margin);
        ObjectSettings settings;
        settings.ffd.mesh = mesh.name;
        const std::string meshName = mesh.name;
        c.scene.beginMerge();
        const int i = c.scene.addObject({meshName + "_lattice", latticeToData(lattice), ""}, "fit lattice");
        c.scene.setSettings(i, settings, "fit lattice");
        c.scene.endMerge();
        c.selection.selectItem(i);
        s.message.clear();
        return true;
    } catch (const Error& e) {
        c.scene.endMerge();
        s.message = e.what();
        return false;
    }
}

bool resetLattice(ToolContext& c, State& s, int latticeItem)
{
    try {
        requireLattice(c.scene, latticeItem);
        DocumentObject o = c.scene.object(latticeItem);
        const Lattice lattice = latticeFromData(std::get<LatticeData>(o.data));
        auto& d = std::get<LatticeData>(o.data);
        d.points = lattice.restPoints();
        c.scene.replaceObject(latticeItem, o, "reset lattice");
        return true;
    } catch (const std::exception& e) {
        s.message = e.what();
        return false;
    }
}

bool exportDeformed(ToolContext& c, State& s, int latticeItem, const std::string& path)
{
    try {
        requireLattice(c.scene, latticeItem);
        const SceneItem& item = c.scene.item(latticeItem);
        const int m = findItem(c.scene, item.settings.ffd.mesh);
        if (m < 0 || c.scene.item(m).kind != SceneItem::Kind::ImportedMesh)
            throw Error("the lattice is bound to no imported mesh");
        const Lattice lattice = latticeFromData(std::get<LatticeData>(c.scene.object(latticeItem).data));
        const DeformReport report = exportDeformedMesh(meshFilePath(c.scene, m), lattice, item.settings.ffd.strength, path);
        s.message = "wrote " + path + " (" + std::to_string(report.vertices) + " positions)";
        return true;
    } catch (const std::exception& e) {
        s.message = e.what();
        return false;
    }
}

bool applyLatticeToObjects(ToolContext& c, State& s, int latticeItem)
{
    try {
        requireLattice(c.scene, latticeItem);
        const Lattice lattice = latticeFromData(std::get<LatticeData>(c.scene.object(latticeItem).data));
        const double w = c.scene.item(latticeItem).settings.ffd.strength;
        int done = 0, skipped = 0;
        std::string why;
        c.scene.beginMerge();
        for (int i = 0; i < c.scene.itemCount(); ++i) {
            if (i == latticeItem || c.scene.item(i).kind != SceneItem::Kind::DocumentObject) continue;
            const DocumentObject& o = c.scene.object(i);
            if (std::holds_alternative<LatticeData>(o.data)) continue;
            std::string reason;
            // A cage in a mesh file is deformed as inline vertices (the file stays as it is), as
            // when one of its vertices is dragged.
            ObjectData data = o.data;
            if (auto* sub = std::get_if<SubdivisionSurfaceData>(&data); sub && !sub->mesh.empty()) {
                try {
                    *sub = inlineCage(*sub, c.scene.documentDirectory(), "the cage file");
                } catch (const Error& e) {
                    ++skipped;
                    why = o.name + ": " + e.what();
                    continue;
                }
            }
            const auto moved = deformObject(lattice, data, w, reason);
            if (!moved) {
                ++skipped;
                why = o.name + ": " + reason;
                continue;
            }
            DocumentObject next = o;
            next.data = *moved;
            c.scene.replaceObject(i, next, "apply lattice");
            ++done;
        }
        c.scene.endMerge();
        s.message = "deformed " + std::to_string(done) + " object(s) exactly";
        if (skipped) s.message += ", left " + std::to_string(skipped) + " (" + why + ")";
        return done > 0;
    } catch (const std::exception& e) {
        c.scene.endMerge();
        s.message = e.what();
        return false;
    }
}

bool computeEdgeContinuity(ToolContext& c, State& s)
{
    PatchComplex complex;
    s.edgePatchNames.clear();
    for (int i = 0; i < c.scene.itemCount(); ++i) {
        if (c.scene.item(i).kind != SceneItem::Kind::DocumentObject) continue;
        if (const auto* d = std::get_if<BezierSurfaceData>(&c.scene.object(i).data)) {
            complex.patches.emplace_back(d->degree[0], d->degree[1], Points3(d->points));
            s.edgePatchNames.push_back(c.scene.item(i).name);
        }
    }
    try {
        s.edges = edgeContinuity(complex);
        s.message = std::to_string(s.edges.size()) + " shared edges between " + std::to_string(complex.patches.size()) + " patches";
        return true;
    } catch (const Error& e) {
        s.message = e.what();
        return false;
    }
}

bool certifyLattice(ToolContext& c, State& s, int latticeItem)
{
    try {
        requireLattice(c.scene, latticeItem);
        const std::string& name = c.scene.item(latticeItem).name;
        const Lattice lattice = latticeFromData(std::get<LatticeData>(c.scene.object(latticeItem).data));
        const Certificate cert = certify(lattice, c.scene.item(latticeItem).settings.ffd.strength);
        if (auto it = s.links.find(name); it != s.links.end()) it->second.certificate = cert;
        s.message = "certificate: " + toString(cert.verdict);
        return true;
    } catch (const std::exception& e) { // also a wrong item (not a lattice, out of range)
        s.message = e.what();
        return false;
    }
}

// ------------------------------------------------------------------ Tools

Tools::Tools() : state_(std::make_unique<State>()) {}
Tools::~Tools() = default;

bool Tools::onKey(ToolContext& c, int key, int mods)
{
    State& s = *state_;
    if (mods & (GLFW_MOD_CONTROL | GLFW_MOD_ALT | GLFW_MOD_SUPER)) return false;
    if (s.creating) {
        if (key == GLFW_KEY_ENTER || key == GLFW_KEY_KP_ENTER) return createCurveFromClicks(c, s), true;
        if (key == GLFW_KEY_ESCAPE) {
            s.creating = false;
            s.newPoints.resize(3, 0);
            return true;
        }
        if (key == GLFW_KEY_BACKSPACE) {
            if (s.newPoints.cols() > 0) s.newPoints.conservativeResize(3, s.newPoints.cols() - 1);
            return true;
        }
    }
    int item = -1;
    const DocumentObject* object = selectedObject(c, item);
    const std::string type = item >= 0 && item < c.scene.itemCount() ? c.scene.item(item).type : std::string();
    const bool curveLike = type == "bezier_curve" || type == "bezier_spline" || type == "deboor_spline";
    switch (key) {
    case GLFW_KEY_C:
        s.creating = !s.creating;
        s.creatingSpline = (mods & GLFW_MOD_SHIFT) != 0;
        s.newPoints.resize(3, 0);
        s.message = !s.creating ? ""
                    : s.creatingSpline ? "click the points the C2 spline passes through; Enter or right click ends, Escape cancels"
                                       : "click control points in the view; Enter or right click ends, Escape cancels";
        return true;
    case GLFW_KEY_P: return createPatch(c, s), true;
    case GLFW_KEY_E:
        if (!curveLike) return false;
        return elevateSelected(c, s), true;
    case GLFW_KEY_K:
        if (!curveLike) return false;
        return splitSelected(c, s), true;
    case GLFW_KEY_I:
        if (!curveLike) return false;
        return insertAtSelected(c, s), true;
    case GLFW_KEY_DELETE:
        if (!curveLike || c.selection.points.empty()) return false;
        return deleteSelected(c, s), true;
    case GLFW_KEY_T:
        if (!curveLike) return false;
        s.construction = !s.construction;
        return true;
    case GLFW_KEY_V:
        if (!curveLike) return false;
        s.comb = !s.comb;
        return true;
    case GLFW_KEY_1: case GLFW_KEY_2: case GLFW_KEY_3: case GLFW_KEY_4:
        if (!object || !std::holds_alternative<BezierSplineData>(object->data) || c.selection.points.empty()) return false;
        return setJointMode(c, s, static_cast<JointMode>(key - GLFW_KEY_1)), true;
    case GLFW_KEY_L:
        if (item < 0 || c.scene.item(item).kind != SceneItem::Kind::ImportedMesh) return false;
        return fitLattice(c, s, item), true;
    case GLFW_KEY_D:
        s.direct = !s.direct;
        s.message = s.direct ? "direct manipulation: drag a point of a deformed mesh" : "";
        return true;
    default: return false;
    }
}

bool Tools::onPointer(ToolContext& c, const PointerEvent& e)
{
    State& s = *state_;
    Scene& scene = c.scene;
    if (s.creating) {
        if (e.type == PointerEvent::Type::Press && e.button == 1) return createCurveFromClicks(c, s), true;
        if (e.type == PointerEvent::Type::Press && e.button == 0) {
            const auto p = rayPlane(e, scene.bounds().center(), scene.camera.back());
            if (p) {
                s.newPoints.conservativeResize(3, s.newPoints.cols() + 1);
                s.newPoints.col(s.newPoints.cols() - 1) = *p;
            }
            return true;
        }
        return e.type != PointerEvent::Type::Move || e.button == 0;
    }
    // Drags in progress.
    if (s.drag != State::Drag::None) {
        if (e.type == PointerEvent::Type::Release) {
            s.drag = State::Drag::None;
            scene.endMerge();
            return true;
        }
        if (e.type != PointerEvent::Type::Move) return true;
        const auto hit = rayPlane(e, s.dragPlanePoint, s.dragPlaneNormal);
        if (!hit || s.dragItem >= scene.itemCount()) return true;
        try {
            DocumentObject next = s.dragObject;
            if (s.drag == State::Drag::DeBoor) {
                Points3 deboor = s.dragDeBoor;
                deboor.col(s.dragIndex) = *hit + s.dragOffset;
                next.data = splineFromDeBoor(std::get<BezierSplineData>(s.dragObject.data), deboor);
                scene.replaceObject(s.dragItem, next, "move de Boor point");
                s.modeSnapshot = std::get<BezierSplineData>(next.data);
            } else {
                const Lattice start = latticeFromData(std::get<LatticeData>(s.dragObject.data));
                s.directTarget = *hit + s.dragOffset;
                const DirectManipulation dm = directManipulation(start, s.directRest, s.directTarget,
                                                                 scene.item(s.dragItem).settings.ffd.strength);
                next.data = latticeToData(dm.lattice);
                scene.replaceObject(s.dragItem, next, "direct manipulation");
            }
        } catch (const Error& err) {
            s.message = err.what();
        }
        return true;
    }
    if (e.type != PointerEvent::Type::Press || e.button != 0 || e.mods != 0) return false;
    // A de Boor point of the selected all-C2 spline.
    int item = -1;
    const DocumentObject* object = selectedObject(c, item);
    if (const auto* d = object ? std::get_if<BezierSplineData>(&object->data) : nullptr; d && allC2(*d, jointModes(scene, item))) {
        try {
            const Points3 deboor = splineDeBoorPoints(*d);
            int best = -1;
            double bestDistance = 9.0; // pixels
            for (Eigen::Index i = 0; i < deboor.cols(); ++i) {
                const auto px = toPixel(c, deboor.col(i));
                if (!px) continue;
                const double dist = (*px - Eigen::Vector2d(e.x, e.y)).norm();
                if (dist < bestDistance) bestDistance = dist, best = static_cast<int>(i);
            }
            if (best >= 0) {
                s.drag = State::Drag::DeBoor;
                s.dragItem = item;
                s.dragIndex = best;
                s.dragDeBoor = deboor;
                s.dragObject = *object;
                s.dragPlanePoint = deboor.col(best);
                s.dragPlaneNormal = scene.camera.back();
                const auto on = rayPlane(e, s.dragPlanePoint, s.dragPlaneNormal);
                s.dragOffset = on ? Eigen::Vector3d(s.dragPlanePoint - *on) : Eigen::Vector3d::Zero();
                scene.beginMerge();
                return true;
            }
        } catch (const Error&) {
            // Not C2 within tolerance: no de Boor points to grab.
        }
    }
    // Direct manipulation: a point of a mesh deformed by a lattice.
    if (s.direct) {
        double nearest = std::numeric_limits<double>::infinity();
        for (const auto& [name, link] : s.links) {
            const int m = findItem(scene, link.mesh), li = findItem(scene, name);
            if (m < 0 || li < 0 || !link.session || !scene.item(m).geometry.surface || !scene.item(m).settings.visible) continue;
            const PolygonMesh& shown = *scene.item(m).geometry.surface;
            const auto hit = rayMeshHit(e.rayOrigin, e.rayDirection, shown);
            if (!hit || hit->distance >= nearest) continue;
            nearest = hit->distance;
            s.drag = State::Drag::Direct;
            s.dragItem = li;
            s.dragObject = scene.object(li);
            s.directRest = pointAt(link.session->rest(), link.session->rest().positions, *hit);
            s.dragPlanePoint = pointAt(shown, shown.positions, *hit);
            s.directTarget = s.dragPlanePoint;
            s.dragPlaneNormal = scene.camera.back();
            s.dragOffset = Eigen::Vector3d::Zero();
        }
        if (s.drag == State::Drag::Direct) {
            c.selection.selectItem(s.dragItem);
            scene.beginMerge();
            return true;
        }
    }
    return false;
}

void Tools::update(ToolContext& c, Overlay& o)
{
    State& s = *state_;
    if (s.drag == State::Drag::None) trackJointModes(c, s);
    s.lastChange = c.scene.changeCount();
    updateLinks(c, s);
    // Overlays.
    if (s.creating) {
        if (s.creatingSpline && s.newPoints.cols() >= 2) {
            // The spline the clicks make so far (nothing while two clicks coincide).
            try {
                const BezierSpline<double, 3> preview = interpolateCubic<double, 3>(s.newPoints);
                Points3 samples(3, 16 * preview.segmentCount() + 1);
                for (Eigen::Index k = 0; k < samples.cols(); ++k)
                    samples.col(k) = preview.evaluate(preview.domainEnd() * double(k) / double(samples.cols() - 1));
                drawPolyline(o, samples, kCreate);
            } catch (const Error&) {
            }
        } else {
            drawPolyline(o, s.newPoints, kCreate);
        }
        for (Eigen::Index i = 0; i < s.newPoints.cols(); ++i) o.addPoint(f3(s.newPoints.col(i)), kCreate);
    }
    try {
        curveOverlays(c, s, o);
    } catch (const Error& e) {
        s.message = e.what();
    }
    if (s.drag == State::Drag::Direct) o.addPoint(f3(s.directTarget), kCurvePoint);
}

void Tools::reset()
{
    *state_ = State{};
}

const char* Tools::keyHelp()
{
    return "C: create a curve by clicking its control points (Enter / right click ends, Backspace removes the last point, Escape cancels)\n"
           "Shift+C: create a C2 cubic spline through the clicked points (ends as C)\n"
           "P: create a Bezier patch of the panel's degrees in the view plane\n"
           "I: insert a control point after the selected one (spline: a joint in its segment)\n"
           "Delete: delete the selected control point (spline: its joint)\n"
           "E: elevate the degree (shape unchanged)\n"
           "K: split the curve or open spline at the t slider\n"
           "T: de Casteljau construction at t;  V: curvature comb\n"
           "1 / 2 / 3 / 4 (spline point selected): joint free / aligned (G1) / mirrored (C1) / C2\n"
           "L (imported mesh selected): fit a lattice to it (degrees and margin in the panel)\n"
           "D: direct manipulation (drag a point of a deformed mesh; the lattice follows)";
}

} // namespace freeform::editor
