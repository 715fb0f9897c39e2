// The kind table (document/kinds.h): one row per object kind, in ObjectKind's order. The rows say
// what the document layer's operations accept (document/operations.h); test_kinds checks each
// claim against the operations themselves.

#include "freeform/document/kinds.h"

#include <string>
#include <variant>

#include "overloaded.h"

namespace freeform {
namespace {

constexpr unsigned bits(std::initializer_list<KindOperation> ops)
{
    unsigned b = 0;
    for (KindOperation op : ops) b |= static_cast<unsigned>(op);
    return b;
}

using Op = KindOperation;
using N = KindNature;
using P = KindParameters;

std::array<KindInfo, objectKindCount> makeTable()
{
    auto row = [](ObjectKind kind, std::string_view summary, N nature, P parameters, int dimension, bool rational,
                  bool knots, bool pieces, unsigned operations) {
        return KindInfo{kind, kindName(kind), summary, nature, parameters, dimension, rational, knots, pieces, operations};
    };
    const unsigned curve = bits({Op::Evaluate, Op::Polyline, Op::Deform});
    const unsigned surface = bits({Op::Evaluate, Op::Tessellate, Op::Deform});
    using K = ObjectKind;
    return {{
        row(K::BezierCurve, "Bézier curve", N::Curve, P::T, 0, false, false, false, curve | bits({Op::ToNurbs})),
        row(K::BezierSpline, "Bézier spline", N::Curve, P::T, 0, false, false, true,
            curve | bits({Op::Continuity, Op::ConvertSpline, Op::ToNurbs})),
        row(K::DeBoorSpline, "de Boor spline", N::Curve, P::T, 0, false, false, true,
            curve | bits({Op::Continuity, Op::ConvertSpline, Op::ToNurbs})),
        row(K::BezierSurface, "Bézier surface", N::Surface, P::UV, 3, false, false, false, surface | bits({Op::ToNurbs})),
        // Deformed only by an affine lattice (it stays a deboor_surface); any other is skipped.
        row(K::DeBoorSurface, "de Boor surface", N::Surface, P::UV, 3, false, false, true,
            bits({Op::Evaluate, Op::Tessellate})),
        row(K::Lattice, "FFD lattice", N::Volume, P::STU, 3, false, false, false, bits({Op::Evaluate, Op::DeformsOthers})),
        row(K::SubdivisionSurface, "subdivision surface", N::Surface, P::FaceUV, 3, false, false, true, surface),
        row(K::RationalBezierCurve, "rational Bézier curve", N::Curve, P::T, 0, true, false, false, curve | bits({Op::ToNurbs})),
        row(K::RationalBezierSurface, "rational Bézier surface", N::Surface, P::UV, 3, true, false, false,
            surface | bits({Op::ToNurbs})),
        row(K::NurbsCurve, "NURBS curve", N::Curve, P::T, 0, true, true, true, curve | bits({Op::Continuity, Op::FromNurbs})),
        row(K::NurbsSurface, "NURBS surface", N::Surface, P::UV, 3, true, true, true, surface | bits({Op::FromNurbs})),
        row(K::TrimmedSurface, "trimmed NURBS surface", N::Surface, P::UV, 3, true, true, true, surface | bits({Op::Part})),
        row(K::Part, "CAD part", N::Part, P::FaceUV, 3, true, true, true, surface | bits({Op::Part})),
    }};
}

} // namespace

const std::array<KindInfo, objectKindCount>& objectKinds()
{
    static const std::array<KindInfo, objectKindCount> table = makeTable();
    return table;
}

const KindInfo& kindInfo(ObjectKind kind) { return objectKinds()[static_cast<std::size_t>(kind)]; }

const KindInfo* findKind(std::string_view name)
{
    const std::optional<ObjectKind> kind = kindNamed(name);
    return kind ? &kindInfo(*kind) : nullptr;
}

std::string partSummary(const PartData& part)
{
    auto count = [](std::size_t n, const char* one, const char* many) { return std::to_string(n) + " " + (n == 1 ? one : many); };
    return count(part.faces.size(), "face", "faces") + ", " + count(part.edges.size(), "edge", "edges") + ", " +
           count(part.vertices.size(), "vertex", "vertices") + ", " + count(part.shells.size(), "shell", "shells") + ", " +
           count(part.solids.size(), "solid", "solids") + ", units " + part.units;
}

std::string objectDetails(const ObjectData& data)
{
    const auto degree = [](auto... d) {
        std::string out = "degree";
        const char* sep = " ";
        ((out += sep + std::to_string(d), sep = " x "), ...);
        return out;
    };
    const auto dim = [](const PointColumns& p) { return std::to_string(p.rows()) + "D"; };
    return std::visit(
        detail::Overloaded{
            [&](const BezierCurveData& d) { return degree(d.points.cols() - 1) + ", " + dim(d.points); },
            [&](const BezierSplineData& d) { return degree(d.degree) + (d.closed ? ", closed" : ", open"); },
            [&](const DeBoorSplineData& d) { return degree(d.degree) + ", end " + d.end; },
            [&](const BezierSurfaceData& d) { return degree(d.degree[0], d.degree[1]); },
            [&](const DeBoorSurfaceData& d) { return degree(d.degree[0], d.degree[1]); },
            [&](const LatticeData& d) { return degree(d.degree[0], d.degree[1], d.degree[2]); },
            [&](const SubdivisionSurfaceData&) { return std::string(); },
            [&](const RationalBezierCurveData& d) { return degree(d.points.cols() - 1) + ", " + dim(d.points); },
            [&](const RationalBezierSurfaceData& d) { return degree(d.degree[0], d.degree[1]); },
            [&](const NurbsCurveData& d) { return degree(d.degree) + ", " + std::to_string(d.knots.size()) + " knots, " + dim(d.points); },
            [&](const NurbsSurfaceData& d) {
                return degree(d.degree[0], d.degree[1]) + ", " + std::to_string(d.rows) + " x " + std::to_string(d.cols) + " points";
            },
            [&](const TrimmedSurfaceData& d) {
                const std::size_t loops = d.loops.size();
                return degree(d.surface.degree[0], d.surface.degree[1]) + ", " + std::to_string(loops) + (loops == 1 ? " trim loop" : " trim loops");
            },
            [&](const PartData& d) { return partSummary(d); },
        },
        data);
}

} // namespace freeform
