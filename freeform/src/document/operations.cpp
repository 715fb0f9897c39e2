// continuity, tessellation and spline conversion on typed objects (document/operations.h): what
// `freeform continuity`, `freeform tessellate`, `freeform convert --to` and the editor's scene
// geometry compute. The control net of every kind is beside its build and toData (model.cpp).

#include <algorithm>

#include "freeform/core/error.h"
#include "freeform/document/operations.h"
#include "freeform/curve/nurbs_continuity.h"
#include "evaluation.h"
#include "part_ops.h"
#include "freeform/tessellate/tessellate_rational.h"
#include "overloaded.h"

namespace freeform {
namespace {

using detail::Overloaded;

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
    // A spline: its joints; a nurbs_curve: every interior breakpoint (C^k from the geometry,
    // docs/nurbs.md). Any other curve has no joints to report.
    const auto curve = AnyCurve::of(object);
    if (!curve || !(curve->isSpline() || curve->form() == AnyCurve::Form::Nurbs)) throw Error(splineError(doc, object));
    return std::visit(
        Overloaded{[&](const BezierSpline<double, 2>& s) { return continuityReport(s, tol); },
                   [&](const BezierSpline<double, 3>& s) { return continuityReport(s, tol); },
                   [&](const NurbsCurve<double, 2>& c) { return continuityReport(c, tol); },
                   [&](const NurbsCurve<double, 3>& c) { return continuityReport(c, tol); },
                   [](const auto&) { return std::vector<JointContinuity<double>>{}; }},
        curve->variant());
}

// ---------------------------------------------------------------- tessellate

PatchComplex surfacePatches(const TypedDocument& doc, const TypedObject& object, std::array<int, 2>* segments)
{
    const auto surface = AnySurface::of(object);
    if (!surface || !surface->patches())
        throw Error(doc.what(object) + ": type " + object.type() + " is not a surface (bezier_surface, deboor_surface)");
    if (segments) *segments = surface->patches()->segments;
    return surface->patches()->patches;
}

namespace {

/// A surface of polynomial patches (its AnySurface has patches()), by its row: (u, v) parameters
/// and no weights. Asks the row, not AnySurface::of, which would copy a NURBS surface to say no.
bool patchSurface(const TypedObject& o) { return o.info().parameters == KindParameters::UV && !o.info().rational; }

} // namespace

PatchComplex documentPatches(const TypedDocument& doc)
{
    PatchComplex complex;
    for (const TypedObject& o : doc.objects())
        if (const auto surface = patchSurface(o) ? AnySurface::of(o) : std::nullopt; surface && surface->patches()) {
            const std::vector<Patch>& patches = surface->patches()->patches.patches;
            complex.patches.insert(complex.patches.end(), patches.begin(), patches.end());
        }
    if (complex.patches.empty())
        throw Error(doc.source + ": the document has no surface objects (bezier_surface, deboor_surface)");
    return complex;
}

std::optional<PolygonMesh> tessellateObject(const TypedObject& object, const ObjectTessellation& options,
                                            TessellationReport* report)
{
    // A trimmed surface and a part: the part mesh (part_ops.cpp), each edge sampled once.
    if (auto mesh = detail::tessellatePartObject(object, options, report)) return mesh;
    if (const auto surface = AnySurface::of(object)) {
        TessellationOptions o;
        if (options.tolerance > 0) {
            o.tolerance = options.tolerance;
            if (surface->patches()) o.patchTolerance = options.patchTolerance;
        } else {
            o.tolerance = 0;
            o.segmentsU = o.segmentsV = options.segments;
        }
        o.flipNormals = options.flip;
        return std::visit(
            Overloaded{
                [&](const AnySurface::Patches& p) { return tessellate(p.patches, o, report); },
                [&](const RationalBezierSurface<double, 3>& s) { return tessellateRational({s}, 1, 1, o, report); },
                [&](const NurbsSurface<double, 3>& s) { return tessellateNurbs(s, o, report); },
                [](const TrimmedSurface&) -> PolygonMesh { throw Error("tessellateObject: a trimmed surface is a part's"); },
            },
            surface->variant());
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
    return std::nullopt;
}

std::optional<Eigen::Matrix<double, 3, Eigen::Dynamic>> objectPolyline(const TypedObject& object, double tolerance)
{
    if (const auto curve = AnyCurve::of(object)) return curve->polyline(tolerance);
    return std::nullopt;
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
        const bool polynomial = std::any_of(doc.objects().begin(), doc.objects().end(), patchSurface);
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
    if (object.kind() == ObjectKind::BezierSpline) throw Error(doc.source + ": object \"" + object.name() + "\" is already a bezier_spline");
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
    if (object.kind() == ObjectKind::DeBoorSpline) throw Error(doc.source + ": object \"" + object.name() + "\" is already a deboor_spline");
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
    const std::optional<ObjectKind> kind = kindNamed(to);
    if (kind == ObjectKind::BezierSpline) doc.replace(id, toBezierSplineData(doc, object));
    else if (kind == ObjectKind::DeBoorSpline) doc.replace(id, toDeBoorSplineData(doc, object, end));
    else throw Error("convertSpline: \"" + to + "\" is not one of bezier_spline, deboor_spline");
}

} // namespace freeform
