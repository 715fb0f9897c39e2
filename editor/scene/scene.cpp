// The Scene (scene/scene.h): its items and their settings, the document's objects and control
// points edited through one undo step each, the undo history, derived geometry rebuilt when dirty,
// the view's tolerance and the background tessellation, bounds and item lookup. Loading, saving,
// importing and exporting are in scene_io.cpp.

#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "freeform/document/object_data.h"
#include "freeform/io/geometry_data.h"
#include "scene/scene_internal.h"
#include "scene/tessellation_worker.h"

namespace freeform::editor {

namespace fs = std::filesystem;

namespace scene_detail {

/// Revisions are unique across all scenes, so a drawer never mistakes a new item for an old one.
int nextRevision()
{
    static int counter = 0;
    return ++counter;
}

/// Content keys are unique across all scenes too.
long nextKey()
{
    static long counter = 0;
    return ++counter;
}

/// Stable item ids, never reused (unique across all scenes, so a drawer or a tool that kept one
/// never finds another item under it).
long nextId()
{
    static long counter = 0;
    return ++counter;
}

} // namespace scene_detail

Scene::Scene() { model_.source = "scene"; }

void Scene::rebuildItems()
{
    std::vector<SceneItem> items;
    for (const DocumentObject& o : document_.objects) {
        SceneItem item;
        item.kind = SceneItem::Kind::DocumentObject;
        item.name = o.name;
        item.type = objectType(o.data);
        item.key = scene_detail::nextKey();
        item.id = scene_detail::nextId();
        items.push_back(std::move(item));
    }
    items_ = std::move(items);
    retypeAll();
}

void Scene::addMeshItem(const std::string& name, const std::string& path)
{
    SceneItem item;
    item.kind = SceneItem::Kind::ImportedMesh;
    item.name = uniqueName(name);
    item.type = "mesh";
    item.meshPath = path;
    item.key = scene_detail::nextKey();
    item.id = scene_detail::nextId();
    items_.push_back(std::move(item));
}

std::string Scene::uniqueName(const std::string& base, const std::vector<SceneItem>& pending) const
{
    std::set<std::string> used;
    for (const SceneItem& i : items_) used.insert(i.name);
    for (const SceneItem& i : pending) used.insert(i.name);
    for (const DocumentObject& o : document_.objects) used.insert(o.name);
    const std::string stem = base.empty() ? "object" : base;
    if (!used.count(stem)) return stem;
    for (int k = 2;; ++k) {
        const std::string candidate = stem + "_" + std::to_string(k);
        if (!used.count(candidate)) return candidate;
    }
}

std::string Scene::resolve(const std::string& meshPath) const
{
    const fs::path p(meshPath);
    if (p.is_absolute() || path_.empty()) return meshPath;
    return (fs::path(path_).parent_path() / p).string();
}

// ------------------------------------------------------------------------------- the typed document

void Scene::retype(std::size_t i)
{
    SceneItem& it = items_[i];
    if (it.kind != SceneItem::Kind::DocumentObject) return;
    const ObjectData& data = document_.objects[i].data;
    try {
        if (it.object != 0 && model_.find(it.object)) {
            model_.replace(it.object, data); // Error: nothing changed, the old geometry goes below
            model_.rename(it.object, it.name);
        } else {
            it.object = model_.add(it.name, data);
        }
        it.invalid.clear();
    } catch (const Error& e) {
        if (it.object != 0 && model_.find(it.object)) model_.remove(it.object);
        it.object = 0;
        // The document layer's message without its "scene: object "name": " (the item names it).
        const std::string prefix = model_.source + ": object \"" + it.name + "\": ", message = e.what();
        it.invalid = message.rfind(prefix, 0) == 0 ? message.substr(prefix.size()) : message;
    }
}

void Scene::retypeAll()
{
    model_ = TypedDocument();
    model_.source = "scene";
    model_.directory = documentDirectory();
    for (SceneItem& it : items_) it.object = 0;
    for (std::size_t i = 0; i < items_.size(); ++i) retype(i);
}

const TypedObject* Scene::typed(int i) const
{
    const SceneItem& it = item(i);
    return it.object != 0 ? model_.find(it.object) : nullptr;
}

const TypedObject& Scene::typedObject(int i) const
{
    if (const TypedObject* o = typed(i)) return *o;
    object(i); // Error for a mesh
    throw Error("\"" + item(i).name + "\": " + item(i).invalid);
}

const Lattice& Scene::lattice(int i) const
{
    const TypedObject& o = typedObject(i);
    if (const auto* l = std::get_if<Lattice>(&o.geometry())) return *l;
    throw Error("\"" + item(i).name + "\" is a " + item(i).type + ", not a lattice");
}

const DocumentObject& Scene::object(int i) const
{
    if (item(i).kind != SceneItem::Kind::DocumentObject) throw Error("\"" + item(i).name + "\" is a mesh, not a document object");
    return document_.objects.at(static_cast<std::size_t>(i));
}

void Scene::replaceObject(int i, const DocumentObject& object, const std::string& label)
{
    const DocumentObject& old = this->object(i);
    if (object.name != old.name) throw Error("replaceObject: the name must stay \"" + old.name + "\"");
    // Validate through the strict reader: a document of this one object must parse.
    Document single;
    single.objects.push_back(object);
    Document checked = parseDocument(formatDocument(single), "object \"" + object.name + "\"");
    record(label);
    setObjectData(i, std::move(checked.objects.front().data));
}

void Scene::amendObject(int i, const DocumentObject& object)
{
    const DocumentObject& old = this->object(i);
    if (object.name != old.name) throw Error("amendObject: the name must stay \"" + old.name + "\"");
    Document single;
    single.objects.push_back(object);
    Document checked = parseDocument(formatDocument(single), "object \"" + object.name + "\"");
    ++changes_;
    setObjectData(i, std::move(checked.objects.front().data));
}

void Scene::setObjectData(int i, ObjectData data)
{
    document_.objects[static_cast<std::size_t>(i)].data = std::move(data);
    retype(static_cast<std::size_t>(i));
    SceneItem& it = items_[static_cast<std::size_t>(i)];
    it.geometryDirty = true;
    it.key = scene_detail::nextKey();
    modified_ = true;
}

void Scene::setControlPoint(int i, int k, const Eigen::Vector3d& p, const std::string& label)
{
    setControlPoints(i, {k}, p, label);
}

void Scene::setControlPoints(int i, const std::vector<int>& ks, const Eigen::Matrix3Xd& ps, const std::string& label)
{
    const DocumentObject& o = object(i);
    if (static_cast<Eigen::Index>(ks.size()) != ps.cols()) {
        std::string message = "setControlPoints: ";
        message += std::to_string(ks.size()) + " indices for " + std::to_string(ps.cols()) + " points";
        throw Error(message);
    }
    ObjectData data = o.data;
    // A subdivision cage read from a mesh file becomes inline vertices and faces (with the file's
    // crease tags) when one of its vertices is edited; the file itself is left as it is.
    if (auto* sub = std::get_if<SubdivisionSurfaceData>(&data); sub && !sub->mesh.empty())
        *sub = inlineCage(*sub, documentDirectory(), "\"" + o.name + "\"");
    PointColumns* held = dataPoints(data);
    if (!held) throw Error("\"" + o.name + "\" is a " + objectType(data) + ": it has no control points to edit");
    PointColumns& points = *held;
    for (std::size_t j = 0; j < ks.size(); ++j) {
        const int k = ks[j];
        if (k < 0 || k >= points.cols()) throw Error("\"" + o.name + "\" has no control point " + std::to_string(k));
        for (Eigen::Index r = 0; r < points.rows(); ++r) {
            const double v = ps(r, static_cast<Eigen::Index>(j));
            if (!std::isfinite(v)) throw Error("\"" + o.name + "\": control point " + std::to_string(k) + " must be finite");
            points(r, k) = v;
        }
    }
    record(label);
    setObjectData(i, std::move(data));
}

std::string Scene::documentDirectory() const
{
    if (!cageDirectory_.empty()) return cageDirectory_;
    return path_.empty() ? std::string() : fs::path(path_).parent_path().string();
}

Eigen::Matrix3Xd Scene::controlPoints(int i) const
{
    if (item(i).kind != SceneItem::Kind::DocumentObject) return {};
    if (const auto* sub = std::get_if<SubdivisionSurfaceData>(&object(i).data); sub && !sub->mesh.empty())
        return item(i).geometry.netPoints; // a file-backed cage: its vertices as read
    const PointColumns* held = dataPoints(object(i).data);
    if (!held) return {};
    const PointColumns& p = *held;
    Eigen::Matrix3Xd out = Eigen::Matrix3Xd::Zero(3, p.cols());
    out.topRows(std::min<Eigen::Index>(3, p.rows())) = p.topRows(std::min<Eigen::Index>(3, p.rows()));
    return out;
}

int Scene::controlPointCount(int i) const
{
    if (item(i).kind != SceneItem::Kind::DocumentObject) return 0;
    if (const auto* sub = std::get_if<SubdivisionSurfaceData>(&object(i).data); sub && !sub->mesh.empty())
        return static_cast<int>(item(i).geometry.netPoints.cols());
    const PointColumns* held = dataPoints(object(i).data);
    return held ? static_cast<int>(held->cols()) : 0;
}

void Scene::setSettings(int i, const ObjectSettings& settings, const std::string& label)
{
    SceneItem& it = item(i);
    if (it.settings == settings) return;
    record(label);
    const bool geometry = !(it.settings.tessellation == settings.tessellation);
    const bool link = it.settings.ffd.mesh != settings.ffd.mesh;
    it.settings = settings;
    if (link) resolveLink(it);
    if (geometry && it.kind == SceneItem::Kind::DocumentObject) {
        it.geometryDirty = true;
        it.key = scene_detail::nextKey();
    }
    modified_ = true;
}

int Scene::addObject(DocumentObject object, const std::string& label)
{
    object.name = uniqueName(object.name);
    Document single;
    single.objects.push_back(object);
    Document checked = parseDocument(formatDocument(single), "object \"" + object.name + "\"");
    record(label);
    const auto at = static_cast<std::ptrdiff_t>(document_.objects.size());
    document_.objects.push_back(std::move(checked.objects.front()));
    SceneItem item;
    item.name = object.name;
    item.type = objectType(document_.objects.back().data);
    item.key = scene_detail::nextKey();
    item.id = scene_detail::nextId();
    items_.insert(items_.begin() + at, std::move(item));
    retype(static_cast<std::size_t>(at));
    modified_ = true;
    return static_cast<int>(at);
}

void Scene::setScalars(int i, std::vector<float> scalars)
{
    SceneItem& it = item(i);
    const long vertices = it.geometry.surface ? it.geometry.surface->vertexCount() : 0;
    if (!scalars.empty() && static_cast<long>(scalars.size()) != vertices)
        throw Error("\"" + it.name + "\": " + std::to_string(scalars.size()) + " scalars for " + std::to_string(vertices) + " vertices");
    it.scalars = std::move(scalars);
    it.revision = scene_detail::nextRevision();
}

void Scene::remove(int i)
{
    record("delete " + item(i).name);
    if (item(i).kind == SceneItem::Kind::DocumentObject) {
        if (item(i).object != 0) model_.remove(item(i).object);
        document_.objects.erase(document_.objects.begin() + i);
    }
    items_.erase(items_.begin() + i);
    modified_ = true;
}

// ------------------------------------------------------------------------------------ undo

void Scene::record(const std::string& label)
{
    ++changes_;
    if (history_.wantsStep()) history_.record(label, state());
}

SceneState Scene::state() const
{
    SceneState s;
    s.objects = document_.objects;
    s.items.reserve(items_.size());
    for (const SceneItem& it : items_) s.items.push_back({it.kind, it.name, it.type, it.meshPath, it.up, it.settings, it.key, it.id, it.deforms});
    return s;
}

void Scene::restore(SceneState state)
{
    std::map<long, std::size_t> byKey;
    for (std::size_t i = 0; i < items_.size(); ++i) byKey[items_[i].key] = i;
    std::vector<SceneItem> items;
    items.reserve(state.items.size());
    std::vector<bool> kept; // the item's content is one the scene holds: its typed object too
    std::set<ObjectId> typedKept;
    for (SceneState::Item& r : state.items) {
        SceneItem it;
        const auto found = byKey.find(r.key);
        if (found != byKey.end()) it = std::move(items_[found->second]); // same content: keep its geometry
        kept.push_back(found != byKey.end());
        if (kept.back() && it.object != 0) typedKept.insert(it.object);
        it.kind = r.kind;
        it.name = std::move(r.name);
        it.type = std::move(r.type);
        it.meshPath = std::move(r.meshPath);
        it.up = r.up;
        it.settings = r.settings;
        it.key = r.key;
        it.id = r.id;
        it.deforms = r.deforms;
        items.push_back(std::move(it));
    }
    items_ = std::move(items);
    document_.objects = std::move(state.objects);
    // The typed objects of the items whose content came back as it was stay; the rest are built
    // again from the restored data, and those of items that are gone are dropped.
    std::vector<ObjectId> gone;
    for (const TypedObject& o : model_.objects())
        if (!typedKept.count(o.id())) gone.push_back(o.id());
    for (const ObjectId id : gone) model_.remove(id);
    for (std::size_t i = 0; i < items_.size(); ++i) {
        if (kept[i]) {
            if (items_[i].object != 0 && model_.object(items_[i].object).name() != items_[i].name) model_.rename(items_[i].object, items_[i].name);
            continue;
        }
        items_[i].object = 0;
        retype(i);
    }
    modified_ = true;
    ++changes_;
}

bool Scene::undo()
{
    std::optional<SceneState> s = history_.undo(state());
    if (!s) return false;
    restore(std::move(*s));
    return true;
}

bool Scene::redo()
{
    std::optional<SceneState> s = history_.redo(state());
    if (!s) return false;
    restore(std::move(*s));
    return true;
}

void Scene::cancelMerge()
{
    if (std::optional<SceneState> s = history_.cancelMerge()) restore(std::move(*s));
}

void Scene::invalidateGeometry()
{
    for (SceneItem& item : items_)
        if (item.kind == SceneItem::Kind::DocumentObject) item.geometryDirty = true;
}

void Scene::buildItem(std::size_t i)
{
    SceneItem& item = items_[i];
    if (item.kind == SceneItem::Kind::DocumentObject) {
        item.builtTolerance = tessellationTolerance();
        item.geometry = buildGeometry(*this, static_cast<int>(i), item.builtTolerance, pixelScale_);
    } else {
        try {
            item.geometry = buildMeshGeometry(resolve(item.meshPath), item.up);
        } catch (const Error& e) {
            item.geometry = ItemGeometry{};
            item.geometry.error = e.what();
        }
    }
    if (item.geometry.surface && item.scalars.size() != static_cast<std::size_t>(item.geometry.surface->vertexCount()))
        item.scalars.clear();
    item.geometryDirty = false;
    item.revision = item.topology = scene_detail::nextRevision();
}

void Scene::updateGeometry()
{
    // Relative cage paths start elsewhere once the document has another folder (Save As): every
    // typed object is built again before an item is built, here or in the background.
    if (model_.directory != documentDirectory()) retypeAll();
    for (std::size_t i = 0; i < items_.size(); ++i)
        if (items_[i].geometryDirty) buildItem(i);
    if (backgroundOn_) {
        takeBackgroundResult();
        submitStale();
    }
    updateDerived();
}

void Scene::updateViewTolerance(int height)
{
    double t = 0;
    if (pixelTolerance > 0 && height > 0) {
        // One pixel at depth z is 2 z tan(fovy/2) / height (perspective) or 2 halfHeight / height
        // (orthographic); z: the nearest corner of the visible items' box, at least 1/20 of the distance.
        const Eigen::AlignedBox3d box = bounds();
        double z = camera.distance;
        if (camera.projection == Projection::Perspective) {
            for (int c = 0; c < 8; ++c)
                z = std::min(z, (box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)) - camera.eye()).dot(-camera.back()));
            z = std::max(z, camera.distance / 20);
        }
        t = pixelTolerance * 2 * camera.halfHeight() * (z / camera.distance) / height;
    }
    // Per patch (bezier and de Boor surfaces): the same pixel size at each patch's own nearest depth.
    PixelScale scale;
    if (t > 0) {
        scale.perspective = camera.projection == Projection::Perspective;
        scale.eye = camera.eye();
        scale.forward = -camera.back();
        scale.span = pixelTolerance * 2 * camera.halfHeight();
        scale.distance = camera.distance;
        scale.height = height;
    }
    pixelScale_ = scale;
    if ((t == 0) != (viewTolerance_ == 0) || t > 2 * viewTolerance_ || t < viewTolerance_ / 2) {
        viewTolerance_ = t;
        // In the background, updateGeometry finds the items built for another tolerance itself.
        if (!backgroundOn_) invalidateGeometry();
    }
    if (!backgroundOn_)
        for (SceneItem& item : items_)
            if (followsViewTolerance(item) && patchesStale(item)) item.geometryDirty = true;
}

