#pragma once
// The live FFD of an imported mesh (no ImGui, no tools): an FfdSession binds the rest mesh to a
// lattice's frame once (FfdBinding: lattice coordinates computed once per fit) and then deforms
// positions AND normals for any control points of that frame, without recomputing the lattice
// coordinates. It computes in float, the precision the GPU draws in (about twice as fast as double
// for positions + normals: docs/performance.md). The scene evaluates deformed meshes through it
// (scene/derived.h); exports compute in double (tools/ffd_tools.h).
//
// Invariant: rest() and the binding describe the same vertices in the same order; deform() writes
// every vertex (3 x V positions and normals) of that mesh.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <memory>
#include <optional>
#include <vector>

#include "freeform/mesh/polygon_mesh.h"
#include "freeform/volume/deform.h"
#include "freeform/volume/lattice.h"

namespace freeform::editor {

class FfdSession {
public:
    /// Binds `rest` (triangles with per-vertex normals, as the scene draws meshes) to the frame,
    /// degrees and outside policy of `lattice`.
    FfdSession(const Lattice& lattice, PolygonMesh rest);

    const PolygonMesh& rest() const { return rest_; }
    /// Whether `lattice` has the bound frame, degrees and outside policy (else bind again).
    bool matches(const Lattice& lattice) const;

    /// Deformed positions and normals (cof(J) n renormalised), computed in float, into `out`
    /// (resized to the rest mesh's vertex count; faces untouched), det J per vertex into detJ when
    /// given (the colour map's scalars), and the bounding box of the deformed positions into
    /// `bounds` when given (the box of out.positions, made in the same pass).
    ///
    /// `live`: a frame of a drag. When the lattice differs from the one of the last full
    /// evaluation of this drag only by one common translation of the points that moved at its
    /// start, the outputs are that evaluation plus the linear change (FFD is linear in the control
    /// points), in one pass on one thread: equal to the full evaluation up to float rounding
    /// (docs/performance.md gives the measured bound), and approximate() says so. Otherwise, and
    /// always when !live, the full evaluation (bit for bit the same as FfdBinding<float>).
    DeformReport deform(const Lattice& lattice, double strength, PolygonMesh& out, std::vector<float>* detJ = nullptr,
                        Eigen::AlignedBox3d* bounds = nullptr, bool live = false);
    /// Whether the last deform() was a linear drag update rather than the full evaluation.
    bool approximate() const { return approximate_; }

private:
    /// positions_/normals_ (and det J) -> out (double), report, bounds: one pass.
    void finish(const float* det, bool normals, PolygonMesh& out, DeformReport& report, Eigen::AlignedBox3d* bounds) const;

    /// The drag's data (dragData_), from the kept last full evaluation (grabDrag) or, when the
    /// grab is not a common translation of points from it, from a full evaluation with Jacobians
    /// and one of the set's unit displacement (startDrag): per vertex, in blocks
    /// of kLanes, the fields p0 (3), n0 (3), h (3), e (3), B, det A (ffd_session.cpp).
    static constexpr int kLanes = 16, kP = 0, kN = 3, kH = 6, kE = 9, kB = 12, kD = 13, kFields = 14;
    struct Drag {
        Eigen::Matrix3Xd points;   // the lattice's control points at that evaluation
        double strength = 0;
        std::vector<int> moved;    // the points that move, ascending
    };
    /// The common translation of the drag's points since its evaluation, when that is all that changed.
    std::optional<Eigen::Vector3d> dragDelta(const Lattice& lattice, double strength) const;
    void startDrag(const Lattice& lattice, double strength, std::vector<int> moved, const std::vector<float>& jacobians,
                   const float* det);
    /// The grab without a library call: the drag's data from the kept base (the last full
    /// evaluation, or the identity) and B, grad B of `moved` per vertex from the bound lattice
    /// coordinates, with the outside policy as the library applies it.
    void grabDrag(const Lattice& lattice, double strength, std::vector<int> moved);
    void dragFrame(const Eigen::Vector3d& delta, bool normals, PolygonMesh& out, float* det, DeformReport& report,
                   Eigen::AlignedBox3d* bounds) const;

    Lattice frame_;
    PolygonMesh rest_;
    FfdBinding<float> binding_;
    Eigen::Matrix<float, 3, Eigen::Dynamic> restNormals_;      // rest_.normals in float
    Eigen::Matrix<float, 3, Eigen::Dynamic> positions_, normals_; // kept between calls (no fresh pages)
    Eigen::Matrix3Xd previous_;          // the control points of the last deform()
    std::unique_ptr<Drag> drag_;         // the current drag's linear update, if any
    std::vector<float> dragData_;        // its per-vertex data (kept between drags, as the scratch below)
    std::vector<float> jacobians_, unitJacobians_;
    Eigen::Matrix<float, 3, Eigen::Dynamic> unitPositions_;
    bool approximate_ = false;
    /// The base of the next grab: the last full evaluation (positions_, normals_, jacobians_ = A,
    /// baseDet_), or the identity (rest mesh, A = I, det 1), at basePoints_ and baseStrength_.
    enum class Base { None, Identity, Evaluated };
    Base base_ = Base::None;
    Eigen::Matrix3Xd basePoints_;
    double baseStrength_ = 0;
    std::vector<float> baseDet_;
};

} // namespace freeform::editor
