#pragma once
// Lattice: a free-form deformation lattice, a Bézier volume placed in space by a frame.
//
// The frame is an origin X0 and three edge vectors S, T, U (columns of axes(); any linearly
// independent triple, orthogonal or not, right- or left-handed). A world point p has the lattice
// coordinates (docs/math.md, "Free-form deformation")
//     s = (T x U)^T (p - X0) / ((T x U)^T S),  t = (S x U)^T (p - X0) / ((S x U)^T T),
//     u = (S x T)^T (p - X0) / ((S x T)^T U),
// and the rest (undeformed) control point (i, j, k) is X0 + (i/l) S + (j/m) T + (k/n) U. Control
// points are stored in world coordinates at column i*(m+1)*(n+1) + j*(n+1) + k (the document's
// order); the deformation is evaluated in displacement form, p' = p + w sum B_ijk(s,t,u) (P_ijk -
// R_ijk), so a lattice whose points equal restPoint() bit for bit maps every point to itself bit
// for bit (see volume/deform.h).
//
// Invariants: degrees 1..kMaxDegree, the edge vectors independent (|det| > 0 relative to their
// lengths), every number finite, (l+1)(m+1)(n+1) control points. Checked in the constructor and in
// the setters (freeform::Error names the field); queries are const and check-free.

#include <array>
#include <string>

#include "freeform/core/types.h"
#include "freeform/volume/bezier_volume.h"

namespace freeform {

/// What happens to points outside the lattice box [0,1]^3 (docs/ffd.md):
///   Keep        - unchanged (the mesh can tear at the box boundary);
///   Clamp       - moved by the displacement of the nearest point of the box in lattice
///                 coordinates (the nearest point in space when the frame is orthogonal):
///                 continuous everywhere, the default;
///   Extrapolate - the polynomial continued outside.
enum class OutsidePolicy { Keep, Clamp, Extrapolate };

/// The outside policy, stated once for every deformation path (the lattice's and the rational
/// lattice's point maps, the FFD binding and its kernels, direct manipulation, the editor's drag,
/// Python's weights): where a point at lattice coordinates stu is evaluated, and what of the
/// lattice follows it.
struct OutsideRule {
    Eigen::Vector3d at;   ///< where the lattice is evaluated: stu, clamped into [0, 1]^3 outside the
                          ///< box under keep and clamp
    unsigned mask = 0x0f; ///< bits 0-2: the axes along which the displacement follows the point (all
                          ///< but those it is clamped on); bit 3: the point moves (not outside under keep)
    bool outside = false; ///< stu lies outside [0, 1]^3

    bool moves() const { return (mask & 0x08u) != 0; }
    bool follows(int axis) const { return ((mask >> axis) & 1u) != 0; }
};
OutsideRule outsideRule(const Eigen::Vector3d& stu, OutsidePolicy policy);
/// Whether outsideRule evaluates a point outside the box at clamped coordinates (keep and clamp;
/// extrapolate evaluates it where it is): the one fact of the rule that the vectorised kernels,
/// which clamp lane by lane (FfdBinding's bind, the editor's drag masks), take from here.
inline bool clampsOutside(OutsidePolicy policy) { return policy != OutsidePolicy::Extrapolate; }

/// "keep" | "clamp" | "extrapolate"; Error naming `what` otherwise.
OutsidePolicy parseOutsidePolicy(const std::string& text, const std::string& what);
std::string toString(OutsidePolicy policy);

class Lattice {
public:
    using Points = Eigen::Matrix<double, 3, Eigen::Dynamic>;

    /// Point and Jacobian of the world-space deformation map at one point.
    struct PointJet {
        Eigen::Vector3d point;
        Eigen::Matrix3d jacobian; // d p' / d p
        bool outside;             // p lies outside the lattice box
    };

    /// Degrees (l, m, n) >= 1, frame and control points (3 x (l+1)(m+1)(n+1), world coordinates).
    Lattice(std::array<int, 3> degree, const Eigen::Vector3d& origin, const Eigen::Matrix3d& axes, Points points,
            OutsidePolicy outside = OutsidePolicy::Clamp);

    /// The rest lattice: control points X0 + (i/l) S + (j/m) T + (k/n) U.
    static Lattice identity(std::array<int, 3> degree, const Eigen::Vector3d& origin, const Eigen::Matrix3d& axes,
                            OutsidePolicy outside = OutsidePolicy::Clamp);

    /// The rest lattice around the axis-aligned bounding box of `positions` (3 x V, V >= 1), each
    /// side pushed out by margin * (the largest extent of the box); an axis along which the padded
    /// box is still flat gets the extent of the largest axis (1 for a single point), centred.
    static Lattice fit(const Points& positions, std::array<int, 3> degree, double margin = 0.05,
                       OutsidePolicy outside = OutsidePolicy::Clamp);

