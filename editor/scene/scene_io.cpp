// Loading, saving, importing and exporting a Scene (scene/scene.h): a document, a .bpt patch file or
// a mesh opened; the document written with its mesh paths; meshes and .bpt patches imported into
// it (with a mesh's up axis); the visible surfaces exported as one mesh; an autosave recovered.

#include "scene/scene.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>

#include "freeform/document/model.h"
#include "freeform/document/object_data.h"
#include "freeform/document/operations.h"
#include "freeform/io/bpt.h"
#include "freeform/io/file.h"
#include "freeform/io/geometry_data.h"
#include "freeform/io/json_check.h"
#include "freeform/io/mesh_io.h"
#include "freeform/io/part_file.h"
#include "freeform/surface/patch_complex.h"
#include "freeform/tessellate/tessellate.h"
#include "freeform/cad/cad_file.h"
#include "scene/json_read.h"
#include "scene/scene_internal.h"

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

/// The part of a STEP or IGES file as one document object named after the file. Open CASCADE's
/// warnings go to freeform::warn (the status line shows them). A build without Open CASCADE
/// refuses the file (readCadFile's error).
DocumentObject cadObject(const std::string& path)
{
    return {fs::path(path).stem().string(), toData(readCadFile(path)), ""};
}

/// 1/1000 of the diagonal of the box of a part's control points: the tessellation tolerance a part
/// read from a CAD file asks of the scene at least (its unit may be mm or m: an absolute default
/// would give millions of triangles, or a few).
Eigen::AlignedBox3d partBox(const PartData& part)
{
    Eigen::AlignedBox3d box;
    for (const PartFaceData& f : part.faces)
        for (Eigen::Index k = 0; k < f.surface.surface.points.cols(); ++k) box.extend(Eigen::Vector3d(f.surface.surface.points.col(k)));
    return box;
}

double partTolerance(const PartData& part)
{
    const Eigen::AlignedBox3d box = partBox(part);
    return box.isEmpty() ? 0.0 : 1e-3 * box.diagonal().norm();
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

} // namespace

Scene Scene::load(const std::string& path, double aspect)
{
    Scene scene;
    const std::string ext = lowerExtension(path);
    if (ext == ".bpt") {
        scene.document_.objects = bptObjects(path);
        scene.document_.source = path;
    } else if (isPartFileName(path)) { // STEP, IGES, BRep: one part object (docs/cad.md, "In the editor")
        // A new document holding the part; Save asks for a .json path (a part is written back as
        // STEP or IGES through File > Export part).
        scene.document_.objects.push_back(cadObject(path));
        scene.document_.source = path;
        scene.display.tolerance = std::max(scene.display.tolerance, partTolerance(std::get<PartData>(scene.document_.objects.back().data)));
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

int Scene::importFile(const std::string& path, std::optional<UpAxis> upAxis)
{
    const std::string ext = lowerExtension(path);
    int first = static_cast<int>(document_.objects.size());
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
            item.key = scene_detail::nextKey();
            item.id = scene_detail::nextId();
            added.push_back(std::move(item));
        }
        record(std::string("import ").append(fs::path(path).filename().string()));
        const auto documentItems = static_cast<std::ptrdiff_t>(document_.objects.size());
        document_ = std::move(next);
        items_.insert(items_.begin() + documentItems, added.begin(), added.end());
        for (std::size_t k = 0; k < added.size(); ++k) retype(static_cast<std::size_t>(documentItems) + k);
    } else if (isMeshFile(ext)) {
        const UpAxis up = upAxis.value_or(formatUpAxis(path).value_or(UpAxis::Z));
        ItemGeometry g = buildMeshGeometry(path, up); // reads it now: Error leaves the scene as it was
        record(std::string("import ").append(fs::path(path).filename().string()));
        addMeshItem(fs::path(path).stem().string(), fs::absolute(path).string());
        items_.back().up = up;
        items_.back().geometry = std::move(g);
        items_.back().geometryDirty = false;
        items_.back().revision = items_.back().topology = scene_detail::nextRevision();
        first = itemCount() - 1;
    } else if (isPartFileName(path)) {
        DocumentObject part = cadObject(path); // read first: an Error leaves the scene as it was
        const double tolerance = partTolerance(std::get<PartData>(part.data));
        first = addObject(std::move(part), std::string("import ").append(fs::path(path).filename().string()));
        display.tolerance = std::max(display.tolerance, tolerance); // (not an undo step: a display setting)
    } else {
        throw Error(path + ": cannot import this kind of file (.bpt, a mesh: .obj .ply .stl .off .gltf .glb, or a part: " + kPartFileExtensions + ")");
    }
    modified_ = true;
    return first;
}

