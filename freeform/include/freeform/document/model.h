#pragma once
// The typed document: every object of a freeform document (io/document.h, plain data) with a
// stable id and its geometry built once (curve, spline, surface, lattice, subdivision surface),
// and the run-time-dimension facades AnyCurve / AnySurface, so callers stop switching on 2 and 3.
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

/// The geometry of one object. A new object type is one more alternative here and one case in
/// buildGeometry (model.cpp); see document/document.h for the operations.
using Geometry = std::variant<BezierCurve<double, 2>, BezierCurve<double, 3>, BezierSpline<double, 2>,
                              BezierSpline<double, 3>, DeBoorSpline<2>, DeBoorSpline<3>, BezierSurface<double, 3>,
                              DeBoorSurface, Lattice, SubdivisionObject, RationalBezierCurve<double, 2>,
                              RationalBezierCurve<double, 3>, RationalBezierSurface<double, 3>, NurbsCurve<double, 2>,
                              NurbsCurve<double, 3>, NurbsSurface<double, 3>, TrimmedSurface, Part>;

/// The geometry of a data object. documentDirectory resolves a subdivision cage's relative mesh
/// path; Error prefixed with `what` (e.g. `doc.json: object "c"`) when the data is not valid.
Geometry buildGeometry(const ObjectData& data, const std::string& documentDirectory, const std::string& what);

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

/// A curve of either dimension: a bezier_curve (domain [0, 1]), a bezier_spline or a
/// deboor_spline (its Bézier form; domain [0, sum of intervals]). Values are Eigen::VectorXd of
/// size dimension().
class AnyCurve {
public:
    using Variant = std::variant<BezierCurve<double, 2>, BezierCurve<double, 3>, BezierSpline<double, 2>,
                                 BezierSpline<double, 3>>;

    explicit AnyCurve(Variant curve) : curve_(std::move(curve)) {}
    /// The curve of an object; nullopt for objects that are not curves or splines.
    static std::optional<AnyCurve> of(const TypedObject& object);

    int dimension() const;
    bool isSpline() const { return curve_.index() >= 2; }
    bool closed() const;
    double domainEnd() const;
    /// dimension() x (order + 1): the point and derivatives 1..order (global parameter).
    Eigen::MatrixXd derivatives(double t, int order) const;
    Eigen::VectorXd point(double t) const { return derivatives(t, 0).col(0); }
    /// The control points (for a spline: the Bézier points as the format stores them).
    Eigen::MatrixXd controlPoints() const;
    /// The polyline the editor draws: adaptive samples (sampleAdaptive(tolerance)) of the curve
    /// lifted to 3D (z = 0 for 2D), 3 x N.
    Eigen::Matrix<double, 3, Eigen::Dynamic> polyline(double tolerance) const;
    /// The spline in 3D (a 2D one with z = 0; a curve as one segment on [0, 1]).
    BezierSpline<double, 3> spline3() const;
    const Variant& variant() const { return curve_; }

private:
    Variant curve_;
};

/// A bezier_surface (one patch on [0,1]^2) or deboor_surface (segments[0] x segments[1] patches
/// on [0, segments[0]] x [0, segments[1]]) as a patch complex.
struct AnySurface {
    PatchComplex patches;
    std::array<int, 2> segments{1, 1};
    /// The surface of an object; nullopt for objects that are not bezier/deboor surfaces.
    static std::optional<AnySurface> of(const TypedObject& object);
};

} // namespace freeform