    const std::array<int, 3>& degrees() const { return degree_; }
    int degree(int axis) const { return degree_[static_cast<std::size_t>(axis)]; }
    const Eigen::Vector3d& origin() const { return origin_; }
    /// Edge vectors S, T, U as columns.
    const Eigen::Matrix3d& axes() const { return axes_; }
    /// The map world -> lattice coordinates is (s,t,u) = dual() * (p - X0); row a is the
    /// normalised cross product of the other two edges (the inverse of axes(), formed as in docs/math.md).
    const Eigen::Matrix3d& dual() const { return dual_; }
    OutsidePolicy outside() const { return outside_; }
    void setOutside(OutsidePolicy policy) { outside_ = policy; }

    int pointCount() const { return static_cast<int>(points_.cols()); }
    int index(int i, int j, int k) const { return (i * (degree_[1] + 1) + j) * (degree_[2] + 1) + k; }
    const Points& controlPoints() const { return points_; }
    Eigen::Vector3d controlPoint(int i, int j, int k) const { return points_.col(index(i, j, k)); }
    /// Error when (i, j, k) is out of range or p is not finite.
    void setControlPoint(int i, int j, int k, const Eigen::Vector3d& p);
    /// Error when the shape is wrong or a point is not finite.
    void setControlPoints(const Points& points);

    Eigen::Vector3d restPoint(int i, int j, int k) const;
    Points restPoints() const;
    /// P - R for every control point (exactly zero for the rest lattice).
    const Points& displacements() const { return displacement_; }
    bool isRest() const { return displacement_.isZero(0.0); }

    /// Lattice coordinates of a world point (the docs/math.md formulas).
    Eigen::Vector3d toLattice(const Eigen::Vector3d& p) const;
    /// X0 + s S + t T + u U.
    Eigen::Vector3d toWorld(const Eigen::Vector3d& stu) const { return origin_ + axes_ * stu; }
    static bool insideBox(const Eigen::Vector3d& stu)
    {
        return (stu.array() >= 0.0).all() && (stu.array() <= 1.0).all();
    }

    /// The lattice as a Bézier volume of its world control points (f(s,t,u) = sum B P).
    BezierVolume<double> volume() const;
    /// The control points R + strength * (P - R) as a volume.
    BezierVolume<double> volume(double strength) const;
    /// The displacement field sum B (P - R) as a volume of vectors.
    BezierVolume<double> displacementVolume() const;

    /// The deformation map (displacement form, outside policy applied) and its Jacobian at a world
    /// point, evaluated directly: the reference for the batched path of volume/deform.h.
    PointJet deform(const Eigen::Vector3d& p, double strength = 1) const;

    /// The lattice map at lattice coordinates (no outside policy): the point
    /// toWorld(stu) + sum B d and the partial derivatives S + sum B_s d, ... (world vectors).
    BezierVolume<double>::Jet map(const Eigen::Vector3d& stu, double strength = 1) const;

    /// Basis weights B_i^l(s) B_j^m(t) B_k^n(u) of every control point at lattice coordinates.
    Eigen::VectorXd basisWeights(const Eigen::Vector3d& stu) const;

    /// The sensitivities of the deformed point to the control points (docs/python.md,
    /// "Sensitivities"): FFD is linear in them, so d p' / d P_q = strength * B_q(at) times the
    /// identity, with `at` and whether p moves from outsideRule (the lattice coordinates, clamped
    /// into the box under keep and clamp). Writes the pointCount() factors strength * B_q,
    /// q = index(i, j, k), to out; zeros when p does not move (outside under keep). The Bernstein
    /// values come from de Casteljau's triangle (convex combinations).
    void sensitivities(const Eigen::Vector3d& p, double strength, double* out) const;
    /// Points per block of sensitivityBlock.
    static constexpr int kSensitivityLanes = 8;
    /// sensitivities() of count <= kSensitivityLanes points (x y z interleaved) lane by lane:
    /// out[q * kSensitivityLanes + lane], zeros for lanes past count. Loops of fixed length, which
    /// the compiler vectorises (Python's matrix-free products W x and W^T y); each value equals
    /// sensitivities()'s bit for bit.
    void sensitivityBlock(const double* points, std::size_t count, double strength, double* out) const;

    /// The same deformation with the degrees raised by (dl, dm, dn): the displacements are
    /// degree-elevated, so every point moves exactly as before (up to rounding).
    Lattice elevated(int dl, int dm, int dn) const;

    /// Same degrees and frame bit for bit (what an FfdBinding bound to `other` needs to stay valid).
    bool sameFrame(const Lattice& other) const
    {
        return degree_ == other.degree_ && origin_ == other.origin_ && axes_ == other.axes_;
    }

private:
    void updateDisplacements();

    std::array<int, 3> degree_;
    Eigen::Vector3d origin_;
    Eigen::Matrix3d axes_;
    Eigen::Matrix3d dual_;
    Eigen::Vector3d dualDenominator_; // (T x U)^T S, (S x U)^T T, (S x T)^T U
    Eigen::Matrix3d dualNumerator_;   // rows T x U, S x U, S x T
    Points points_;
    Points displacement_;
    OutsidePolicy outside_;
};

} // namespace freeform
