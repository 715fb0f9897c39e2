// evaluate() and parameterDomain() (document/operations.h): what `freeform eval` prints, per type.

#include <Eigen/LU>

#include <cmath>

#include "freeform/core/format.h"
#include "freeform/core/error.h"
#include "freeform/document/operations.h"
#include "evaluation.h"
#include "part_ops.h"
#include "rational.h"

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
    if (!curve.isSpline())
        inDomain(what, "t", t, 0, 1, "curve");
    else
        inDomain(what, "T", t, 0, curve.domainEnd(), "spline");
    return detail::curveEvaluation(curve.derivatives(t, order), order);
}

Evaluation evaluateSurface(const std::string& what, const AnySurface& surface, const std::vector<double>& uv, int order)
{
    expectCount(what, uv, 2, "U,V");
    const auto& segments = surface.segments;
    int index[2] = {0, 0};
    double local[2] = {0, 0};
    for (int d = 0; d < 2; ++d) {
        const double t = uv[static_cast<std::size_t>(d)];
        inDomain(what, d == 0 ? "u" : "v", t, 0, segments[d], "surface");
        index[d] = std::min(static_cast<int>(std::floor(t)), segments[d] - 1);
        local[d] = t - index[d];
    }
    const Patch& patch = surface.patches.patches[static_cast<std::size_t>(index[0] * segments[1] + index[1])];
    return detail::surfaceEvaluation(patch.jet(local[0], local[1], order), patch.normal(local[0], local[1]), order);
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
    if (const auto surface = AnySurface::of(object)) return evaluateSurface(what, *surface, at, order);
    if (const auto* lattice = std::get_if<Lattice>(&object.geometry())) return evaluateLattice(what, *lattice, at, order);
    if (const auto* s = std::get_if<SubdivisionObject>(&object.geometry())) return evaluateSubdivision(what, *s, at, order);
    if (auto e = detail::evaluateRational(what, object, at, order)) return std::move(*e);
    if (auto e = detail::evaluatePartObject(what, object, at, order)) return std::move(*e);
    throw Error(what + ": eval does not support type \"" + object.type() + "\" yet");
}

std::vector<double> parameterDomain(const TypedObject& object)
{
    if (const auto curve = AnyCurve::of(object)) return {curve->domainEnd()};
    if (const auto surface = AnySurface::of(object))
        return {static_cast<double>(surface->segments[0]), static_cast<double>(surface->segments[1])};
    if (std::holds_alternative<Lattice>(object.geometry())) return {1, 1, 1};
    if (const auto* s = std::get_if<SubdivisionObject>(&object.geometry()))
        return {static_cast<double>(s->surface.faceCount()), 1, 1};
    if (auto d = detail::rationalDomain(object)) return *d;
    if (auto d = detail::partDomain(object)) return *d;
    return {};
}

} // namespace freeform
