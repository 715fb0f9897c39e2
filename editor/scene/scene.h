#pragma once
// The scene: a freeform Document (the truth, saved as it is), its typed form (the document layer's
// TypedDocument: every object's geometry built once per change of its data, item k tied to its
// object id) plus, per object, the settings and the derived geometry the renderer draws. Imported meshes are scene items too; the document records
// them by file path in its "editor" member, so saving never loses them.
//
// Invariants: items_ holds one item per document object, in document order, followed by the
// imported meshes; every change to the document goes through replaceObject / setControlPoint(s) /
// setSettings / addObject / importFile / remove, the one path that marks an item dirty, the scene
// modified, records an undo step (SceneState before the change) in the scene's History, and keeps
// the typed document in step: a valid object is in model() under item(i).object, an object the
// document layer refuses is held as its data plus item(i).invalid (no geometry), so that it is
// still shown (its stored points) and can be mended.
// undo()/redo() restore the objects and items exactly (text() equal byte for byte, the camera and
// display aside, which are not undo steps) and rebuild only items whose content key changed.
// Derived geometry is rebuilt lazily by updateGeometry() for dirty items only. Loading is all or
// nothing: a file that cannot be read throws Error and leaves the scene untouched (load() builds a
// new Scene; the caller swaps it in).

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "freeform/document/kinds.h"
#include "freeform/document/model.h"
#include "freeform/brep/part_deform.h"
#include "freeform/io/document.h"
#include "freeform/io/up_axis.h"
#include "freeform/mesh/polygon_mesh.h"
#include "scene/history.h"
#include "render/render_types.h"
#include "scene/camera.h"
#include "scene/derived.h"
#include "scene/settings.h"

namespace freeform::editor {

/// What the renderer draws for one item, derived from the document.
/// The world size of the view's pixel tolerance at a box's nearest depth (docs/editor.md,
/// "Tessellation to the view"): span * (z / distance) / height, span = pixels * 2 * halfHeight
/// (the world size of `pixels` pixels times the view's height at the target's depth), z the depth
/// of the box's nearest corner along the view direction from the eye, at least distance / 20
/// (perspective), or z = distance (orthographic: the same everywhere). The formula of the one
/// tolerance per view (Scene::tessellationTolerance), at each patch's own depth. Off (the
/// default): no per-patch tolerances.
struct PixelScale {
    bool perspective = true;
    Eigen::Vector3d eye = Eigen::Vector3d::Zero(), forward = -Eigen::Vector3d::UnitZ();
    double span = 0, distance = 1, height = 0;
    bool on() const { return span > 0 && height > 0; }
    double tolerance(const Eigen::AlignedBox3d& box) const;
    bool operator==(const PixelScale&) const = default;
};

/// Whether tolerances `built` are still good for `wanted`: none differs by more than 2x.
bool withinTwice(const std::vector<double>& built, const std::vector<double>& wanted);

struct ItemGeometry {
    std::optional<PolygonMesh> surface;   // triangles with per-vertex normals
    /// Surfaces tessellated per patch to the view (a bezier/deboor surface in adaptive mode with
    /// a PixelScale on): the control-point box of each patch and the tolerance it was built for;
    /// empty otherwise.
    std::vector<Eigen::AlignedBox3d> patchBoxes;
    std::vector<double> patchTolerance;
    Eigen::Matrix<double, 3, Eigen::Dynamic> curve;  // polyline points (3 x P), may be empty
    bool curveClosed = false;
    std::vector<std::pair<int, int>> netEdges;       // control net / polygon edges into netPoints
    /// A part's face boundaries (its edges and trims), as vertex pairs of `surface`: drawn as lines
    /// on the shading, following the surface's vertices (a lattice preview moves them too).
    std::vector<std::pair<int, int>> outline;
    /// A part: the face (index into its faces) of each vertex of `surface`, whose faces have
    /// vertices of their own; empty for other items.
    std::vector<int> vertexFace;
    Eigen::Matrix<double, 3, Eigen::Dynamic> netPoints; // control points (3 x N; 2D padded with z = 0)
    Eigen::AlignedBox3d bounds;
    /// The surface's positions and normals in float as drawn, when the pass that wrote the surface
    /// wrote them too (a mesh an FFD lattice deforms); current while drawn.revision equals the
    /// item's revision, else the drawer converts the surface itself.
    FloatVertices drawn;
    std::string error;                    // set when the geometry could not be built
};

struct SceneItem {
    enum class Kind { DocumentObject, ImportedMesh };
    Kind kind = Kind::DocumentObject;
    std::string name;
    std::string type;                     // document type, or "mesh"
    std::string meshPath;                 // imported mesh: the file as given in the document
    UpAxis up = UpAxis::Z;                // imported mesh: its file's up axis (Y: turned to Z up on load)
    ObjectSettings settings;
    ItemGeometry geometry;
    bool geometryDirty = true;            // the CPU geometry must be rebuilt
    int revision = 0;                     // bumped with every rebuild (the GPU copy compares it)
    int topology = 0;                     // the revision of the last full rebuild: while it stays,
                                          // only vertex data changed (positions, normals, scalars:
                                          // an FFD update), so the GPU keeps the triangles
    std::vector<float> scalars;           // per-vertex scalars of the surface (colour map), or empty
    long key = 0;                         // content key: new whenever the data behind the geometry
                                          // (object, tessellation settings, mesh file) changes
    long id = 0;                          // stable id: given when the item is made, kept through
                                          // renames, undo/redo and reordering, never reused
    ObjectId object = 0;                  // the object's id in Scene::model(); 0: an imported mesh,
                                          // or an object the document layer refuses (invalid)
    std::string invalid;                  // why the object is refused (its data is kept), or empty
    long deforms = 0;                     // lattice: the id of the mesh it deforms (from
                                          // settings.ffd.mesh, the document's form), 0: none
    double builtTolerance = 0;            // the world tolerance `geometry` was built for
                                          // (buildGeometry's argument; 0: not built)

