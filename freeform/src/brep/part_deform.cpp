// Exact FFD of a part (brep/part_deform.h, docs/cad.md "Deformation").

#include "freeform/brep/part_deform.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

#include <Eigen/QR>

#include "freeform/core/bernstein.h"
#include "freeform/core/error.h"
#include "freeform/core/parallel.h"

namespace freeform {
namespace {

template <typename Points>
bool insideBox(const Lattice& lattice, const Points& points)
{
    for (Eigen::Index i = 0; i < points.cols(); ++i)
        if (!Lattice::insideBox(lattice.toLattice(points.col(i)))) return false;
    return true;
}

/// |A/W - B/V| <= H (1 + max|B_i/V_i|) / min W_i: H bounds the homogeneous difference (A, W) -
/// (B, V) over the domain, the original weights are positive, and so are the reduced ones
/// (checked by the reductions), so W >= min W_i and |B/V| <= max |B_i/V_i| (convex hulls).
template <typename Original, typename Reduced>
double euclideanBound(double homogeneous, const Original& original, const Reduced& reduced)
{
    const double minWeight = original.weights().minCoeff();
    const double radius = reduced.controlPoints().colwise().norm().maxCoeff();
    return homogeneous * (1 + radius) / minWeight;
}

/// The middle of every knot span, `times` times each.
std::vector<double> spanMiddles(const std::vector<double>& breaks, int times)
{
    std::vector<double> out;
    for (std::size_t k = 0; k + 1 < breaks.size(); ++k)
        for (int r = 0; r < times; ++r) out.push_back(0.5 * (breaks[k] + breaks[k + 1]));
    return out;
}

/// The face's NURBS cut down (by knot insertion, the parameters kept) to the face's parameter box
/// where the file's surface is larger (a B-spline surface the face uses a part of), so that less
/// is composed and the box test sees only the face. Periodic maps are left alone.
NurbsSurface<double, 3> cutToFaceBox(const MappedSurface& s, const Box<double, 2>& domain)
{
    NurbsSurface<double, 3> n = s.nurbs;
    if (s.mapU.period == 0) {
        const double a = std::max(s.mapU(domain.min().x()), n.knotsU().front());
        const double b = std::min(s.mapU(domain.max().x()), n.knotsU().back());
        if (a < b && (a > n.knotsU().front() || b < n.knotsU().back())) n = n.restrictedU(a, b);
    }
    if (s.mapV.period == 0) {
        const double a = std::max(s.mapV(domain.min().y()), n.knotsV().front());
        const double b = std::min(s.mapV(domain.max().y()), n.knotsV().back());
        if (a < b && (a > n.knotsV().front() || b < n.knotsV().back())) n = n.restrictedV(a, b);
    }
    return n;
}

/// Least-squares degree reduction n -> m of Bézier coefficients (rows), the end coefficients
/// kept: the interior ones minimise |E c - p| with E the elevation matrix from m to n, one QR
/// for every row set of the same degrees. The error is certified after the fact:
/// max_i |(E c)_i - p_i| bounds the difference of the two curves (both of degree n then, and
/// Bernstein polynomials sum to 1).
class Reduction {
public:
    Reduction(int n, int m) : n_(n), m_(m), elevate_(n + 1, m + 1)
    {
        elevate_.setZero();
        for (int i = 0; i <= n; ++i)
            for (int j = std::max(0, i - (n - m)); j <= std::min(m, i); ++j)
                elevate_(i, j) = double(binomial(m, j)) * double(binomial(n - m, i - j)) / double(binomial(n, i));
        if (m >= 2) qr_.compute(elevate_.middleCols(1, m - 1));
    }

