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

#include <array>
#include <atomic>
#include <exception>
#include <memory>
#include <optional>
#include <thread>
#include <vector>

#include "freeform/mesh/polygon_mesh.h"
#include "freeform/volume/deform.h"
#include "freeform/volume/drag_pass.h"
#include "freeform/volume/lattice.h"

namespace freeform::editor {

/// A deformed mesh's positions and normals in float (3 x V each), as the GPU takes them: written
/// by the pass that writes the double mesh, so that drawing needs no conversion (the double values
/// are these widened, so they are also the double mesh's values rounded to float). `revision`: the
/// scene item's revision they belong to (-1: none; the scene sets it).
struct FloatVertices {
    Eigen::Matrix<float, 3, Eigen::Dynamic> positions, normals;
    int revision = -1;
};

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
    /// `live`: a frame of a drag. When the lattice differs from the base (the last full
    /// evaluation, or the identity) only by one common translation of a set of points (the same
    /// set through the drag), the outputs are the base plus the linear change (FFD is linear in
    /// the control points), in one pass on one thread straight from the base, the grab included:
    /// equal to the full evaluation up to float rounding (docs/performance.md gives the measured
    /// bound), and approximate() says so. Otherwise, and always when !live, the full evaluation
    /// (bit for bit the same as FfdBinding<float>), which becomes the base.
    ///
    /// `drawn` (with normals only): the same positions and normals in float, resized as `out`.
    DeformReport deform(const Lattice& lattice, double strength, PolygonMesh& out, std::vector<float>* detJ = nullptr,
                        Eigen::AlignedBox3d* bounds = nullptr, bool live = false, FloatVertices* drawn = nullptr);
    /// Whether the last deform() was a linear drag update rather than the full evaluation.
    bool approximate() const { return approximate_; }

    // ---- the release's exact evaluation on a worker thread (docs/architecture.md, "A lattice drag")
    /// Starts the full evaluation of `lattice` (bit for bit what deform(.., live = false) computes)
    /// on a thread of its own, with one thread fewer than the hardware has (at least one), and
    /// returns at once. Until its result is taken, the caller keeps showing what it has (the
    /// drag's last linear frame). Any deform() call first waits for it: the evaluation becomes the
    /// base of that call (a grab right after a release starts from the exact release).
    void deformInBackground(const Lattice& lattice, double strength);
    /// Whether a background evaluation is running or done and not yet taken.
    bool backgroundPending() const { return job_.joinable(); }
    /// Whether the background evaluation has finished (its result waits for takeBackground()).
    bool backgroundDone() const { return job_.joinable() && jobDone_.load(std::memory_order_acquire); }
    /// The finished background evaluation (waiting for it when `wait`; nullopt when none is
    /// pending, or when it is still running and !wait): its positions and normals are swapped into
    /// `out` (resized to the rest mesh's vertex count), det J into detJ and the box into bounds, as
    /// deform() writes them; the buffers swapped out are kept for the next one. Rethrows the
    /// evaluation's Error. `drawn` (with normals): its float positions and normals, swapped likewise.
    std::optional<DeformReport> takeBackground(PolygonMesh& out, std::vector<float>& detJ, Eigen::AlignedBox3d& bounds, bool wait,
                                               FloatVertices* drawn = nullptr);

    FfdSession(const FfdSession&) = delete;
    FfdSession& operator=(const FfdSession&) = delete;
    /// Waits for a background evaluation still running.
    ~FfdSession();

private:
    /// The full evaluation into the kept base (positions_, normals_, jacobians_ with normals,
    /// baseDet_), then its outputs: out (double), detJ, report, bounds. `threads` as DeformOptions.
    void evaluate(const Lattice& lattice, double strength, PolygonMesh& out, std::vector<float>* detJ, DeformReport& report,
                  Eigen::AlignedBox3d* bounds, int threads, FloatVertices* drawn);
    /// The identity (the rest lattice or strength 0): the rest mesh itself; the base is the identity.
    void identity(const Lattice& lattice, double strength, PolygonMesh& out, std::vector<float>* detJ, DeformReport& report,
                  Eigen::AlignedBox3d* bounds, FloatVertices* drawn);
    /// positions_/normals_ (and det J) -> out (double), drawn (float), report, bounds: one pass.
    /// With normals, also the base's blocks (baseBlocks_) from positions_, jacobians_ and det.
    void finish(const float* det, bool normals, PolygonMesh& out, FloatVertices* drawn, DeformReport& report, Eigen::AlignedBox3d* bounds,
                int threads);
    /// Waits for a background evaluation and drops its result (its base stays).
    void settle();

