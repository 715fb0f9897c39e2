#pragma once
// SubdivisionSurface: the Catmull-Clark or Loop limit surface of a polygon cage, evaluated through
// OpenSubdiv's Bfr (the library links OpenSubdiv privately; no OpenSubdiv header is included here).
//
// Guarantees: the cage is validated once, in the constructor (validateCage: indices in range, at
// least three distinct vertices per face, a manifold and consistently oriented cage, all triangles
// for Loop, creases on existing edges, sharpness finite and >= 0), and every Error names the face,
// edge or vertex. Afterwards everything is const: one Bfr::Surface per face is built up front (the
// per-face cache), and evaluation, tessellation and the Bézier conversion read it without further
// setup. withPositions() keeps that topology and only recomputes the patch points, so moving cage
// vertices (the editor, a deformation) does not rebuild it. A face has a limit surface unless the
// boundary interpolation is None and the face touches the boundary (hasLimitSurface()).
//
// Face parameterisation (OpenSubdiv's, Bfr::Parameterization): a quad's (u, v) is the unit square
// with (0,0) at face corner 0, (1,0) at corner 1, (1,1) at corner 2, (0,1) at corner 3, so u runs
// along the first edge and v along the last edge backwards; a triangle (Loop) has u, v >= 0,
// u + v <= 1 with corners (0,0), (1,0), (0,1); any other polygon under Catmull-Clark is split into
// quad sub-faces (Bfr's QUAD_SUBFACES). The normal is (f_u x f_v)/|f_u x f_v|: outward for a cage
// whose faces run counter-clockwise seen from outside. The math (the regular-face tie to bicubic
// Bézier patches, cage deformation) is in docs/subdivision.md.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "freeform/mesh/polygon_mesh.h"
#include "freeform/surface/patch_complex.h"
#include "freeform/volume/deform.h"
#include "freeform/volume/lattice.h"

