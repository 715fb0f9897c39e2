// continuity, tessellation, control nets and spline conversion on typed objects
// (document/operations.h): what `freeform continuity`, `freeform tessellate`, `freeform convert
// --to` and the editor's scene geometry compute.

#include <algorithm>
#include <set>

#include "freeform/core/error.h"
#include "freeform/document/operations.h"
#include "freeform/curve/nurbs_continuity.h"
#include "evaluation.h"
#include "part_ops.h"
#include "rational.h"
#include "overloaded.h"

namespace freeform {
namespace {

using detail::gridEdges;
using detail::Overloaded;

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


std::string splineError(const TypedDocument& doc, const TypedObject& object)
{
    return doc.source + ": object \"" + object.name() + "\" is a " + object.type() +
           ", not a spline (bezier_spline or deboor_spline)";
}

} // namespace

// ---------------------------------------------------------------- continuity

std::vector<JointContinuity<double>> continuity(const TypedDocument& doc, const TypedObject& object,
                                                const ContinuityTolerances<double>& tol)
{
    // nurbs_curve: every interior breakpoint (C^k from the geometry, docs/nurbs.md).
    if (const auto* c = std::get_if<NurbsCurve<double, 2>>(&object.geometry())) return continuityReport(*c, tol);
    if (const auto* c = std::get_if<NurbsCurve<double, 3>>(&object.geometry())) return continuityReport(*c, tol);
    const auto curve = AnyCurve::of(object);
    if (!curve || !curve->isSpline()) throw Error(splineError(doc, object));
    return std::visit(
        Overloaded{[&](const BezierSpline<double, 2>& s) { return continuityReport(s, tol); },
                   [&](const BezierSpline<double, 3>& s) { return continuityReport(s, tol); },
                   [](const auto&) { return std::vector<JointContinuity<double>>{}; }},
        curve->variant());
}

// ---------------------------------------------------------------- tessellate

PatchComplex surfacePatches(const TypedDocument& doc, const TypedObject& object, std::array<int, 2>* segments)
{
    const auto surface = AnySurface::of(object);
    if (!surface)
        throw Error(doc.what(object) + ": type " + object.type() + " is not a surface (bezier_surface, deboor_surface)");
    if (segments) *segments = surface->segments;
    return surface->patches;
}

PatchComplex documentPatches(const TypedDocument& doc)
{
    PatchComplex complex;
    for (const TypedObject& o : doc.objects())
        if (const auto surface = AnySurface::of(o))
            complex.patches.insert(complex.patches.end(), surface->patches.patches.begin(), surface->patches.patches.end());
    if (complex.patches.empty())
        throw Error(doc.source + ": the document has no surface objects (bezier_surface, deboor_surface)");
    return complex;
}

std::optional<PolygonMesh> tessellateObject(const TypedObject& object, const ObjectTessellation& options,
                                            TessellationReport* report)
{
    if (const auto surface = AnySurface::of(object)) {
        TessellationOptions o;
        if (options.tolerance > 0) {
            o.tolerance = options.tolerance;
            o.patchTolerance = options.patchTolerance;
        } else {
            o.tolerance = 0;
            o.segmentsU = o.segmentsV = options.segments;
        }
        o.flipNormals = options.flip;
        return tessellate(surface->patches, o, report);
    }
    if (const auto* s = std::get_if<SubdivisionObject>(&object.geometry())) {
        SubdivisionTessellationOptions o;
        if (options.tolerance > 0) {
            o.tolerance = options.tolerance;
            o.toleranceOf = options.toleranceOf;
        } else o.level = std::clamp(options.segments, 1, o.maxLevel);
        PolygonMesh mesh = s->surface.tessellate(o);
        if (options.flip) {
            for (int f = 0; f < mesh.faceCount(); ++f) std::swap(mesh.faceVertices[3 * f + 1], mesh.faceVertices[3 * f + 2]);
            mesh.normals = -mesh.normals;
        }
        return mesh;
    }
    if (auto mesh = detail::tessellatePartObject(object, options, report)) return mesh;
    return detail::tessellateRationalObject(object, options, report);
}

std::optional<Eigen::Matrix<double, 3, Eigen::Dynamic>> objectPolyline(const TypedObject& object, double tolerance)
{
    if (const auto curve = AnyCurve::of(object)) return curve->polyline(tolerance);
    return detail::rationalPolyline(object, tolerance);
}

ControlNet controlNet(const TypedObject& object)
{
    ControlNet net;
    if (detail::rationalControlNet(object, net) || detail::partControlNet(object, net)) return net;
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
            [](const auto&) {}, // the rational types, parts: rationalControlNet, partControlNet above
        },
        object.data());
    return net;
}

