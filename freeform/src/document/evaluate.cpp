// evaluate() and parameterDomain() (document/operations.h): what `freeform eval` prints, per type.

#include <Eigen/LU>

#include <cmath>

#include "freeform/core/format.h"
#include "freeform/core/error.h"
#include "freeform/document/operations.h"
#include "evaluation.h"
#include "part_ops.h"

namespace freeform {
namespace detail {

void expectCount(const std::string& what, const std::vector<double>& at, std::size_t count, const char* form)
{
    if (at.size() != count)
        throw Error(what + ": the parameter is " + form + " (" + std::to_string(count) + " numbers), got " +
                    std::to_string(at.size()));
}

void inDomain(const std::string& what, const char* name, double t, double a, double b, const char* kind)
{
    if (!(t >= a && t <= b))
        throw Error(what + ": " + name + " = " + formatNumber(t) + " is outside the " + kind + "'s domain [" + formatNumber(a) + ", " +
                    formatNumber(b) + "]");
}

Evaluation curveEvaluation(const Eigen::Ref<const Eigen::MatrixXd>& derivatives, int order)
{
    Evaluation e;
    e.point = derivatives.col(0);
    for (int k = 1; k <= order; ++k) e.derivatives.push_back(derivatives.col(k));
    return e;
}

Evaluation surfaceEvaluation(const Eigen::Ref<const Eigen::MatrixXd>& jet, const Eigen::Vector3d& normal, int order)
{
    Evaluation e;
    e.point = jet.col(0);
    e.normal = normal;
    for (int k = 1; k <= order; ++k)
        for (int a = k; a >= 0; --a) {
            // "u"*a + "v"*b: the key of d^(a+b) f / du^a dv^b.
            e.keys.push_back(std::string(static_cast<std::size_t>(a), 'u') + std::string(static_cast<std::size_t>(k - a), 'v'));
            e.derivatives.push_back(jet.col(Patch::jetIndex(a, k - a)));
        }
    return e;
}

void gridEdges(std::vector<std::pair<int, int>>& edges, int rows, int cols)
{
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j) {
            if (j + 1 < cols) edges.emplace_back(i * cols + j, i * cols + j + 1);
            if (i + 1 < rows) edges.emplace_back(i * cols + j, (i + 1) * cols + j);
        }
}

} // namespace detail
namespace {

using detail::expectCount;
using detail::inDomain;

Evaluation evaluateCurve(const std::string& what, const AnyCurve& curve, const std::vector<double>& at, int order)
{
    expectCount(what, at, 1, "T");
    const double t = at[0];
    // A spline and a NURBS curve take a global T, a Bézier curve (rational or not) its t.
    const bool global = curve.isSpline() || curve.form() == AnyCurve::Form::Nurbs;
    inDomain(what, global ? "T" : "t", t, curve.domainStart(), curve.domainEnd(), curve.isSpline() ? "spline" : "curve");
    return detail::curveEvaluation(curve.derivatives(t, order), order);
}

Evaluation evaluateSurface(const std::string& what, const AnySurface& surface, const std::vector<double>& uv, int order)
{
    expectCount(what, uv, 2, "U,V");
    const std::array<double, 4> domain = surface.domain();
    inDomain(what, "u", uv[0], domain[0], domain[1], "surface");
    inDomain(what, "v", uv[1], domain[2], domain[3], "surface");
    return detail::surfaceEvaluation(surface.jet(uv[0], uv[1], order), surface.normal(uv[0], uv[1]), order);
}

Evaluation evaluateLattice(const std::string& what, const Lattice& lattice, const std::vector<double>& stu, int order)
{
    expectCount(what, stu, 3, "S,T,U");
    for (double x : stu)
        if (!(x >= 0 && x <= 1))
            throw Error(what + ": (s, t, u) = " + formatNumber(stu[0]) + "," + formatNumber(stu[1]) + "," + formatNumber(stu[2]) +
                        " is outside the lattice's domain [0, 1]^3");
    if (order > 1) throw Error(what + ": a lattice has --derivatives 0 or 1, not " + std::to_string(order));
    const auto jet = lattice.map(Eigen::Vector3d(stu[0], stu[1], stu[2]));
    Evaluation e;
    e.point = jet.point;
    if (order == 1) {
        e.keys = {"s", "t", "u"};
        e.derivatives = {jet.ds, jet.dt, jet.du};
        // det J of p -> p' = det[f_s f_t f_u] / det[S T U] (chain rule through the frame).
        e.det = jet.jacobian().determinant() / lattice.axes().determinant();
    }
    return e;
}

Evaluation evaluateSubdivision(const std::string& what, const SubdivisionObject& s, const std::vector<double>& fuv, int order)
{
    expectCount(what, fuv, 3, "FACE,U,V");
    if (fuv[0] != std::floor(fuv[0]) || fuv[0] < 0 || fuv[0] > 1e9)
        throw Error(what + ": FACE must be a non-negative integer (FACE,U,V)");
    if (order > 1) throw Error(what + ": a subdivision surface gives first derivatives only (--derivatives 0 or 1)");
    const int face = static_cast<int>(fuv[0]);
    LimitPoint p;
    try {
        p = s.surface.evaluate(face, fuv[1], fuv[2]);
    } catch (const Error& e) {
        throw Error(what + ": " + e.what());
    }
    Evaluation e;
    e.face = face;
    e.point = p.position;
    e.keys = {"u", "v"};
    e.derivatives = {p.du, p.dv};
    e.normal = p.normal;
    return e;
}

} // namespace

Evaluation evaluate(const TypedDocument& doc, const TypedObject& object, const std::vector<double>& at, int order)
{
    const std::string what = doc.what(object);
    if (order < 0) throw Error(what + ": the derivative order must not be negative");
    if (const auto curve = AnyCurve::of(object)) return evaluateCurve(what, *curve, at, order);
    // A trimmed surface and a part print whether the point is inside the trims (part_ops.cpp).
    if (auto e = detail::evaluatePartObject(what, object, at, order)) return std::move(*e);
    if (const auto surface = AnySurface::of(object)) return evaluateSurface(what, *surface, at, order);
    if (const auto* lattice = std::get_if<Lattice>(&object.geometry())) return evaluateLattice(what, *lattice, at, order);
    if (const auto* s = std::get_if<SubdivisionObject>(&object.geometry())) return evaluateSubdivision(what, *s, at, order);
    throw Error(what + ": eval does not support type \"" + object.type() + "\" yet");
}

std::vector<double> parameterDomain(const TypedObject& object)
{
    if (const auto curve = AnyCurve::of(object)) return {curve->domainEnd()};
    if (auto d = detail::partDomain(object)) return *d; // a trimmed surface's box, a part's face count
    if (const auto surface = AnySurface::of(object)) {
        const std::array<double, 4> d = surface->domain();
        return {d[1], d[3]};
    }
    if (std::holds_alternative<Lattice>(object.geometry())) return {1, 1, 1};
    if (const auto* s = std::get_if<SubdivisionObject>(&object.geometry()))
        return {static_cast<double>(s->surface.faceCount()), 1, 1};
    return {};
}

} // namespace freeform
