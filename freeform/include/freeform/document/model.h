#pragma once
// The typed document: every object of a freeform document (io/document.h, plain data) with a
// stable id and its geometry built once (curve, spline, surface, lattice, subdivision surface),
// and the facades AnyCurve / AnySurface over every curve and (u, v) surface kind, so callers stop
// switching on dimension and kind.
// The operations on it are in document/operations.h; the overview for front ends in
// document/document.h. Layer: core -> geometry -> io -> document (this) -> cli, editor.

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "freeform/brep/part.h"
#include "freeform/curve/aframe.h"
#include "freeform/curve/bezier_curve.h"
#include "freeform/curve/bezier_spline.h"
#include "freeform/curve/nurbs_curve.h"
#include "freeform/curve/rational_bezier_curve.h"
#include "freeform/document/kinds.h"
#include "freeform/io/document.h"
#include "freeform/subdivision/subdivision_surface.h"
#include "freeform/surface/bezier_surface.h"
#include "freeform/surface/nurbs_surface.h"
#include "freeform/surface/rational_bezier_surface.h"
#include "freeform/surface/patch_complex.h"
#include "freeform/volume/lattice.h"

namespace freeform {

/// Stable for the life of a TypedDocument in memory and never reused (not written to the file).
using ObjectId = std::uint64_t;

/// A deboor_spline: its de Boor points and end condition as stored, and the Bézier form (A-frame).
template <int Dim>
struct DeBoorSpline {
    PointMatrix<double, Dim> points;
    EndCondition end = EndCondition::Open;
    std::vector<double> intervals; // as stored (empty: all 1)
    BezierSpline<double, Dim> bezier;
};

/// A deboor_surface: its grid as stored and the Bézier patches (patch (a, b) at a * segments[1] + b).
struct DeBoorSurface {
    PointMatrix<double, 3> points; // 3 x rows*cols, index i*cols + j
    int rows = 0, cols = 0;
    std::array<EndCondition, 2> end{EndCondition::Open, EndCondition::Open};
    PatchComplex patches;
    std::array<int, 2> segments{};
};

/// A subdivision_surface: the cage (inline, or read from its mesh file with the OBJ crease tags,
/// then the object's creases and corners) and the surface built on it.
struct SubdivisionObject {
    SubdivisionSurface surface;
    const SubdivisionCage& cage() const { return surface.cage(); }
};

/// The geometry of one object: the alternatives of every kind (a curve's 2D and 3D forms). A new
/// kind adds its alternatives here and builds them in its document file (src/document/kinds/TYPE.cpp);
/// docs/architecture.md, "Adding an object kind".
using Geometry = std::variant<BezierCurve<double, 2>, BezierCurve<double, 3>, BezierSpline<double, 2>,
                              BezierSpline<double, 3>, DeBoorSpline<2>, DeBoorSpline<3>, BezierSurface<double, 3>,
                              DeBoorSurface, Lattice, SubdivisionObject, RationalBezierCurve<double, 2>,
                              RationalBezierCurve<double, 3>, RationalBezierSurface<double, 3>, NurbsCurve<double, 2>,
                              NurbsCurve<double, 3>, NurbsSurface<double, 3>, TrimmedSurface, Part>;

/// The geometry of a data object. documentDirectory resolves a subdivision cage's relative mesh
/// path; Error prefixed with `what` (e.g. `doc.json: object "c"`) when the data is not valid.
Geometry buildGeometry(const ObjectData& data, const std::string& documentDirectory, const std::string& what);

/// The data of any geometry, so that buildGeometry(toData(g)) is g again (each defined in its
/// kind's document file, src/document/kinds/TYPE.cpp): a spline's intervals as it holds them; a
/// subdivision cage written inline, its file's crease tags as the object's creases and corners.
/// Error when the format cannot hold it: a cage with holes, `creasemethod chaikin` or
/// `smoothtriangles` from its mesh file (the inline form has no field for them).
BezierCurveData toData(const BezierCurve<double, 2>& curve);
BezierCurveData toData(const BezierCurve<double, 3>& curve);
BezierSplineData toData(const BezierSpline<double, 2>& spline);
BezierSplineData toData(const BezierSpline<double, 3>& spline);
/// A nurbs_curve: degree, knots, points; the weights only when the curve is rational (empty
/// weights mean all 1 and are not written).
NurbsCurveData toData(const NurbsCurve<double, 2>& curve);
NurbsCurveData toData(const NurbsCurve<double, 3>& curve);
/// A nurbs_surface: degrees, both knot vectors, the rows x cols grid (rows along u); the weights
/// only when the surface is rational.
NurbsSurfaceData toData(const NurbsSurface<double, 3>& surface);
/// A rational_bezier_curve: points and weights (always written).
RationalBezierCurveData toData(const RationalBezierCurve<double, 2>& curve);
RationalBezierCurveData toData(const RationalBezierCurve<double, 3>& curve);
/// A rational_bezier_surface: degrees, points at i*(n+1) + j and their weights (always written).
RationalBezierSurfaceData toData(const RationalBezierSurface<double, 3>& surface);
DeBoorSplineData toData(const DeBoorSpline<2>& spline);
DeBoorSplineData toData(const DeBoorSpline<3>& spline);
BezierSurfaceData toData(const BezierSurface<double, 3>& surface);
DeBoorSurfaceData toData(const DeBoorSurface& surface);
LatticeData toData(const Lattice& lattice);
/// A trimmed_surface: its NURBS, parameter maps, parameter box and loops (src/document/part_data.cpp).
TrimmedSurfaceData toData(const TrimmedSurface& surface);
/// A part: every face, edge and vertex, the shells and solids, the units.
PartData toData(const Part& part);
SubdivisionSurfaceData toData(const SubdivisionObject& surface);
ObjectData toData(const Geometry& geometry);


class TypedObject {
public:
    ObjectId id() const { return id_; }
    const std::string& name() const { return name_; }
    /// The "type" string of the format ("bezier_curve", ...).
    std::string type() const { return objectType(data_); }
    ObjectKind kind() const { return objectKind(data_); }
    /// The kind's row of the kind table (document/kinds.h): what it is and supports.
    const KindInfo& info() const { return kindInfo(data_); }
    /// The plain data as it is written to the file (the source of truth for formatting).
    const ObjectData& data() const { return data_; }
    const Geometry& geometry() const { return geometry_; }
    /// The object's "editor" member as JSON text, or empty.
    const std::string& editor() const { return editor_; }
    /// 2 or 3 (3 for surfaces, lattices, subdivision surfaces).
    int dimension() const;

private:
    friend class TypedDocument;
    TypedObject(ObjectId id, std::string name, ObjectData data, Geometry geometry, std::string editor)
        : id_(id), name_(std::move(name)), data_(std::move(data)), geometry_(std::move(geometry)),
          editor_(std::move(editor))
    {
    }
    ObjectId id_;
    std::string name_;
    ObjectData data_;
    Geometry geometry_;
    std::string editor_;
};

/// A document as typed objects (ids 1, 2, ... in document order on reading; added objects get the
/// next unused id). Every object's geometry is valid: building a TypedDocument or replacing an
/// object validates it (Error naming the source, the object and the field).
class TypedDocument {
public:
    TypedDocument() = default;
    /// Builds every object's geometry; documentDirectory defaults to the folder of document.source.
    explicit TypedDocument(const Document& document, std::optional<std::string> documentDirectory = std::nullopt);