DocumentTessellation tessellateDocument(const TypedDocument& doc, const TypedObject* object,
                                        const TessellationOptions& options)
{
    // Rational surfaces, trimmed surfaces and parts: each meshed alone (tessellateObject).
    auto rationalSurface = [](const TypedObject& o) {
        return o.info().rational && (o.info().isSurface() || o.info().nature == KindNature::Part);
    };
    PatchComplex complex;
    std::vector<const TypedObject*> rational;
    if (object) {
        if (rationalSurface(*object)) rational.push_back(object);
        else complex = surfacePatches(doc, *object);
    } else {
        for (const TypedObject& o : doc.objects())
            if (rationalSurface(o)) rational.push_back(&o);
        const bool polynomial = std::any_of(doc.objects().begin(), doc.objects().end(),
                                            [](const TypedObject& o) { return AnySurface::of(o).has_value(); });
        // documentPatches says "no surface objects" when the document has none of any kind.
        if (polynomial || rational.empty()) complex = documentPatches(doc);
    }
    DocumentTessellation out;
    if (!complex.patches.empty()) out.mesh = tessellate(complex, options, &out.report);
    out.patches = complex.patches.size();
    if (rational.empty()) return out;

    ObjectTessellation settings;
    settings.tolerance = options.tolerance;
    settings.segments = options.segmentsU;
    settings.flip = options.flipNormals;
    std::vector<PolygonMesh> meshes;
    if (!complex.patches.empty()) meshes.push_back(std::move(out.mesh));
    for (const TypedObject* o : rational) {
        TessellationReport report;
        std::optional<PolygonMesh> mesh = tessellateObject(*o, settings, &report);
        out.patches += report.segments.size();
        out.report.errorBound = std::max(out.report.errorBound, report.errorBound);
        meshes.push_back(std::move(*mesh)); // a rational surface always has one
    }
    if (meshes.size() == 1) {
        out.mesh = std::move(meshes.front());
    } else {
        std::vector<const PolygonMesh*> parts;
        for (const PolygonMesh& m : meshes) parts.push_back(&m);
        out.mesh = mergeMeshes(parts);
    }
    return out;
}

// ---------------------------------------------------------------- convert

BezierSplineData toBezierSplineData(const TypedDocument& doc, const TypedObject& object)
{
    const auto curve = AnyCurve::of(object);
    if (!curve || !curve->isSpline()) throw Error(splineError(doc, object));
    if (object.type() == "bezier_spline") throw Error(doc.source + ": object \"" + object.name() + "\" is already a bezier_spline");
    BezierSplineData out;
    out.degree = 3;
    out.closed = curve->closed();
    out.points = curve->controlPoints();
    out.intervals = std::get<DeBoorSplineData>(object.data()).intervals;
    return out;
}

DeBoorSplineData toDeBoorSplineData(const TypedDocument& doc, const TypedObject& object, std::optional<EndCondition> requested)
{
    const auto curve = AnyCurve::of(object);
    if (!curve || !curve->isSpline()) throw Error(splineError(doc, object));
    if (object.type() == "deboor_spline") throw Error(doc.source + ": object \"" + object.name() + "\" is already a deboor_spline");
    const auto& data = std::get<BezierSplineData>(object.data());
    if (data.degree != 3)
        throw Error(doc.source + ": object \"" + object.name() + "\": de Boor points need a cubic spline, this one has degree " +
                    std::to_string(data.degree));
    const bool closed = curve->closed();
    const EndCondition end = requested ? *requested : closed ? EndCondition::Closed : EndCondition::Clamped;
    if ((end == EndCondition::Closed) != closed)
        throw Error(doc.source + ": object \"" + object.name() + "\": " + (closed ? "a closed" : "an open") +
                    " spline has no de Boor points with end condition " + toString(end) +
                    (closed ? " (use --end closed)" : " (use --end open or --end clamped)"));
    DeBoorSplineData out;
    out.degree = 3;
    out.end = toString(end);
    try {
        out.points = std::visit(
            Overloaded{[&](const BezierSpline<double, 2>& s) -> PointColumns { return s.deBoorPoints(end); },
                       [&](const BezierSpline<double, 3>& s) -> PointColumns { return s.deBoorPoints(end); },
                       [](const auto&) -> PointColumns { return {}; }},
            curve->variant());
    } catch (const Error& e) {
        throw Error(doc.source + ": object \"" + object.name() + "\": " + e.what());
    }
    out.intervals = data.intervals;
    return out;
}

void convertObject(TypedDocument& doc, ObjectId id, const std::string& to, std::optional<EndCondition> end)
{
    const TypedObject& object = doc.object(id);
    const KindInfo* target = findKind(to);
    if ((target && target->knots) || object.info().supports(KindOperation::FromNurbs)) {
        if (end) throw Error(doc.what(object) + ": an end condition goes with a bezier_spline converted to deboor_spline only");
        ObjectData data = target && target->knots ? toNurbsData(doc, object) : fromNurbsData(doc, object);
        const std::string got = objectType(data);
        if (got != to) throw ConversionMismatch(doc.what(object) + ": a " + object.type() + " converts to a " + got + ", not a " + to, got);
        doc.replace(id, std::move(data));
        return;
    }
    if (target && target->supports(KindOperation::ConvertSpline)) return convertSpline(doc, id, to, end);
    throw Error(doc.what(object) + ": a " + object.type() + " does not convert to \"" + to + "\"");
}

void convertSpline(TypedDocument& doc, ObjectId id, const std::string& to, std::optional<EndCondition> end)
{
    const TypedObject& object = doc.object(id);
    if (to == "bezier_spline") doc.replace(id, toBezierSplineData(doc, object));
    else if (to == "deboor_spline") doc.replace(id, toDeBoorSplineData(doc, object, end));
    else throw Error("convertSpline: \"" + to + "\" is not one of bezier_spline, deboor_spline");
}

} // namespace freeform
