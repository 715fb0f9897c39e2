// The typed document (document/model.h) and what each object kind needs of it, one visitor per
// direction: the geometry built from the plain data (buildGeometry), the data of the geometry
// (toData), the control net (controlNet, document/operations.h). The visitors over ObjectData
// have no catch-all, so a new kind does not compile until it has its case in each. The facades
// AnyCurve and AnySurface are in any_geometry.cpp.

#include "freeform/document/model.h"

#include <filesystem>
#include <set>
#include <type_traits>
#include <utility>

#include "freeform/core/error.h"
#include "freeform/document/operations.h"
#include "freeform/io/geometry_data.h"
#include "../io/object_lookup.h"
#include "evaluation.h"
#include "overloaded.h"
#include "part_data.h"

namespace freeform {
namespace {

using detail::gridEdges;
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

// ---------------------------------------------------------------- toData: geometry -> data

namespace {

std::vector<double> weightList(const Eigen::Matrix<double, Eigen::Dynamic, 1>& w)
{
    return std::vector<double>(w.data(), w.data() + w.size());
}

template <int Dim>
NurbsCurveData curveData(const NurbsCurve<double, Dim>& c)
{
    NurbsCurveData d;
    d.degree = c.degree();
    d.knots = c.knots();
    d.points = c.controlPoints();
    if (c.isRational()) d.weights = weightList(c.weights());
    return d;
}

template <int Dim>
RationalBezierCurveData rationalData(const RationalBezierCurve<double, Dim>& c)
{
    RationalBezierCurveData d;
    d.points = c.controlPoints();
    d.weights = weightList(c.weights());
    return d;
}

template <int Dim>
BezierSplineData splineToData(const BezierSpline<double, Dim>& s)
{
    BezierSplineData d;
    d.degree = s.degree();
    d.closed = s.closed();
    d.points = s.controlPoints();
    d.intervals = s.intervals();
    return d;
}

template <int Dim>
DeBoorSplineData deBoorToData(const DeBoorSpline<Dim>& s)
{
    DeBoorSplineData d;
    d.degree = 3;
    d.end = toString(s.end);
    d.points = s.points;
    d.intervals = s.intervals;
    return d;
}

} // namespace

BezierCurveData toData(const BezierCurve<double, 2>& curve) { return {curve.controlPoints()}; }
BezierCurveData toData(const BezierCurve<double, 3>& curve) { return {curve.controlPoints()}; }
BezierSplineData toData(const BezierSpline<double, 2>& spline) { return splineToData(spline); }
BezierSplineData toData(const BezierSpline<double, 3>& spline) { return splineToData(spline); }
DeBoorSplineData toData(const DeBoorSpline<2>& spline) { return deBoorToData(spline); }
DeBoorSplineData toData(const DeBoorSpline<3>& spline) { return deBoorToData(spline); }

BezierSurfaceData toData(const BezierSurface<double, 3>& surface)
{
    BezierSurfaceData d;
    d.degree = {surface.degreeU(), surface.degreeV()};
    d.points = surface.controlPoints();
    return d;
}

DeBoorSurfaceData toData(const DeBoorSurface& surface)
{
    DeBoorSurfaceData d;
    d.degree = {3, 3};
    d.end = {toString(surface.end[0]), toString(surface.end[1])};
    d.rows = surface.rows;
    d.cols = surface.cols;
    d.points = surface.points;
    return d;
}

LatticeData toData(const Lattice& lattice) { return latticeToData(lattice); }

SubdivisionSurfaceData toData(const SubdivisionObject& surface)
{
    return cageToData(surface.cage(), toString(surface.surface.scheme()), toString(surface.surface.boundary()),
                      "subdivision_surface");
}

ObjectData toData(const Geometry& geometry)
{
    return std::visit([](const auto& g) -> ObjectData { return toData(g); }, geometry);
}

NurbsCurveData toData(const NurbsCurve<double, 2>& curve) { return curveData(curve); }
NurbsCurveData toData(const NurbsCurve<double, 3>& curve) { return curveData(curve); }

NurbsSurfaceData toData(const NurbsSurface<double, 3>& surface)
{
    NurbsSurfaceData d;
    d.degree = {surface.degreeU(), surface.degreeV()};
    d.knots = {surface.knotsU().knots(), surface.knotsV().knots()};
    d.rows = surface.countU();
    d.cols = surface.countV();
    d.points = surface.controlPoints();
    if (surface.isRational()) d.weights = weightList(surface.weights());
    return d;
}

RationalBezierCurveData toData(const RationalBezierCurve<double, 2>& curve) { return rationalData(curve); }
RationalBezierCurveData toData(const RationalBezierCurve<double, 3>& curve) { return rationalData(curve); }

RationalBezierSurfaceData toData(const RationalBezierSurface<double, 3>& surface)
{
    RationalBezierSurfaceData d;
    const int m = surface.degreeU(), n = surface.degreeV();
    d.degree = {m, n};
    d.points.resize(3, (m + 1) * (n + 1));
    for (int i = 0; i <= m; ++i)
        for (int j = 0; j <= n; ++j) {
            d.points.col(i * (n + 1) + j) = surface.controlPoint(i, j);
            d.weights.push_back(surface.weight(i, j));
        }
    return d;
}

// ---------------------------------------------------------------- the control net of every kind

namespace {

Eigen::Matrix<double, 3, Eigen::Dynamic> to3d(const PointColumns& p)
{
    Eigen::Matrix<double, 3, Eigen::Dynamic> out = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, p.cols());
    out.topRows(p.rows()) = p;
    return out;
}

void polygonEdges(std::vector<std::pair<int, int>>& edges, int count, bool closed)
{
    for (int i = 0; i + 1 < count; ++i) edges.emplace_back(i, i + 1);
    if (closed && count > 2) edges.emplace_back(count - 1, 0);
}

} // namespace

ControlNet controlNet(const TypedObject& object)
{
    ControlNet net;
    std::visit(
        Overloaded{
            [&](const BezierCurveData& d) {
                net.points = to3d(d.points);
                polygonEdges(net.edges, static_cast<int>(d.points.cols()), false);
            },
            [&](const BezierSplineData& d) {
                net.points = to3d(d.points);
                polygonEdges(net.edges, static_cast<int>(d.points.cols()), d.closed);
            },
            [&](const DeBoorSplineData& d) {
                net.points = to3d(d.points);
                polygonEdges(net.edges, static_cast<int>(d.points.cols()), d.end == "closed");
            },
            [&](const BezierSurfaceData& d) {
                net.points = d.points;
                gridEdges(net.edges, d.degree[0] + 1, d.degree[1] + 1);
            },
            [&](const DeBoorSurfaceData& d) {
                net.points = d.points;
                gridEdges(net.edges, d.rows, d.cols);
            },
            [&](const LatticeData& d) {
                net.points = d.points;
                const int a = d.degree[0] + 1, b = d.degree[1] + 1, c = d.degree[2] + 1;
                auto index = [&](int i, int j, int k) { return (i * b + j) * c + k; };
                for (int i = 0; i < a; ++i)
                    for (int j = 0; j < b; ++j)
                        for (int k = 0; k < c; ++k) {
                            if (i + 1 < a) net.edges.emplace_back(index(i, j, k), index(i + 1, j, k));
                            if (j + 1 < b) net.edges.emplace_back(index(i, j, k), index(i, j + 1, k));
                            if (k + 1 < c) net.edges.emplace_back(index(i, j, k), index(i, j, k + 1));
                        }
            },
            [&](const SubdivisionSurfaceData&) {
                const SubdivisionCage& cage = std::get<SubdivisionObject>(object.geometry()).cage();
                net.points = cage.mesh.positions;
                std::set<std::pair<int, int>> edges;
                for (int f = 0; f < cage.mesh.faceCount(); ++f)
                    for (int k = 0; k < cage.mesh.faceSize(f); ++k) {
                        const int u = cage.mesh.face(f)[k], v = cage.mesh.face(f)[(k + 1) % cage.mesh.faceSize(f)];
                        edges.insert({std::min(u, v), std::max(u, v)});
                    }
                net.edges.assign(edges.begin(), edges.end());
            },
            [&](const RationalBezierCurveData& d) {
                net.points = to3d(d.points);
                polygonEdges(net.edges, static_cast<int>(d.points.cols()), false);
            },
            [&](const NurbsCurveData& d) {
                net.points = to3d(d.points);
                polygonEdges(net.edges, static_cast<int>(d.points.cols()), false);
            },
            [&](const RationalBezierSurfaceData& d) {
                net.points = d.points;
                gridEdges(net.edges, d.degree[0] + 1, d.degree[1] + 1);
            },
            [&](const NurbsSurfaceData& d) {
                net.points = d.points;
                gridEdges(net.edges, d.rows, d.cols);
            },
            [&](const TrimmedSurfaceData& d) { // its NURBS's grid
                net.points = d.surface.points;
                gridEdges(net.edges, d.surface.rows, d.surface.cols);
            },
            [](const PartData&) {}, // a part's faces are not edited point by point: no net drawn
        },
        object.data());
    return net;
}

} // namespace freeform