    /// The object's row of the kind table (document/kinds.h); nullptr for an imported mesh.
    const KindInfo* info() const { return kind == Kind::DocumentObject ? findKind(type) : nullptr; }
    bool is(ObjectKind objectKind) const
    {
        const KindInfo* k = info();
        return k && k->kind == objectKind;
    }
};

class TessellationWorker;

/// A scene's background tessellation (scene/tessellation_worker.h): the worker, made at the first
/// job, and the job in flight. A copy of a scene starts without a worker and without a job.
struct BackgroundTessellation {
    std::unique_ptr<TessellationWorker> worker;
    long generation = 0;   // the job in flight, 0: none
    double tolerance = 0;  // its tolerance
    long lastGeneration = 0;
    BackgroundTessellation();
    ~BackgroundTessellation();
    BackgroundTessellation(const BackgroundTessellation&);
    BackgroundTessellation& operator=(const BackgroundTessellation&);
    BackgroundTessellation(BackgroundTessellation&&) noexcept;
    BackgroundTessellation& operator=(BackgroundTessellation&&) noexcept;
};

/// What undo and redo restore: the document objects and the items without their derived geometry.
struct SceneState {
    struct Item {
        SceneItem::Kind kind = SceneItem::Kind::DocumentObject;
        std::string name, type, meshPath;
        UpAxis up = UpAxis::Z;
        ObjectSettings settings;
        long key = 0;
        long id = 0, deforms = 0;
    };
    std::vector<DocumentObject> objects;
    std::vector<Item> items;
};

class Scene {
public:
    Scene();

    /// Reads a document (.json), a patch file (.bpt: one bezier_surface per patch) or a mesh in any
    /// format the library reads, with the camera and display settings saved in a document (or a
    /// view fitted to the geometry otherwise). Error when the file cannot be read: nothing changes.
    static Scene load(const std::string& path, double aspect = 4.0 / 3.0);

    /// Writes the document with the editor's settings to path atomically and remembers the path.
    void save(const std::string& path);
    /// How imported mesh paths are written: as the document stores them (relative to its folder
    /// where possible), or absolute, for a copy saved elsewhere (the autosave file).
    enum class MeshPaths { AsStored, Absolute };
    /// The document as it would be saved (objects, object settings, camera, display, meshes).
    Document toDocument(MeshPaths meshPaths = MeshPaths::AsStored) const;
    /// Reads an autosave file as the unsaved state of the document at `originalPath` (empty for
    /// an untitled one): the result has that path and is modified. Error as load().
    static Scene recover(const std::string& autosavePath, const std::string& originalPath, double aspect = 4.0 / 3.0);
    std::string text() const { return formatDocument(toDocument()); }

