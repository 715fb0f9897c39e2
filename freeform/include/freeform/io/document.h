#pragma once
// The freeform document, format version 1 (specified in docs/format.md).
//
//   {"format": "freeform", "version": 1,
//    "objects": [{"name": "c", "type": "bezier_curve", "points": [[0,0],[1,2],[3,2],[4,0]]}, ...],
//    "editor": {...}}
//
// The reader is strict: an unknown type or field, a wrong array shape, a non-integer degree or a
// number that is not finite is a freeform::Error naming the source, the object and the field.
// The document holds plain data (points in double, dimension known at run time); the geometry
// classes are built from it by the document layer (document/document.h: TypedDocument) and by
// io/geometry_data.h (latticeFromData, cageFromData).

#include <Eigen/Core>

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "freeform/brep/parameter_map.h"
#include "freeform/io/file.h"
#include "freeform/volume/lattice.h"

namespace freeform {

/// Points are the columns of a dim x count matrix (dim 2 or 3).
using PointColumns = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic>;

struct BezierCurveData {
    PointColumns points; // dim x (degree + 1)
};

struct BezierSplineData {
    int degree = 3;
    bool closed = false;
    PointColumns points;          // dim x (L*degree + 1) open, dim x (L*degree) closed
    std::vector<double> intervals; // L lengths; empty means all 1
};

struct DeBoorSplineData {
    int degree = 3;
    std::string end = "open";      // "open" | "clamped" | "closed"
    PointColumns points;           // de Boor points
    std::vector<double> intervals; // empty means all 1
};

struct BezierSurfaceData {
    std::array<int, 2> degree{};   // (m, n)
    PointColumns points;           // 3 x (m+1)(n+1), index i*(n+1) + j
};

struct DeBoorSurfaceData {
    std::array<int, 2> degree{3, 3};
    std::array<std::string, 2> end{"open", "open"};
    int rows = 0, cols = 0;        // grid size: rows along u, cols along v
    PointColumns points;           // 3 x rows*cols, index i*cols + j
};

struct LatticeData {
    std::array<int, 3> degree{};   // (l, m, n)
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    Eigen::Matrix3d axes = Eigen::Matrix3d::Identity(); // columns S, T, U
    PointColumns points;           // 3 x (l+1)(m+1)(n+1), index i*(m+1)*(n+1) + j*(n+1) + k
    OutsidePolicy outside = OutsidePolicy::Clamp; // "keep" | "clamp" | "extrapolate" in the file
};

struct SubdivisionSurfaceData {
    std::string mesh;                      // path of a mesh file (relative to the document), or empty
    PointColumns vertices;                 // 3 x V when given inline
    std::vector<std::vector<int>> faces;   // inline faces (vertex indices)
    std::string scheme = "catmark";        // "catmark" | "loop"
    std::vector<std::array<double, 3>> creases; // [v0, v1, sharpness] (vertex indices as integers)
    std::vector<std::array<double, 2>> corners; // [v, sharpness]
    std::string boundary = "edge_only";    // "edge_only" | "edge_and_corner" | "none"
};

/// A rational Bézier curve: points and one positive weight per point (degree = count - 1).
struct RationalBezierCurveData {
    PointColumns points;         // dim x (degree + 1)
    std::vector<double> weights; // degree + 1 positive weights
};

/// A rational Bézier patch: grid and weights as bezier_surface, one positive weight per point.
struct RationalBezierSurfaceData {
    std::array<int, 2> degree{}; // (m, n)
    PointColumns points;         // 3 x (m+1)(n+1), index i*(n+1) + j
    std::vector<double> weights; // (m+1)(n+1), same index
};

/// A NURBS curve: degree p, knots (count + p + 1, non-decreasing), points, weights (empty: all 1).
struct NurbsCurveData {
    int degree = 3;
    std::vector<double> knots;
    PointColumns points;         // dim x count
    std::vector<double> weights; // count positive weights, or empty (all 1, not written)
};

/// A NURBS surface: degrees (p, q), knots in u and v, a rows x cols grid (rows = countU).
struct NurbsSurfaceData {
    std::array<int, 2> degree{3, 3};
    std::array<std::vector<double>, 2> knots;
    int rows = 0, cols = 0;
    PointColumns points;         // 3 x rows*cols, index i*cols + j
    std::vector<double> weights; // rows*cols, same index, or empty (all 1, not written)
};

/// A NURBS curve of a CAD form in the file's parameter t (brep/exact_forms.h: point(t) =
/// nurbs(map(t)) on [first, last]); map empty: the identity.
struct MappedCurveData {
    NurbsCurveData nurbs;
    ParameterMap map;
    double first = 0, last = 1;
};

/// One trim curve of a loop (2D, in the face's parameters), traversed from last to first when
/// reversed, on the part's edge `edge` (-1: none).
struct TrimCurveData {
    MappedCurveData curve;
    bool reversed = false;
    int edge = -1;
};

/// A trimmed surface (brep/trimmed_surface.h): a NURBS surface with a parameter map per direction,
/// the parameter box of the face (u0, u1, v0, v1) and its loops (the first the outer boundary; no
/// loops: the whole box).
struct TrimmedSurfaceData {
    NurbsSurfaceData surface;
    std::array<ParameterMap, 2> map{};
    std::array<double, 4> domain{0, 1, 0, 1};
    std::vector<std::vector<TrimCurveData>> loops;
};

/// A part (brep/part.h): faces, edges, vertices, shells and solids, indices into each other.
struct PartFaceData {
    TrimmedSurfaceData surface;
    bool reversed = false;
    std::string kind;     // the file's surface kind ("plane", "bspline", ...), empty when unknown
    double tolerance = 0;
};
struct PartEdgeData {
    std::optional<MappedCurveData> curve; // none: degenerate, or only pcurves
    double first = 0, last = 0;
    int start = -1, end = -1;
    double tolerance = 0;
    bool degenerate = false;
};
struct PartVertexData {
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    double tolerance = 0;
};
struct PartData {
    std::string units = "mm";
    std::vector<PartFaceData> faces;
    std::vector<PartEdgeData> edges;
    std::vector<PartVertexData> vertices;
    std::vector<std::vector<int>> shells; // face indices
    std::vector<std::vector<int>> solids; // shell indices
};

/// Every object kind, one line each in the order of ObjectData's alternatives: X(Kind, Data, "type").
/// The ObjectKind enumerator, the data struct above and the "type" string as docs/format.md spells
/// it (the only place the names are written). This list is the kind table's entry for each kind:
/// the document layer declares from it the functions each kind's document file defines
/// (src/document/kinds/TYPE.cpp), so a kind without its file does not link; docs/architecture.md,
/// "Adding an object kind".
#define FREEFORM_OBJECT_KINDS(X)                                                                     \
    X(BezierCurve, BezierCurveData, "bezier_curve")                                                  \
    X(BezierSpline, BezierSplineData, "bezier_spline")                                               \
    X(DeBoorSpline, DeBoorSplineData, "deboor_spline")                                               \
    X(BezierSurface, BezierSurfaceData, "bezier_surface")                                            \
    X(DeBoorSurface, DeBoorSurfaceData, "deboor_surface")                                            \
    X(Lattice, LatticeData, "lattice")                                                               \
    X(SubdivisionSurface, SubdivisionSurfaceData, "subdivision_surface")                             \
    X(RationalBezierCurve, RationalBezierCurveData, "rational_bezier_curve")                         \
    X(RationalBezierSurface, RationalBezierSurfaceData, "rational_bezier_surface")                   \
    X(NurbsCurve, NurbsCurveData, "nurbs_curve")                                                     \
    X(NurbsSurface, NurbsSurfaceData, "nurbs_surface")                                               \
    X(TrimmedSurface, TrimmedSurfaceData, "trimmed_surface")                                         \
    X(Part, PartData, "part")

namespace detail {
template <class First, class... Rest>
struct DropFirst {
    using Variant = std::variant<Rest...>;
};
} // namespace detail

#define FREEFORM_KIND_DATA_TYPE(Kind, Data, name) , Data
/// The plain data of one object: one alternative per kind, in FREEFORM_OBJECT_KINDS' order.
using ObjectData = detail::DropFirst<void FREEFORM_OBJECT_KINDS(FREEFORM_KIND_DATA_TYPE)>::Variant;
#undef FREEFORM_KIND_DATA_TYPE

struct DocumentObject {
    std::string name;
    ObjectData data;
    std::string editor; // the object's "editor" member as JSON text (display settings), or empty
};

struct Document {
    std::vector<DocumentObject> objects;
    std::string editor; // the document's "editor" member as JSON text (camera, display), or empty
    std::string source; // where it was read from, for messages

