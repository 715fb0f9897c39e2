#pragma once
// Internal to the document layer: what each object kind's document file defines. Every kind of
// FREEFORM_OBJECT_KINDS (io/document.h) has one file, src/document/kinds/TYPE.cpp, holding all the
// document layer does with that kind: its row of the kind table, its geometry built from its data
// and its data from its geometry (toData), its control net, its words for people, its place behind
// AnyCurve or AnySurface, its free-form deformation, its NURBS conversions and its control points.
// The functions below are declared for every kind from that one list; the central files
// (model.cpp, kinds.cpp, any_geometry.cpp, deform.cpp, nurbs_convert.cpp, object_data.cpp) visit
// an object's data and call them, so they name no kind's data, and a kind whose file lacks one
// does not link (docs/architecture.md, "Adding an object kind"; tests/test_kind_files.cpp keeps
// the central files free of the kinds' data types). What AnyCurve and AnySurface do with the
// geometry classes behind them is any_geometry.cpp's.

#include <cmath>
#include <initializer_list>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "freeform/document/kinds.h"
#include "freeform/document/model.h"
#include "freeform/document/operations.h"
#include "evaluation.h"

namespace freeform::detail {

/// What building an object's geometry needs besides its data: the folder that resolves a
/// subdivision cage's relative mesh path, and the prefix of its messages (`doc.json: object "c"`).
struct KindBuild {
    const std::string& directory;
    const std::string& what;
};

/// deformDocument's lattice and settings, the same for every object.
struct KindDeformInput {
    const Lattice& lattice;
    double strength;
    bool affine; ///< the lattice (at this strength) is an affine map
    const DeformDocumentOptions& options;
};

/// One object through the lattice (deformDocument, docs/ffd.md): the new data, or the reason it
/// is skipped.
struct KindDeform {
    std::optional<ObjectData> result; ///< empty: skipped for `skip`
    std::string skip;
    bool inside = true;      ///< every control point inside the lattice box
    std::vector<int> degree; ///< the result's degrees ({d}, {p, q}; empty for a cage)
    std::string note;        ///< why the kind changed (empty when it did not)
    /// A subdivision cage: its points follow the outside policy point by point, as a mesh's do,
    /// and the result is exact only for an affine lattice. Every other kind is the lattice
    /// polynomial continued.
    bool pointwise = false;

    static KindDeform skipped(std::string reason)
    {
        KindDeform d;
        d.skip = std::move(reason);
        return d;
    }
};

/// A row of the kind table without its kind and name (which come from FREEFORM_OBJECT_KINDS).
struct KindRow {
    std::string_view summary;
    KindNature nature;
    KindParameters parameters;
    int dimension; ///< 3, or 0 for 2 or 3 as its points are
    bool rational;
    bool knots;
    bool pieces;
    unsigned operations; ///< KindOperation bits: kindOps({...})
};

constexpr unsigned kindOps(std::initializer_list<KindOperation> ops)
{
    unsigned b = 0;
    for (KindOperation op : ops) b |= static_cast<unsigned>(op);
    return b;
}
/// What every curve and every surface (but a deboor_surface) supports.
inline constexpr unsigned curveOps = kindOps({KindOperation::Evaluate, KindOperation::Polyline, KindOperation::Deform});
inline constexpr unsigned surfaceOps = kindOps({KindOperation::Evaluate, KindOperation::Tessellate, KindOperation::Deform});

// ---------------------------------------------------------------- the functions of a kind's file

#define FREEFORM_DECLARE_KIND_FILE(Kind, Data, name)                                                          \
    /** Its row of the kind table. */                                                                       \
    KindRow kindRow(std::type_identity<Data>);                                                              \
    /** Its geometry (an Error without the object prefix, which buildGeometry adds). */                     \
    Geometry kindBuild(const Data& data, const KindBuild& build);                                            \
    /** Its control net as the editor draws it (ControlNet, document/operations.h). */                       \
    void kindNet(const Data& data, const Geometry& geometry, ControlNet& net);                               \
    /** Its degrees and form in words (objectDetails, document/kinds.h). */                                  \
    std::string kindDetails(const Data& data);                                                              \
    /** Its curve behind AnyCurve; nullopt when it is not a curve. */                                        \
    std::optional<AnyCurve> kindCurve(const Geometry& geometry, std::type_identity<Data>);                  \
    /** Its surface behind AnySurface; nullopt when it is not a (u, v) surface. */                          \
    std::optional<AnySurface> kindSurface(const Geometry& geometry, std::type_identity<Data>);              \
    /** The object through the lattice; the 3D checks and the report are deformDocument's. */               \
    KindDeform kindDeform(const Data& data, const Geometry& geometry, const KindDeformInput& input);         \
    /** Its NURBS form (toNurbsData); nullopt when it has none. */                                          \
    std::optional<ObjectData> kindToNurbs(const Data& data, const Geometry& geometry, const std::string& what); \
    /** A NURBS of one piece as its Bézier kind (fromNurbsData); nullopt when it is not a NURBS. */          \
    std::optional<ObjectData> kindFromNurbs(const Data& data, const Geometry& geometry, const std::string& what); \
    /** Its control points as its data holds them (dataPoints); nullptr when it has none to edit. */       \
    PointColumns* kindPoints(Data& data);                                                                   \
    /** The first field that holds a number that is not finite, or "" (deformDocument's check). */           \
    std::string kindNonFinite(const Data& data);

FREEFORM_OBJECT_KINDS(FREEFORM_DECLARE_KIND_FILE)
#undef FREEFORM_DECLARE_KIND_FILE

// ---------------------------------------------------------------- helpers the kind files share

/// Points lifted to 3D (z = 0 for 2D points).
inline Eigen::Matrix<double, 3, Eigen::Dynamic> lift3(const PointColumns& p)
{
    Eigen::Matrix<double, 3, Eigen::Dynamic> out = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, p.cols());
    out.topRows(p.rows()) = p;
    return out;
}