    /// The reduced rows of p ((n+1) x k); `error` grows to the largest row distance.
    Eigen::MatrixXd operator()(const Eigen::MatrixXd& p, double& error) const
    {
        Eigen::MatrixXd c(m_ + 1, p.cols());
        c.row(0) = p.row(0);
        c.row(m_) = p.row(n_);
        if (m_ >= 2) {
            const Eigen::MatrixXd rhs = p - elevate_.col(0) * p.row(0) - elevate_.col(m_) * p.row(n_);
            c.middleRows(1, m_ - 1) = qr_.solve(rhs);
        }
        error = std::max(error, (elevate_ * c - p).rowwise().norm().maxCoeff());
        return c;
    }

private:
    int n_, m_;
    Eigen::MatrixXd elevate_;
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr_;
};

/// The knot vector with every interior breakpoint at full multiplicity p (Bézier form).
std::vector<double> bezierKnots(const std::vector<double>& breaks, int p)
{
    std::vector<double> k(static_cast<std::size_t>(p + 1), breaks.front());
    for (std::size_t i = 1; i + 1 < breaks.size(); ++i) k.insert(k.end(), static_cast<std::size_t>(p), breaks[i]);
    k.insert(k.end(), static_cast<std::size_t>(p + 1), breaks.back());
    return k;
}

/// Knots to insert so that every interior breakpoint has multiplicity p.
std::vector<double> missingKnots(const KnotVector<double>& knots)
{
    std::vector<double> extra;
    const std::vector<double> br = knots.breakpoints();
    for (std::size_t i = 1; i + 1 < br.size(); ++i)
        for (int r = knots.multiplicity(br[i]); r < knots.degree(); ++r) extra.push_back(br[i]);
    return extra;
}

/// The homogeneous net reduced to degree m in u, piece by piece (the net in Bézier form in u).
NurbsSurface<double, 3> reduceU(const NurbsSurface<double, 3>& s, int m, double& error)
{
    const int n = s.degreeU(), nv = s.countV();
    const std::vector<double> br = s.knotsU().breakpoints();
    const int pieces = static_cast<int>(br.size()) - 1;
    const Reduction reduce(n, m);
    const auto& h = s.homogeneousPoints();
    Eigen::Matrix<double, 4, Eigen::Dynamic> out(4, (pieces * m + 1) * nv);
    Eigen::MatrixXd rows(n + 1, 4);
    for (int j = 0; j < nv; ++j)
        for (int k = 0; k < pieces; ++k) {
            for (int i = 0; i <= n; ++i) rows.row(i) = h.col(s.index(k * n + i, j)).transpose();
            const Eigen::MatrixXd c = reduce(rows, error);
            for (int i = 0; i <= m; ++i) out.col((k * m + i) * nv + j) = c.row(i).transpose();
        }
    return NurbsSurface<double, 3>(KnotVector<double>(bezierKnots(br, m), m, "reduced surface"), s.knotsV(), std::move(out));
}

struct ReducedSurface {
    NurbsSurface<double, 3> surface;
    double error = 0;
};

/// The surface at degrees <= cap within `tolerance`: reduced about the centre of its control box
/// (so the bound's max|B_i/V_i| is the net's radius, not its distance from the origin), the spans
/// halved (full multiplicity, so the pieces are reduced separately) while the bound is too large.
/// Nothing when that does not reach it; `best` then holds the smallest error seen.
std::optional<ReducedSurface> reduceSurface(const NurbsSurface<double, 3>& surface, int cap, double tolerance,
                                            int maxSplits, double& best)
{
    const Eigen::Vector3d centre = surface.controlBox().center();
    NurbsSurface<double, 3> work(surface.knotsU(), surface.knotsV(), surface.controlPoints().colwise() - centre,
                                 surface.weights());
    work = work.refinedU(missingKnots(work.knotsU())).refinedV(missingKnots(work.knotsV()));
    best = std::numeric_limits<double>::infinity();
    for (int split = 0;; ++split) {
        // The u pass moves the surface by at most hu, the v pass the result by at most hv: the
        // bound is their sum.
        double hu = 0, hv = 0;
        NurbsSurface<double, 3> r = work;
        if (r.degreeU() > cap) r = reduceU(r, cap, hu);
        if (r.degreeV() > cap) r = reduceU(r.transposed(), cap, hv).transposed();
        double h = hu + hv;
        for (Eigen::Index i = 0; i < r.homogeneousPoints().cols(); ++i)
            if (!(r.homogeneousPoints()(3, i) > 0)) h = std::numeric_limits<double>::infinity();
        const double error = std::isfinite(h) ? euclideanBound(h, work, r) : h;
        if (error <= tolerance)
            return ReducedSurface{NurbsSurface<double, 3>(r.knotsU(), r.knotsV(), r.controlPoints().colwise() + centre,
                                                          r.weights()),
                                  error};
        // Halving the spans shrinks a reduction's error by a large power of 2 where the surface is
        // smooth; when it does not even halve it, more halvings only multiply the work.
        if (split == maxSplits || !(error < 0.5 * best)) {
            best = std::min(best, error);
            return std::nullopt;
        }
        best = error;
        if (work.degreeU() > cap) work = work.refinedU(spanMiddles(work.knotsU().breakpoints(), work.degreeU()));
        if (work.degreeV() > cap) work = work.refinedV(spanMiddles(work.knotsV().breakpoints(), work.degreeV()));
    }
}

struct ReducedCurve {
    NurbsCurve<double, 3> curve;
    double error = 0;
};

std::optional<ReducedCurve> reduceCurve(const NurbsCurve<double, 3>& curve, int cap, double tolerance, int maxSplits,
                                        double& best)
{
    const Eigen::Vector3d centre = curve.controlBox().center();
    NurbsCurve<double, 3> work(curve.degree(), curve.knots(), curve.controlPoints().colwise() - centre,
                               curve.weights());
    work = work.refined(missingKnots(work.knotVector()));
    best = std::numeric_limits<double>::infinity();
    for (int split = 0;; ++split) {
        const int n = work.degree();
        const std::vector<double> br = work.breakpoints();
        const int pieces = static_cast<int>(br.size()) - 1;
        const Reduction reduce(n, cap);
        Eigen::Matrix<double, 4, Eigen::Dynamic> out(4, pieces * cap + 1);
        double h = 0;
        for (int k = 0; k < pieces; ++k) {
            const Eigen::MatrixXd c = reduce(work.homogeneousPoints().middleCols(k * n, n + 1).transpose(), h);
            out.middleCols(k * cap, cap + 1) = c.transpose();
        }
        bool positive = true;
        for (Eigen::Index i = 0; i < out.cols(); ++i) positive = positive && out(3, i) > 0;
        std::optional<NurbsCurve<double, 3>> r;
        if (positive) r.emplace(KnotVector<double>(bezierKnots(br, cap), cap, "reduced curve"), out);
        const double error = r ? euclideanBound(h, work, *r) : std::numeric_limits<double>::infinity();
        if (error <= tolerance)
            return ReducedCurve{NurbsCurve<double, 3>(cap, r->knots(), r->controlPoints().colwise() + centre,
                                                      r->weights()),
                                error};
        if (split == maxSplits || !(error < 0.5 * best)) {
            best = std::min(best, error);
            return std::nullopt;
        }
        best = error;
        work = work.refined(spanMiddles(br, n));
    }
}

NurbsSurface<double, 3> affineImage(const AffineMap& map, const NurbsSurface<double, 3>& s)
{
    const Eigen::Matrix<double, 3, Eigen::Dynamic> p = (map.linear * s.controlPoints()).colwise() + map.offset;
    return NurbsSurface<double, 3>(s.knotsU(), s.knotsV(), p, s.weights());
}

NurbsCurve<double, 3> affineImage(const AffineMap& map, const NurbsCurve<double, 3>& c)
{
    const Eigen::Matrix<double, 3, Eigen::Dynamic> p = (map.linear * c.controlPoints()).colwise() + map.offset;
    return NurbsCurve<double, 3>(c.degree(), c.knots(), p, c.weights());
}

/// The largest |J| of a rational lattice's map at 9^3 points of its box (not a bound).
double sampledLipschitz(const RationalLattice& lattice, double strength)
{
    double largest = 1;
    for (int i = 0; i <= 8; ++i)
        for (int j = 0; j <= 8; ++j)
            for (int k = 0; k <= 8; ++k) {
                const Eigen::Vector3d p = lattice.lattice().toWorld(Eigen::Vector3d(i / 8.0, j / 8.0, k / 8.0));
                const Eigen::Matrix3d J = lattice.deform(p, strength).jacobian;
                largest = std::max(largest, J.norm()); // Frobenius: >= the operator norm
            }
    return largest;
}

std::string number(double x)
{
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.3g", x);
    return buffer;
}

} // namespace

DeformedPart deformPart(const Part& part, const RationalLattice& lattice, const PartDeformOptions& options)
{
    const double w = options.strength;
    if (!std::isfinite(w)) throw Error("deformPart: the strength is not finite");
    // The compositions continue the lattice polynomial beyond the box; the vertices go the same way.
    Lattice continued = lattice.lattice();
    continued.setOutside(OutsidePolicy::Extrapolate);
    const RationalLattice map(continued, lattice.weights());
    const bool extrapolate = lattice.lattice().outside() == OutsidePolicy::Extrapolate;
    const std::optional<AffineMap> affine =
        lattice.isPolynomial() ? affineMap(lattice.lattice(), w) : std::optional<AffineMap>();
    double tolerance = options.tolerance;
    if (!(tolerance > 0)) tolerance = 1e-6 * part.bounds().diagonal().norm();

    DeformedPart out;
    PartDeformReport& report = out.report;
    report.faces = static_cast<int>(part.faces.size());
    report.affine = affine.has_value();
    report.lipschitzCertified = lattice.isPolynomial();
    report.lipschitz = report.lipschitzCertified ? lipschitzBound(lattice.lattice(), w) : sampledLipschitz(map, w);
    report.faceErrors.assign(part.faces.size(), 0.0);

    // Faces and edges are independent: composed in parallel, errors collected per item.
    std::vector<std::optional<MappedSurface>> surfaces(part.faces.size());
    std::vector<std::string> faceErrors(part.faces.size());
    std::vector<char> faceOutside(part.faces.size(), 0);
    auto composeFace = [&](std::size_t f) {
        const PartFace& face = part.faces[f];
        try {
            MappedSurface next = face.surface.surface();
            next.nurbs = cutToFaceBox(next, face.surface.domain());
            faceOutside[f] = !extrapolate && !insideBox(lattice.lattice(), next.nurbs.controlPoints());
            next.nurbs = affine ? affineImage(*affine, next.nurbs) : deformSurface(map, next.nurbs, w);
            if (!next.nurbs.homogeneousPoints().allFinite())
                throw Error("the deformed control points are not finite (the lattice polynomial overflows this far "
                            "outside its box)");
            if (options.maxDegree > 0 && std::max(next.nurbs.degreeU(), next.nurbs.degreeV()) > options.maxDegree) {
                double best = 0;
                auto reduced = reduceSurface(next.nurbs, options.maxDegree, tolerance, options.maxSplits, best);
                if (!reduced)
                    throw Error("degree " + std::to_string(next.nurbs.degreeU()) + " x " +
                                std::to_string(next.nurbs.degreeV()) + " cannot be brought to " +
                                std::to_string(options.maxDegree) + " within " + number(tolerance) + " (best " +
                                number(best) + " after " + std::to_string(options.maxSplits) + " halvings)");
                next.nurbs = std::move(reduced->surface);
                report.faceErrors[f] = reduced->error;
            }
            surfaces[f] = std::move(next);
        } catch (const Error& e) {
            faceErrors[f] = "face " + std::to_string(f + 1) + ": " + e.what();
        }
    };
    parallelFor(0, part.faces.size(), 1, options.threads, [&](int, std::size_t begin, std::size_t end) {
        for (std::size_t f = begin; f < end; ++f) composeFace(f);
    });
    for (const std::string& e : faceErrors)
        if (!e.empty()) throw Error(e);

    std::vector<std::optional<MappedCurve<3>>> curves(part.edges.size());
    std::vector<double> edgeErrors(part.edges.size(), 0.0);
    std::vector<std::string> edgeFailures(part.edges.size());
    auto composeEdge = [&](std::size_t i) {
        const PartEdge& edge = part.edges[i];
        if (!edge.curve) return;
        try {
            MappedCurve<3> next = *edge.curve;
            next.nurbs = affine ? affineImage(*affine, edge.curve->nurbs) : deformCurve(map, edge.curve->nurbs, w);
            if (!next.nurbs.homogeneousPoints().allFinite())
                throw Error("the deformed control points are not finite (the lattice polynomial overflows this far "
                            "outside its box)");
            if (options.maxDegree > 0 && next.nurbs.degree() > options.maxDegree) {
                double best = 0;
                auto reduced = reduceCurve(next.nurbs, options.maxDegree, tolerance, options.maxSplits, best);
                if (!reduced)
                    throw Error("degree " + std::to_string(next.nurbs.degree()) + " cannot be brought to " +
                                std::to_string(options.maxDegree) + " within " + number(tolerance) + " (best " +
                                number(best) + ")");
                next.nurbs = std::move(reduced->curve);
                edgeErrors[i] = reduced->error;
            }
            curves[i] = std::move(next);
        } catch (const Error& e) {
            edgeFailures[i] = "edge " + std::to_string(i + 1) + ": " + e.what();
        }
    };
    parallelFor(0, part.edges.size(), 1, options.threads, [&](int, std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) composeEdge(i);
    });
    for (const std::string& e : edgeFailures)
        if (!e.empty()) throw Error(e);

