#pragma once
// The parameter of a CAD curve or surface and the parameter of its exact NURBS form (docs/cad.md,
// "Parameters").
//
// A CAD file's circle, ellipse, cylinder, cone, sphere or torus runs on an angle; its exact NURBS
// form (a rational quadratic spline) runs on another parameter, and no rational function turns one
// into the other. A hyperbola runs on t with points cosh t, sinh t; its rational form runs on
// e^t. The trims of a face (pcurves) and the edges shared by faces are written in the file's
// parameters, so freeform keeps them there and maps the parameter once, exactly, where the NURBS
// is evaluated: point(t) = nurbs(map(t)). The map is increasing, so the point set, the
// orientation and every tangent direction are those of the NURBS.
//
//   Identity     s = t (lines, B-splines, Bézier, parabolas, planes); with a period p > 0, t is
//                first reduced into [start, start + p) (a periodic B-spline made non-periodic);
//   HalfAngle    the angle t in [start, start + spans * span] on `spans` arcs of `span` <= pi/2
//                each. Arc k has its knots at start + k * span (so s = t at every knot) and, with
//                phi = t minus the arc's middle angle and alpha = span / 2, its local parameter is
//                w = (1 + tan(phi / 2) / tan(alpha / 2)) / 2: the rational quadratic arc with
//                weights 1, cos alpha, 1 is the circle parameterised by tan(phi / 2), linearly;
//   Exponential  s = e^t (hyperbolas: cosh t = (s^2 + 1) / 2s, sinh t = (s^2 - 1) / 2s).
//
// inverse() is the map back and derivative() its slope; all are exact to a few units in the last
// place.

#include <algorithm>
#include <cmath>
#include <numbers>

namespace freeform {

struct ParameterMap {
    enum class Kind { Identity, HalfAngle, Exponential };
    Kind kind = Kind::Identity;
    double start = 0;  // HalfAngle: the first angle; Identity with a period: the period's start
    double span = 0;   // HalfAngle: the angle of one arc
    int spans = 0;     // HalfAngle: the number of arcs
    double period = 0; // Identity: > 0 reduces t into [start, start + period)

    static ParameterMap identity() { return {}; }
    static ParameterMap periodic(double start, double period) { return {Kind::Identity, start, 0, 0, period}; }
    /// The arcs for the angles [t0, t1]: as few as keep each within a quarter turn.
    static ParameterMap halfAngle(double t0, double t1)
    {
        const double quarter = std::numbers::pi / 2;
        const int n = std::max(1, static_cast<int>(std::ceil((t1 - t0) / quarter * (1 - 1e-12))));
        return {Kind::HalfAngle, t0, (t1 - t0) / n, n, 0};
    }
    static ParameterMap exponential() { return {Kind::Exponential, 0, 0, 0, 0}; }

    bool isIdentity() const { return kind == Kind::Identity && period == 0; }

    /// The NURBS parameter of the file's parameter t.
    double operator()(double t) const
    {
        switch (kind) {
        case Kind::Identity:
            if (period > 0) {
                const double r = std::fmod(t - start, period);
                return start + (r < 0 ? r + period : r);
            }
            return t;
        case Kind::HalfAngle: {
            const int k = arc(t);
            const double mid = start + (k + 0.5) * span;
            const double w = 0.5 * (1 + std::tan(0.5 * (t - mid)) / std::tan(0.25 * span));
            return start + (k + w) * span;
        }
        case Kind::Exponential:
            return std::exp(t);
        }
        return t;
    }

    /// ds/dt: the derivative of operator() (positive everywhere: the map is increasing).
    double derivative(double t) const
    {
        switch (kind) {
        case Kind::Identity:
            return 1;
        case Kind::HalfAngle: {
            const double mid = start + (arc(t) + 0.5) * span, c = std::cos(0.5 * (t - mid));
            return span / (4 * std::tan(0.25 * span) * c * c);
        }
        case Kind::Exponential:
            return std::exp(t);
        }
        return 1;
    }

    /// The file's parameter of the NURBS parameter s (the inverse of operator()).
    double inverse(double s) const
    {
        switch (kind) {
        case Kind::Identity:
            return s;
        case Kind::HalfAngle: {
            const int k = std::clamp(static_cast<int>(std::floor((s - start) / span)), 0, spans - 1);
            const double w = (s - start) / span - k;
            const double mid = start + (k + 0.5) * span;
            return mid + 2 * std::atan((2 * w - 1) * std::tan(0.25 * span));
        }
        case Kind::Exponential:
            return std::log(s);
        }
        return s;
    }

private:
    int arc(double t) const { return std::clamp(static_cast<int>(std::floor((t - start) / span)), 0, spans - 1); }
};

} // namespace freeform