    /// readDocument(path), then as above.
    static TypedDocument read(const std::string& path);

    /// The plain document (objects in order, editor members kept): formatDocument/writeDocument it.
    Document toDocument() const;

    const std::vector<TypedObject>& objects() const { return objects_; }
    const TypedObject* find(ObjectId id) const;
    const TypedObject* find(const std::string& name) const;
    /// Error listing the names (as Document::object) when there is none.
    const TypedObject& object(const std::string& name) const;
    const TypedObject& object(ObjectId id) const;

    /// Appends an object; returns its new id. Error (and nothing added) when the data is invalid.
    ObjectId add(std::string name, ObjectData data, std::string editor = {});
    /// Replaces an object's data (name, id, position and editor settings kept). Error (and nothing
    /// changed) when the data is invalid or there is no such id.
    void replace(ObjectId id, ObjectData data);
    void rename(ObjectId id, std::string name);
    void remove(ObjectId id);

    /// `source: object "name"`, the prefix of every error about an object.
    std::string what(const TypedObject& object) const;

    std::string source = "document"; // where it was read from, for messages
    std::string directory;           // resolves relative mesh paths of subdivision cages
    std::string editor;              // the document's "editor" member as JSON text, or empty

private:
    std::vector<TypedObject> objects_;
    ObjectId nextId_ = 1;
};

/// Every curve kind at run-time dimension: a bezier_curve (domain [0, 1]), a bezier_spline or a
/// deboor_spline (its Bézier form; domain [0, sum of intervals]), a rational_bezier_curve (domain
/// [0, 1]) or a nurbs_curve (domain [first knot, last knot]). Values are Eigen::VectorXd of size
/// dimension().
class AnyCurve {
public:
    using Variant = std::variant<BezierCurve<double, 2>, BezierCurve<double, 3>, BezierSpline<double, 2>,
                                 BezierSpline<double, 3>, RationalBezierCurve<double, 2>, RationalBezierCurve<double, 3>,
                                 NurbsCurve<double, 2>, NurbsCurve<double, 3>>;
    /// What the curve is made of (the variant's pairs of alternatives, 2D then 3D).
    enum class Form { Bezier, Spline, RationalBezier, Nurbs };