/// The control polygon of a curve: points lifted to 3D, edges i -- i+1 (and back to 0 when closed).
inline void polygonNet(ControlNet& net, const PointColumns& points, bool closed)
{
    net.points = lift3(points);
    const int count = static_cast<int>(points.cols());
    for (int i = 0; i + 1 < count; ++i) net.edges.emplace_back(i, i + 1);
    if (closed && count > 2) net.edges.emplace_back(count - 1, 0);
}

/// The net of a rows x cols grid of points (index i * cols + j).
inline void gridNet(ControlNet& net, const PointColumns& points, int rows, int cols)
{
    net.points = points;
    gridEdges(net.edges, rows, cols);
}

/// "degree 3", "degree 2 x 3", ...
template <class... D>
std::string degreeWords(D... d)
{
    std::string out = "degree";
    const char* sep = " ";
    ((out += sep + std::to_string(d), sep = " x "), ...);
    return out;
}

/// "2D" or "3D", from the points' rows.
inline std::string dimensionWords(const PointColumns& p) { return std::to_string(p.rows()) + "D"; }

/// The weights of a data struct as a vector.
inline Eigen::VectorXd weightVector(const std::vector<double>& w)
{
    return Eigen::Map<const Eigen::VectorXd>(w.data(), static_cast<Eigen::Index>(w.size()));
}
inline std::vector<double> weightList(const Eigen::VectorXd& w) { return std::vector<double>(w.data(), w.data() + w.size()); }

/// kindNonFinite of a kind whose numbers are its points and, when it has them, its weights.
template <class Data>
std::string nonFinitePointsWeights(const Data& d)
{
    if (!d.points.allFinite()) return "points";
    if constexpr (requires { d.weights; })
        for (double x : d.weights)
            if (!std::isfinite(x)) return "weights";
    return "";
}

/// Every control point of `points` inside the lattice's box.
bool pointsInsideLattice(const Lattice& lattice, const Eigen::Ref<const Eigen::Matrix<double, 3, Eigen::Dynamic>>& points);

/// A Bézier spline's segments through the lattice exactly, as a bezier_spline of degree d (l+m+n)
/// on the same intervals (joints shared, as the format stores them).
BezierSplineData deformSplineData(const Lattice& lattice, const BezierSpline<double, 3>& spline, double strength);

/// Points moved by the lattice polynomial (displacement form, no outside policy).
PointColumns mapByPolynomial(const Lattice& lattice, const PointColumns& points, double strength);

/// A Bézier spline (or a deboor_spline's Bézier form) as a nurbs_curve: clamped knots at the joints.
template <int Dim>
NurbsCurveData splineNurbsData(const BezierSpline<double, Dim>& s)
{
    const int d = s.degree(), L = s.segmentCount();
    std::vector<double> knots(static_cast<std::size_t>(d + 1), 0.0);
    double t = 0;
    for (int i = 0; i < L; ++i) {
        t += s.intervals().empty() ? 1.0 : s.intervals()[static_cast<std::size_t>(i)];
        knots.insert(knots.end(), static_cast<std::size_t>(i + 1 < L ? d : d + 1), t);
    }
    PointColumns points = s.controlPoints();
    if (s.closed()) {
        points.conservativeResize(Eigen::NoChange, points.cols() + 1);
        points.col(points.cols() - 1) = points.col(0);
    }
    NurbsCurveData out;
    out.degree = d;
    out.knots = std::move(knots);
    out.points = std::move(points);
    return out;
}

} // namespace freeform::detail