namespace freeform {

enum class SubdivisionScheme { Catmark, Loop };
/// "catmark" | "loop"; Error naming `what` otherwise.
SubdivisionScheme parseSubdivisionScheme(const std::string& text, const std::string& what);
std::string toString(SubdivisionScheme scheme);

/// How the boundary is treated (OpenSubdiv's vertex boundary interpolation):
///   None          - boundary faces have no limit surface (the cage's boundary ring is a frame);
///   EdgeOnly      - boundary edges are infinitely sharp creases (the default);
///   EdgeAndCorner - as EdgeOnly, and boundary vertices with one face are sharp corners.
enum class BoundaryInterpolation { None, EdgeOnly, EdgeAndCorner };
/// "none" | "edge_only" | "edge_and_corner"; Error naming `what` otherwise.
BoundaryInterpolation parseBoundaryInterpolation(const std::string& text, const std::string& what);
std::string toString(BoundaryInterpolation boundary);

/// OpenSubdiv's infinite sharpness (Sdc::Crease::SHARPNESS_INFINITE): a crease or corner of this
/// sharpness or more stays sharp at every level.
constexpr double kInfiniteSharpness = 10.0;

/// Sharpness of the cage edge between vertices v0 and v1 (either order).
struct EdgeCrease {
    int v0 = 0, v1 = 0;
    double sharpness = 0;
};

/// Sharpness of a cage vertex.
struct VertexCorner {
    int vertex = 0;
    double sharpness = 0;
};

/// A control cage: the polygon mesh and its creases.
struct SubdivisionCage {
    PolygonMesh mesh;
    std::vector<EdgeCrease> creases;
    std::vector<VertexCorner> corners;
    // The other tags of OpenSubdiv's shape format (docs/subdivision.md, "Tags"):
    std::vector<int> holes;                        ///< `hole`: faces without a limit surface
    std::optional<BoundaryInterpolation> boundary; ///< `interpolateboundary` (0 none, 1 edge and corner, 2 edge only)
    bool chaikin = false;                          ///< `creasemethod chaikin` (else "normal": uniform)
    bool smoothTriangles = false;                  ///< `smoothtriangles smooth` (Catmark only)
};

/// Loop when every face is a triangle, Catmark otherwise.
SubdivisionScheme defaultScheme(const PolygonMesh& mesh);

/// Throws Error naming `what` and the face / edge / vertex when the cage is not usable (see the
/// header comment).
void validateCage(const SubdivisionCage& cage, SubdivisionScheme scheme, const std::string& what = "cage");

// Reading a cage from a mesh file (OBJ crease tags) and from a document object: io/geometry_data.h.

/// Position, first partial derivatives and unit normal of the limit surface at a point.
struct LimitPoint {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    Eigen::Vector3d du = Eigen::Vector3d::Zero();
    Eigen::Vector3d dv = Eigen::Vector3d::Zero();
    Eigen::Vector3d normal = Eigen::Vector3d::Zero(); ///< zero only where f_u x f_v vanishes
};

struct SubdivisionTessellationOptions {
    /// Segments per face edge in uniform mode (tolerance 0), at least 1.
    int level = 8;
    /// > 0: adaptive, on the certified path (docs/subdivision.md, "Certified tessellation") for
    /// every cage. Catmull-Clark (holes, boundary none, smooth triangles, creases, corners and
    /// edge_only one-face corners included): every base face is cut into cells (OpenSubdiv's
    /// adaptive refinement and patch table), a regular cell is a bicubic Bézier patch split by
    /// de Casteljau until netErrorBound is at most this, an irregular cell (at an extraordinary
    /// vertex, a sharp corner, an irregular crease or boundary vertex, an edge_only one-face corner)
    /// is bounded by the convex hull of its 1-ring; the bound holds both ways (mesh to surface,
    /// surface to mesh) and the mesh is conforming, and watertight for closed cages. Loop cages take
    /// the same kind of path with quartic Bézier triangles for interior regular cells and 1-ring
    /// hulls for the rest (docs/subdivision.md, "Loop cages"). With `certified` false, the estimate:
    /// each face gets the fewest segments whose error estimate is at most this (regular faces: the
    /// certified bound of their Bézier patch; other faces: sampled second derivatives, not
    /// certified); a shared edge gets the larger count of its two faces.
    double tolerance = 0;
    int maxLevel = 256;
    /// false: the estimate path (per-face segment counts, rates in the report) even where the
    /// certified path applies.
    bool certified = true;
    /// Certified path: how deep irregular cells are refined by OpenSubdiv, 1..10 (its patch table
    /// holds no deeper level). At 10 (the default), a cell still above the tolerance gets its own
    /// local cage (its level-10 1-ring) and is refined further, down to level 30 in all
    /// (docs/subdivision.md, "Deeper than level 10"); below 10 it is a hard cap, and where it binds
    /// the report's errorBound exceeds the tolerance.
    int maxDepth = 10;
    /// Certified path: how often a regular cell may be halved by de Casteljau (per direction; Loop:
    /// how many generations of four-way splits).
    int maxSplits = 16;
    /// Certified path only (ignored by the estimate path and in uniform mode): a tolerance per
    /// region, e.g. the editor's pixel size at a region's nearest depth (docs/subdivision.md,
    /// "A tolerance per region"). When set, every cell's own tolerance is
    /// min(tolerance, toleranceOf(box)), where box bounds the points whose convex hull the cell's
    /// bound uses (the Bézier net of a regular cell or leaf, the 1-ring of an irregular cell), so
    /// it bounds the cell's limit surface; each cell is refined until its bound is within its own
    /// tolerance. Must return a value > 0 (a non-positive or non-finite value is an Error).
    std::function<double(const Eigen::AlignedBox3d&)> toleranceOf;
};

struct SubdivisionTessellationReport {
    std::vector<int> rates; ///< per face: segments chosen for the face (0: no limit surface); estimate path only
    int regularFaces = 0;   ///< faces whose rate came from the certified Bézier bound (adaptive, estimate path)
    // Certified path (tolerance > 0 on a Catmark cage or a closed Loop cage, see the options):
    bool certifiedPath = false;      ///< the certified path ran
    double errorBound = 0;           ///< the largest certified bound over all leaves (both ways)
    long long cells = 0;             ///< cells from the patch table (regular patches + irregular cells)
    long long irregularCells = 0;    ///< of them, irregular (bounded by their 1-ring hull)
    long long leaves = 0;            ///< leaves after de Casteljau splitting
    int depth = 0;                   ///< refinement level of the irregular cells
    std::vector<double> faceBounds;  ///< per cage face: its largest leaf bound (0: no limit surface)
    std::vector<char> faceCertified; ///< per cage face: 1 when every leaf's bound is certified and within the leaf's own
                                     ///< tolerance (the tolerance, or with toleranceOf the cell's min(tolerance, toleranceOf(box)))
    std::vector<double> faceTolerance; ///< per cage face: the smallest own tolerance of its leaves (the tolerance without toleranceOf)
};

class SubdivisionSurface {
public:
    /// Validates the cage (Error) and builds the topology and one Bfr::Surface per face.
    SubdivisionSurface(SubdivisionCage cage, SubdivisionScheme scheme,
                       BoundaryInterpolation boundary = BoundaryInterpolation::EdgeOnly);
    ~SubdivisionSurface();
    SubdivisionSurface(const SubdivisionSurface&);
    SubdivisionSurface& operator=(const SubdivisionSurface&);
    SubdivisionSurface(SubdivisionSurface&&) noexcept;
    SubdivisionSurface& operator=(SubdivisionSurface&&) noexcept;