    explicit AnyCurve(Variant curve) : curve_(std::move(curve)) {}
    /// The curve of an object; nullopt for objects that are not curves (KindNature::Curve).
    static std::optional<AnyCurve> of(const TypedObject& object);

    int dimension() const { return curve_.index() % 2 == 0 ? 2 : 3; }
    Form form() const { return static_cast<Form>(curve_.index() / 2); }
    /// A Bézier spline (bezier_spline or deboor_spline): joined Bézier segments, a global T.
    bool isSpline() const { return form() == Form::Spline; }
    /// Has weights (a rational_bezier_curve or nurbs_curve; a nurbs_curve whose weights are all 1 too).
    bool isRational() const { return form() == Form::RationalBezier || form() == Form::Nurbs; }
    /// A closed bezier_spline or deboor_spline; false for every other curve (a closed NURBS, the
    /// circle, ends where it starts by its points).
    bool closed() const;
    double domainStart() const;
    double domainEnd() const;
    /// dimension() x (order + 1): the point and derivatives 1..order (global parameter).
    Eigen::MatrixXd derivatives(double t, int order) const;
    Eigen::VectorXd point(double t) const { return derivatives(t, 0).col(0); }
    /// The control points (for a spline: the Bézier points as the format stores them; for a
    /// rational curve: the points, not their homogeneous form).
    Eigen::MatrixXd controlPoints() const;
    /// The weights of the control points (all 1 for a polynomial curve).
    Eigen::VectorXd weights() const;
    /// The polyline the editor draws, lifted to 3D (z = 0 for 2D), 3 x N: adaptive samples
    /// (sampleAdaptive(tolerance)) of a polynomial curve; for a rational one, the certified
    /// flattening of its Bézier pieces (every control point within tolerance of its chord).
    Eigen::Matrix<double, 3, Eigen::Dynamic> polyline(double tolerance) const;
    /// A polynomial curve as a spline in 3D (a 2D one with z = 0; a curve as one segment on
    /// [0, 1]); nullopt for a rational curve, which has no polynomial form.
    std::optional<BezierSpline<double, 3>> spline3() const;
    const Variant& variant() const { return curve_; }

private:
    Variant curve_;
};

/// Every surface kind with (u, v) parameters: a bezier_surface (one patch on [0,1]^2) or
/// deboor_surface (segments[0] x segments[1] patches on [0, segments[0]] x [0, segments[1]]) as a
/// patch complex; a rational_bezier_surface (on [0,1]^2); a nurbs_surface (on its knot vectors'
/// ranges); a trimmed_surface (its NURBS in the file's parameters, on its parameter box, with its
/// trims). A subdivision surface takes (FACE, u, v) and is not one of them.
class AnySurface {
public:
    /// A bezier_surface or deboor_surface: its patches and how many along u and v.
    struct Patches {
        PatchComplex patches;
        std::array<int, 2> segments{1, 1};
    };
    using Variant = std::variant<Patches, RationalBezierSurface<double, 3>, NurbsSurface<double, 3>, TrimmedSurface>;

    explicit AnySurface(Variant surface) : surface_(std::move(surface)) {}
    /// The surface of an object; nullopt for objects that are not (u, v) surfaces.
    static std::optional<AnySurface> of(const TypedObject& object);

    /// The polynomial patches (bezier_surface, deboor_surface); nullptr for the other kinds.
    const Patches* patches() const { return std::get_if<Patches>(&surface_); }
    /// The trimmed surface (trimmed_surface); nullptr for the other kinds.
    const TrimmedSurface* trimmed() const { return std::get_if<TrimmedSurface>(&surface_); }
    bool isRational() const { return !patches(); }
    /// {u0, u1, v0, v1}.
    std::array<double, 4> domain() const;
    /// 3 x (order + 1)(order + 2)/2: the point and the partial derivatives in BezierSurface::jetIndex
    /// order, in the surface's own parameters (a deboor_surface's global ones, a trimmed surface's
    /// file parameters: first derivatives only there, Error for order > 1).
    Eigen::MatrixXd jet(double u, double v, int order) const;
    Eigen::Vector3d point(double u, double v) const { return jet(u, v, 0).col(0); }
    /// The unit normal (du x dv normalised).
    Eigen::Vector3d normal(double u, double v) const;
    const Variant& variant() const { return surface_; }

private:
    Variant surface_;
};

} // namespace freeform
