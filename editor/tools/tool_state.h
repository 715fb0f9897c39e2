#pragma once
// The tools' state (Tools::State) and the operations the keys and the panels share. Each operation
// changes the document only through Scene's methods (one undo step each: multi-change operations
// are merged with beginMerge/endMerge) and reports a failure in `message` rather than throwing.

#include <Eigen/Core>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "freeform/curve/continuity.h"
#include "freeform/surface/patch_complex.h"
#include "freeform/volume/deform.h"
#include "tools/curve_tools.h"
#include "tools/ffd_tools.h"
#include "tools/tools.h"

namespace freeform::editor {

/// One lattice deforming one imported mesh (keyed by the lattice's name in Tools::State).
struct FfdLink {
    std::string mesh;                       // the mesh item's name
    long meshKey = 0;                       // SceneItem::key of the mesh when bound
    std::unique_ptr<FfdSession> session;
    PointColumns appliedPoints;             // the lattice points last applied
    double appliedStrength = 0;
    int appliedRevision = -1;               // the mesh item's revision after the last update
    DeformReport report;
    double deformMs = 0;                    // CPU time of the last update (positions, normals, det J)
    std::optional<Certificate> certificate; // computed on request for appliedPoints
};

struct Tools::State {
    std::string message;                    // the last operation's error or result, shown in the panel

    // Curves and splines.
    bool creating = false;                  // "create" mode: clicks add points ...
    bool creatingSpline = false;            // ... of a C2 cubic spline through them (else a curve)
    Points3 newPoints;                      // the points clicked so far
    double t = 0.5;                         // the t slider (global parameter fraction for splines)
    bool construction = false;              // draw the de Casteljau construction at t
    bool comb = false;                      // draw curvature combs
    double combScale = 1;                   // comb length relative to the automatic scale
    int modeItem = -1;                      // the spline item whose modes are tracked ...
    std::optional<BezierSplineData> modeSnapshot; // ... and its data as last seen
    long lastChange = -1;

    // de Boor drag of an all-C2 spline, and direct manipulation of a lattice through its mesh.
    enum class Drag { None, DeBoor, Direct } drag = Drag::None;
    int dragItem = -1, dragIndex = -1;
    Eigen::Vector3d dragPlanePoint = Eigen::Vector3d::Zero(), dragPlaneNormal = Eigen::Vector3d::UnitZ();
    Eigen::Vector3d dragOffset = Eigen::Vector3d::Zero();
    Points3 dragDeBoor;
    DocumentObject dragObject;              // the object at the start of the drag
    Eigen::Vector3d directRest = Eigen::Vector3d::Zero(), directTarget = Eigen::Vector3d::Zero();
    bool direct = false;                    // direct-manipulation mode (key D)

    // Surfaces.
    int patchDegree[2] = {3, 3};
    std::vector<EdgeContinuity> edges;      // the last edge-continuity read-out ...
    std::vector<std::string> edgePatchNames; // ... and the object name of each patch index

    // FFD.
    int latticeDegree[3] = {3, 3, 3};
    double margin = 0.05;
    std::map<std::string, FfdLink> links;   // by lattice name
    char exportPath[512] = "deformed.obj";
};

// ---- operations shared by keys and panels (true on success; else state.message says why)
bool createCurveFromClicks(ToolContext& context, Tools::State& state);
bool createPatch(ToolContext& context, Tools::State& state);
bool elevateSelected(ToolContext& context, Tools::State& state);
bool splitSelected(ToolContext& context, Tools::State& state);
bool insertAtSelected(ToolContext& context, Tools::State& state);
bool deleteSelected(ToolContext& context, Tools::State& state);
/// Sets the mode of the joint of the selected point (or of `joint` >= 0) and applies it at once.
bool setJointMode(ToolContext& context, Tools::State& state, JointMode mode, int joint = -1);
/// All inner joints to `mode`. For C2 on a cubic spline the joints stay where they are and the
/// handles become those of the C2 interpolant of the joints on the spline's own intervals (the end
/// tangents kept; closed: periodic); other modes go joint by joint, left to right.
bool setAllJointModes(ToolContext& context, Tools::State& state, JointMode mode);
bool fitLattice(ToolContext& context, Tools::State& state, int meshItem);
bool resetLattice(ToolContext& context, Tools::State& state, int latticeItem);
bool exportDeformed(ToolContext& context, Tools::State& state, int latticeItem, const std::string& path);
bool applyLatticeToObjects(ToolContext& context, Tools::State& state, int latticeItem);
bool computeEdgeContinuity(ToolContext& context, Tools::State& state);
bool certifyLattice(ToolContext& context, Tools::State& state, int latticeItem);

/// Item index of the item named `name`, or -1.
int findItem(const Scene& scene, const std::string& name);
/// The mesh file behind an imported mesh item (relative paths resolved against the document).
std::string meshFilePath(const Scene& scene, int meshItem);
/// The joint modes of a spline item, one per joint (missing ones free).
std::vector<JointMode> jointModes(const Scene& scene, int item);

} // namespace freeform::editor
