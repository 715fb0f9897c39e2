#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "freeform/document/object_data.h"
#include "freeform/io/bpt.h"
#include "freeform/io/geometry_data.h"
#include "freeform/io/json_check.h"
#include "freeform/io/file.h"
#include "freeform/io/mesh_io.h"
#include "freeform/subdivision/subdivision_surface.h"
#include "freeform/surface/patch_complex.h"
#include "freeform/tessellate/tessellate.h"
#include "scene/json_read.h"
#include "scene/tessellation_worker.h"

namespace freeform::editor {

namespace fs = std::filesystem;

namespace {

std::string lowerExtension(const std::string& path)
{
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

bool isMeshFile(const std::string& ext)
{
    return ext == ".obj" || ext == ".ply" || ext == ".stl" || ext == ".off" || ext == ".gltf" || ext == ".glb";
}

/// Six times the signed volume enclosed by a triangle mesh (positive when its triangles face out).
double signedVolume6(const PolygonMesh& mesh)
{
    double sum = 0;
    for (int f = 0; f < mesh.faceCount(); ++f) {
        const int* v = mesh.face(f);
        for (int k = 1; k + 1 < mesh.faceSize(f); ++k)
            sum += mesh.positions.col(v[0]).dot(mesh.positions.col(v[k]).cross(mesh.positions.col(v[k + 1])));
    }
    return sum;
}

/// One bezier_surface object per patch of a .bpt file. Patch files do not agree on orientation
/// (teapot.bpt's f_u x f_v points inwards): when the complex encloses a negative volume, every
/// patch is transposed (u and v swapped) so that the normals point out.
std::vector<DocumentObject> bptObjects(const std::string& path)
{
    PatchComplex complex = readBpt(path);
    if (signedVolume6(tessellateUniform(complex, 4, 4)) < 0)
        for (Patch& patch : complex.patches) patch = patch.transposed();
    std::vector<DocumentObject> objects;
    for (std::size_t i = 0; i < complex.patches.size(); ++i) {
        const auto& patch = complex.patches[i];
        char name[32];
        std::snprintf(name, sizeof name, "patch_%02zu", i);
        objects.push_back({name, toData(patch), ""});
    }
    return objects;
}

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

PointColumns& pointsOf(ObjectData& data)
{
    return std::visit(
        [](auto& d) -> PointColumns& {
            using T = std::decay_t<decltype(d)>;
            if constexpr (std::is_same_v<T, SubdivisionSurfaceData>) return d.vertices;
            else return d.points;
        },
        data);
}

} // namespace

Scene::Scene() = default;

Scene Scene::load(const std::string& path, double aspect)
{
    Scene scene;
    const std::string ext = lowerExtension(path);
    if (ext == ".bpt") {
        scene.document_.objects = bptObjects(path);
        scene.document_.source = path;
    } else if (isMeshFile(ext)) {
        scene.document_.source = path;
        scene.addMeshItem(fs::path(path).stem().string(), fs::absolute(path).string());
        scene.items_.back().up = formatUpAxis(path).value_or(UpAxis::Z); // glTF and GLB: Y up, as on import
    } else {
        scene.document_ = readDocument(path);
        scene.path_ = path;
        scene.cageDirectory_ = fs::path(path).parent_path().string();
    }
    // The editor member: camera, display, imported meshes. Errors name the file.
    bool hasCamera = false;
    if (!scene.document_.editor.empty()) {
        try {
            // Through the library's one JSON gate (docs/mesh-io.md, "Hostile input"): the text
            // may come from anywhere a Document does, not only from readDocument's checked file.
            checkJsonText(scene.document_.editor, "editor");
            Json e;
            try {
                e = Json::parse(scene.document_.editor);
            } catch (const Json::exception& x) {
                throw Error(std::string("editor: not valid JSON: ") + x.what());
            }
            for (const auto& [key, value] : e.items())
                if (key != "camera" && key != "display" && key != "meshes") json::fail("editor." + key, "unknown field");
            if (e.contains("camera")) {
                scene.camera = Camera::fromJson(e["camera"]);
                hasCamera = true;
            }
            if (e.contains("display")) scene.display = DisplaySettings::fromJson(e["display"]);
            if (e.contains("meshes")) {
                const Json& meshes = e["meshes"];
                if (!meshes.is_array()) json::fail("editor.meshes", "expected an array");
                for (std::size_t i = 0; i < meshes.size(); ++i) {
                    const std::string mp = "editor.meshes[" + std::to_string(i) + "]";
                    const Json& m = meshes[i];
                    json::requireObject(m, mp);
                    if (!m.contains("name") || !m["name"].is_string()) json::fail(mp + ".name", "expected a string");
                    if (!m.contains("path") || !m["path"].is_string()) json::fail(mp + ".path", "expected a string");
                    for (const auto& [key, value] : m.items())
                        if (key != "name" && key != "path" && key != "up" && key != "editor") json::fail(mp + "." + key, "unknown field");
                    UpAxis up = UpAxis::Z; // absent: the file is Z-up, as before the field existed
                    if (m.contains("up")) {
                        if (!m["up"].is_string()) json::fail(mp + ".up", "expected \"z\" or \"y\"");
                        up = parseUpAxis(m["up"].get<std::string>(), mp + ".up");
                    }
                    scene.addMeshItem(m["name"].get<std::string>(), m["path"].get<std::string>());
                    scene.items_.back().up = up;
                    if (m.contains("editor")) scene.items_.back().settings = ObjectSettings::fromJson(m["editor"], mp + ".editor");
                }
            }
        } catch (const Error& e) {
            throw Error(path + ": " + e.what());
        }
    }
    // Object settings.
    std::vector<SceneItem> meshes(scene.items_.begin(), scene.items_.end());
    scene.rebuildItems();
    scene.items_.insert(scene.items_.end(), meshes.begin(), meshes.end());
    for (std::size_t i = 0; i < scene.document_.objects.size(); ++i) {
        const DocumentObject& o = scene.document_.objects[i];
        if (o.editor.empty()) continue;
        try {
            scene.items_[i].settings = ObjectSettings::fromText(o.editor, "object \"" + o.name + "\".editor"); // gated
        } catch (const Error& e) {
            throw Error(path + ": " + e.what());
        }
    }
    for (SceneItem& item : scene.items_) scene.resolveLink(item);
    // Mesh files are read now, so that an unreadable one fails the load.
    scene.updateGeometry();
    for (const SceneItem& item : scene.items_)
        if (item.kind == SceneItem::Kind::ImportedMesh && !item.geometry.error.empty()) throw Error(item.geometry.error);
    if (!hasCamera) {
        const Eigen::AlignedBox3d box = scene.bounds();
        scene.camera.setView("iso");
        scene.camera.fit(box, aspect);
    }
    scene.modified_ = scene.path_.empty() && scene.itemCount() > 0; // imported content is unsaved
    return scene;
}

void Scene::rebuildItems()
{
    std::vector<SceneItem> items;
    for (const DocumentObject& o : document_.objects) {
        SceneItem item;
        item.kind = SceneItem::Kind::DocumentObject;
        item.name = o.name;
        item.type = objectType(o.data);
        item.key = nextKey();
        item.id = nextId();
        items.push_back(std::move(item));
    }
    items_ = std::move(items);
}

void Scene::addMeshItem(const std::string& name, const std::string& path)
{
    SceneItem item;
    item.kind = SceneItem::Kind::ImportedMesh;
    item.name = uniqueName(name);
    item.type = "mesh";
    item.meshPath = path;
    item.key = nextKey();
    item.id = nextId();
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

Document Scene::toDocument(MeshPaths meshPaths) const
{
    Document doc = document_;
    for (std::size_t i = 0; i < doc.objects.size(); ++i) {
        ObjectSettings s = items_[i].settings;
        // The link is the mesh's id; the document names the mesh as it is called now.
        if (const int m = indexOf(items_[i].deforms); m >= 0) s.ffd.mesh = items_[static_cast<std::size_t>(m)].name;
        doc.objects[i].editor = s.isDefault() ? std::string() : s.toJson().dump();
        // A relative cage path starts at cageDirectory_; for a document in another folder (after
        // Save As) it is rebased there, so that it names the same file. (The autosave keeps it
        // relative to the document's folder too: recovery resolves it there.)
        auto* sub = std::get_if<SubdivisionSurfaceData>(&doc.objects[i].data);
        if (!sub || sub->mesh.empty() || fs::path(sub->mesh).is_absolute() || path_.empty()) continue;
        const fs::path from = fs::absolute(fs::path(documentDirectory())).lexically_normal();
        const fs::path to = fs::absolute(fs::path(path_).parent_path()).lexically_normal();
        if (from != to) sub->mesh = (from / sub->mesh).lexically_normal().lexically_relative(to).generic_string();
    }
    Json e;
    e["camera"] = camera.toJson();
    e["display"] = display.toJson();
    Json meshes = Json::array();
    for (const SceneItem& item : items_) {
        if (item.kind != SceneItem::Kind::ImportedMesh) continue;
        Json m;
        m["name"] = item.name;
        m["path"] = meshPaths == MeshPaths::Absolute ? fs::absolute(resolve(item.meshPath)).lexically_normal().string() : item.meshPath;
        if (item.up != UpAxis::Z) m["up"] = toString(item.up);
        if (!item.settings.isDefault()) m["editor"] = item.settings.toJson();
        meshes.push_back(std::move(m));
    }
    if (!meshes.empty()) e["meshes"] = std::move(meshes);
    doc.editor = e.dump();
    return doc;
}

void Scene::save(const std::string& path)
{
    // Mesh paths are stored relative to the document when they lie beside or below it, and when
    // they were relative already (rebased onto the new folder, ".." allowed: a document and its
    // meshes that travel together keep working); others stay absolute.
    const std::string oldPath = path_;
    std::vector<std::string> oldMeshPaths;
    for (SceneItem& item : items_) {
        if (item.kind != SceneItem::Kind::ImportedMesh) continue;
        oldMeshPaths.push_back(item.meshPath);
        const fs::path absolute = fs::absolute(resolve(item.meshPath));
        const fs::path base = fs::absolute(path).parent_path();
        const fs::path relative = absolute.lexically_relative(base);
        const bool wasRelative = fs::path(item.meshPath).is_relative();
        item.meshPath = (!relative.empty() && (wasRelative || *relative.begin() != "..")) ? relative.generic_string()
                                                                                         : absolute.string();
    }
    try {
        path_ = path;
        writeDocument(toDocument(), path);
    } catch (...) {
        path_ = oldPath;
        std::size_t k = 0;
        for (SceneItem& item : items_)
            if (item.kind == SceneItem::Kind::ImportedMesh) item.meshPath = oldMeshPaths[k++];
        throw;
    }
    document_.source = path;
    modified_ = false;
}

void Scene::importFile(const std::string& path, std::optional<UpAxis> upAxis)
{
    const std::string ext = lowerExtension(path);
    if (ext == ".bpt") {
        std::vector<DocumentObject> objects = bptObjects(path);
        const std::string stem = fs::path(path).stem().string();
        std::vector<SceneItem> added;
        Document next = document_;
        for (DocumentObject& o : objects) {
            o.name = uniqueName(stem + "_" + o.name, added);
            next.objects.push_back(o);
            SceneItem item;
            item.name = o.name;
            item.type = objectType(o.data);
            item.key = nextKey();
            item.id = nextId();
            added.push_back(std::move(item));
        }
        record(std::string("import ").append(fs::path(path).filename().string()));
        const auto documentItems = static_cast<std::ptrdiff_t>(document_.objects.size());
        document_ = std::move(next);
        items_.insert(items_.begin() + documentItems, added.begin(), added.end());
    } else if (isMeshFile(ext)) {
        const UpAxis up = upAxis.value_or(formatUpAxis(path).value_or(UpAxis::Z));
        ItemGeometry g = buildMeshGeometry(path, up); // reads it now: Error leaves the scene as it was
        record(std::string("import ").append(fs::path(path).filename().string()));
        addMeshItem(fs::path(path).stem().string(), fs::absolute(path).string());
        items_.back().up = up;
        items_.back().geometry = std::move(g);
        items_.back().geometryDirty = false;
        items_.back().revision = items_.back().topology = nextRevision();
    } else {
        throw Error(path + ": cannot import this kind of file (.bpt or a mesh: .obj .ply .stl .off .gltf .glb)");
    }
    modified_ = true;
}

void Scene::setUpAxis(int i, UpAxis up)
{
    SceneItem& it = item(i);
    if (it.kind != SceneItem::Kind::ImportedMesh) throw Error("\"" + it.name + "\": only an imported mesh has an up axis");
    if (it.up == up) return;
    record(up == UpAxis::Y ? "up axis Y" : "up axis Z");
    it.up = up;
    it.geometryDirty = true;
    it.key = nextKey();
    modified_ = true;
}

namespace {

/// The visible meshes as one, as the editor exports them: positions and normals (no texture
/// coordinates, which not every drawn mesh has).
PolygonMesh exportedMesh(const std::vector<const PolygonMesh*>& meshes)
{
    PolygonMesh out = mergeMeshes(meshes);
    out.texcoords.resize(2, 0);
    return out;
}

} // namespace

PolygonMesh Scene::mergedMesh()
{
    updateGeometry();
    std::vector<const PolygonMesh*> meshes;
    for (const SceneItem& item : items_)
        if (item.settings.visible && item.geometry.surface) meshes.push_back(&*item.geometry.surface);
    return exportedMesh(meshes);
}

void Scene::exportMesh(const std::string& path)
{
    // Exports keep the world tolerance (display.tolerance), not the view's pixel tolerance: an
    // object drawn at the view's tolerance is tessellated again for the file only; what the view
    // draws stays as it is.
    updateGeometry();
    std::vector<ItemGeometry> world;
    world.reserve(items_.size()); // no reallocation: pointers into it are kept below
    std::vector<const PolygonMesh*> meshes;
    for (std::size_t i = 0; i < items_.size(); ++i) {
        const SceneItem& item = items_[i];
        if (!item.settings.visible) continue;
        const ItemGeometry* g = &item.geometry;
        if (followsViewTolerance(item) && (item.builtTolerance != display.tolerance || !item.geometry.patchTolerance.empty())) {
            world.push_back(buildGeometry(document_.objects[i].data, item.settings, display.tolerance, documentDirectory()));
            g = &world.back();
        }
        if (g->surface) meshes.push_back(&*g->surface);
    }
    const PolygonMesh mesh = exportedMesh(meshes);
    if (mesh.faceCount() == 0) throw Error("export: the scene has no visible surfaces or meshes");
    writePolygonMesh(mesh, path);
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
    SceneItem& it = items_[static_cast<std::size_t>(i)];
    it.geometryDirty = true;
    it.key = nextKey();
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
    PointColumns& points = pointsOf(data);
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
    const PointColumns& p = std::visit(
        [](const auto& d) -> const PointColumns& {
            using T = std::decay_t<decltype(d)>;
            if constexpr (std::is_same_v<T, SubdivisionSurfaceData>) return d.vertices;
            else return d.points;
        },
        object(i).data);
    Eigen::Matrix3Xd out = Eigen::Matrix3Xd::Zero(3, p.cols());
    out.topRows(std::min<Eigen::Index>(3, p.rows())) = p.topRows(std::min<Eigen::Index>(3, p.rows()));
    return out;
}

int Scene::controlPointCount(int i) const
{
    if (item(i).kind != SceneItem::Kind::DocumentObject) return 0;
    if (const auto* sub = std::get_if<SubdivisionSurfaceData>(&object(i).data); sub && !sub->mesh.empty())
        return static_cast<int>(item(i).geometry.netPoints.cols());
    return static_cast<int>(std::visit(
        [](const auto& d) {
            using T = std::decay_t<decltype(d)>;
            if constexpr (std::is_same_v<T, SubdivisionSurfaceData>) return d.vertices.cols();
            else return d.points.cols();
        },
        object(i).data));
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
        it.key = nextKey();
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
    item.key = nextKey();
    item.id = nextId();
    items_.insert(items_.begin() + at, std::move(item));
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
    it.revision = nextRevision();
}

void Scene::remove(int i)
{
    record("delete " + item(i).name);
    if (item(i).kind == SceneItem::Kind::DocumentObject)
        document_.objects.erase(document_.objects.begin() + i);
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
    for (SceneState::Item& r : state.items) {
        SceneItem it;
        if (const auto found = byKey.find(r.key); found != byKey.end()) it = std::move(items_[found->second]); // same content: keep its geometry
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

Scene Scene::recover(const std::string& autosavePath, const std::string& originalPath, double aspect)
{
    Scene scene = load(autosavePath, aspect);
    scene.path_ = originalPath;
    scene.cageDirectory_ = originalPath.empty() ? std::string() : fs::path(originalPath).parent_path().string();
    scene.document_.source = originalPath.empty() ? autosavePath : originalPath;
    // A relative cage path belongs to the original document's folder, not the autosave's.
    for (std::size_t i = 0; i < scene.document_.objects.size(); ++i)
        if (const auto* sub = std::get_if<SubdivisionSurfaceData>(&scene.document_.objects[i].data); sub && !sub->mesh.empty())
            scene.items_[i].geometryDirty = true;
    scene.updateGeometry();
    scene.modified_ = true;
    return scene;
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
        item.geometry = buildGeometry(document_.objects[i].data, item.settings, item.builtTolerance, documentDirectory(), pixelScale_);
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
    item.revision = item.topology = nextRevision();
}

void Scene::updateGeometry()
{
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
        item.revision = item.topology = nextRevision();
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
        if (stale(items_[i]))
            job.items.push_back({items_[i].id, items_[i].key, document_.objects[i].data, items_[i].settings});
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

int Scene::indexOf(const std::string& name) const
{
    for (std::size_t i = 0; i < items_.size(); ++i)
        if (items_[i].name == name) return static_cast<int>(i);
    return -1;
}

} // namespace freeform::editor
