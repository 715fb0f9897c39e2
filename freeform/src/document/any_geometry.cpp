// AnyCurve and AnySurface (document/model.h): every curve kind and every (u, v) surface kind behind
// one run-time interface, so the document layer's evaluate, polylines and domains, the editor's
// curve overlays and Python take each kind the same way. Which object is which curve or surface is
// its kind file's word (kindCurve, kindSurface: src/document/kind_file.h).

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <vector>

#include "freeform/core/error.h"
#include "freeform/document/model.h"
#include "kind_file.h"
#include "overloaded.h"

namespace freeform {
namespace {

using detail::Overloaded;

using detail::lift3;

/// Certified flattening of a rational Bézier piece (positive weights: the curve lies in the
/// convex hull of its control points): split at 1/2 until every control point is within
/// tolerance of the chord; the piece's end point is appended.
template <int Dim>
void flatten(const RationalBezierCurve<double, Dim>& c, double tolerance, std::vector<Eigen::Vector3d>& out, int depth)
{
    const auto p = c.controlPoints();
    const Eigen::Matrix<double, Dim, 1> a = p.col(0), b = p.col(p.cols() - 1);
    const Eigen::Matrix<double, Dim, 1> ab = b - a;
    const double len2 = ab.squaredNorm();
    double dev = 0;
    for (Eigen::Index i = 1; i + 1 < p.cols(); ++i) {
        const Eigen::Matrix<double, Dim, 1> ap = p.col(i) - a;
        const double t = len2 > 0 ? std::clamp(ap.dot(ab) / len2, 0.0, 1.0) : 0.0;
        dev = std::max(dev, (ap - t * ab).norm());
    }
    if (dev <= tolerance || depth >= 40) {
        Eigen::Vector3d q = Eigen::Vector3d::Zero();
        q.head<Dim>() = b;
        out.push_back(q);
        return;
    }
    const auto [l, r] = c.split(0.5);
    flatten(l, tolerance, out, depth + 1);
    flatten(r, tolerance, out, depth + 1);
}

template <int Dim>
Eigen::Matrix<double, 3, Eigen::Dynamic> flattenPieces(const std::vector<RationalBezierCurve<double, Dim>>& pieces, double tolerance)
{
    if (!(tolerance > 0)) throw Error("polyline: the tolerance must be positive");
    std::vector<Eigen::Vector3d> pts;
    Eigen::Vector3d first = Eigen::Vector3d::Zero();
    first.head<Dim>() = pieces.front().controlPoint(0);
    pts.push_back(first);
    for (const auto& piece : pieces) flatten(piece, tolerance, pts, 0);
    Eigen::Matrix<double, 3, Eigen::Dynamic> out(3, static_cast<Eigen::Index>(pts.size()));
    for (std::size_t i = 0; i < pts.size(); ++i) out.col(static_cast<Eigen::Index>(i)) = pts[i];
    return out;
}

} // namespace

// ---------------------------------------------------------------- AnyCurve

std::optional<AnyCurve> AnyCurve::of(const TypedObject& object)
{
    return std::visit([&](const auto& d) { return detail::kindCurve(object.geometry(), std::type_identity<std::decay_t<decltype(d)>>{}); },
                      object.data());
}

// The members below read what a curve class has by its member functions' names, so a new curve
// class joins AnyCurve (its alternatives and Form in document/model.h) with no case here when it
// has them: closed() (a Bézier spline), domainStart() / domainEnd() (else 0 and 1), weights()
// (else all 1), bezierPieces() (a rational curve of several pieces).

bool AnyCurve::closed() const
{
    return std::visit(
        [](const auto& c) {
            if constexpr (requires { c.closed(); }) return c.closed();
            else return false;
        },
        curve_);
}

double AnyCurve::domainStart() const
{
    return std::visit(
        [](const auto& c) -> double {
            if constexpr (requires { c.domainStart(); }) return c.domainStart();
            else return 0.0;
        },
        curve_);
}

double AnyCurve::domainEnd() const
{
    return std::visit(
        [](const auto& c) -> double {
            if constexpr (requires { c.domainEnd(); }) return c.domainEnd();
            else return 1.0;
        },
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

Eigen::VectorXd AnyCurve::weights() const
{
    return std::visit(
        [](const auto& c) -> Eigen::VectorXd {
            if constexpr (requires { c.weights(); }) return c.weights();
            else return Eigen::VectorXd::Ones(c.controlPoints().cols());
        },
        curve_);
}

std::optional<BezierSpline<double, 3>> AnyCurve::spline3() const
{
    return std::visit(
        Overloaded{
            [](const BezierSpline<double, 3>& s) -> std::optional<BezierSpline<double, 3>> { return s; },
            [](const BezierSpline<double, 2>& s) -> std::optional<BezierSpline<double, 3>> {
                return BezierSpline<double, 3>(s.degree(), s.closed(), lift3(s.controlPoints()), s.intervals());
            },
            [](const BezierCurve<double, 2>& c) -> std::optional<BezierSpline<double, 3>> {
                return BezierSpline<double, 3>(c.degree(), false, lift3(c.controlPoints()));
            },
            [](const BezierCurve<double, 3>& c) -> std::optional<BezierSpline<double, 3>> {
                return BezierSpline<double, 3>(c.degree(), false, lift3(c.controlPoints()));
            },
            [](const auto&) -> std::optional<BezierSpline<double, 3>> { return std::nullopt; },
        },
        curve_);
}

Eigen::Matrix<double, 3, Eigen::Dynamic> AnyCurve::polyline(double tolerance) const
{
    switch (form()) {
    case Form::Bezier: { // as the editor samples (scene/geometry.cpp): the curve in 3D, adaptive parameters
        const BezierCurve<double, 3> curve(lift3(controlPoints()));
        return curve.evaluateMany(curve.sampleAdaptive(tolerance));
    }
    case Form::Spline: {
        const BezierSpline<double, 3> spline = *spline3();
        const std::vector<double> ts = spline.sampleAdaptive(tolerance);
        Eigen::Matrix<double, 3, Eigen::Dynamic> out(3, static_cast<Eigen::Index>(ts.size()));
        for (std::size_t k = 0; k < ts.size(); ++k) out.col(static_cast<Eigen::Index>(k)) = spline.evaluate(ts[k]);
        return out;
    }
    case Form::RationalBezier:
    case Form::Nurbs: break;
    }
    return std::visit(
        [&](const auto& c) -> Eigen::Matrix<double, 3, Eigen::Dynamic> {
            if constexpr (requires { c.bezierPieces(); }) return flattenPieces(c.bezierPieces(), tolerance);
            else if constexpr (requires { c.weights(); }) return flattenPieces(std::vector{c}, tolerance);
            else return Eigen::Matrix<double, 3, Eigen::Dynamic>(3, 0); // the polynomial forms: above
        },
        curve_);
}

// ---------------------------------------------------------------- AnySurface

std::optional<AnySurface> AnySurface::of(const TypedObject& object)
{
    return std::visit(
        [&](const auto& d) { return detail::kindSurface(object.geometry(), std::type_identity<std::decay_t<decltype(d)>>{}); },
        object.data());
}

std::array<double, 4> AnySurface::domain() const
{
    return std::visit(
        Overloaded{
            [](const Patches& p) -> std::array<double, 4> {
                return {0, static_cast<double>(p.segments[0]), 0, static_cast<double>(p.segments[1])};
            },
            [](const RationalBezierSurface<double, 3>&) -> std::array<double, 4> { return {0, 1, 0, 1}; },
            [](const NurbsSurface<double, 3>& s) -> std::array<double, 4> {
                return {s.knotsU().front(), s.knotsU().back(), s.knotsV().front(), s.knotsV().back()};
            },
            [](const TrimmedSurface& s) -> std::array<double, 4> {
                const Box<double, 2>& b = s.domain();
                return {b.min().x(), b.max().x(), b.min().y(), b.max().y()};
            },
        },
        surface_);
}

namespace {

/// The patch of a patch complex holding the global (u, v), and (u, v) in it.
const Patch& locate(const AnySurface::Patches& p, double& u, double& v)
{
    int index[2];
    double* t[2] = {&u, &v};
    for (int d = 0; d < 2; ++d) {
        index[d] = std::clamp(static_cast<int>(std::floor(*t[d])), 0, p.segments[d] - 1);
        *t[d] -= index[d];
    }
    return p.patches.patches[static_cast<std::size_t>(index[0] * p.segments[1] + index[1])];
}

} // namespace

Eigen::MatrixXd AnySurface::jet(double u, double v, int order) const
{
    return std::visit(
        Overloaded{
            [&](const Patches& p) -> Eigen::MatrixXd { return locate(p, u, v).jet(u, v, order); },
            [&](const RationalBezierSurface<double, 3>& s) -> Eigen::MatrixXd { return s.jet(u, v, order); },
            [&](const NurbsSurface<double, 3>& s) -> Eigen::MatrixXd { return s.jet(u, v, order); },
            [&](const TrimmedSurface& s) -> Eigen::MatrixXd {
                if (order > 1)
                    throw Error("a trimmed surface gives first derivatives only in its file's parameters, not order " +
                                std::to_string(order));
                const MappedSurface& m = s.surface();
                Eigen::MatrixXd j = m.nurbs.jet(m.mapU(u), m.mapV(v), order);
                if (order == 1) {
                    j.col(1) *= m.mapU.derivative(u);
                    j.col(2) *= m.mapV.derivative(v);
                }
                return j;
            },
        },
        surface_);
}

Eigen::Vector3d AnySurface::normal(double u, double v) const
{
    return std::visit(
        Overloaded{
            [&](const Patches& p) -> Eigen::Vector3d { return locate(p, u, v).normal(u, v); },
            [&](const auto& s) -> Eigen::Vector3d { return s.normal(u, v); },
        },
        surface_);
}

} // namespace freeform
