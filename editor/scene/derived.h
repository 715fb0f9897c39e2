#pragma once
// Derived items: results the scene computes from other items and never stores in the document.
// Today one kind: the mesh a lattice deforms (the lattice's editor member "ffd" names the mesh;
// at run time the link is the mesh item's stable id, SceneItem::deforms). The "mesh" is an imported
// mesh, or the tessellation of a part or trimmed surface object (isFfdTarget): a preview, which the
// lattice tool's "apply exactly" replaces by the exact composition (docs/cad.md, "In the editor").
// A part's tessellation is rebuilt when the view's tolerance changes (a new SceneItem::topology):
// the link then binds the new rest mesh. Scene::updateGeometry
// evaluates every link after rebuilding dirty items: the one path by which a deformed mesh is
// written. Its inputs are the lattice's points, frame and outside policy, the strength and the
// mesh item's content (key) and revision; when none changed, nothing is computed (except the full
// evaluation owed after a drag's linear updates: FfdLink::approximate, made on a worker thread when
// the scene's background work is on: FfdLink::pending). A link that
// goes away (lattice deleted, its mesh changed to another or none) puts the rest mesh back.

#include <memory>
#include <optional>
#include <string>

#include "freeform/io/document.h"
#include "freeform/volume/deform.h"
#include "scene/ffd_session.h"

namespace freeform::editor {

/// One lattice deforming one imported mesh (Scene::ffdLinks(), by the lattice item's id).
struct FfdLink {
    long meshId = 0;                        // SceneItem::id of the mesh
    long meshKey = 0;                       // SceneItem::key of the mesh when bound
    int meshTopology = 0;                   // SceneItem::topology of the mesh when bound
    std::shared_ptr<FfdSession> session;    // shared by copies of the scene (a cache)
    PointColumns appliedPoints;             // the lattice points last applied
    double appliedStrength = 0;
    int appliedRevision = -1;               // the mesh item's revision after the last update
    DeformReport report;
    double deformMs = 0;                    // CPU time of the last update (positions, normals, det J)
    bool approximate = false;               // the last update was a drag's linear update (float rounding)
    bool pending = false;                   // the exact evaluation owed runs in the background
                                            // (FfdSession::deformInBackground; approximate until taken)
    std::optional<Certificate> certificate; // computed on request for appliedPoints
    std::string error;                      // why the last update failed (empty: it did not)
};

} // namespace freeform::editor