    /// Adds the patches of a .bpt file, a mesh file or the part of a STEP or IGES file (one `part`
    /// object named after the file) to this scene (Error: nothing changes); returns the index of
    /// the first item added. A mesh is read with `up` as its file's up axis (Y-up files are turned
    /// to the Z-up world); nullopt: the format's own convention (glTF and GLB: Y), else Z.
    int importFile(const std::string& path, std::optional<UpAxis> up = std::nullopt);
    /// Sets imported mesh i's up axis (one undo step; the mesh is read again).
    void setUpAxis(int i, UpAxis up);
    /// The tessellation of every visible surface and mesh, merged, written by extension (.obj ...).
    void exportMesh(const std::string& path);
    /// What writing a part as STEP or IGES did (File > Export part, the lattice panel's export).
    struct PartExport {
        std::string name;          // the object written
        int faces = 0;
        bool deformed = false;     // through a lattice (the fields below)
        PartDeformReport deform;   // exact faces, approximated ones and their certified error
        bool valid = false;        // Open CASCADE's BRepCheck on the written shape
    };
    /// ", N faces and E edges approximated at degree 25 (certified error <= X)" for the status
    /// line, or "" when every face and edge was written exactly.
    static std::string approximationText(const PartDeformReport& report);
    /// The part to export: item `selected` when it is a part or trimmed surface, else the
    /// document's only one; -1 when there is none, or several and none selected (then `why`, when
    /// given, says which, for a person).
    int findPartItem(int selected, std::string* why = nullptr) const;
    /// findPartItem, with an Error saying why when there is no such item.
    int partItem(int selected) const;
    /// Writes object i (a part or trimmed surface) as STEP or IGES by the path's extension,
    /// deformed exactly by `lattice` (times strength) when one is given, faces over Open CASCADE's
    /// degree 25 approximated at 25 with a certified error (deformPart); else as it is, where a
    /// face or edge over degree 25 (an exact composition) is approximated the same way through the
    /// rest lattice of the part's box (an affine map: the other faces to rounding). Error: nothing
    /// is written.
    PartExport exportPart(int i, const std::string& path, const Lattice* lattice = nullptr, double strength = 1) const;
    PolygonMesh mergedMesh();

    const Document& document() const { return document_; }
    /// The typed document: the geometry of every valid document object, built once per change of
    /// its data (its order is not the items' order: find an item's object by item(i).object).
    const TypedDocument& model() const { return model_; }
    /// The typed object behind item i; nullptr for an imported mesh or an invalid object.
    const TypedObject* typed(int i) const;
    /// The typed object behind item i; Error for an imported mesh, or why the object is invalid.
    const TypedObject& typedObject(int i) const;
    /// The lattice of item i; Error when item i is no lattice or is invalid.
    const Lattice& lattice(int i) const;
    const std::string& path() const { return path_; }
    /// The folder of path() (empty for an untitled document): relative cage paths start there.
    std::string documentDirectory() const;
    bool modified() const { return modified_; }
    void markSaved() { modified_ = false; }

    int itemCount() const { return static_cast<int>(items_.size()); }
    SceneItem& item(int i) { return items_.at(static_cast<std::size_t>(i)); }
    const SceneItem& item(int i) const { return items_.at(static_cast<std::size_t>(i)); }
    /// The document object behind item i (Error for an imported mesh).
    const DocumentObject& object(int i) const;
    /// The index of the item with stable id `id`, or -1.
    int indexOf(long id) const;
    /// The index of the item named `name`, or -1.
    int indexOf(const std::string& name) const;
    /// The index of the item whose object in model() is `object`, or -1 (0 and refused objects: -1).
    int itemOfObject(ObjectId object) const;

    /// Replaces the document object behind item i (same name) after validating it through the
    /// document reader; Error (nothing changes) when the new object is invalid. `label` names the
    /// undo step (Edit > Undo <label>).
    void replaceObject(int i, const DocumentObject& object, const std::string& label = "edit");
    /// Replaces object i as part of the change recorded last, without a step of its own: for a
    /// fix-up that completes the edit just made (a spline's joint modes enforced after one of its
    /// handles was typed in), so that one undo takes both back. Validated as replaceObject.
    void amendObject(int i, const DocumentObject& object);
    /// Moves control point k of item i (2D objects ignore z). Error when invalid.
    void setControlPoint(int i, int k, const Eigen::Vector3d& p, const std::string& label = "move point");
    /// Moves control points ks[j] of item i to column j of ps (one step, one rebuild); Error
    /// (nothing changes) on an index out of range or a coordinate that is not finite.
    void setControlPoints(int i, const std::vector<int>& ks, const Eigen::Matrix3Xd& ps,
                          const std::string& label = "move points");
    /// The control points of item i in setControlPoint's order (3 x N, 2D padded with z = 0; empty
    /// for meshes and for subdivision surfaces that reference a mesh file).
    Eigen::Matrix3Xd controlPoints(int i) const;
    /// The number of columns controlPoints(i) has, without copying them.
    int controlPointCount(int i) const;
    void setSettings(int i, const ObjectSettings& settings, const std::string& label = "object settings");
    /// Per-vertex scalars on item i's surface (size = its vertex count, or empty). Derived data,
    /// not an undo step.
    void setScalars(int i, std::vector<float> scalars);
    /// Appends a document object (after the other objects, before the meshes) after validating it;
    /// a name already in use gets a suffix. Returns its item index. Error: nothing changes.
    int addObject(DocumentObject object, const std::string& label = "add object");
    void remove(int i);

