// Trimmed surfaces: the certified trim polygons and the even-odd classification
// (brep/trimmed_surface.h, docs/cad.md "Trimmed surfaces").

#include "freeform/brep/trimmed_surface.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "freeform/core/error.h"

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