bool Scene::patchesStale(const SceneItem& item) const
{
    if (!pixelScale_.on() || item.geometry.patchBoxes.empty()) return false;
    std::vector<double> wanted;
    wanted.reserve(item.geometry.patchBoxes.size());
    for (const Eigen::AlignedBox3d& box : item.geometry.patchBoxes) wanted.push_back(pixelScale_.tolerance(box));
    return !withinTwice(item.geometry.patchTolerance, wanted);
}

// ------------------------------------------------------------------------------------ background

BackgroundTessellation::BackgroundTessellation() = default;
BackgroundTessellation::~BackgroundTessellation() = default;
BackgroundTessellation::BackgroundTessellation(const BackgroundTessellation&) {}
BackgroundTessellation& BackgroundTessellation::operator=(const BackgroundTessellation& other)
{
    if (this != &other) *this = BackgroundTessellation();
    return *this;
}
BackgroundTessellation::BackgroundTessellation(BackgroundTessellation&&) noexcept = default;
BackgroundTessellation& BackgroundTessellation::operator=(BackgroundTessellation&&) noexcept = default;

void Scene::setBackgroundTessellation(bool on)
{
    if (on == backgroundOn_) return;
    backgroundOn_ = on;
    if (!on) {
        background_ = BackgroundTessellation(); // stops and joins the worker; its result is not wanted
        for (SceneItem& item : items_)
            if (stale(item)) item.geometryDirty = true;
    }
}

