#pragma once
// Operations on typed document objects, the same for every front end: evaluate, continuity,
// tessellate (surfaces to meshes, curves to polylines), convert (spline forms) and deformDocument
// (free-form deformation of a whole document, one rule for every type: docs/ffd.md). Errors are
// freeform::Error prefixed `source: object "name": `.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "freeform/core/error.h"
#include "freeform/curve/continuity.h"
#include "freeform/document/model.h"
#include "freeform/mesh/polygon_mesh.h"
#include "freeform/tessellate/tessellate.h"
#include "freeform/volume/deform.h"

namespace freeform {

// ---------------------------------------------------------------- evaluate (freeform eval)

/// An object evaluated at one parameter, per type (as `freeform eval` prints it, docs/cli.md):
///   bezier_curve        at = {t}, t in [0, 1]; derivatives[k-1] = k-th derivative, keys empty;
///   bezier/deboor_spline at = {T}, T in [0, sum of intervals]; as curves (global parameter);
///   bezier/deboor_surface at = {u, v} in [0, segments]; normal; derivatives keyed "u", "v",
///                       "uu", "uv", "vv", ... (orders 1..K, u-order first);
///   lattice             at = {s, t, u} in [0,1]^3, order 0 or 1; keys "s", "t", "u" and det
///                       (det J of the world-space map);
///   subdivision_surface at = {face, u, v}; order 0 or 1 (the first derivatives are always given,
///                       keys "u", "v"); normal;
///   trimmed_surface     at = {u, v} in the file's parameters, inside the face's parameter box;
///                       order 0 or 1 (keys "u", "v"); normal; trim (inside, outside, boundary);
///   part                at = {face, u, v}: as trimmed_surface on that face, the normal outward
///                       (negated on a reversed face).
struct Evaluation {
    Eigen::VectorXd point;
    std::vector<Eigen::VectorXd> derivatives;
    std::vector<std::string> keys; // empty for curves and splines, else one per derivative
    std::optional<Eigen::Vector3d> normal;
    std::optional<double> det; // lattice, order 1
    int face = -1;             // subdivision_surface, part
    /// trimmed_surface, part: where (u, v) lies against the face's trims (TrimmedSurface::classify).
    std::optional<TrimClass> trim;
};

/// Error (prefixed with the object) when the parameter count is wrong, the parameter lies outside
/// the domain, or the order is not available for the type; order must be >= 0.
Evaluation evaluate(const TypedDocument& doc, const TypedObject& object, const std::vector<double>& at, int order);

/// The domain end of a curve/spline (T in [0, end]) or the segments of a surface; for messages.
std::vector<double> parameterDomain(const TypedObject& object);

// ---------------------------------------------------------------- continuity (freeform continuity)

/// The continuity of every joint of a bezier_spline or deboor_spline (through the A-frame);
/// Error for other types.
std::vector<JointContinuity<double>> continuity(const TypedDocument& doc, const TypedObject& object,
                                                const ContinuityTolerances<double>& tol = {});

// ---------------------------------------------------------------- tessellate

/// The patches of a bezier_surface or deboor_surface (segments receives the counts); Error for
/// other types ("type T is not a surface (bezier_surface, deboor_surface)").
PatchComplex surfacePatches(const TypedDocument& doc, const TypedObject& object,
                            std::array<int, 2>* segments = nullptr);

/// Every surface object's patches in document order (`freeform tessellate DOC` without --object);
/// Error when there is none.
PatchComplex documentPatches(const TypedDocument& doc);

/// A document's surfaces as one mesh (`freeform tessellate DOC`), with what was measured.
struct DocumentTessellation {
    PolygonMesh mesh;
    std::size_t patches = 0;   ///< Bézier patches tessellated (the NURBS ones after extraction)
    TessellationReport report; ///< of the polynomial complex; errorBound the largest of all
};

/// One surface object, or (object null) every bezier_surface, deboor_surface,
/// rational_bezier_surface and nurbs_surface of the document, as one mesh: the polynomial patches
/// as one complex (tessellate(); patches that share a side share its vertices), then each rational
/// one (tessellateObject, its certified rational bound; uniform `segmentsU` per patch without a
/// tolerance), merged in that order. Error as surfacePatches when the object is not one of these,
/// or the document has no surface.
DocumentTessellation tessellateDocument(const TypedDocument& doc, const TypedObject* object,
                                        const TessellationOptions& options);

/// How an object is tessellated for display (the editor's per-object settings, resolved).
struct ObjectTessellation {
    double tolerance = 0; ///< > 0: adaptive to this distance; 0: uniform `segments`
    int segments = 8;     ///< per patch and direction; the subdivision level (clamped to 1..maxLevel)
    bool flip = false;    ///< reverse the triangles and negate the normals
    /// bezier_surface / deboor_surface in adaptive mode: one tolerance per patch of AnySurface::of's
    /// patch complex (TessellationOptions::patchTolerance; empty: `tolerance` everywhere); other
    /// types use `tolerance`.
    std::vector<double> patchTolerance;
    /// subdivision_surface in adaptive mode (the certified path): a tolerance per region, each
    /// cell's min(tolerance, toleranceOf(box)) (SubdivisionTessellationOptions::toleranceOf;
    /// empty: `tolerance` everywhere); other types ignore it.
    std::function<double(const Eigen::AlignedBox3d&)> toleranceOf;
    /// part and trimmed_surface: each face's triangles on vertices of their own, with normals
    /// averaged over that face only (how a viewer shades the creases between faces); false: the
    /// watertight mesh, every edge's vertices shared by its faces, no normals.
    bool splitFaces = false;
};

/// The triangle mesh of a bezier_surface, deboor_surface (tessellate()) or subdivision_surface
/// (its limit surface); nullopt for other types.
std::optional<PolygonMesh> tessellateObject(const TypedObject& object, const ObjectTessellation& options,
                                            TessellationReport* report = nullptr);

/// The polyline of a curve or spline (AnyCurve::polyline); nullopt for other types.
std::optional<Eigen::Matrix<double, 3, Eigen::Dynamic>> objectPolyline(const TypedObject& object, double tolerance);

/// The control net as the editor draws it: points (3D; 2D with z = 0) and edges between them
/// (polygon for curves/splines, closed when the spline is; grid for surfaces; the lattice's
/// i, j, k lines; the cage's edges, each once, sorted).
struct ControlNet {
    Eigen::Matrix<double, 3, Eigen::Dynamic> points;
    std::vector<std::pair<int, int>> edges;
};
ControlNet controlNet(const TypedObject& object);

// ---------------------------------------------------------------- convert (freeform convert --to)

/// A deboor_spline as bezier_spline data (degree 3, the A-frame, same intervals); Error for any
/// other type (a bezier_spline: "is already a bezier_spline").
BezierSplineData toBezierSplineData(const TypedDocument& doc, const TypedObject& object);

/// A cubic bezier_spline as deboor_spline data under `end` (default: closed for a closed spline,
/// clamped for an open one); Error when the degree is not 3, the end does not fit the spline
/// (closed vs open), or the spline is not C2 where de Boor points need it.
DeBoorSplineData toDeBoorSplineData(const TypedDocument& doc, const TypedObject& object,
                                    std::optional<EndCondition> end = std::nullopt);

/// Replaces the object by its other spline form ("bezier_spline" or "deboor_spline"), keeping id,
/// name and editor settings. Error when it is already of that form or cannot be converted.
void convertSpline(TypedDocument& doc, ObjectId id, const std::string& to,
                   std::optional<EndCondition> end = std::nullopt);

/// The object as nurbs_curve data (bezier_curve, rational_bezier_curve: clamped knots on [0, 1];
/// bezier_spline, deboor_spline: degree d, every interior breakpoint d times, on [0, sum of
/// intervals], a closed spline's first point repeated at the end) or nurbs_surface data
/// (bezier_surface, rational_bezier_surface: clamped knots on [0, 1]^2); weights left out when all
/// are 1. Error naming the object for other types (and for a nurbs type: "is already").
ObjectData toNurbsData(const TypedDocument& doc, const TypedObject& object);

/// A nurbs_curve as its Bézier pieces in one object: a polynomial one as a bezier_spline (degree p,
/// the pieces' points, intervals = the knot span lengths), a rational one with one span as a
/// rational_bezier_curve; a nurbs_surface with one span pair as a bezier_surface or
/// rational_bezier_surface. Error when one object of the format cannot hold the pieces (several
/// rational pieces or patches).
ObjectData fromNurbsData(const TypedDocument& doc, const TypedObject& object);

/// convertObject's Error when the object converts, but to another kind than asked (a rational
/// curve of several pieces asked for as a rational_bezier_curve, a curve asked for as a
/// nurbs_surface): `converted` is the kind it does convert to, so a front end can suggest it.
class ConversionMismatch : public Error {
public:
    ConversionMismatch(const std::string& message, std::string converted) : Error(message), converted(std::move(converted)) {}
    std::string converted;
};

/// Replaces the object by its form `to`, keeping id, name and editor settings (`freeform convert
/// --to`, Python's Document.convert). The route is the kind table's: to a kind with knots
/// (toNurbsData), from a kind that has Bézier pieces (fromNurbsData), between the two spline forms
/// (convertSpline; `end` for deboor_spline, else Error). Error naming the object when there is no
/// route, ConversionMismatch when the route gives another kind; nothing is changed then.
void convertObject(TypedDocument& doc, ObjectId id, const std::string& to, std::optional<EndCondition> end = std::nullopt);

// ---------------------------------------------------------------- deformDocument (freeform ffd DOC)

struct DeformDocumentOptions {
    double strength = 1;
    int threads = 0; // for subdivision cages (deformPoints)
    /// false (the command line): an object whose control points leave the lattice box under the
    /// keep or clamp policy is still deformed (the lattice polynomial continued) and reported
    /// exact = false. true (the editor's former rule): such an object is skipped instead.
    bool skipInexact = false;
};

struct DeformedObject {
    ObjectId id = 0;
    std::string name;
    std::string from;        // the type before
    std::string type;        // the type after
    std::vector<int> degree; // curve/spline: {d}; surface: {p, q}; subdivision: empty
    bool inside = true;      // every control point (de Boor point, cage vertex) in the lattice box
    bool exact = true;       // the result equals point-wise FFD under the lattice's policy
    std::string note;        // why the type changed, why it is not exact (empty when neither)
};

struct SkippedObject {
    ObjectId id = 0;
    std::string name;
    std::string type;
    std::string reason;
};

struct DeformDocumentReport {
    std::vector<DeformedObject> objects; // in document order
    std::vector<SkippedObject> skipped;  // in document order
    Certificate certificate;             // certify(lattice, strength): the lattice box
};

/// Deforms every object of the document through the lattice, one rule for every type
/// (docs/ffd.md, "Documents"):
///   - 2D objects and lattices are skipped;
///   - bezier_curve / bezier_spline / bezier_surface: composed exactly with the lattice polynomial
///     (degree d (l+m+n)); outside the box the polynomial continues (exact = inside || policy is
///     extrapolate);
///   - deboor_spline: stays a deboor_spline (its de Boor points mapped) when the lattice map is
///     affine, since then the result is again a cubic C2 spline on the same intervals; otherwise
///     the composition raises the degree and it becomes a bezier_spline of degree 3 (l+m+n);
///   - deboor_surface: the same when affine (stays a deboor_surface); otherwise skipped (its exact
///     image is several Bézier patches, which one object of the format cannot hold);
///   - rational_bezier_curve / nurbs_curve / rational_bezier_surface / nurbs_surface (3D): composed
///     exactly (volume/deform_rational.h), NURBS span by span (patch by patch) through the Bézier
///     extraction, keeping the breakpoints; the same type; outside the box as for Bézier objects;
///   - subdivision_surface: its cage is deformed as a cage (vertices through deformPoints, the
///     outside policy as for meshes; a cage from a mesh file is written inline); the limit surface
///     of the moved cage is the moved limit surface only when the lattice is affine (exact).
/// The document is changed only when nothing throws.
DeformDocumentReport deformDocument(TypedDocument& doc, const Lattice& lattice, const DeformDocumentOptions& options = {});

/// Whether the lattice's displacement field (times strength) is an affine function of (s, t, u)
/// within a relative tolerance of 1e-12 of the lattice size (the rest lattice is).
bool isAffineLattice(const Lattice& lattice, double strength = 1);

// ---------------------------------------------------------------- parts (docs/cad.md)

/// The part an object is, for what takes whole parts (STEP and IGES output, the part report): a
/// part itself, or a trimmed surface as a part of one face (singleFacePart, brep/part.h); nullopt
/// for every other kind.
std::optional<Part> objectPart(const TypedObject& object);

/// The document's part: the object named `name` (Error when it is of another kind), else the
/// document's only part or trimmed surface (Error naming the document when there is none, or
/// listing them when there are several).
const TypedObject& documentPart(const TypedDocument& doc, const std::optional<std::string>& name = std::nullopt);

} // namespace freeform