    // The drag pass's layouts (volume/drag_pass.h).
    static constexpr int kLanes = kDragLanes, kCoordFields = kDragCoordFields, kBaseFields = kDragBaseFields;
    struct Drag {
        Eigen::Matrix3Xd points;   // the lattice's control points at the base (basePoints_)
        double strength = 0;
        std::vector<int> moved;    // the points that move, ascending
        std::vector<std::array<int, 3>> ijk; // their (i, j, k)
    };
    /// The common translation of the drag's points since the base, when that is all that changed.
    std::optional<Eigen::Vector3d> dragDelta(const Lattice& lattice, double strength) const;
    /// One frame of a drag, the grab included, in one pass over the vertices straight from the
    /// base: p = p0 + B u, det J = det A + (cof(A) v) . u, cof(J) n = cof(A) n + u x (A (n x v)),
    /// with B and v = dual^T grad B of the moved points at the vertex's lattice coordinates
    /// (coords_, the outside policy folded in), u = strength * delta.
    void dragFrame(const Lattice& lattice, const Eigen::Vector3d& delta, PolygonMesh& out, FloatVertices* drawn, float* det,
                   DeformReport& report, Eigen::AlignedBox3d* bounds) const;

    Lattice frame_;
    PolygonMesh rest_;
    FfdBinding<float> binding_;
    Eigen::Matrix<float, 3, Eigen::Dynamic> restNormals_;      // rest_.normals in float
    Eigen::Matrix<float, 3, Eigen::Dynamic> positions_, normals_; // the last full evaluation (the base)
    /// Lattice coordinates per vertex in blocks of kLanes (s[W] t[W] u[W], then the rest normal
    /// x[W] y[W] z[W]) as the library's kernel uses them (the outside policy applied: clamped
    /// under keep and clamp), made once per bind; and, only when some vertex lies outside the box, a mask per vertex: bit a (a < 3) the
    /// axis contributes to the Jacobian, bit 3 the vertex moves at all (off under keep).
    std::vector<float> coords_;
    std::vector<unsigned char> masks_;
    std::unique_ptr<Drag> drag_;         // the current drag, if any
    std::vector<float> jacobians_;       // A of the base (9 per vertex, column-major; the library's output)
    /// The base as the frames read it, in blocks of kLanes: p0 x, y, z, A (9, column-major),
    /// det A (written by finish() with every full evaluation with normals).
    std::vector<float> baseBlocks_;
    bool approximate_ = false;
    /// The base of a drag: the last full evaluation (positions_, normals_, jacobians_ = A,
    /// baseDet_), or the identity (rest mesh, A = I, det 1), at basePoints_ and baseStrength_.
    enum class Base { None, Identity, Evaluated };
    Base base_ = Base::None;
    Eigen::Matrix3Xd basePoints_;
    double baseStrength_ = 0;
    std::vector<float> baseDet_;
    // The background evaluation: its thread, its outputs (swapped into the scene's mesh when
    // taken), and whether it is done. Only the job touches the base and these while it runs.
    std::thread job_;
    std::atomic<bool> jobDone_{false};
    PolygonMesh jobMesh_;
    FloatVertices jobDrawn_;
    std::vector<float> jobDet_;
    Eigen::AlignedBox3d jobBounds_;
    DeformReport jobReport_;
    std::exception_ptr jobError_;
};

} // namespace freeform::editor