    // ---- undo and redo (Ctrl+Z, Ctrl+Shift+Z / Ctrl+Y)
    bool undo();
    bool redo();
    const History<SceneState>& history() const { return history_; }
    /// One continuous gesture (a drag): the changes between beginMerge and endMerge are one step.
    void beginMerge() { history_.beginMerge(); }
    void endMerge() { history_.endMerge(); }
    /// Ends the gesture and takes its changes back without a redo entry (Escape during a drag).
    void cancelMerge();
    /// The state undo would restore to (a copy of the objects and items, no geometry).
    SceneState state() const;
    /// Counts every change to the document (edits, undo, redo): tools compare it to notice changes.
    long changeCount() const { return changes_; }

    /// Rebuilds the geometry of dirty items (tessellation, sampling), then evaluates the derived
    /// items whose inputs changed (scene/derived.h: the meshes lattices deform). With background
    /// tessellation on, it also swaps in the result of a finished background job and submits the
    /// items built for another tolerance than tessellationTolerance() as a new job.
    void updateGeometry();
    /// The lattice -> mesh links evaluated by updateGeometry, by the lattice item's id.
    const std::map<long, FfdLink>& ffdLinks() const { return ffdLinks_; }
    /// The link of lattice item i (nullptr when it deforms no mesh, or not yet evaluated).
    const FfdLink* ffdLink(int i) const;
    /// Stores a certificate computed for lattice item i's current points with its link.
    void setCertificate(int i, const Certificate& certificate);
    /// The bounding box of the visible items (updateGeometry first); a unit box when empty.
    Eigen::AlignedBox3d bounds() const;

    Camera camera;
    DisplaySettings display;
    /// Tessellation to the view (docs/editor.md): > 0 tessellates surfaces and curves to this many
    /// pixels at the visible items' nearest depth instead of display.tolerance (not saved; 0: off,
    /// as with the command line's --tolerance).
    double pixelTolerance = 0.5;
    /// The world tolerance of pixelTolerance for a view `height` pixels high; marks the geometry
    /// dirty when it differs from the one in use by more than 2x (or pixelTolerance was switched).
    void updateViewTolerance(int height);
    /// The world tolerance the geometry is built with (display.tolerance when pixelTolerance is 0).
    /// Bezier and de Boor surfaces take it per patch instead, from pixelScale(): each patch gets
    /// the world size of pixelTolerance pixels at its own nearest depth (far patches coarser), and
    /// is built again when that differs from the one it was built for by more than 2x.
    double tessellationTolerance() const { return viewTolerance_ > 0 ? viewTolerance_ : display.tolerance; }
    /// The view's pixel scale from the last updateViewTolerance (off when pixelTolerance is 0).
    const PixelScale& pixelScale() const { return pixelScale_; }
    /// Marks the settings (camera, display) as changed, i.e. the file as unsaved.
    void touch() { modified_ = true; }
    /// Marks all geometry dirty (e.g. after the tessellation tolerance changed).
    void invalidateGeometry();

