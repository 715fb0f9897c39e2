// Exact NURBS forms of CAD curves and surfaces (brep/exact_forms.h, docs/cad.md "Exact forms").

#include "freeform/brep/exact_forms.h"

#include <cmath>
#include <string>
#include <vector>

#include "freeform/core/error.h"
#include "freeform/core/format.h"

namespace freeform {
namespace {

void requireRange(double t0, double t1, const char* what)
{
    if (!(t0 < t1) || !std::isfinite(t0) || !std::isfinite(t1))
        throw Error(std::string(what) + ": the parameter range [" + formatNumber(t0) + ", " + formatNumber(t1) + "] is empty or not finite");
}

/// The unit circle's arcs on a half-angle map: for arc k, control points (cos, sin) of its start,
/// its middle (over cos alpha) and its end, with weights 1, cos alpha, 1 (the end of arc k is the
/// start of arc k + 1), and the knots start^3, start + span^2, ..., end^3.
struct UnitArcs {
    std::vector<Eigen::Vector2d> points;
    std::vector<double> weights;
    std::vector<double> knots;
};

UnitArcs unitArcs(const ParameterMap& map)
{
    UnitArcs a;
    const double alpha = map.span / 2, c = std::cos(alpha);
    const double t1 = map.start + map.spans * map.span;
    for (int k = 0; k < map.spans; ++k) {
        const double s = map.start + k * map.span, m = s + alpha;
        a.points.emplace_back(std::cos(s), std::sin(s));
        a.weights.push_back(1);
        a.points.emplace_back(std::cos(m) / c, std::sin(m) / c);
        a.weights.push_back(c);
    }
    a.points.emplace_back(std::cos(t1), std::sin(t1));
    a.weights.push_back(1);
    a.knots = {map.start, map.start, map.start};
    for (int k = 1; k < map.spans; ++k) a.knots.insert(a.knots.end(), 2, map.start + k * map.span);
    a.knots.insert(a.knots.end(), 3, t1);
    return a;
}

/// Bernstein coefficients on [x0, x1] of the quadratic with value f0 and derivative d0 at x0 and
/// value f1 at x1.
template <typename V>
std::array<V, 3> quadraticBernstein(const V& f0, const V& d0, const V& f1, double h)
{
    return {f0, f0 + d0 * (h / 2), f1};
}

} // namespace

template <int Dim>
MappedCurve<Dim> exactLine(const Eigen::Matrix<double, Dim, 1>& origin, const Eigen::Matrix<double, Dim, 1>& direction,
                           double t0, double t1)
{
    requireRange(t0, t1, "line");
    PointMatrix<double, Dim> p(Dim, 2);
    p.col(0) = origin + t0 * direction;
    p.col(1) = origin + t1 * direction;
    return {NurbsCurve<double, Dim>(1, {t0, t0, t1, t1}, p), ParameterMap::identity(), t0, t1};
}

template <int Dim>
MappedCurve<Dim> exactEllipse(const Eigen::Matrix<double, Dim, 1>& center, const Eigen::Matrix<double, Dim, 1>& X,
                              const Eigen::Matrix<double, Dim, 1>& Y, double a, double b, double t0, double t1)
{
    requireRange(t0, t1, "ellipse");
    const ParameterMap map = ParameterMap::halfAngle(t0, t1);
    const UnitArcs arcs = unitArcs(map);
    PointMatrix<double, Dim> p(Dim, static_cast<Eigen::Index>(arcs.points.size()));
    Eigen::VectorXd w(p.cols());
    for (Eigen::Index i = 0; i < p.cols(); ++i) {
        p.col(i) = center + a * arcs.points[i].x() * X + b * arcs.points[i].y() * Y;
        w[i] = arcs.weights[i];
    }
    return {NurbsCurve<double, Dim>(2, arcs.knots, p, w), map, t0, t1};
}

template <int Dim>
MappedCurve<Dim> exactHyperbola(const Eigen::Matrix<double, Dim, 1>& center, const Eigen::Matrix<double, Dim, 1>& X,
                                const Eigen::Matrix<double, Dim, 1>& Y, double a, double b, double t0, double t1)
{
    requireRange(t0, t1, "hyperbola");
    // With s = e^t: 2s (point) = 2s center + a (s^2 + 1) X + b (s^2 - 1) Y, weight 2s; both are
    // quadratics in s, written in Bernstein form on [s0, s1].
    using V = Eigen::Matrix<double, Dim, 1>;
    const double s0 = std::exp(t0), s1 = std::exp(t1), h = s1 - s0;
    auto f = [&](double s) -> V { return 2 * s * center + a * (s * s + 1) * X + b * (s * s - 1) * Y; };
    auto df = [&](double s) -> V { return 2 * center + 2 * a * s * X + 2 * b * s * Y; };
    const auto hp = quadraticBernstein<V>(f(s0), df(s0), f(s1), h);
    const auto hw = quadraticBernstein<double>(2 * s0, 2.0, 2 * s1, h);
    PointMatrix<double, Dim> p(Dim, 3);
    Eigen::VectorXd w(3);
    for (int i = 0; i < 3; ++i) {
        p.col(i) = hp[i] / hw[i];
        w[i] = hw[i];
    }
    return {NurbsCurve<double, Dim>(2, {s0, s0, s0, s1, s1, s1}, p, w), ParameterMap::exponential(), t0, t1};
}

template <int Dim>
MappedCurve<Dim> exactParabola(const Eigen::Matrix<double, Dim, 1>& vertex, const Eigen::Matrix<double, Dim, 1>& X,
                               const Eigen::Matrix<double, Dim, 1>& Y, double focal, double t0, double t1)
{
    requireRange(t0, t1, "parabola");
    using V = Eigen::Matrix<double, Dim, 1>;
    auto f = [&](double t) -> V { return vertex + t * t / (4 * focal) * X + t * Y; };
    auto df = [&](double t) -> V { return t / (2 * focal) * X + Y; };
    const auto c = quadraticBernstein<V>(f(t0), df(t0), f(t1), t1 - t0);
    PointMatrix<double, Dim> p(Dim, 3);
    for (int i = 0; i < 3; ++i) p.col(i) = c[i];
    return {NurbsCurve<double, Dim>(2, {t0, t0, t0, t1, t1, t1}, p), ParameterMap::identity(), t0, t1};
}

template <int Dim>
MappedCurve<Dim> exactRestriction(const NurbsCurve<double, Dim>& curve, const ParameterMap& map, double t0, double t1)
{
    requireRange(t0, t1, "curve");
    NurbsCurve<double, Dim> c = curve;
    double s0 = map(t0), s1 = map(t1);
    if (s1 <= s0) s1 = s0 == c.domainEnd() ? s1 : c.domainEnd(); // t1 closes a period
    if (s0 > c.domainStart() && s0 < c.domainEnd()) c = c.split(s0).second;
    if (s1 > c.domainStart() && s1 < c.domainEnd()) c = c.split(s1).first;
    return {std::move(c), map, t0, t1};
}

MappedSurface exactPlane(const Eigen::Vector3d& origin, const Eigen::Vector3d& X, const Eigen::Vector3d& Y, double u0,
                         double u1, double v0, double v1)
{
    requireRange(u0, u1, "plane (u)");
    requireRange(v0, v1, "plane (v)");
    PointMatrix<double, 3> p(3, 4);
    p.col(0) = origin + u0 * X + v0 * Y;
    p.col(1) = origin + u0 * X + v1 * Y;
    p.col(2) = origin + u1 * X + v0 * Y;
    p.col(3) = origin + u1 * X + v1 * Y;
    return {NurbsSurface<double, 3>(1, 1, {u0, u0, u1, u1}, {v0, v0, v1, v1}, p), ParameterMap::identity(),
            ParameterMap::identity()};
}

MappedSurface exactRevolution(const MappedCurve<3>& meridian, const Eigen::Vector3d& origin, const Eigen::Vector3d& axis,
                              double u0, double u1)
{
    requireRange(u0, u1, "surface of revolution (u)");
    const ParameterMap mapU = ParameterMap::halfAngle(u0, u1);
    const UnitArcs arcs = unitArcs(mapU);
    const Eigen::Vector3d D = axis.normalized();
    const auto& m = meridian.nurbs;
    const int nu = static_cast<int>(arcs.points.size()), nv = m.controlCount();
    PointMatrix<double, 3> p(3, nu * nv);
    Eigen::VectorXd w(nu * nv);
    for (int j = 0; j < nv; ++j) {
        const Eigen::Vector3d q = m.controlPoint(j) - origin;
        const double along = q.dot(D);
        const Eigen::Vector3d r = q - along * D, rp = D.cross(r);
        for (int i = 0; i < nu; ++i) {
            p.col(i * nv + j) = origin + along * D + arcs.points[i].x() * r + arcs.points[i].y() * rp;
            w[i * nv + j] = arcs.weights[i] * m.weight(j);
        }
    }
    return {NurbsSurface<double, 3>(2, m.degree(), arcs.knots, m.knots(), p, w), mapU, meridian.map};
}

MappedSurface exactExtrusion(const MappedCurve<3>& base, const Eigen::Vector3d& direction, double v0, double v1)
{
    requireRange(v0, v1, "surface of extrusion (v)");
    const auto& c = base.nurbs;
    const int nu = c.controlCount();
    PointMatrix<double, 3> p(3, 2 * nu);
    Eigen::VectorXd w(2 * nu);
    for (int i = 0; i < nu; ++i) {
        p.col(2 * i) = c.controlPoint(i) + v0 * direction;
        p.col(2 * i + 1) = c.controlPoint(i) + v1 * direction;
        w[2 * i] = w[2 * i + 1] = c.weight(i);
    }
    return {NurbsSurface<double, 3>(c.degree(), 1, c.knots(), {v0, v0, v1, v1}, p, w), base.map,
            ParameterMap::identity()};
}

#define FREEFORM_EXACT_FORMS(D)                                                                                        \
    template MappedCurve<D> exactLine<D>(const Eigen::Matrix<double, D, 1>&, const Eigen::Matrix<double, D, 1>&, double, \
                                         double);                                                                      \
    template MappedCurve<D> exactEllipse<D>(const Eigen::Matrix<double, D, 1>&, const Eigen::Matrix<double, D, 1>&,    \
                                            const Eigen::Matrix<double, D, 1>&, double, double, double, double);       \
    template MappedCurve<D> exactHyperbola<D>(const Eigen::Matrix<double, D, 1>&, const Eigen::Matrix<double, D, 1>&,  \
                                              const Eigen::Matrix<double, D, 1>&, double, double, double, double);     \
    template MappedCurve<D> exactParabola<D>(const Eigen::Matrix<double, D, 1>&, const Eigen::Matrix<double, D, 1>&,   \
                                             const Eigen::Matrix<double, D, 1>&, double, double, double);              \
    template MappedCurve<D> exactRestriction<D>(const NurbsCurve<double, D>&, const ParameterMap&, double, double);
FREEFORM_EXACT_FORMS(2)
FREEFORM_EXACT_FORMS(3)
#undef FREEFORM_EXACT_FORMS

} // namespace freeform