TessellationWorker& Scene::tessellationWorker()
{
    if (!background_.worker) background_.worker = std::make_unique<TessellationWorker>();
    return *background_.worker;
}

bool Scene::followsViewTolerance(const SceneItem& item) const
{
    if (item.kind != SceneItem::Kind::DocumentObject || item.is(ObjectKind::Lattice)) return false;
    const Tessellation& t = item.settings.tessellation;
    if (t.tolerance > 0) return false; // its own tolerance
    // Uniform surfaces ignore the tolerance; a curve's polyline follows it in either mode.
    return t.mode == Tessellation::Mode::Adaptive || item.geometry.curve.cols() > 0;
}

bool Scene::stale(const SceneItem& item) const
{
    return !item.geometryDirty && followsViewTolerance(item) &&
           (item.builtTolerance != tessellationTolerance() || patchesStale(item));
}

bool Scene::tessellationPending() const
{
    if (background_.generation != 0) return true;
    for (const SceneItem& item : items_)
        if (stale(item)) return true;
    return false;
}

void Scene::takeBackgroundResult()
{
    if (!background_.worker || background_.generation == 0) return;
    std::optional<TessellationResult> result = background_.worker->take();
    if (!result) return;
    if (result->generation != background_.generation) { // cannot happen: a superseded job never publishes
        backgroundStats_.dropped += static_cast<long>(result->items.size());
        return;
    }
    background_.generation = 0;
    for (TessellationResult::Item& r : result->items) {
        const int i = indexOf(r.id);
        // Only onto the content the job copied, for the tolerance wanted now.
        if (i < 0 || items_[static_cast<std::size_t>(i)].key != r.key || items_[static_cast<std::size_t>(i)].geometryDirty ||
            result->tolerance != tessellationTolerance()) {
            ++backgroundStats_.dropped;
            continue;
        }
        SceneItem& item = items_[static_cast<std::size_t>(i)];
        std::swap(item.geometry, r.geometry);
        if (patchesStale(item)) { // per-patch tolerances for a view that has since moved past 2x
            std::swap(item.geometry, r.geometry);
            ++backgroundStats_.dropped;
            continue;
        }
        item.builtTolerance = result->tolerance;
        if (item.geometry.surface && item.scalars.size() != static_cast<std::size_t>(item.geometry.surface->vertexCount()))
            item.scalars.clear();
        item.revision = item.topology = scene_detail::nextRevision();
        ++backgroundStats_.applied;
    }
}

