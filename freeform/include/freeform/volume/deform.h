#pragma once
// Free-form deformation of points, meshes and Bézier geometry through a Lattice.
//
// Positions move in displacement form, p' = p + w sum B_ijk(s,t,u) (P_ijk - R_ijk) with the
// lattice's outside policy applied, so the rest lattice (or w = 0) returns every point bit for bit.
// The world-space Jacobian is J = I + w [D_s D_t D_u] dual() (chain rule through the frame);
// normals map to cof(J) n = det(J) J^-T n, renormalised, which stays defined where J is singular
// and flips with the surface where the map folds (det J < 0); tangents map to J t, renormalised,
// handedness kept. det J is the local volume ratio; det J <= 0 is a fold-over.
//
// Speed: FfdBinding caches what does not change while control points move (the lattice
// coordinates and rest positions of every vertex, in blocks of SIMD lanes, float or double), and
// each deform() call runs a CPU-dispatched (x86-64-v4 / v3 / baseline), multi-threaded kernel over
// the blocks. Results do not depend on the thread count. Math and design: docs/ffd.md.

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "freeform/curve/bezier_curve.h"
#include "freeform/mesh/polygon_mesh.h"
#include "freeform/surface/bezier_surface.h"
#include "freeform/volume/lattice.h"

namespace freeform {

struct DeformOptions {
    double strength = 1; ///< w in [0, 1] (other values extrapolate the effect)
    int threads = 0;     ///< 0: hardware concurrency
};

/// What a deformation did, from det J at every vertex.
struct DeformReport {
    std::size_t vertices = 0;
    std::size_t outside = 0;          ///< vertices outside the lattice box
    double minDetJ = 1, maxDetJ = 1;  ///< over all vertices (1 and 1 for an empty mesh)
    std::size_t foldCount = 0;        ///< vertices with det J <= 0
    std::vector<int> folds;           ///< their indices, ascending
};

/// Where the outputs of FfdBinding::deform go; null pointers are skipped. Arrays are column-major
/// (3 x V for points and normals, 9 x V for Jacobians, V for determinants), V = binding size.
template <typename Scalar>
struct FfdOutputs {
    Scalar* positions = nullptr;       ///< deformed positions (required)
    const Scalar* normalsIn = nullptr; ///< rest normals to transform ...
    Scalar* normalsOut = nullptr;      ///< ... into here (cof(J) n renormalised; may equal normalsIn)
    Scalar* jacobians = nullptr;       ///< J per vertex
    Scalar* determinants = nullptr;    ///< det J per vertex
};

/// A set of points bound to a lattice's frame and degrees: lattice coordinates are computed once,
/// deform() re-evaluates only the deformation when control points move.
///
/// Invariants: the bound lattice's degrees and frame (Lattice::sameFrame) and outside policy are
/// fixed at construction; deform() throws Error for a lattice that differs in any of them. Points
/// are stored in Scalar (float or double); lattice coordinates are computed in double.
template <typename Scalar>
class FfdBinding {
public:
    static constexpr int kLanes = 64 / static_cast<int>(sizeof(Scalar)); ///< vertices per block

    /// positions: 3 x count, column-major (xyz of each vertex together).
    FfdBinding(const Lattice& lattice, const double* positions, std::size_t count);
    FfdBinding(const Lattice& lattice, const float* positions, std::size_t count);
    FfdBinding(const Lattice& lattice, const Eigen::Matrix<double, 3, Eigen::Dynamic>& positions)
        : FfdBinding(lattice, positions.data(), static_cast<std::size_t>(positions.cols()))
    {
    }

    std::size_t size() const { return count_; }
    /// Vertices outside the lattice box, ascending.
    const std::vector<int>& outsideVertices() const { return outside_; }
    /// The cached lattice coordinates of vertex v (before the outside policy).
    Eigen::Vector3d parameters(std::size_t v) const;
    /// The bound positions as stored (3 x size(), column-major, in Scalar) into out: with the
    /// bound lattice, what a copy of the binding is rebuilt from (the Python module's pickling).
    void copyPositions(Scalar* out) const;
    /// The lattice the points were bound to (its degrees, frame and outside policy are the ones
    /// deform() accepts).
    const Lattice& boundLattice() const { return lattice_; }