    const SubdivisionCage& cage() const;
    SubdivisionScheme scheme() const;
    BoundaryInterpolation boundary() const;
    int faceCount() const;

    /// Whether the face has a limit surface (see the header comment).
    bool hasLimitSurface(int face) const;
    /// Whether OpenSubdiv represents the face's limit surface as one regular patch.
    bool isRegularPatch(int face) const;
    /// Whether (u, v) lies in the face's parameter domain (see the header comment).
    bool inDomain(int face, double u, double v) const;

    /// The limit surface at (u, v) of a face. Error when the face is out of range, has no limit
    /// surface or (u, v) is outside its domain.
    LimitPoint evaluate(int face, double u, double v) const;

    /// The 16 cage vertices around a regular Catmull-Clark face: a quad whose four corners are
    /// interior vertices with four quads each, no crease or sharp corner touching the 4 x 4 points.
    /// Index r * 4 + c, r along u (corner 0 -> corner 1), c along v (corner 0 -> corner 3); corner 0
    /// is (1, 1). Empty for any other face and for Loop. Found from the cage's topology alone.
    std::optional<std::array<int, 16>> regularNeighbourhood(int face) const;

    /// The bicubic Bézier patch of a regular face (tensor-product A-frame of its 4 x 4 de Boor
    /// points, uniform knots), in the face's (u, v). Empty when the face is not regular.
    std::optional<Patch> bezierPatch(int face) const;

    /// The patches of every regular face, and (when faces is not null) which face each came from.
    PatchComplex regularBezierPatches(std::vector<int>* faces = nullptr) const;

    /// The limit surface as a triangle mesh with analytic unit normals: one vertex per cage vertex
    /// (its limit point), the points inside a cage edge shared by its faces, so the mesh is closed
    /// when the cage is. Error on bad options.
    PolygonMesh tessellate(const SubdivisionTessellationOptions& options = {},
                           SubdivisionTessellationReport* report = nullptr) const;

    /// The same cage topology and creases with new vertex positions (3 x V); Error on a wrong
    /// shape or a non-finite value.
    SubdivisionSurface withPositions(const Eigen::Matrix<double, 3, Eigen::Dynamic>& positions) const;

private:
    PolygonMesh tessellateCertified(const SubdivisionTessellationOptions& options,
                                    SubdivisionTessellationReport* report) const;
    PolygonMesh tessellateCertifiedLoop(const SubdivisionTessellationOptions& options,
                                        SubdivisionTessellationReport* report) const;
    struct Topology;
    std::shared_ptr<const Topology> topology_;
    SubdivisionCage cage_;
    std::vector<double> patchPoints_; // all faces' patch points, xyz, at topology offsets
};

/// The cage with its vertices moved through the lattice (deformPoints); faces and creases kept.
/// The limit surface of the deformed cage equals the deformed limit surface only when the
/// deformation is affine (docs/subdivision.md).
SubdivisionCage deformCage(const SubdivisionCage& cage, const Lattice& lattice, const DeformOptions& options = {});

} // namespace freeform