    Part& result = out.part;
    result.units = part.units;
    result.shells = part.shells;
    result.solids = part.solids;
    const double L = report.lipschitz;
    double largest = 0;
    for (std::size_t f = 0; f < part.faces.size(); ++f) {
        const PartFace& face = part.faces[f];
        const TrimmedSurface& t = face.surface;
        // What the face is now: an affine map keeps a plane a plane; any other image is a B-spline
        // surface (a cylinder under a non-uniform scale is no cylinder).
        const std::string kind = report.affine && face.surfaceKind == "plane" ? "plane" : "bspline";
        result.faces.push_back({TrimmedSurface(std::move(*surfaces[f]), t.domain(), t.loops(), t.flatness()),
                                face.reversed, kind, L * face.tolerance + report.faceErrors[f]});
        if (report.faceErrors[f] > 0) report.approximatedFaces.push_back(static_cast<int>(f));
        if (faceOutside[f]) ++report.outsideFaces;
        if (report.faceErrors[f] == 0 && !faceOutside[f]) ++report.exactFaces;
        largest = std::max(largest, report.faceErrors[f]);
    }
    // An edge's tolerance grows by L, and by its own approximation error and its faces'.
    std::vector<double> edgeSlack = edgeErrors;
    for (std::size_t f = 0; f < part.faces.size(); ++f)
        for (const TrimLoop& loop : part.faces[f].surface.loops())
            for (const TrimCurve& c : loop.curves)
                if (c.edge >= 0) {
                    const auto e = static_cast<std::size_t>(c.edge);
                    edgeSlack[e] = std::max(edgeSlack[e], edgeErrors[e] + report.faceErrors[f]);
                }
    for (std::size_t i = 0; i < part.edges.size(); ++i) {
        PartEdge edge = part.edges[i];
        edge.curve = std::move(curves[i]);
        edge.tolerance = L * edge.tolerance + edgeSlack[i];
        if (edgeErrors[i] > 0) ++report.approximatedEdges;
        largest = std::max(largest, edgeErrors[i]);
        report.maxTolerance = std::max(report.maxTolerance, edge.tolerance);
        result.edges.push_back(std::move(edge));
    }
    report.maxApproximationError = largest;
    for (const PartVertex& v : part.vertices) {
        const Eigen::Vector3d p = affine ? Eigen::Vector3d(affine->linear * v.point + affine->offset)
                                         : map.deform(v.point, w).point;
        if (!p.allFinite()) throw Error("deformPart: a vertex moves to a point that is not finite");
        result.vertices.push_back({p, L * v.tolerance + largest});
    }
    report.maxDegree = result.maxDegree();
    report.maxGap = checkPart(result).maxGap;
    return out;
}

} // namespace freeform
