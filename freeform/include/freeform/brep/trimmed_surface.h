#pragma once
// A trimmed surface: a NURBS surface (brep/exact_forms.h, in the file's parameters) and the loops
// of 2D curves in its parameter plane that bound the face (docs/cad.md, "Trimmed surfaces").
//
// The first loop is the outer boundary, the others are holes; each loop is a closed chain of
// trim curves, each traversed forward or reversed. A parameter point is classified against the
// loops by the even-odd rule on a polygon that is certified to stay within `flatness` of the
// curves: every rational Bézier piece of a trim is halved until its control points lie within
// the flatness of its chord (the piece lies in the convex hull of its control points, so then
// within the flatness of the chord too). A point farther than the flatness from that polygon lies
// on the same side of the curves as of the polygon, so its answer (Inside, Outside) is exact; a
// point within it is Boundary. The classification does not depend on the loops' orientation, so
// a file whose loops run the wrong way is still read right.

#include <vector>

#include <Eigen/Core>

#include "freeform/brep/exact_forms.h"
#include "freeform/core/types.h"

namespace freeform {

/// One trim curve of a loop: a 2D curve in the face's parameters, and the edge of the part it
/// lies on (-1 when the surface stands alone).
struct TrimCurve {
    MappedCurve<2> curve;
    bool reversed = false; // traversed from last to first
    int edge = -1;

    Eigen::Vector2d start() const { return curve.point(reversed ? curve.last : curve.first); }
    Eigen::Vector2d end() const { return curve.point(reversed ? curve.first : curve.last); }
};

struct TrimLoop {
    std::vector<TrimCurve> curves; // in traversal order
};

enum class TrimClass { Outside, Inside, Boundary };

class TrimmedSurface {
public:
    /// `domain` is the file's parameter box of the face (u0, u1, v0, v1); loops[0] is the outer
    /// loop. No loops: the whole domain. flatness <= 0: 1e-7 of the domain's diagonal.
    TrimmedSurface(MappedSurface surface, const Box<double, 2>& domain, std::vector<TrimLoop> loops,
                   double flatness = 0);

    const MappedSurface& surface() const { return surface_; }
    const Box<double, 2>& domain() const { return domain_; }
    const std::vector<TrimLoop>& loops() const { return loops_; }
    double flatness() const { return flatness_; }
    /// The certified polygon of each loop (closed: its last point joins its first).
    const std::vector<std::vector<Eigen::Vector2d>>& polygons() const { return polygons_; }

    Eigen::Vector3d point(double u, double v) const { return surface_.point(u, v); }
    Eigen::Vector3d normal(double u, double v) const { return surface_.normal(u, v); }
    TrimClass classify(const Eigen::Vector2d& uv) const;
    /// The area of the face: the integral of |P_u x P_v| over the trimmed domain, by Green's theorem
    /// in the parameter plane (docs/cad.md, "Area"): over each loop's trim curves themselves (not
    /// the polygon), of F(u, v) dv with F(u, v) the integral of |P_u x P_v| from the domain's u0 to
    /// u (a fixed 15-point Kronrod rule on two panels per knot span) by adaptive Gauss-Kronrod split
    /// at the curves' knots; the outer loop's absolute value less the holes'. `relative` is the
    /// outer quadrature's tolerance against the area of the surface's box.
    double area(double relative = 1e-10) const;
    /// A box holding the surface over its parameter box: the control box of the surface restricted
    /// to that box (the convex hull of a NURBS's control points holds it).
    Box<double, 3> bounds() const;

private:
    MappedSurface surface_;
    Box<double, 2> domain_;
    std::vector<TrimLoop> loops_;
    double flatness_ = 0;
    std::vector<std::vector<Eigen::Vector2d>> polygons_;
};

/// Appends to `out` the points of the polygon within `flatness` of the curve between its first
/// and last parameter, from its start to its end (without the start point itself).
void flattenTrim(const TrimCurve& trim, double flatness, std::vector<Eigen::Vector2d>& out);

} // namespace freeform