void Scene::submitStale()
{
    const double t = tessellationTolerance();
    if (background_.generation != 0 && background_.tolerance == t) return; // on its way
    TessellationJob job;
    job.tolerance = t;
    job.view = pixelScale_;
    for (std::size_t i = 0; i < items_.size(); ++i)
        if (stale(items_[i])) {
            TessellationJob::Item item{items_[i].id, items_[i].key, std::nullopt, {}, items_[i].invalid, items_[i].settings};
            if (const TypedObject* o = typed(static_cast<int>(i))) item.object = *o;
            else item.data = document_.objects[i].data;
            job.items.push_back(std::move(item));
        }
    if (job.items.empty() && background_.generation == 0) return;
    // A job for another tolerance is superseded (an empty job only cancels it).
    job.generation = ++background_.lastGeneration;
    job.directory = documentDirectory();
    const bool cancelOnly = job.items.empty();
    if (!cancelOnly) ++backgroundStats_.jobs;
    tessellationWorker().submit(std::move(job));
    background_.generation = cancelOnly ? 0 : background_.lastGeneration;
    background_.tolerance = t;
}

void Scene::finishTessellation()
{
    updateGeometry();
    while (backgroundOn_ && background_.generation != 0) {
        background_.worker->wait();
        updateGeometry();
    }
    finishDeformation();
}

Eigen::AlignedBox3d Scene::bounds() const
{
    Eigen::AlignedBox3d box;
    box.setEmpty();
    for (const SceneItem& item : items_)
        if (item.settings.visible && !item.geometry.bounds.isEmpty()) box.extend(item.geometry.bounds);
    if (box.isEmpty()) box = Eigen::AlignedBox3d(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1));
    return box;
}

// ------------------------------------------------------------------------------------ ids, links

int Scene::indexOf(long id) const
{
    if (id == 0) return -1;
    for (std::size_t i = 0; i < items_.size(); ++i)
        if (items_[i].id == id) return static_cast<int>(i);
    return -1;
}

int Scene::itemOfObject(ObjectId object) const
{
    if (object == 0) return -1;
    for (std::size_t i = 0; i < items_.size(); ++i)
        if (items_[i].object == object) return static_cast<int>(i);
    return -1;
}

int Scene::indexOf(const std::string& name) const
{
    for (std::size_t i = 0; i < items_.size(); ++i)
        if (items_[i].name == name) return static_cast<int>(i);
    return -1;
}

} // namespace freeform::editor