void Scene::setUpAxis(int i, UpAxis up)
{
    SceneItem& it = item(i);
    if (it.kind != SceneItem::Kind::ImportedMesh) throw Error("\"" + it.name + "\": only an imported mesh has an up axis");
    if (it.up == up) return;
    record(up == UpAxis::Y ? "up axis Y" : "up axis Z");
    it.up = up;
    it.geometryDirty = true;
    it.key = scene_detail::nextKey();
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
            world.push_back(buildGeometry(*this, static_cast<int>(i), display.tolerance));
            g = &world.back();
        }
        if (g->surface) meshes.push_back(&*g->surface);
    }
    const PolygonMesh mesh = exportedMesh(meshes);
    if (mesh.faceCount() == 0) throw Error("export: the scene has no visible surfaces or meshes");
    writePolygonMesh(mesh, path);
}

int Scene::findPartItem(int selected, std::string* why) const
{
    auto isPart = [&](int i) { return items_[static_cast<std::size_t>(i)].kind == SceneItem::Kind::DocumentObject && isFfdTarget(items_[static_cast<std::size_t>(i)]); };
    if (selected >= 0 && selected < itemCount() && isPart(selected)) return selected;
    int found = -1;
    for (int i = 0; i < itemCount(); ++i)
        if (isPart(i)) {
            if (found >= 0) {
                if (why) *why = "the document has several parts: select the one to export";
                return -1;
            }
            found = i;
        }
    if (found < 0 && why) *why = "the document has no part or trimmed surface to export (File > Import reads STEP and IGES files)";
    return found;
}

int Scene::partItem(int selected) const
{
    std::string why;
    const int found = findPartItem(selected, &why);
    if (found < 0) throw Error(why);
    return found;
}

std::string Scene::approximationText(const PartDeformReport& report)
{
    const std::size_t faces = report.approximatedFaces.size();
    if (faces + static_cast<std::size_t>(report.approximatedEdges) == 0) return {};
    const int cap = cadFilesSupported() ? cadMaxDegree() : report.maxDegree; // (no writer caps a degree without one)
    char error[32];
    std::snprintf(error, sizeof error, "%.2g", report.maxApproximationError);
    return ", " + std::to_string(faces) + " faces and " + std::to_string(report.approximatedEdges) + " edges approximated at degree " +
           std::to_string(cap) + " (certified error <= " + error + ")";
}

Scene::PartExport Scene::exportPart(int i, const std::string& path, const Lattice* lattice, double strength) const
{
    const SceneItem& it = item(i);
    if (!isPartFileName(path))
        throw Error(path + ": a part is written as STEP (.step .stp), IGES (.iges .igs) or BRep (.brep); File > Save writes the document");
    requireCadFiles(path); // (before any deformation, where this build writes no STEP, IGES or BRep)
    // The document layer's part of the object (a trimmed surface: a part of one face).
    std::optional<Part> part = objectPart(typedObject(i));
    if (!part) throw Error("\"" + it.name + "\" is a " + it.type + ", not a part or trimmed_surface");
    PartExport out;
    out.name = it.name;
    // A part over Open CASCADE's degree (an exact composition rose past it) goes through the rest
    // lattice of its box, an affine map (control points mapped, to rounding), whose degree cap
    // approximates the faces and edges above 25 with a certified error, as "export deformed" does.
    std::optional<Lattice> rest;
    if (!lattice && part->maxDegree() > cadMaxDegree()) {
        const Eigen::AlignedBox3d box = part->bounds();
        Eigen::Matrix<double, 3, 2> corners;
        corners << box.min(), box.max();
        rest = Lattice::fit(corners, {1, 1, 1}, 0.05);
        lattice = &*rest;
    }
    if (lattice) {
        PartDeformOptions options;
        options.strength = strength;
        options.maxDegree = cadMaxDegree();
        DeformedPart deformed = deformPart(*part, RationalLattice(*lattice), options);
        out.deformed = true;
        out.deform = std::move(deformed.report);
        part = std::move(deformed.part);
    }
    out.faces = static_cast<int>(part->faces.size());
    out.valid = writeCadFile(*part, path).valid;
    return out;
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

} // namespace freeform::editor