    /// Deforms every bound point through `lattice` (control points may differ from the bound one).
    /// Fills report (when given) from det J, which is then computed even without `determinants`.
    void deform(const Lattice& lattice, const FfdOutputs<Scalar>& out, const DeformOptions& options = {},
                DeformReport* report = nullptr) const;

private:
    template <typename In>
    void bind(const Lattice& lattice, const In* positions, std::size_t count);

    std::size_t count_ = 0;
    std::size_t blocks_ = 0;
    std::shared_ptr<Scalar> data_;         // blocks of 6 * kLanes: x, y, z, s, t, u (policy applied)
    std::vector<double> raw_;              // 3 x count lattice coordinates of the outside vertices
    std::vector<int> outside_;
    Lattice lattice_;                      // the bound frame (control points irrelevant)
};

extern template class FfdBinding<float>;
extern template class FfdBinding<double>;

/// Deforms points (3 x V) in place; the report covers det J.
DeformReport deformPoints(const Lattice& lattice, Eigen::Matrix<double, 3, Eigen::Dynamic>& points,
                          const DeformOptions& options = {});

enum class NormalMode {
    Jacobian, ///< cof(J) n, renormalised (needs normals in the mesh; absent normals stay absent)
    Recompute ///< area-weighted vertex normals of the deformed mesh (always written)
};
NormalMode parseNormalMode(const std::string& text, const std::string& what);

/// Deforms a mesh in place: positions, and normals as chosen. The report covers det J.
DeformReport deformMesh(const Lattice& lattice, PolygonMesh& mesh, const DeformOptions& options = {},
                        NormalMode normals = NormalMode::Jacobian);

/// Area-weighted vertex normals (3 x V): the normalised sum of the vector areas of the incident
/// faces (for a polygon, half the sum of the cross products of consecutive corners about its
/// first corner); zero for a vertex without faces or with zero total area.
Eigen::Matrix<double, 3, Eigen::Dynamic> areaWeightedNormals(const PolygonMesh& mesh);

/// cof(J) n normalised (zero stays zero), and J t normalised.
Eigen::Vector3d transformNormal(const Eigen::Matrix3d& j, const Eigen::Vector3d& n);
Eigen::Vector3d transformTangent(const Eigen::Matrix3d& j, const Eigen::Vector3d& t);

// ------------------------------------------------------------------------ certificate

enum class Verdict { CertifiedInjective, Folds, Undecided };
/// "certified injective" | "folds" | "undecided".
std::string toString(Verdict verdict);

/// det J of the world-space map over the lattice box, as a Bernstein polynomial.
struct JacobianPolynomial {
    std::array<int, 3> degree{}; ///< (3l-1, 3m-1, 3n-1)
    std::vector<double> coefficients; ///< index i*(b+1)*(c+1) + j*(c+1) + k for degree (a, b, c)
};

/// The Bernstein coefficients of det J(s,t,u) = det[f_s f_t f_u] / det[S T U] for the volume with
/// control points R + w (P - R): products of the derivative volumes' coefficients by the Bernstein
/// product formula, accumulated in long double (exact binomial weights).
JacobianPolynomial jacobianPolynomial(const Lattice& lattice, double strength = 1);

struct Certificate {
    Verdict verdict = Verdict::Undecided;
    double minCoefficient = 0, maxCoefficient = 0; ///< bounds of det J over the box
    Eigen::Vector3d witness = Eigen::Vector3d::Zero(); ///< (s,t,u) with det J <= 0 when Folds
    int boxes = 0; ///< sub-boxes examined
};

/// Certified injective: every Bernstein coefficient of det J is positive, on the whole box or on
/// every piece of an adaptive subdivision (pieces halved along their longest side, at most
/// maxDepth halvings per direction), so det J > 0 throughout the lattice; folds: det J <= 0 at a
/// corner of a piece (the coefficient there is the value there; `witness`); undecided otherwise.
Certificate certify(const Lattice& lattice, double strength = 1, int maxDepth = 4);

// ------------------------------------------------------------------------ affine lattices, Lipschitz bound

/// The lattice map as x -> A x + b when its displacement field (times strength) is an affine
/// function of (s, t, u) within 1e-12 of the lattice's size (Bernstein polynomials reproduce
/// linear functions, so then every displacement equals the affine one at (i/l, j/m, k/n)):
/// A = I + w D dual, b = w (d0 - D dual X0) with D = [d_l00 - d0, d_0m0 - d0, d_00n - d0].
/// Nothing when it is not affine. The rest lattice gives (I, 0).
struct AffineMap {
    Eigen::Matrix3d linear = Eigen::Matrix3d::Identity();
    Eigen::Vector3d offset = Eigen::Vector3d::Zero();
};
std::optional<AffineMap> affineMap(const Lattice& lattice, double strength = 1);

/// A bound of the operator norm of the Jacobian of the lattice map over the lattice box:
/// J = I + w sum_a (dd/da) dual_a^T, and |dd/da| <= deg_a max |d_(next along a) - d| over the
/// control net (the derivative volume's control points, convex hull), so
/// |J| <= 1 + |w| sum_a deg_a max|delta_a d| |dual_a|. Points of the box move apart by at most this
/// factor (the box is convex).
double lipschitzBound(const Lattice& lattice, double strength = 1);

// ------------------------------------------------------------------------ exact composition

/// The curve pushed through the lattice's polynomial, exactly: a Bézier curve of degree
/// d (l+m+n) (composition by Bernstein products in long double, as deformSurface). It equals
/// point-wise deformation wherever the curve lies in the lattice box (for example when its control
/// points do), and everywhere under the extrapolate policy. Error when the degree would exceed
/// kMaxDegree or the strength is not finite.
BezierCurve<double, 3> deformCurve(const Lattice& lattice, const BezierCurve<double, 3>& curve,
                                   double strength = 1);

/// The patch pushed through the lattice's polynomial, exactly: a Bézier patch of degrees
/// (p (l+m+n), q (l+m+n)) for a patch of degrees (p, q), by composition (the lattice coordinates of
/// the patch are a tensor polynomial of degrees (p, q); the composed Bernstein functions and their
/// products with the displacements are formed by the Bernstein product formula in long double).
/// It equals point-wise deformation wherever the patch lies in the lattice box (for example when
/// its control points do), and everywhere under the extrapolate policy. Error when a degree would
/// exceed kMaxDegree or the strength is not finite.
BezierSurface<double, 3> deformSurface(const Lattice& lattice, const BezierSurface<double, 3>& surface,
                                       double strength = 1);

// ------------------------------------------------------------------------ direct manipulation

struct DirectManipulation {
    Lattice lattice;                             ///< the lattice with moved control points
    Eigen::Matrix<double, 3, Eigen::Dynamic> change; ///< the control-point change, 3 x N
    double residual = 0;                          ///< max distance of a deformed point to its target
    int rank = 0;                                 ///< rank of the constraint system
};

/// Hsu, Hughes and Kaufman (1992): the smallest change (Frobenius norm) of the control points that
/// moves the deformed images of `points` (3 x K, undeformed positions) to `targets` (3 x K):
/// the pseudo-inverse solution of w B dP = targets - deformed(points), B_pq the basis weight of
/// control point q at point p (outside policy applied; a kept outside point constrains nothing).
/// Exact (residual at rounding level) whenever the system is consistent, else least squares.
DirectManipulation directManipulation(const Lattice& lattice, const Eigen::Matrix<double, 3, Eigen::Dynamic>& points,
                                      const Eigen::Matrix<double, 3, Eigen::Dynamic>& targets, double strength = 1);

} // namespace freeform