    /// The object called name; throws Error listing the names when there is none.
    const DocumentObject& object(const std::string& name) const;
    DocumentObject* find(const std::string& name);
    const DocumentObject* find(const std::string& name) const;
};

/// The kind of an object: one per alternative of ObjectData, in its order. What each kind is and
/// supports is described once, in the kind table (document/kinds.h).
#define FREEFORM_KIND_ENUMERATOR(Kind, Data, name) Kind,
enum class ObjectKind { FREEFORM_OBJECT_KINDS(FREEFORM_KIND_ENUMERATOR) };
#undef FREEFORM_KIND_ENUMERATOR
inline constexpr int objectKindCount = static_cast<int>(std::variant_size_v<ObjectData>);

inline ObjectKind objectKind(const ObjectData& data) { return static_cast<ObjectKind>(data.index()); }

/// The "type" string of a kind as docs/format.md spells it ("bezier_curve", ...), from
/// FREEFORM_OBJECT_KINDS.
std::string_view kindName(ObjectKind kind);

/// The kind whose "type" string is name; nullopt for any other text.
std::optional<ObjectKind> kindNamed(std::string_view name);

/// The "type" string of an object ("bezier_curve", ...).
std::string objectType(const ObjectData& data);

/// The lattice object called name, or the document's only lattice when there is no name: what
/// `freeform ffd --lattice`, `subdivide --lattice` and Python's Lattice.load look up. Error naming
/// the document when the object is not a lattice, when there is none, or when there are several
/// (listing them, then `choose`: how the caller's user picks one, e.g. "choose one with --object").
const DocumentObject& findLattice(const Document& doc, const std::optional<std::string>& name, const std::string& choose);

/// Parses a document from JSON text; sourceName is used in error messages.
Document parseDocument(const std::string& text, const std::string& sourceName = "document");

/// Reads and parses a file; Error when it cannot be read or parsed.
Document readDocument(const std::string& path);

/// The document as JSON text (numbers in shortest round-trip form, two-space indentation).
std::string formatDocument(const Document& document);

/// Writes the document to path atomically (temporary file in the same folder, then rename).
void writeDocument(const Document& document, const std::string& path);

} // namespace freeform
