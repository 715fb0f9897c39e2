// The typed document (document/model.h): geometry built from the plain data, stable ids, and the
// run-time-dimension facades.

#include "freeform/document/model.h"

#include <filesystem>
#include <type_traits>
#include <utility>

#include "freeform/core/error.h"
#include "freeform/io/geometry_data.h"
#include "../io/object_lookup.h"
#include "overloaded.h"
#include "part_data.h"

namespace freeform {
namespace {

using detail::Overloaded;

template <int Dim>
DeBoorSpline<Dim> deboorSpline(const DeBoorSplineData& d)
{
    using Points = PointMatrix<double, Dim>;
    if (d.degree != 3) throw Error("field \"degree\": a deboor_spline is cubic (degree 3), not " + std::to_string(d.degree));
    const EndCondition end = parseEndCondition(d.end, "field \"end\"");
    Points points(d.points);
    BezierSpline<double, Dim> bezier = BezierSpline<double, Dim>::fromDeBoor(points, end, d.intervals);
    return DeBoorSpline<Dim>{std::move(points), end, d.intervals, std::move(bezier)};
}

Geometry build(const ObjectData& data, const std::string& directory, const std::string& what)
{
    return std::visit(
        Overloaded{
            [](const BezierCurveData& d) -> Geometry {
                if (d.points.rows() == 2) return BezierCurve<double, 2>(PointMatrix<double, 2>(d.points));
                return BezierCurve<double, 3>(PointMatrix<double, 3>(d.points));
            },
            [](const BezierSplineData& d) -> Geometry {
                if (d.points.rows() == 2)
                    return BezierSpline<double, 2>(d.degree, d.closed, PointMatrix<double, 2>(d.points), d.intervals);
                return BezierSpline<double, 3>(d.degree, d.closed, PointMatrix<double, 3>(d.points), d.intervals);
            },
            [](const DeBoorSplineData& d) -> Geometry {
                if (d.points.rows() == 2) return deboorSpline<2>(d);
                return deboorSpline<3>(d);
            },
            [](const BezierSurfaceData& d) -> Geometry {
                return BezierSurface<double, 3>(d.degree[0], d.degree[1], PointMatrix<double, 3>(d.points));
            },
            [](const DeBoorSurfaceData& d) -> Geometry {
                DeBoorSurface s;
                s.points = d.points;
                s.rows = d.rows;
                s.cols = d.cols;
                s.end = {parseEndCondition(d.end[0], "field \"end[0]\""), parseEndCondition(d.end[1], "field \"end[1]\"")};
                s.segments = deboorSurfaceSegments(d.rows, d.cols, s.end[0], s.end[1]);
                s.patches = deboorSurfacePatches(s.points, d.rows, d.cols, s.end[0], s.end[1]);
                return s;
            },
            [](const LatticeData& d) -> Geometry { return latticeFromData(d); },
            [](const RationalBezierCurveData& d) -> Geometry {
                const Eigen::VectorXd w = Eigen::Map<const Eigen::VectorXd>(d.weights.data(), static_cast<Eigen::Index>(d.weights.size()));
                if (d.points.rows() == 2) return RationalBezierCurve<double, 2>(PointMatrix<double, 2>(d.points), w);
                return RationalBezierCurve<double, 3>(PointMatrix<double, 3>(d.points), w);
            },
            [](const RationalBezierSurfaceData& d) -> Geometry {
                const Eigen::VectorXd w = Eigen::Map<const Eigen::VectorXd>(d.weights.data(), static_cast<Eigen::Index>(d.weights.size()));
                return RationalBezierSurface<double, 3>(d.degree[0], d.degree[1], PointMatrix<double, 3>(d.points), w);
            },
            [](const NurbsCurveData& d) -> Geometry {
                const Eigen::VectorXd w = Eigen::Map<const Eigen::VectorXd>(d.weights.data(), static_cast<Eigen::Index>(d.weights.size()));
                if (d.points.rows() == 2) return NurbsCurve<double, 2>(d.degree, d.knots, PointMatrix<double, 2>(d.points), w);
                return NurbsCurve<double, 3>(d.degree, d.knots, PointMatrix<double, 3>(d.points), w);
            },
            [](const NurbsSurfaceData& d) -> Geometry {
                const Eigen::VectorXd w = Eigen::Map<const Eigen::VectorXd>(d.weights.data(), static_cast<Eigen::Index>(d.weights.size()));
                return NurbsSurface<double, 3>(d.degree[0], d.degree[1], d.knots[0], d.knots[1], PointMatrix<double, 3>(d.points), w);
            },
            [](const TrimmedSurfaceData& d) -> Geometry { return detail::trimmedSurfaceFromData(d); },
            [](const PartData& d) -> Geometry { return detail::partFromData(d); },
            [&](const SubdivisionSurfaceData& d) -> Geometry {
                // surfaceFromData prefixes its own errors with `what`; unwrap below avoids doubling.
                return SubdivisionObject{surfaceFromData(d, directory, what)};
            },
        },
        data);
}

} // namespace

Geometry buildGeometry(const ObjectData& data, const std::string& documentDirectory, const std::string& what)
{
    try {
        return build(data, documentDirectory, what);
    } catch (const Error& e) {
        const std::string message = e.what();
        if (message.rfind(what, 0) == 0) throw; // already prefixed (subdivision cages)
        throw Error(what + ": " + message);
    }
}

int TypedObject::dimension() const
{
    return std::visit(
        [](const auto& d) -> int {
            using T = std::decay_t<decltype(d)>;
            if constexpr (std::is_same_v<T, BezierCurveData> || std::is_same_v<T, BezierSplineData> ||
                          std::is_same_v<T, DeBoorSplineData> || std::is_same_v<T, RationalBezierCurveData> ||
                          std::is_same_v<T, NurbsCurveData>)
                return static_cast<int>(d.points.rows());
            else
                return 3;
        },
        data_);
}

TypedDocument::TypedDocument(const Document& document, std::optional<std::string> documentDirectory)
    : source(document.source), editor(document.editor)
{
    directory = documentDirectory ? *documentDirectory : std::filesystem::path(document.source).parent_path().string();
    objects_.reserve(document.objects.size());
    for (const DocumentObject& o : document.objects) add(o.name, o.data, o.editor);
}

TypedDocument TypedDocument::read(const std::string& path) { return TypedDocument(readDocument(path)); }

Document TypedDocument::toDocument() const
{
    Document d;
    d.source = source;
    d.editor = editor;
    d.objects.reserve(objects_.size());
    for (const TypedObject& o : objects_) d.objects.push_back(DocumentObject{o.name(), o.data(), o.editor()});
    return d;
}

const TypedObject* TypedDocument::find(ObjectId id) const
{
    for (const TypedObject& o : objects_)
        if (o.id() == id) return &o;
    return nullptr;
}

const TypedObject* TypedDocument::find(const std::string& name) const
{
    for (const TypedObject& o : objects_)
        if (o.name() == name) return &o;
    return nullptr;
}

const TypedObject& TypedDocument::object(const std::string& name) const
{
    if (const TypedObject* o = find(name)) return *o;
    std::vector<std::string> names;
    for (const TypedObject& o : objects_) names.push_back(o.name());
    throw Error(noObjectMessage(source, name, names)); // the reader's message (src/io/object_lookup.h)
}

const TypedObject& TypedDocument::object(ObjectId id) const
{
    if (const TypedObject* o = find(id)) return *o;
    throw Error(source + ": no object with id " + std::to_string(id));
}

std::string TypedDocument::what(const TypedObject& object) const { return source + ": object \"" + object.name() + "\""; }

ObjectId TypedDocument::add(std::string name, ObjectData data, std::string editorText)
{
    Geometry geometry = buildGeometry(data, directory, source + ": object \"" + name + "\"");
    const ObjectId id = nextId_++;
    objects_.push_back(TypedObject(id, std::move(name), std::move(data), std::move(geometry), std::move(editorText)));
    return id;
}

void TypedDocument::replace(ObjectId id, ObjectData data)
{
    const TypedObject& current = object(id);
    Geometry geometry = buildGeometry(data, directory, what(current));
    for (TypedObject& o : objects_)
        if (o.id_ == id) {
            o.data_ = std::move(data);
            o.geometry_ = std::move(geometry);
        }
}

void TypedDocument::rename(ObjectId id, std::string name)
{
    object(id);
    for (TypedObject& o : objects_)
        if (o.id_ == id) o.name_ = std::move(name);
}

void TypedDocument::remove(ObjectId id)
{
    object(id);
    std::erase_if(objects_, [id](const TypedObject& o) { return o.id() == id; });
}

// ---------------------------------------------------------------- AnyCurve

std::optional<AnyCurve> AnyCurve::of(const TypedObject& object)
{
    return std::visit(
        Overloaded{
            [](const BezierCurve<double, 2>& c) -> std::optional<AnyCurve> { return AnyCurve(c); },
            [](const BezierCurve<double, 3>& c) -> std::optional<AnyCurve> { return AnyCurve(c); },
            [](const BezierSpline<double, 2>& s) -> std::optional<AnyCurve> { return AnyCurve(s); },
            [](const BezierSpline<double, 3>& s) -> std::optional<AnyCurve> { return AnyCurve(s); },
            [](const DeBoorSpline<2>& s) -> std::optional<AnyCurve> { return AnyCurve(s.bezier); },
            [](const DeBoorSpline<3>& s) -> std::optional<AnyCurve> { return AnyCurve(s.bezier); },
            [](const auto&) -> std::optional<AnyCurve> { return std::nullopt; },
        },
        object.geometry());
}

int AnyCurve::dimension() const { return curve_.index() % 2 == 0 ? 2 : 3; }

bool AnyCurve::closed() const
{
    return std::visit(
        Overloaded{[](const BezierSpline<double, 2>& s) { return s.closed(); },
                   [](const BezierSpline<double, 3>& s) { return s.closed(); }, [](const auto&) { return false; }},
        curve_);
}

double AnyCurve::domainEnd() const
{
    return std::visit(
        Overloaded{[](const BezierSpline<double, 2>& s) { return s.domainEnd(); },
                   [](const BezierSpline<double, 3>& s) { return s.domainEnd(); }, [](const auto&) { return 1.0; }},
        curve_);
}

Eigen::MatrixXd AnyCurve::derivatives(double t, int order) const
{
    return std::visit([&](const auto& c) -> Eigen::MatrixXd { return c.derivatives(t, order); }, curve_);
}

Eigen::MatrixXd AnyCurve::controlPoints() const
{
    return std::visit([](const auto& c) -> Eigen::MatrixXd { return c.controlPoints(); }, curve_);
}

namespace {
PointMatrix<double, 3> lift(const Eigen::MatrixXd& p)
{
    PointMatrix<double, 3> out = PointMatrix<double, 3>::Zero(3, p.cols());
    out.topRows(p.rows()) = p;
    return out;
}
} // namespace

BezierSpline<double, 3> AnyCurve::spline3() const
{
    return std::visit(
        Overloaded{
            [](const BezierSpline<double, 3>& s) { return s; },
            [](const BezierSpline<double, 2>& s) {
                return BezierSpline<double, 3>(s.degree(), s.closed(), lift(s.controlPoints()), s.intervals());
            },
            [](const auto& c) { return BezierSpline<double, 3>(c.degree(), false, lift(c.controlPoints())); },
        },
        curve_);
}

Eigen::Matrix<double, 3, Eigen::Dynamic> AnyCurve::polyline(double tolerance) const
{
    // As the editor samples (scene/geometry.cpp): the curve in 3D, adaptive parameters, evaluated.
    if (curve_.index() < 2) {
        const BezierCurve<double, 3> curve(lift(controlPoints()));
        return curve.evaluateMany(curve.sampleAdaptive(tolerance));
    }
    const BezierSpline<double, 3> spline = spline3();
    const std::vector<double> ts = spline.sampleAdaptive(tolerance);
    Eigen::Matrix<double, 3, Eigen::Dynamic> out(3, static_cast<Eigen::Index>(ts.size()));
    for (std::size_t k = 0; k < ts.size(); ++k) out.col(static_cast<Eigen::Index>(k)) = spline.evaluate(ts[k]);
    return out;
}

std::optional<AnySurface> AnySurface::of(const TypedObject& object)
{
    if (const auto* p = std::get_if<BezierSurface<double, 3>>(&object.geometry())) return AnySurface{PatchComplex{{*p}}, {1, 1}};
    if (const auto* d = std::get_if<DeBoorSurface>(&object.geometry())) return AnySurface{d->patches, d->segments};
    return std::nullopt;
}

} // namespace freeform
