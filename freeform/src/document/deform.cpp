// deformDocument (document/operations.h): one rule for every object type under free-form
// deformation, written out in docs/ffd.md ("Documents").

#include <cmath>
#include <type_traits>

#include "freeform/brep/part_deform.h"
#include "freeform/core/error.h"
#include "freeform/core/format.h"
#include "freeform/document/object_data.h"
#include "freeform/document/operations.h"
#include "freeform/volume/deform_rational.h"

namespace freeform {
namespace {

bool controlPointsInside(const Lattice& lattice, const Eigen::Ref<const Eigen::Matrix<double, 3, Eigen::Dynamic>>& points)
{
    for (Eigen::Index i = 0; i < points.cols(); ++i)
        if (!Lattice::insideBox(lattice.toLattice(points.col(i)))) return false;
    return true;
}

/// The first field of `data` that holds a number that is not finite ("points", "weights",
/// "vertices"), or "" when every number is finite.
std::string firstNonFinite(const ObjectData& data)
{
    return std::visit(
        [](const auto& d) -> std::string {
            using T = std::decay_t<decltype(d)>;
            if constexpr (std::is_same_v<T, TrimmedSurfaceData>) {
                return d.surface.points.allFinite() ? "" : "points";
            } else if constexpr (std::is_same_v<T, PartData>) {
                for (const PartFaceData& f : d.faces)
                    if (!f.surface.surface.points.allFinite()) return "face points";
                for (const PartEdgeData& e : d.edges)
                    if (e.curve && !e.curve->nurbs.points.allFinite()) return "edge points";
                for (const PartVertexData& v : d.vertices)
                    if (!v.point.allFinite()) return "vertices";
                return "";
            } else {
                if constexpr (requires { d.points; })
                    if (!d.points.allFinite()) return "points";
                if constexpr (requires { d.vertices; })
                    if (!d.vertices.allFinite()) return "vertices";
                if constexpr (requires { d.weights; })
                    for (double x : d.weights)
                        if (!std::isfinite(x)) return "weights";
                return "";
            }
        },
        data);
}

/// A spline's segments pushed through the lattice exactly, as a bezier_spline of degree
/// d (l+m+n) on the same intervals (joints shared, as the format stores them).
BezierSplineData deformSpline(const Lattice& lattice, const BezierSpline<double, 3>& spline, double strength)
{
    BezierSplineData out;
    out.closed = spline.closed();
    out.intervals = spline.intervals();
    const int segments = spline.segmentCount();
    for (int i = 0; i < segments; ++i) {
        const BezierCurve<double, 3> piece = deformCurve(lattice, spline.segment(i), strength);
        const int d = piece.degree();
        if (i == 0) {
            out.degree = d;
            out.points.resize(3, static_cast<Eigen::Index>(spline.closed() ? segments * d : segments * d + 1));
        }
        // Segment i owns its first d points; the last open segment also its end point.
        out.points.middleCols(static_cast<Eigen::Index>(i) * d, d) = piece.controlPoints().leftCols(d);
        if (!spline.closed() && i + 1 == segments) out.points.col(out.points.cols() - 1) = piece.controlPoints().col(d);
    }
    return out;
}

/// Points moved by the lattice polynomial (displacement form, no outside policy).
PointColumns mapPolynomial(const Lattice& lattice, const PointColumns& points, double strength)
{
    Lattice continued = lattice;
    continued.setOutside(OutsidePolicy::Extrapolate);
    PointColumns out(3, points.cols());
    for (Eigen::Index i = 0; i < points.cols(); ++i) out.col(i) = continued.deform(points.col(i), strength).point;
    return out;
}

bool allPatchesInside(const Lattice& lattice, const PatchComplex& complex)
{
    for (const Patch& p : complex.patches)
        if (!controlPointsInside(lattice, p.controlPoints())) return false;
    return true;
}

} // namespace

bool isAffineLattice(const Lattice& lattice, double strength)
{
    return affineMap(lattice, strength).has_value();
}

DeformDocumentReport deformDocument(TypedDocument& doc, const Lattice& lattice, const DeformDocumentOptions& options)
{
    const double w = options.strength;
    const bool extrapolate = lattice.outside() == OutsidePolicy::Extrapolate;
    const bool affine = isAffineLattice(lattice, w);
    DeformDocumentReport report;
    std::vector<std::pair<ObjectId, ObjectData>> changes;

    for (const TypedObject& o : doc.objects()) {
        const std::string type = o.type();
        auto skip = [&](const std::string& reason) { report.skipped.push_back({o.id(), o.name(), type, reason}); };
        if (std::holds_alternative<Lattice>(o.geometry())) {
            skip("no exact deformation for a " + type);
            continue;
        }
        if (o.dimension() != 3) {
            skip("a 2D object (the lattice deforms 3D space)");
            continue;
        }
        DeformedObject r;
        r.id = o.id();
        r.name = o.name();
        r.from = type;
        ObjectData result;
        std::string note;
        try {
            const Geometry& g = o.geometry();
            if (const auto* c = std::get_if<BezierCurve<double, 3>>(&g)) {
                r.inside = controlPointsInside(lattice, c->controlPoints());
                BezierCurveData d;
                d.points = deformCurve(lattice, *c, w).controlPoints();
                r.degree = {static_cast<int>(d.points.cols()) - 1};
                result = std::move(d);
            } else if (const auto* s = std::get_if<BezierSurface<double, 3>>(&g)) {
                r.inside = controlPointsInside(lattice, s->controlPoints());
                const BezierSurface<double, 3> moved = deformSurface(lattice, *s, w);
                BezierSurfaceData d;
                d.degree = {moved.degreeU(), moved.degreeV()};
                d.points = moved.controlPoints();
                r.degree = {moved.degreeU(), moved.degreeV()};
                result = std::move(d);
            } else if (const auto* b = std::get_if<BezierSpline<double, 3>>(&g)) {
                r.inside = controlPointsInside(lattice, b->controlPoints());
                BezierSplineData d = deformSpline(lattice, *b, w);
                r.degree = {d.degree};
                result = std::move(d);
            } else if (const auto* db = std::get_if<DeBoorSpline<3>>(&g)) {
                r.inside = controlPointsInside(lattice, db->bezier.controlPoints());
                if (affine) {
                    // An affine map commutes with the A-frame: the image is the cubic C2 spline on the
                    // same intervals whose de Boor points are the mapped de Boor points.
                    DeBoorSplineData d = std::get<DeBoorSplineData>(o.data());
                    d.points = mapPolynomial(lattice, d.points, w);
                    r.degree = {3};
                    result = std::move(d);
                } else {
                    BezierSplineData d = deformSpline(lattice, db->bezier, w);
                    r.degree = {d.degree};
                    note = "the lattice is not affine: the composition raises the degree to " + std::to_string(d.degree) +
                           ", so the result is a bezier_spline, not a cubic deboor_spline";
                    result = std::move(d);
                }
            } else if (const auto* ds = std::get_if<DeBoorSurface>(&g)) {
                if (!affine) {
                    skip("no exact deformation for a " + type);
                    continue;
                }
                r.inside = allPatchesInside(lattice, ds->patches);
                DeBoorSurfaceData d = std::get<DeBoorSurfaceData>(o.data());
                d.points = mapPolynomial(lattice, d.points, w);
                r.degree = {3, 3};
                result = std::move(d);
            } else if (const auto* rc = std::get_if<RationalBezierCurve<double, 3>>(&g)) {
                // Exact composition through the lattice (volume/deform_rational.h).
                r.inside = controlPointsInside(lattice, rc->controlPoints());
                const RationalBezierCurve<double, 3> moved = deformCurve(RationalLattice(lattice), *rc, w);
                r.degree = {moved.degree()};
                result = toData(moved);
            } else if (const auto* nc = std::get_if<NurbsCurve<double, 3>>(&g)) {
                // Span by span through the Bézier extraction; the result keeps the breakpoints.
                r.inside = controlPointsInside(lattice, nc->controlPoints());
                const NurbsCurve<double, 3> moved = deformCurve(RationalLattice(lattice), *nc, w);
                r.degree = {moved.degree()};
                result = toData(moved);
            } else if (const auto* rs = std::get_if<RationalBezierSurface<double, 3>>(&g)) {
                // Exact composition (volume/deform_rational.h): degrees (m (l+m+n), n (l+m+n)).
                const auto& h = rs->homogeneous().controlPoints();
                PointColumns points(3, h.cols());
                for (Eigen::Index i = 0; i < h.cols(); ++i) points.col(i) = h.col(i).head<3>() / h(3, i);
                r.inside = controlPointsInside(lattice, points);
                const RationalBezierSurface<double, 3> moved = deformSurface(RationalLattice(lattice), *rs, w);
                r.degree = {moved.degreeU(), moved.degreeV()};
                result = toData(moved);
            } else if (const auto* ns = std::get_if<NurbsSurface<double, 3>>(&g)) {
                // Patch by patch through the Bézier extraction; the result keeps the breakpoints.
                r.inside = controlPointsInside(lattice, ns->controlPoints());
                const NurbsSurface<double, 3> moved = deformSurface(RationalLattice(lattice), *ns, w);
                r.degree = {moved.degreeU(), moved.degreeV()};
                result = toData(moved);
            } else if (std::holds_alternative<TrimmedSurface>(g) || std::holds_alternative<Part>(g)) {
                // Every face and edge composed exactly (brep/part_deform.h, no degree cap: the
                // document holds degrees up to 67); a trimmed surface alone as a part of one face.
                const auto* t = std::get_if<TrimmedSurface>(&g);
                const Part part = t ? singleFacePart(*t) : std::get<Part>(g);
                PartDeformOptions deform;
                deform.strength = w;
                deform.threads = options.threads;
                const DeformedPart moved = deformPart(part, RationalLattice(lattice), deform);
                r.inside = moved.report.outsideFaces == 0;
                r.degree = {moved.report.maxDegree};
                if (std::holds_alternative<TrimmedSurface>(g)) {
                    TrimmedSurfaceData d = toData(moved.part.faces.front().surface);
                    for (auto& loop : d.loops)
                        for (TrimCurveData& trim : loop) trim.edge = -1; // the part's edges were singleFacePart's
                    result = std::move(d);
                } else {
                    result = toData(moved.part);
                    note = std::to_string(moved.report.faces) + " faces composed exactly; edge tolerances x " +
                           formatNumber(moved.report.lipschitz) + " (the lattice's Lipschitz bound), largest gap " +
                           formatNumber(moved.report.maxGap);
                }
            } else if (const auto* sub = std::get_if<SubdivisionObject>(&g)) {
                const SubdivisionCage& cage = sub->cage();
                const auto& data = std::get<SubdivisionSurfaceData>(o.data());
                r.inside = controlPointsInside(lattice, cage.mesh.positions);
                SubdivisionSurfaceData d = data;
                Eigen::Matrix<double, 3, Eigen::Dynamic> v;
                if (data.mesh.empty()) {
                    v = data.vertices;
                } else {
                    // A cage from a mesh file is written inline (its OBJ crease tags become the
                    // object's creases and corners), so the document holds the deformed cage.
                    d = toData(*sub); // Error when the file's cage has what the inline form cannot hold
                    v = d.vertices;
                    note = "the cage from \"" + data.mesh + "\" is written inline; ";
                }
                DeformOptions deform;
                deform.strength = w;
                deform.threads = options.threads;
                deformPoints(lattice, v, deform);
                d.vertices = v;
                result = std::move(d);
                note += affine ? "cage deformed as a cage (the lattice is affine: the limit surface moves exactly)"
                               : "cage deformed as a cage: its limit surface is not the deformed limit surface "
                                 "(exact only for affine lattices)";
            } else {
                skip("no exact deformation for a " + type);
                continue;
            }
        } catch (const Error& e) {
            throw Error(doc.what(o) + ": " + e.what());
        }
        // Far outside the box the lattice polynomial (continued there for the exact compositions, and
        // for a cage under the extrapolate policy) can overflow: refuse before the document changes
        // (JSON has no number for infinity or NaN).
        if (const std::string field = firstNonFinite(result); !field.empty())
            throw Error(doc.what(o) + ": the deformed " + field +
                        " are not finite (the lattice polynomial overflows this far outside its box: use a lattice "
                        "that covers the object)");
        const bool isCage = std::holds_alternative<SubdivisionObject>(o.geometry());
        // Subdivision cages follow the outside policy point by point (as meshes); everything else is
        // the polynomial continued, which equals point-wise FFD inside the box or under extrapolate.
        r.exact = isCage ? affine && (r.inside || extrapolate) : (r.inside || extrapolate);
        if (!isCage && !r.exact) {
            if (options.skipInexact) {
                skip("control points outside the lattice box (exact only inside, or with the extrapolate policy)");
                continue;
            }
            if (!note.empty()) note += "; ";
            note += "control points outside the lattice box: the lattice polynomial is continued there, not the " +
                    toString(lattice.outside()) + " policy";
        }
        r.type = objectType(result);
        r.note = std::move(note);
        report.objects.push_back(std::move(r));
        changes.emplace_back(o.id(), std::move(result));
    }
    report.certificate = certify(lattice, w);
    // Build every new geometry before changing the document, so an error leaves it as it was.
    TypedDocument next = doc;
    for (auto& [id, data] : changes) next.replace(id, std::move(data));
    doc = std::move(next);
    return report;
}

} // namespace freeform
