// Trimmed surfaces: the certified trim polygons and the even-odd classification
// (brep/trimmed_surface.h, docs/cad.md "Trimmed surfaces").

#include "freeform/brep/trimmed_surface.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "freeform/core/error.h"
#include "freeform/core/quadrature.h"

namespace freeform {
namespace {

using Piece = RationalBezierCurve<double, 2>;

/// Largest distance of the piece's control points from the chord of its end points.
double chordDeviation(const Piece& piece)
{
    const int n = piece.degree();
    const Eigen::Vector2d a = piece.controlPoint(0), b = piece.controlPoint(n), d = b - a;
    const double len = d.norm();
    double worst = 0;
    for (int i = 1; i < n; ++i) {
        const Eigen::Vector2d q = piece.controlPoint(i) - a;
        // Distance to the segment (not the line): a control point beyond an end counts in full.
        const double t = len > 0 ? std::clamp(q.dot(d) / (len * len), 0.0, 1.0) : 0.0;
        worst = std::max(worst, (q - t * d).norm());
    }
    return worst;
}

void flattenPiece(const Piece& piece, double flatness, int depth, std::vector<Eigen::Vector2d>& out)
{
    if (depth >= 40 || chordDeviation(piece) <= flatness) {
        out.push_back(piece.controlPoint(piece.degree()));
        return;
    }
    const auto [left, right] = piece.split(0.5);
    flattenPiece(left, flatness, depth + 1, out);
    flattenPiece(right, flatness, depth + 1, out);
}

double segmentDistance2(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b)
{
    const Eigen::Vector2d d = b - a, q = p - a;
    const double l2 = d.squaredNorm();
    const double t = l2 > 0 ? std::clamp(q.dot(d) / l2, 0.0, 1.0) : 0.0;
    return (q - t * d).squaredNorm();
}

} // namespace

void flattenTrim(const TrimCurve& trim, double flatness, std::vector<Eigen::Vector2d>& out)
{
    std::vector<Eigen::Vector2d> pts;
    for (const Piece& piece : trim.curve.nurbs.bezierPieces()) flattenPiece(piece, flatness, 0, pts);
    if (!trim.reversed) {
        out.insert(out.end(), pts.begin(), pts.end());
        return;
    }
    // Reversed: from the end back to the start (the start is the curve's first point).
    for (auto it = pts.rbegin() + 1; it != pts.rend(); ++it) out.push_back(*it);
    out.push_back(trim.curve.nurbs.evaluate(trim.curve.nurbs.domainStart()));
}

TrimmedSurface::TrimmedSurface(MappedSurface surface, const Box<double, 2>& domain, std::vector<TrimLoop> loops,
                               double flatness)
    : surface_(std::move(surface)), domain_(domain), loops_(std::move(loops)), flatness_(flatness)
{
    if (domain_.isEmpty()) throw Error("TrimmedSurface: the parameter domain is empty");
    if (!(flatness_ > 0)) flatness_ = 1e-7 * domain_.diagonal().norm();
    for (std::size_t l = 0; l < loops_.size(); ++l) {
        const TrimLoop& loop = loops_[l];
        if (loop.curves.empty()) throw Error("TrimmedSurface: loop " + std::to_string(l) + " has no curves");
        std::vector<Eigen::Vector2d> poly{loop.curves.front().start()};
        // Each curve from its start; the step from one curve's end to the next one's start (a gap
        // within the file's tolerance) is a segment of the polygon too, so the polygon is closed.
        for (const TrimCurve& c : loop.curves) {
            if (poly.empty() || (poly.back() - c.start()).norm() > 0) poly.push_back(c.start());
            flattenTrim(c, flatness_, poly);
        }
        polygons_.push_back(std::move(poly));
    }
}

TrimClass TrimmedSurface::classify(const Eigen::Vector2d& uv) const
{
    if (polygons_.empty()) {
        const Box<double, 2> inner(domain_.min().array() + flatness_, domain_.max().array() - flatness_);
        if (inner.contains(uv)) return TrimClass::Inside;
        const Box<double, 2> outer(domain_.min().array() - flatness_, domain_.max().array() + flatness_);
        return outer.contains(uv) ? TrimClass::Boundary : TrimClass::Outside;
    }
    bool inside = false;
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& poly : polygons_) {
        const std::size_t n = poly.size();
        for (std::size_t i = 0; i < n; ++i) {
            const Eigen::Vector2d& a = poly[i];
            const Eigen::Vector2d& b = poly[(i + 1) % n];
            nearest = std::min(nearest, segmentDistance2(uv, a, b));
            // Even-odd: the ray from uv towards +u crosses the segment (half-open in v).
            if ((a.y() > uv.y()) != (b.y() > uv.y())) {
                const double x = a.x() + (uv.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
                if (x > uv.x()) inside = !inside;
            }
        }
    }
    if (nearest <= flatness_ * flatness_ * 4) return TrimClass::Boundary;
    return inside ? TrimClass::Inside : TrimClass::Outside;
}

namespace {

/// The file's parameters of a curve's or a direction's knots inside (a, b), with a and b: the
/// pieces an adaptive quadrature integrates one by one (the integrand is smooth inside each).
std::vector<double> breakpoints(const std::vector<double>& knots, const ParameterMap& map, double a, double b)
{
    std::vector<double> out{a};
    for (double k : knots) {
        const double t = map.inverse(k);
        if (t > out.back() && t < b) out.push_back(t);
    }
    out.push_back(b);
    return out;
}

/// The 15-point Kronrod rule on [a, b] split into `panels`: a fixed rule, so that the inner
/// integral F(u, v) of area() is a smooth function of (u, v), which the outer adaptive rule needs
/// (an adaptive inner rule's error jumps from one (u, v) to the next, and the outer rule then
/// never meets its tolerance).
template <typename F>
double fixedKronrod(const F& f, double a, double b, int panels)
{
    double sum = 0;
    const double width = (b - a) / panels;
    for (int p = 0; p < panels; ++p) {
        const double lo = a + p * width, half = width / 2, centre = lo + half;
        double s = double(detail::kKronrodWeights[7]) * f(centre);
        for (int i = 0; i < 7; ++i) {
            const double dx = half * double(detail::kGkNodes[i]);
            s += double(detail::kKronrodWeights[i]) * (f(centre - dx) + f(centre + dx));
        }
        sum += s * half;
    }
    return sum;
}

} // namespace

double TrimmedSurface::area(double relative) const
{
    const MappedSurface& S = surface_;
    const Box<double, 3> box = bounds();
    const Eigen::Vector3d d = box.diagonal();
    const double scale = std::max({d.x() * d.y(), d.y() * d.z(), d.z() * d.x(), 1e-300});
    const double tol = relative * scale;
    const std::vector<double>& uKnots = S.nurbs.knotsU().knots();
    const double u0 = domain_.min().x();
    // |P_u x P_v| in the file's parameters: the NURBS's area element times both maps' slopes.
    auto element = [&](double u, double v) {
        const auto jet = S.nurbs.jet(S.mapU(u), S.mapV(v), 1);
        return Eigen::Vector3d(jet.col(1)).cross(Eigen::Vector3d(jet.col(2))).norm() * S.mapU.derivative(u) *
               S.mapV.derivative(v);
    };
    // F(u, v): the integral of the element along u from u0 to u. (Along v for surfaces with more
    // knots in u was slower on linkrods.step's B-spline faces: 14.9 s for the part against 5.9 s.)
    auto F = [&](double u, double v) {
        if (u == u0) return 0.0;
        const std::vector<double> cuts = breakpoints(uKnots, S.mapU, std::min(u0, u), std::max(u0, u));
        double sum = 0;
        for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
            sum += fixedKronrod([&](double x) { return element(x, v); }, cuts[i], cuts[i + 1], 2);
        return u > u0 ? sum : -sum;
    };
    if (loops_.empty()) {
        // The whole box: only the side u = u1 of its boundary has F dv != 0.
        const double u1 = domain_.max().x();
        const std::vector<double> cuts =
            breakpoints(S.nurbs.knotsV().knots(), S.mapV, domain_.min().y(), domain_.max().y());
        double sum = 0;
        for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
            sum += integrate<double>([&](double v) { return F(u1, v); }, cuts[i], cuts[i + 1], tol);
        return sum;
    }
    double total = 0;
    for (std::size_t l = 0; l < loops_.size(); ++l) {
        double loop = 0;
        for (const TrimCurve& trim : loops_[l].curves) {
            const MappedCurve<2>& c = trim.curve;
            // F(c(t)) c_v'(t) over the curve's own pieces, in the file's parameter.
            auto integrand = [&](double t) {
                const auto jet = c.nurbs.derivatives(c.map(t), 1);
                return F(jet(0, 0), jet(1, 0)) * jet(1, 1) * c.map.derivative(t);
            };
            const std::vector<double> cuts = breakpoints(c.nurbs.knots(), c.map, c.first, c.last);
            double sum = 0;
            for (std::size_t i = 0; i + 1 < cuts.size(); ++i) sum += integrate<double>(integrand, cuts[i], cuts[i + 1], tol);
            loop += trim.reversed ? -sum : sum;
        }
        total += l == 0 ? std::abs(loop) : -std::abs(loop);
    }
    return total;
}

Box<double, 3> TrimmedSurface::bounds() const
{
    // The control box of the surface restricted to the face's parameter box (a periodic map whose
    // box wraps around keeps that direction whole).
    NurbsSurface<double, 3> s = surface_.nurbs;
    const double a0 = surface_.mapU(domain_.min().x()), a1 = surface_.mapU(domain_.max().x());
    const double b0 = surface_.mapV(domain_.min().y()), b1 = surface_.mapV(domain_.max().y());
    if (a0 < a1) s = s.restrictedU(a0, a1);
    if (b0 < b1) s = s.restrictedV(b0, b1);
    return s.controlBox();
}

} // namespace freeform
