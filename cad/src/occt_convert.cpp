// Open CASCADE geometry into exact NURBS forms (occt_convert.h, docs/cad.md "Exact forms").

#include "occt_convert.h"

#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_BezierCurve.hxx>
#include <Geom2d_Circle.hxx>
#include <Geom2d_Ellipse.hxx>
#include <Geom2d_Hyperbola.hxx>
#include <Geom2d_Line.hxx>
#include <Geom2d_Parabola.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_BezierCurve.hxx>
#include <Geom_BezierSurface.hxx>
#include <Geom_Circle.hxx>
#include <Geom_ConicalSurface.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_Ellipse.hxx>
#include <Geom_Hyperbola.hxx>
#include <Geom_Line.hxx>
#include <Geom_Parabola.hxx>
#include <Geom_Plane.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_SphericalSurface.hxx>
#include <Geom_SurfaceOfLinearExtrusion.hxx>
#include <Geom_SurfaceOfRevolution.hxx>
#include <Geom_ToroidalSurface.hxx>
#include <Geom_TrimmedCurve.hxx>

#include "freeform/core/error.h"

namespace freeform::occt {
namespace {

Eigen::Vector3d vec(const gp_XYZ& p) { return {p.X(), p.Y(), p.Z()}; }
Eigen::Vector3d vec(const gp_Pnt& p) { return vec(p.XYZ()); }
Eigen::Vector3d vec(const gp_Dir& d) { return vec(d.XYZ()); }
Eigen::Vector2d vec(const gp_Pnt2d& p) { return {p.X(), p.Y()}; }
Eigen::Vector2d vec(const gp_Dir2d& d) { return {d.X(), d.Y()}; }

/// A B-spline or Bézier curve of either dimension: its poles, weights and flat knots, made
/// non-periodic (a periodic curve keeps its parameter through a periodic map).
template <int Dim, typename BSpline>
MappedCurve<Dim> fromBSpline(const Handle(BSpline)& source, double f, double l)
{
    Handle(BSpline) c = Handle(BSpline)::DownCast(source->Copy());
    ParameterMap map;
    if (c->IsPeriodic()) {
        const double start = c->FirstParameter(), period = c->Period();
        c->SetNotPeriodic();
        map = ParameterMap::periodic(start, period);
    }
    const int n = c->NbPoles();
    PointMatrix<double, Dim> p(Dim, n);
    Eigen::VectorXd w(n);
    for (int i = 1; i <= n; ++i) {
        p.col(i - 1) = vec(c->Pole(i));
        w[i - 1] = c->Weight(i);
    }
    std::vector<double> knots;
    const TColStd_Array1OfReal& seq = c->KnotSequence();
    for (int i = seq.Lower(); i <= seq.Upper(); ++i) knots.push_back(seq(i));
    return exactRestriction<Dim>(NurbsCurve<double, Dim>(c->Degree(), std::move(knots), p, w), map, f, l);
}

template <int Dim, typename Bezier>
MappedCurve<Dim> fromBezier(const Handle(Bezier)& c, double f, double l)
{
    const int n = c->NbPoles();
    PointMatrix<double, Dim> p(Dim, n);
    Eigen::VectorXd w(n);
    for (int i = 1; i <= n; ++i) {
        p.col(i - 1) = vec(c->Pole(i));
        w[i - 1] = c->Weight(i);
    }
    std::vector<double> knots(static_cast<std::size_t>(n), 0.0);
    knots.resize(static_cast<std::size_t>(2 * n), 1.0);
    return exactRestriction<Dim>(NurbsCurve<double, Dim>(n - 1, std::move(knots), p, w), ParameterMap::identity(), f, l);
}

std::string typeName(const Handle(Standard_Transient)& t) { return t->DynamicType()->Name(); }

/// Open CASCADE's curve classes of one dimension: Geom_* in 3D, Geom2d_* in 2D. Their conics have
/// the same members (Position() with Location, XDirection, YDirection; Radius, MajorRadius,
/// MinorRadius, Focal), so one conversion serves both.
struct Curves3 {
    using Curve = Geom_Curve;
    using Trimmed = Geom_TrimmedCurve;
    using Line = Geom_Line;
    using Circle = Geom_Circle;
    using Ellipse = Geom_Ellipse;
    using Hyperbola = Geom_Hyperbola;
    using Parabola = Geom_Parabola;
    using BSpline = Geom_BSplineCurve;
    using Bezier = Geom_BezierCurve;
    static constexpr const char* what = "a curve";
};
struct Curves2 {
    using Curve = Geom2d_Curve;
    using Trimmed = Geom2d_TrimmedCurve;
    using Line = Geom2d_Line;
    using Circle = Geom2d_Circle;
    using Ellipse = Geom2d_Ellipse;
    using Hyperbola = Geom2d_Hyperbola;
    using Parabola = Geom2d_Parabola;
    using BSpline = Geom2d_BSplineCurve;
    using Bezier = Geom2d_BezierCurve;
    static constexpr const char* what = "a trim curve";
};

template <int Dim, typename C>
MappedCurve<Dim> exactAnyCurve(const Handle(typename C::Curve)& curve, double f, double l)
{
    if (auto t = Handle(typename C::Trimmed)::DownCast(curve)) return exactAnyCurve<Dim, C>(t->BasisCurve(), f, l);
    if (auto c = Handle(typename C::Line)::DownCast(curve))
        return exactLine<Dim>(vec(c->Position().Location()), vec(c->Position().Direction()), f, l);
    if (auto c = Handle(typename C::Circle)::DownCast(curve)) {
        const auto& a = c->Position();
        return exactEllipse<Dim>(vec(a.Location()), vec(a.XDirection()), vec(a.YDirection()), c->Radius(), c->Radius(), f, l);
    }
    if (auto c = Handle(typename C::Ellipse)::DownCast(curve)) {
        const auto& a = c->Position();
        return exactEllipse<Dim>(vec(a.Location()), vec(a.XDirection()), vec(a.YDirection()), c->MajorRadius(),
                                 c->MinorRadius(), f, l);
    }
    if (auto c = Handle(typename C::Hyperbola)::DownCast(curve)) {
        const auto& a = c->Position();
        return exactHyperbola<Dim>(vec(a.Location()), vec(a.XDirection()), vec(a.YDirection()), c->MajorRadius(),
                                   c->MinorRadius(), f, l);
    }
    if (auto c = Handle(typename C::Parabola)::DownCast(curve)) {
        const auto& a = c->Position();
        return exactParabola<Dim>(vec(a.Location()), vec(a.XDirection()), vec(a.YDirection()), c->Focal(), f, l);
    }
    if (auto c = Handle(typename C::BSpline)::DownCast(curve)) return fromBSpline<Dim>(c, f, l);
    if (auto c = Handle(typename C::Bezier)::DownCast(curve)) return fromBezier<Dim>(c, f, l);
    throw Error(std::string(C::what) + " of kind " + typeName(curve) + " has no exact rational form freeform reads");
}

} // namespace

MappedCurve<3> exactCurve(const Handle(Geom_Curve)& curve, double f, double l)
{
    return exactAnyCurve<3, Curves3>(curve, f, l);
}

MappedCurve<2> exactCurve2d(const Handle(Geom2d_Curve)& curve, double f, double l)
{
    return exactAnyCurve<2, Curves2>(curve, f, l);
}

std::pair<MappedSurface, std::string> exactSurface(const Handle(Geom_Surface)& surface, double u0, double u1, double v0,
                                                   double v1)
{
    if (auto t = Handle(Geom_RectangularTrimmedSurface)::DownCast(surface))
        return exactSurface(t->BasisSurface(), u0, u1, v0, v1);
    if (auto s = Handle(Geom_Plane)::DownCast(surface)) {
        const gp_Ax3& a = s->Position();
        return {exactPlane(vec(a.Location()), vec(a.XDirection()), vec(a.YDirection()), u0, u1, v0, v1), "plane"};
    }
    // The elementary surfaces of revolution: a meridian in the plane of X and the axis Z, turned
    // about X x Y (which is -Z in a left-handed frame, where Y = -(Z x X)).
    auto revolve = [&](const gp_Ax3& a, const MappedCurve<3>& meridian) {
        const Eigen::Vector3d X = vec(a.XDirection()), Y = vec(a.YDirection());
        return exactRevolution(meridian, vec(a.Location()), X.cross(Y), u0, u1);
    };
    if (auto s = Handle(Geom_CylindricalSurface)::DownCast(surface)) {
        const gp_Ax3& a = s->Position();
        const Eigen::Vector3d O = vec(a.Location()), X = vec(a.XDirection()), Z = vec(a.Direction());
        return {revolve(a, exactLine<3>(O + s->Radius() * X, Z, v0, v1)), "cylinder"};
    }
    if (auto s = Handle(Geom_ConicalSurface)::DownCast(surface)) {
        const gp_Ax3& a = s->Position();
        const Eigen::Vector3d O = vec(a.Location()), X = vec(a.XDirection()), Z = vec(a.Direction());
        const double ang = s->SemiAngle();
        return {revolve(a, exactLine<3>(O + s->RefRadius() * X, std::sin(ang) * X + std::cos(ang) * Z, v0, v1)), "cone"};
    }
    if (auto s = Handle(Geom_SphericalSurface)::DownCast(surface)) {
        const gp_Ax3& a = s->Position();
        const Eigen::Vector3d O = vec(a.Location()), X = vec(a.XDirection()), Z = vec(a.Direction());
        return {revolve(a, exactEllipse<3>(O, X, Z, s->Radius(), s->Radius(), v0, v1)), "sphere"};
    }
    if (auto s = Handle(Geom_ToroidalSurface)::DownCast(surface)) {
        const gp_Ax3& a = s->Position();
        const Eigen::Vector3d O = vec(a.Location()), X = vec(a.XDirection()), Z = vec(a.Direction());
        const double R = s->MajorRadius(), r = s->MinorRadius();
        return {revolve(a, exactEllipse<3>(O + R * X, X, Z, r, r, v0, v1)), "torus"};
    }
    if (auto s = Handle(Geom_SurfaceOfRevolution)::DownCast(surface)) {
        const gp_Ax1 axis = s->Axis();
        return {exactRevolution(exactCurve(s->BasisCurve(), v0, v1), vec(axis.Location()), vec(axis.Direction()), u0, u1),
                "revolution"};
    }
    if (auto s = Handle(Geom_SurfaceOfLinearExtrusion)::DownCast(surface))
        return {exactExtrusion(exactCurve(s->BasisCurve(), u0, u1), vec(s->Direction()), v0, v1), "extrusion"};
    if (auto src = Handle(Geom_BSplineSurface)::DownCast(surface)) {
        Handle(Geom_BSplineSurface) s = Handle(Geom_BSplineSurface)::DownCast(src->Copy());
        ParameterMap mapU, mapV;
        // A face whose range straddles the start of a periodic direction's period (Open CASCADE
        // reads a closed B-spline that freeform wrote as periodic, its origin where the file's
        // knots start) gets the period started at its range's start: a knot inserted there (the
        // same surface) and made the origin. A range inside the period stays as it is.
        auto startAt = [&](bool alongU, double lo, double hi) {
            double a0, a1, b0, b1;
            s->Bounds(a0, a1, b0, b1);
            const double first = alongU ? a0 : b0, period = alongU ? s->UPeriod() : s->VPeriod();
            const double slack = 1e-9 * period;
            if ((lo >= first - slack && hi <= first + period + slack) || hi - lo > period + slack) return;
            double at = first + std::fmod(lo - first, period);
            if (at < first) at += period;
            const double tol = 1e-12 * period;
            if (alongU) s->InsertUKnot(at, 1, tol, false);
            else s->InsertVKnot(at, 1, tol, false);
            const int n = alongU ? s->NbUKnots() : s->NbVKnots();
            for (int k = 1; k <= n; ++k)
                if (std::abs((alongU ? s->UKnot(k) : s->VKnot(k)) - at) <= tol) {
                    if (alongU) s->SetUOrigin(k);
                    else s->SetVOrigin(k);
                    return;
                }
        };
        if (s->IsUPeriodic()) startAt(true, u0, u1);
        if (s->IsVPeriodic()) startAt(false, v0, v1);
        double a0, a1, b0, b1;
        s->Bounds(a0, a1, b0, b1);
        if (s->IsUPeriodic()) {
            mapU = ParameterMap::periodic(a0, s->UPeriod());
            s->SetUNotPeriodic();
        }
        if (s->IsVPeriodic()) {
            mapV = ParameterMap::periodic(b0, s->VPeriod());
            s->SetVNotPeriodic();
        }
        const int nu = s->NbUPoles(), nv = s->NbVPoles();
        PointMatrix<double, 3> p(3, nu * nv);
        Eigen::VectorXd w(nu * nv);
        for (int i = 1; i <= nu; ++i)
            for (int j = 1; j <= nv; ++j) {
                p.col((i - 1) * nv + j - 1) = vec(s->Pole(i, j));
                w[(i - 1) * nv + j - 1] = s->Weight(i, j);
            }
        auto flat = [](const TColStd_Array1OfReal& seq) {
            std::vector<double> k;
            for (int i = seq.Lower(); i <= seq.Upper(); ++i) k.push_back(seq(i));
            return k;
        };
        return {{NurbsSurface<double, 3>(s->UDegree(), s->VDegree(), flat(s->UKnotSequence()), flat(s->VKnotSequence()), p, w),
                 mapU, mapV},
                "bspline"};
    }
    if (auto s = Handle(Geom_BezierSurface)::DownCast(surface)) {
        const int nu = s->NbUPoles(), nv = s->NbVPoles();
        PointMatrix<double, 3> p(3, nu * nv);
        Eigen::VectorXd w(nu * nv);
        for (int i = 1; i <= nu; ++i)
            for (int j = 1; j <= nv; ++j) {
                p.col((i - 1) * nv + j - 1) = vec(s->Pole(i, j));
                w[(i - 1) * nv + j - 1] = s->Weight(i, j);
            }
        auto clamped = [](int n) {
            std::vector<double> k(static_cast<std::size_t>(n), 0.0);
            k.resize(static_cast<std::size_t>(2 * n), 1.0);
            return k;
        };
        return {{NurbsSurface<double, 3>(nu - 1, nv - 1, clamped(nu), clamped(nv), p, w), {}, {}}, "bezier"};
    }
    throw Error("a surface of kind " + typeName(surface) + " has no exact rational form freeform reads");
}

} // namespace freeform::occt
