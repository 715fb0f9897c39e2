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
#include "../volume/composition.h"

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
double euclideanBound(double homogeneous, double minWeight, double radius)
{
    return homogeneous * (1 + radius) / minWeight;
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
                elevate_(i, j) = static_cast<double>(binomialWide(m, j) * binomialWide(n - m, i - j) / binomialWide(n, i));
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

using Net = Eigen::Matrix<double, 4, Eigen::Dynamic>;

/// A surface in Bézier form as its patches' homogeneous nets, of any degree (a composition above
/// kMaxDegree has no NurbsSurface): patch (a, b) over [bu[a], bu[a+1]] x [bv[b], bv[b+1]] at
/// a * nv() + b, its coefficient (i, j) at column i (dv + 1) + j. A curve is a grid of degree
/// (d, 0) with bv = {0, 1}.
struct PatchGrid {
    int du = 0, dv = 0;
    std::vector<double> bu, bv;
    std::vector<Net> patches;
    int nu() const { return static_cast<int>(bu.size()) - 1; }
    int nv() const { return static_cast<int>(bv.size()) - 1; }
};

PatchGrid gridOf(const NurbsSurface<double, 3>& s)
{
    PatchGrid g{s.degreeU(), s.degreeV(), s.knotsU().breakpoints(), s.knotsV().breakpoints(), {}};
    for (const auto& patch : s.bezierPatches()) g.patches.push_back(patch.homogeneous().controlPoints());
    return g;
}

PatchGrid gridOf(const NurbsCurve<double, 3>& c)
{
    PatchGrid g{c.degree(), 0, c.breakpoints(), {0.0, 1.0}, {}};
    for (const auto& piece : c.bezierPieces()) g.patches.push_back(piece.homogeneous().controlPoints());
    return g;
}

/// The face's surface through the lattice, patch by patch, at whatever degree that gives.
PatchGrid composedGrid(const RationalLattice& map, const NurbsSurface<double, 3>& s, double strength)
{
    PatchGrid g{0, 0, s.knotsU().breakpoints(), s.knotsV().breakpoints(), {}};
    for (const auto& patch : s.bezierPatches()) {
        // A polynomial surface's patches: the extracted points themselves, weights exactly 1.
        const detail::HomogeneousPatch p =
            s.isRational()
                ? detail::composePatch(map, patch, strength)
                : detail::composePatch(map,
                                       RationalBezierSurface<double, 3>(BezierSurface<double, 3>(
                                           patch.degreeU(), patch.degreeV(), patch.homogeneous().controlPoints().topRows<3>())),
                                       strength);
        g.du = p.du;
        g.dv = p.dv;
        g.patches.push_back(p.points);
    }
    return g;
}

PatchGrid composedGrid(const RationalLattice& map, const NurbsCurve<double, 3>& c, double strength)
{
    PatchGrid g{0, 0, c.breakpoints(), {0.0, 1.0}, {}};
    for (const auto& piece : c.bezierPieces()) {
        g.patches.push_back(detail::composePiece(map, piece, strength));
        g.du = static_cast<int>(g.patches.back().cols()) - 1;
    }
    return g;
}

bool allFinite(const PatchGrid& g)
{
    return std::all_of(g.patches.begin(), g.patches.end(), [](const Net& n) { return n.allFinite(); });
}

/// The grid with u and v exchanged.
PatchGrid transposed(const PatchGrid& g)
{
    PatchGrid t{g.dv, g.du, g.bv, g.bu, std::vector<Net>(g.patches.size())};
    for (int a = 0; a < g.nu(); ++a)
        for (int b = 0; b < g.nv(); ++b) {
            const Net& p = g.patches[static_cast<std::size_t>(a * g.nv() + b)];
            Net& q = t.patches[static_cast<std::size_t>(b * g.nu() + a)];
            q.resize(4, p.cols());
            for (int i = 0; i <= g.du; ++i)
                for (int j = 0; j <= g.dv; ++j) q.col(j * (g.du + 1) + i) = p.col(i * (g.dv + 1) + j);
        }
    return t;
}

/// Every patch cut in two at the middle of its u span (de Casteljau at 1/2, column by column).
PatchGrid halvedU(const PatchGrid& g)
{
    PatchGrid h{g.du, g.dv, {}, g.bv, {}};
    for (int a = 0; a < g.nu(); ++a) {
        h.bu.push_back(g.bu[static_cast<std::size_t>(a)]);
        h.bu.push_back(0.5 * (g.bu[static_cast<std::size_t>(a)] + g.bu[static_cast<std::size_t>(a + 1)]));
    }
    h.bu.push_back(g.bu.back());
    h.patches.resize(2 * g.patches.size());
    const int stride = g.dv + 1;
    std::vector<Eigen::Vector4d> work(static_cast<std::size_t>(g.du + 1));
    for (int a = 0; a < g.nu(); ++a)
        for (int b = 0; b < g.nv(); ++b) {
            const Net& p = g.patches[static_cast<std::size_t>(a * g.nv() + b)];
            Net& left = h.patches[static_cast<std::size_t>(2 * a * g.nv() + b)];
            Net& right = h.patches[static_cast<std::size_t>((2 * a + 1) * g.nv() + b)];
            left.resize(4, p.cols());
            right.resize(4, p.cols());
            for (int j = 0; j < stride; ++j) {
                for (int i = 0; i <= g.du; ++i) work[static_cast<std::size_t>(i)] = p.col(i * stride + j);
                // Level r of de Casteljau: its first point is the left half's r-th, its last the
                // right half's (du - r)-th.
                for (int r = 0; r <= g.du; ++r) {
                    left.col(r * stride + j) = work[0];
                    right.col((g.du - r) * stride + j) = work[static_cast<std::size_t>(g.du - r)];
                    for (int i = 0; i < g.du - r; ++i)
                        work[static_cast<std::size_t>(i)] =
                            0.5 * (work[static_cast<std::size_t>(i)] + work[static_cast<std::size_t>(i + 1)]);
                }
            }
        }
    return h;
}

/// Every patch reduced to degree m in u, row by row; `error` grows to the largest row distance.
PatchGrid reducedU(const PatchGrid& g, int m, double& error)
{
    const Reduction reduce(g.du, m);
    PatchGrid out{m, g.dv, g.bu, g.bv, {}};
    const int stride = g.dv + 1;
    Eigen::MatrixXd rows(g.du + 1, 4);
    for (const Net& p : g.patches) {
        Net q(4, (m + 1) * stride);
        for (int j = 0; j < stride; ++j) {
            for (int i = 0; i <= g.du; ++i) rows.row(i) = p.col(i * stride + j).transpose();
            const Eigen::MatrixXd c = reduce(rows, error);
            for (int i = 0; i <= m; ++i) q.col(i * stride + j) = c.row(i).transpose();
        }
        out.patches.push_back(std::move(q));
    }
    return out;
}

/// The grid's nets moved by `offset` (in homogeneous form: w offset added to w p).
void translate(PatchGrid& g, const Eigen::Vector3d& offset)
{
    for (Net& p : g.patches) p.topRows<3>() += offset * p.row(3);
}

NurbsSurface<double, 3> surfaceOf(const PatchGrid& g)
{
    return NurbsSurface<double, 3>::fromBezierPatches(g.bu, g.bv, g.du, g.dv, g.patches, "reduced surface");
}

NurbsCurve<double, 3> curveOf(const PatchGrid& g)
{
    return NurbsCurve<double, 3>::fromBezierPieces(g.bu, g.du, g.patches, "reduced curve");
}

struct ReducedGrid {
    PatchGrid grid;
    double error = 0;
};

/// The grid at degrees <= cap within `tolerance`: reduced about the centre of its control points
/// (so the bound's max|B_i/V_i| is the net's radius, not its distance from the origin), the spans
/// halved while the bound is too large. Nothing when that does not reach it; `best` then holds the
/// smallest error seen.
std::optional<ReducedGrid> reduceGrid(const PatchGrid& grid, int cap, double tolerance, int maxSplits, double& best,
                                      int& halvings)
{
    Eigen::AlignedBox3d box;
    for (const Net& p : grid.patches)
        for (Eigen::Index i = 0; i < p.cols(); ++i) box.extend(Eigen::Vector3d(p.col(i).head<3>() / p(3, i)));
    const Eigen::Vector3d centre = box.center();
    PatchGrid work = grid;
    translate(work, -centre);
    best = std::numeric_limits<double>::infinity();
    for (int split = 0;; ++split) {
        // The u pass moves the surface by at most hu, the v pass the result by at most hv: the
        // bound is their sum.
        double hu = 0, hv = 0;
        PatchGrid r = work;
        if (r.du > cap) r = reducedU(r, cap, hu);
        if (r.dv > cap) r = transposed(reducedU(transposed(r), cap, hv));
        double h = hu + hv, minWeight = std::numeric_limits<double>::infinity(), radius = 0;
        for (const Net& p : work.patches) minWeight = std::min(minWeight, p.row(3).minCoeff());
        for (const Net& p : r.patches)
            for (Eigen::Index i = 0; i < p.cols(); ++i) {
                if (!(p(3, i) > 0)) h = std::numeric_limits<double>::infinity();
                else radius = std::max(radius, (p.col(i).head<3>() / p(3, i)).norm());
            }
        const double error = std::isfinite(h) ? euclideanBound(h, minWeight, radius) : h;
        if (error <= tolerance) {
            translate(r, centre);
            return ReducedGrid{std::move(r), error};
        }
        // Halving the spans shrinks a reduction's error by a large power of 2 where the surface is
        // smooth; when it does not even halve it, more halvings only multiply the work. (A
        // reduction with a weight that is not positive has no bound: its spans are halved too.)
        halvings = split;
        if (split == maxSplits || (std::isfinite(best) && !(error < 0.5 * best))) {
            best = std::min(best, error);
            return std::nullopt;
        }
        best = error;
        if (work.du > cap) work = halvedU(work);
        if (work.dv > cap) work = transposed(halvedU(transposed(work)));
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

int degreeOf(const NurbsSurface<double, 3>& s) { return std::max(s.degreeU(), s.degreeV()); }
int degreeOf(const NurbsCurve<double, 3>& c) { return c.degree(); }
void assemble(const PatchGrid& g, NurbsSurface<double, 3>& out) { out = surfaceOf(g); }
void assemble(const PatchGrid& g, NurbsCurve<double, 3>& out) { out = curveOf(g); }

const char* const kOverflow =
    "the deformed control points are not finite (the lattice polynomial overflows this far outside its box)";

/// What deformPart does with a face's surface or an edge's curve: through the lattice (`exact`,
/// as a NURBS, where the result stays within kMaxDegree; above, patch by patch, composedGrid), then
/// reduced to `cap` where it is over it. Returns the reduction's certified error (0: exact).
template <class Nurbs, class Exact>
double composeCapped(Nurbs& nurbs, const Exact& exact, const RationalLattice& map, double strength, int factor, int cap,
                     double tolerance, int maxSplits)
{
    PatchGrid grid;
    if (degreeOf(nurbs) * factor > kMaxDegree) {
        grid = composedGrid(map, nurbs, strength);
        if (!allFinite(grid)) throw Error(kOverflow);
    } else {
        nurbs = exact(nurbs);
        if (!nurbs.homogeneousPoints().allFinite()) throw Error(kOverflow);
        if (degreeOf(nurbs) <= cap) return 0;
        grid = gridOf(nurbs);
    }
    double best = 0;
    int halvings = 0;
    const std::optional<ReducedGrid> reduced = reduceGrid(grid, cap, tolerance, maxSplits, best, halvings);
    if (!reduced)
        throw Error("degree " + std::to_string(grid.du) + (grid.dv > 0 ? " x " + std::to_string(grid.dv) : std::string()) +
                    " cannot be brought to " + std::to_string(cap) + " within " + number(tolerance) + " (" +
                    (std::isfinite(best) ? "best " + number(best) : std::string("a reduced weight is not positive")) +
                    " after " + std::to_string(halvings) + (halvings == 1 ? " halving)" : " halvings)"));
    assemble(reduced->grid, nurbs);
    return reduced->error;
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

    // A face or edge over the cap (options.maxDegree; kMaxDegree, the most the library's NURBS
    // hold, in any case) is degree reduced. A composition that would rise above kMaxDegree is
    // formed patch by patch at its own degree (detail::composePatch) and reduced from there.
    const int cap = options.maxDegree > 0 ? std::min(options.maxDegree, kMaxDegree) : kMaxDegree;
    const int factor = affine ? 1 : detail::degreeFactor(map);

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
            report.faceErrors[f] = composeCapped(
                next.nurbs,
                [&](const NurbsSurface<double, 3>& s) { return affine ? affineImage(*affine, s) : deformSurface(map, s, w); },
                map, w, factor, cap, tolerance, options.maxSplits);
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
            edgeErrors[i] = composeCapped(
                next.nurbs,
                [&](const NurbsCurve<double, 3>& c) { return affine ? affineImage(*affine, c) : deformCurve(map, c, w); },
                map, w, factor, cap, tolerance, options.maxSplits);
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