    // ---- background tessellation (docs/editor.md, "Tessellation to the view")
    /// Off (the default): a new view tolerance marks every object dirty and updateGeometry
    /// rebuilds them at once. On (the editor's window): items whose geometry depends on the
    /// tolerance and was built for another one are "stale"; updateGeometry hands copies of them to
    /// a worker thread, keeps their old geometry until the result is back, then swaps it in on the
    /// calling thread, item by item, only where the item's content key is still the one copied (an
    /// edit meanwhile gives a new key and its own synchronous rebuild). A newer tolerance
    /// supersedes the job in flight. Edits are always rebuilt synchronously. On also moves the
    /// exact evaluation of a lattice's mesh owed at the release of a drag to a worker thread
    /// (scene/derived.h, FfdLink::pending): the release frame keeps the drag's last linear frame.
    void setBackgroundTessellation(bool on);
    bool backgroundTessellation() const { return backgroundOn_; }
    /// Whether some item waits for the current tolerance (a job in flight or not yet submitted).
    bool tessellationPending() const;
    /// Blocks until every item is built for the current tolerance, waiting for the job in flight
    /// and applying it: headless runs call it every frame, so they are deterministic (the same
    /// geometry as the synchronous path).
    void finishTessellation();
    /// Blocks until the exact evaluation of a lattice's mesh owed after a drag (made on a worker
    /// thread at the release while background work is on: FfdLink::pending) is done and applied.
    /// finishTessellation() calls it.
    void finishDeformation();
    /// Background counters: jobs submitted, items swapped in, results dropped (their item was
    /// edited or removed, or the tolerance had changed, while the job ran).
    struct BackgroundStats {
        long jobs = 0, applied = 0, dropped = 0;
    };
    const BackgroundStats& backgroundStats() const { return backgroundStats_; }
    /// The worker (made now if there is none yet): tests use its hold to interleave an edit with a
    /// running job deterministically.
    TessellationWorker& tessellationWorker();

private:
    double viewTolerance_ = 0;
    PixelScale pixelScale_;
    /// Whether item's per-patch tolerances are more than 2x off those of pixelScale_.
    bool patchesStale(const SceneItem& item) const;
    /// Whether item's geometry depends on tessellationTolerance() (curves, surfaces and cages
    /// tessellated adaptively without a tolerance of their own).
    bool followsViewTolerance(const SceneItem& item) const;
    bool stale(const SceneItem& item) const;
    void buildItem(std::size_t i);
    void takeBackgroundResult();
    void submitStale();
    bool backgroundOn_ = false;
    bool waitDeformation_ = false; // updateDerived waits for background lattice evaluations
    BackgroundTessellation background_;
    BackgroundStats backgroundStats_;
    void rebuildItems();
    void updateDerived();
    void resolveLink(SceneItem& item) const;
    void record(const std::string& label);
    void restore(SceneState state);
    void setObjectData(int i, ObjectData data);
    /// Builds item i's typed object from its document data (model_ and the item's object/invalid).
    void retype(std::size_t i);
    /// Builds every object's typed form again (a new document, or a new folder for cage paths).
    void retypeAll();
    void addMeshItem(const std::string& name, const std::string& path);
    std::string uniqueName(const std::string& base, const std::vector<SceneItem>& pending = {}) const;
    std::string resolve(const std::string& meshPath) const;

    Document document_;
    TypedDocument model_;
    std::vector<SceneItem> items_;
    std::string path_;
    std::string cageDirectory_;   // where relative cage paths of the objects in memory (and in the
                                  // undo history) start: the folder the document was read from
    bool modified_ = false;
    History<SceneState> history_;
    long changes_ = 0;
    std::map<long, FfdLink> ffdLinks_; // derived: by lattice id
};

/// Builds the geometry of a typed document object (tolerance: adaptive sampling in world units).
/// With `view` on, a bezier/deboor surface in adaptive mode without a tolerance of its own is
/// tessellated per patch to view.tolerance(control-point box of the patch) (geometry.patchBoxes /
/// patchTolerance). An Error of the tessellation is the geometry's error (the net is kept).
ItemGeometry buildGeometry(const TypedObject& object, const ObjectSettings& settings, double tolerance, const PixelScale& view = {});
/// The geometry of an object the document layer refuses: its stored points (so it can be seen and
/// mended) and the error. documentDirectory resolves a subdivision_surface's relative mesh path.
ItemGeometry invalidGeometry(const ObjectData& data, const std::string& error, const std::string& documentDirectory = {});
/// The geometry of scene item i as Scene::updateGeometry builds it (a typed object's, or an
/// invalid one's), at `tolerance`.
ItemGeometry buildGeometry(const Scene& scene, int i, double tolerance, const PixelScale& view = {});
/// Reads a mesh file and makes sure it has triangles and per-vertex normals.
ItemGeometry buildMeshGeometry(const std::string& path, UpAxis up = UpAxis::Z);
/// Triangulates polygons (fans) and fills in area-weighted vertex normals where the mesh has none.
PolygonMesh withNormals(PolygonMesh mesh);
/// The edges of a mesh used by one polygon only: for a part tessellated face by face
/// (splitFaces), the boundaries of its faces.
std::vector<std::pair<int, int>> faceOutline(const PolygonMesh& mesh);
/// One face of a part in words: "face 8: cylinder, degree 2 x 1, 1 trim loop" (empty when out of
/// range), the face counted from 1 as errors and Open CASCADE count it.
std::string faceSummary(const PartData& part, int face);
/// Whether a lattice can deform item i live (a link, scene/derived.h): an imported mesh, or a
/// part or trimmed surface object, whose tessellation follows the drag (applied exactly on request).
bool isFfdTarget(const SceneItem& item);

} // namespace freeform::editor
