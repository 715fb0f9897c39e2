#pragma once
// BezierSurface<Scalar, Dim>: f(u,v) = sum_{i=0..m} sum_{j=0..n} b_ij B_i^m(u) B_j^n(v), (u,v) in [0,1]^2.
//
// Invariants: degrees 0..kMaxDegree in each direction, exactly (m+1)(n+1) control points, every
// coordinate finite; control point (i, j) is column i*(n+1) + j (row i runs along v). They are
// checked once, in the constructor (freeform::Error names what is wrong); everything after that is
// const and check-free. Structural operations (split, elevate, sub-patch, transform, iso-curves)
// return new objects.
//
// Evaluation: evaluate() is nested de Casteljau (the m+1 rows at v, then the resulting curve at
// u: convex combinations only); bernsteinSum() sums tabulated basis values; jet() returns the
// position and every partial derivative up to an order in one call; evaluateGrid() is the bulk
// path (basis rows and columns tabulated once, reused across the grid). normal() (3D only) is
// the unit normal (f_u x f_v)/|f_u x f_v| and, where f_u x f_v vanishes (collapsed edges and
// corners, as on the Utah teapot), its limit approached from inside the patch: never NaN, the
// zero vector only for a patch that is degenerate along the whole approach line (a curve or a
// point). The math is in docs/surfaces.md.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <queue>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "freeform/core/bernstein.h"
#include "freeform/core/types.h"
#include "freeform/curve/bezier_curve.h"

namespace freeform {

namespace detail {

/// de Casteljau in place on w[0..n]; returns w[0] at the end.
template <typename P, typename Scalar>
P deCasteljauInPlace(P* w, int n, Scalar t)
{
    const Scalar s = Scalar(1) - t;
    for (int k = 1; k <= n; ++k)
        for (int i = 0; i <= n - k; ++i) w[i] = s * w[i] + t * w[i + 1];
    return w[0];
}

/// Derivatives of orders 0..k of the Bézier curve with control points pts[0..n] at t into
/// out[0..k] (orders above n are zero). One de Casteljau run; the j-th derivative is n!/(n-j)!
/// times the j-th forward difference of the level n-j points. scratch holds 2(n+1) points.
template <typename P, typename Scalar>
void curveJet(const P* pts, int n, Scalar t, int k, P* out, P* scratch)
{
    P* w = scratch;
    P* d = scratch + (n + 1);
    for (int i = 0; i <= n; ++i) w[i] = pts[i];
    for (int j = 0; j <= k; ++j) out[j].setZero();
    const Scalar s = Scalar(1) - t;
    for (int level = 0; level <= n; ++level) {
        if (level > 0)
            for (int i = 0; i <= n - level; ++i) w[i] = s * w[i] + t * w[i + 1];
        const int order = n - level;
        if (order > k) continue;
        for (int i = 0; i <= order; ++i) d[i] = w[i];
        for (int r = 1; r <= order; ++r)
            for (int i = 0; i <= order - r; ++i) d[i] = d[i + 1] - d[i];
        Scalar factor(1);
        for (int r = 0; r < order; ++r) factor *= Scalar(n - r);
        out[order] = factor * d[0];
    }
}

} // namespace detail

template <typename Scalar, int Dim>
class BezierSurface {
    static_assert(Dim >= 1, "BezierSurface needs a fixed dimension of at least 1");

public:
    using PointType = Point<Scalar, Dim>;
    using Points = PointMatrix<Scalar, Dim>;
    using Linear = LinearMap<Scalar, Dim>;
    using BoxType = Box<Scalar, Dim>;
    using Curve = BezierCurve<Scalar, Dim>;
    /// Columns of jet(): position and partials, see jetIndex().
    using Jet = Eigen::Matrix<Scalar, Dim, Eigen::Dynamic>;

    /// Result of closestPoint().
    struct Closest {
        Scalar u, v;
        PointType point;
        Scalar distance;
    };

    /// Result of curvature(): principal curvatures k1 >= k2 with their unit directions, mean
    /// curvature (k1 + k2)/2 and Gaussian curvature k1 k2. Signs are relative to normal(u, v):
    /// positive where the surface bends towards the normal. regular is false (and everything 0)
    /// where f_u x f_v vanishes and the curvature is not defined by the parametrisation.
    struct Curvature {
        Scalar k1 = 0, k2 = 0, mean = 0, gaussian = 0;
        PointType direction1 = PointType::Zero(), direction2 = PointType::Zero();
        bool regular = false;
    };

    /// Degrees m (along u) and n (along v); points Dim x (m+1)(n+1), point (i, j) at column
    /// i*(n+1) + j. Throws Error when a degree is out of range, the count does not fit or a
    /// coordinate is not finite.
    BezierSurface(int m, int n, Points points) : m_(m), n_(n), points_(std::move(points))
    {
        requireDegree(m, "BezierSurface (degree in u)");
        requireDegree(n, "BezierSurface (degree in v)");
        const Eigen::Index expected = static_cast<Eigen::Index>(m + 1) * (n + 1);
        if (points_.cols() != expected)
            throw Error("BezierSurface: degree (" + std::to_string(m) + ", " + std::to_string(n) + ") needs " +
                        std::to_string(expected) + " control points, found " + std::to_string(points_.cols()));
        requireFinite(points_, "BezierSurface");
    }

    int degreeU() const { return m_; }
    int degreeV() const { return n_; }
    const Points& controlPoints() const { return points_; }
    PointType controlPoint(int i, int j) const { return points_.col(index(i, j)); }
    int index(int i, int j) const { return i * (n_ + 1) + j; }

    // ---------------------------------------------------------------- evaluation

    /// f(u, v) by nested de Casteljau: each row i (a curve in v) at v, then those m+1 points as a
    /// curve in u at u.
    PointType evaluate(Scalar u, Scalar v) const
    {
        std::array<PointType, kMaxDegree + 1> row, col;
        for (int i = 0; i <= m_; ++i) {
            for (int j = 0; j <= n_; ++j) row[j] = points_.col(index(i, j));
            col[i] = detail::deCasteljauInPlace(row.data(), n_, v);
        }
        return detail::deCasteljauInPlace(col.data(), m_, u);
    }
    PointType operator()(Scalar u, Scalar v) const { return evaluate(u, v); }

    /// f(u, v) as sum b_ij B_i^m(u) B_j^n(v) with the basis values tabulated in O(m + n).
    PointType bernsteinSum(Scalar u, Scalar v) const
    {
        Scalar bu[kMaxDegree + 1], bv[kMaxDegree + 1];
        bernsteinAll(m_, u, bu);
        bernsteinAll(n_, v, bv);
        PointType p = PointType::Zero();
        for (int i = 0; i <= m_; ++i) {
            PointType rowSum = PointType::Zero();
            for (int j = 0; j <= n_; ++j) rowSum += bv[j] * points_.col(index(i, j));
            p += bu[i] * rowSum;
        }
        return p;
    }

    /// The partial derivative d^a/du^a d^b/dv^b f at (u, v) (zero when a > m or b > n): the
    /// difference net m!/(m-a)! n!/(n-b)! Delta_u^a Delta_v^b b_ij evaluated by nested de Casteljau.
    PointType partial(int a, int b, Scalar u, Scalar v) const
    {
        if (a < 0 || b < 0) throw Error("BezierSurface::partial: negative derivative order");
        if (a > m_ || b > n_) return PointType::Zero();
        const int mm = m_ - a, nn = n_ - b;
        Points net = points_;
        // Differences in u (rows), then in v, in place on the (m+1) x (n+1) layout.
        for (int r = 1; r <= a; ++r)
            for (int i = 0; i <= m_ - r; ++i)
                for (int j = 0; j <= n_; ++j) net.col(index(i, j)) = net.col(index(i + 1, j)) - net.col(index(i, j));
        for (int r = 1; r <= b; ++r)
            for (int i = 0; i <= mm; ++i)
                for (int j = 0; j <= n_ - r; ++j) net.col(index(i, j)) = net.col(index(i, j + 1)) - net.col(index(i, j));
        Scalar factor(1);
        for (int r = 0; r < a; ++r) factor *= Scalar(m_ - r);
        for (int r = 0; r < b; ++r) factor *= Scalar(n_ - r);
        std::array<PointType, kMaxDegree + 1> row, col;
        for (int i = 0; i <= mm; ++i) {
            for (int j = 0; j <= nn; ++j) row[j] = net.col(index(i, j));
            col[i] = detail::deCasteljauInPlace(row.data(), nn, v);
        }
        return factor * detail::deCasteljauInPlace(col.data(), mm, u);
    }

    /// Column of jet() that holds d^a/du^a d^b/dv^b f: orders grouped by a + b, u-order first:
    /// f, f_u, f_v, f_uu, f_uv, f_vv, f_uuu, f_uuv, ...
    static int jetIndex(int a, int b)
    {
        const int k = a + b;
        return k * (k + 1) / 2 + b;
    }

    /// Position and every partial derivative of total order <= order, in one call (columns by
    /// jetIndex). One de Casteljau derivative run per row in v, then one per v-order in u.
    Jet jet(Scalar u, Scalar v, int order) const
    {
        if (order < 0) throw Error("BezierSurface::jet: order " + std::to_string(order) + " is negative");
        Jet out(Dim, (order + 1) * (order + 2) / 2);
        std::vector<PointType> rowJet(static_cast<std::size_t>((m_ + 1) * (order + 1)));
        std::vector<PointType> scratch(static_cast<std::size_t>(2 * (std::max(m_, n_) + 1)));
        std::vector<PointType> pts(static_cast<std::size_t>(std::max(m_, n_) + 1));
        std::vector<PointType> res(static_cast<std::size_t>(order + 1));
        for (int i = 0; i <= m_; ++i) {
            for (int j = 0; j <= n_; ++j) pts[j] = points_.col(index(i, j));
            detail::curveJet(pts.data(), n_, v, order, res.data(), scratch.data());
            for (int b = 0; b <= order; ++b) rowJet[static_cast<std::size_t>(i * (order + 1) + b)] = res[b];
        }
        for (int b = 0; b <= order; ++b) {
            for (int i = 0; i <= m_; ++i) pts[i] = rowJet[static_cast<std::size_t>(i * (order + 1) + b)];
            detail::curveJet(pts.data(), m_, u, order - b, res.data(), scratch.data());
            for (int a = 0; a + b <= order; ++a) out.col(jetIndex(a, b)) = res[a];
        }
        return out;
    }

    /// Positions (and, in 3D, unit normals when normals is not null) on the grid us x vs, point
    /// (iu, iv) at column iu * vs.size() + iv. The basis values and derivatives are tabulated once
    /// per row and column; normals that the fast formula cannot resolve (collapsed edges) come
    /// from normal(). See src/surface/grid.cpp for the double 3D kernel.
    void evaluateGrid(const std::vector<Scalar>& us, const std::vector<Scalar>& vs, Points& positions,
                      Points* normals = nullptr) const;

    /// Unit normal (3D): (f_u x f_v)/|f_u x f_v|, and where that vanishes its limit approached
    /// from (u, v) towards the patch centre: the first non-vanishing Taylor coefficient of
    /// f_u x f_v along that line (for a collapsed edge v = 0 this is f_uv x f_v). Zero vector only
    /// when f_u x f_v vanishes identically along the line (the patch is a curve or a point there).
    PointType normal(Scalar u, Scalar v) const
        requires(Dim == 3)
    {
        const Jet d = jet(u, v, 1);
        const PointType fu = d.col(1), fv = d.col(2);
        const PointType c = fu.cross(fv);
        const Scalar len = c.norm();
        if (!negligible(len, fu.norm() * fv.norm(), true)) return c / len;
        return limitNormal(u, v);
    }

    /// Principal, mean and Gaussian curvature from the first and second fundamental forms (3D).
    Curvature curvature(Scalar u, Scalar v) const
        requires(Dim == 3)
    {
        Curvature out;
        const Jet d = jet(u, v, 2);
        const PointType fu = d.col(1), fv = d.col(2), fuu = d.col(3), fuv = d.col(4), fvv = d.col(5);
        const PointType c = fu.cross(fv);
        const Scalar len = c.norm();
        if (negligible(len, fu.norm() * fv.norm(), true)) return out;
        const PointType nrm = c / len;
        const Scalar E = fu.dot(fu), F = fu.dot(fv), G = fv.dot(fv);
        const Scalar L = fuu.dot(nrm), M = fuv.dot(nrm), N = fvv.dot(nrm);
        const Scalar det = E * G - F * F;
        out.regular = true;
        out.gaussian = (L * N - M * M) / det;
        out.mean = (E * N - Scalar(2) * F * M + G * L) / (Scalar(2) * det);
        const Scalar disc = std::sqrt(std::max(Scalar(0), out.mean * out.mean - out.gaussian));
        out.k1 = out.mean + disc;
        out.k2 = out.mean - disc;
        // Principal directions: (II - k I) x = 0 in (du, dv); pick the better-conditioned row.
        auto direction = [&](Scalar k) {
            const Scalar a = L - k * E, b = M - k * F, cc = N - k * G;
            Scalar du, dv;
            if (std::abs(a) + std::abs(b) >= std::abs(b) + std::abs(cc)) {
                du = -b;
                dv = a;
            } else {
                du = cc;
                dv = -b;
            }
            PointType t = du * fu + dv * fv;
            const Scalar tl = t.norm();
            if (!(tl > Scalar(0))) return PointType(fu.normalized());
            return PointType(t / tl);
        };
        if (disc <= std::sqrt(std::numeric_limits<Scalar>::epsilon()) * (std::abs(out.mean) + Scalar(1e-300))) {
            // Umbilic: every direction is principal; report the orthonormal pair (f_u, n x f_u).
            out.direction1 = fu.normalized();
            out.direction2 = nrm.cross(out.direction1);
        } else {
            out.direction1 = direction(out.k1);
            out.direction2 = direction(out.k2);
        }
        return out;
    }

    // ---------------------------------------------------------------- structure

    /// The curve v -> f(u, v) (degree n): the rows evaluated at u. curveAtU(0) and curveAtU(1) are
    /// the boundary curves made of rows 0 and m.
    Curve curveAtU(Scalar u) const
    {
        Points cp(Dim, n_ + 1);
        std::array<PointType, kMaxDegree + 1> col;
        for (int j = 0; j <= n_; ++j) {
            for (int i = 0; i <= m_; ++i) col[i] = points_.col(index(i, j));
            cp.col(j) = detail::deCasteljauInPlace(col.data(), m_, u);
        }
        return Curve(std::move(cp));
    }

    /// The curve u -> f(u, v) (degree m).
    Curve curveAtV(Scalar v) const
    {
        Points cp(Dim, m_ + 1);
        std::array<PointType, kMaxDegree + 1> row;
        for (int i = 0; i <= m_; ++i) {
            for (int j = 0; j <= n_; ++j) row[j] = points_.col(index(i, j));
            cp.col(i) = detail::deCasteljauInPlace(row.data(), n_, v);
        }
        return Curve(std::move(cp));
    }

    /// The patch split at u = t into the pieces over [0, t] and [t, 1] in u (each reparametrised
    /// to [0, 1]): every column (fixed j, a curve in u) split by de Casteljau.
    std::pair<BezierSurface, BezierSurface> splitU(Scalar t) const { return split(t, true); }
    /// The same in v: every row split at v = t.
    std::pair<BezierSurface, BezierSurface> splitV(Scalar t) const { return split(t, false); }

    /// splitU(t) for 0 <= t <= 1, its first piece written into `left` and this patch becoming the
    /// second: the same points to the bit, without allocating where `left` already holds a net of
    /// this size (a grid search cuts thousands of cells, one column after the other).
    void splitOffU(Scalar t, BezierSurface& left) { splitOff(t, true, left); }
    /// The same in v.
    void splitOffV(Scalar t, BezierSurface& left) { splitOff(t, false, left); }

    /// The piece over [u0, u1] x [v0, v1] (0 <= u0 < u1 <= 1, the same in v), reparametrised.
    BezierSurface subPatch(Scalar u0, Scalar u1, Scalar v0, Scalar v1) const
    {
        if (!(Scalar(0) <= u0 && u0 < u1 && u1 <= Scalar(1) && Scalar(0) <= v0 && v0 < v1 && v1 <= Scalar(1)))
            throw Error("BezierSurface::subPatch: needs 0 <= u0 < u1 <= 1 and 0 <= v0 < v1 <= 1");
        return pieceU(u0, u1).pieceV(v0, v1);
    }

    /// The piece over [a, b] in u (0 <= a < b <= 1, unchecked), reparametrised: splitU(b)'s first
    /// piece, then that one's splitU(a / b) second (where b < 1 and a > 0), the same de Casteljau
    /// steps to the bit, without building the pieces it drops.
    BezierSurface pieceU(Scalar a, Scalar b) const { return piece(a, b, true); }
    /// The same in v.
    BezierSurface pieceV(Scalar a, Scalar b) const { return piece(a, b, false); }
    /// pieceU and pieceV written into `out` (its storage kept where it has this net's size).
    void pieceUInto(Scalar a, Scalar b, BezierSurface& out) const { pieceInto(a, b, true, out); }
    void pieceVInto(Scalar a, Scalar b, BezierSurface& out) const { pieceInto(a, b, false, out); }

    /// The same surface with degree m + times in u (every column elevated).
    BezierSurface elevatedU(int times = 1) const
    {
        if (times < 0) throw Error("BezierSurface::elevatedU: count " + std::to_string(times) + " is negative");
        requireDegree(m_ + times, "BezierSurface::elevatedU");
        const int m2 = m_ + times;
        Points out(Dim, static_cast<Eigen::Index>(m2 + 1) * (n_ + 1));
        for (int j = 0; j <= n_; ++j) {
            Points col(Dim, m_ + 1);
            for (int i = 0; i <= m_; ++i) col.col(i) = points_.col(index(i, j));
            const Points e = Curve(std::move(col)).elevated(times).controlPoints();
            for (int i = 0; i <= m2; ++i) out.col(i * (n_ + 1) + j) = e.col(i);
        }
        return BezierSurface(m2, n_, std::move(out));
    }

    /// The same surface with degree n + times in v (every row elevated).
    BezierSurface elevatedV(int times = 1) const
    {
        if (times < 0) throw Error("BezierSurface::elevatedV: count " + std::to_string(times) + " is negative");
        requireDegree(n_ + times, "BezierSurface::elevatedV");
        const int n2 = n_ + times;
        Points out(Dim, static_cast<Eigen::Index>(m_ + 1) * (n2 + 1));
        for (int i = 0; i <= m_; ++i) {
            const Points e = Curve(Points(points_.middleCols(index(i, 0), n_ + 1))).elevated(times).controlPoints();
            out.middleCols(static_cast<Eigen::Index>(i) * (n2 + 1), n2 + 1) = e;
        }
        return BezierSurface(m_, n2, std::move(out));
    }

    /// The same surface with u and v exchanged: g(u, v) = f(v, u) (normals flip in 3D).
    BezierSurface transposed() const
    {
        Points out(Dim, points_.cols());
        for (int i = 0; i <= m_; ++i)
            for (int j = 0; j <= n_; ++j) out.col(j * (m_ + 1) + i) = points_.col(index(i, j));
        return BezierSurface(n_, m_, std::move(out), Unchecked{});
    }

    /// The image under x -> A x + b (exact: the surface is affinely invariant).
    BezierSurface transformed(const Linear& a, const PointType& b = PointType::Zero()) const
    {
        return BezierSurface(m_, n_, Points((a * points_).colwise() + b));
    }

    // ---------------------------------------------------------------- measures

    /// The box of the control points: contains the surface (convex hull property).
    BoxType controlBox() const
    {
        BoxType box(PointType(points_.rowwise().minCoeff()), PointType(points_.rowwise().maxCoeff()));
        return box;
    }

    /// A box that contains the surface and lies within relativeTolerance times the control box's
    /// diagonal of the tight box, per face: branch and bound over sub-patches, each face of the
    /// box from the surface points found (lower bound) and the control boxes of the sub-patches
    /// not yet pruned (upper bound).
    BoxType boundingBox(Scalar relativeTolerance = Scalar(1e-6)) const
    {
        const BoxType hull = controlBox();
        const Scalar tol = relativeTolerance * hull.diagonal().norm();
        BoxType box(PointType(points_.col(index(0, 0))));
        box.extend(PointType(points_.col(index(m_, 0))));
        box.extend(PointType(points_.col(index(0, n_))));
        box.extend(PointType(points_.col(index(m_, n_))));
        for (int k = 0; k < Dim; ++k) {
            for (int side = 0; side < 2; ++side) {
                const Scalar sign = side == 0 ? Scalar(-1) : Scalar(1); // maximise sign * x_k
                Scalar known = sign * (side == 0 ? box.min()[k] : box.max()[k]);
                Scalar bound = known;
                std::vector<std::pair<BezierSurface, int>> stack{{*this, 0}};
                while (!stack.empty()) {
                    auto [patch, depth] = std::move(stack.back());
                    stack.pop_back();
                    const Scalar hullMax = sign > 0 ? patch.points_.row(k).maxCoeff() : -patch.points_.row(k).minCoeff();
                    if (hullMax <= known + tol) {
                        bound = std::max(bound, hullMax);
                        continue;
                    }
                    const PointType mid = patch.evaluate(Scalar(0.5), Scalar(0.5));
                    known = std::max(known, sign * mid[k]);
                    for (int c = 0; c < 4; ++c) {
                        const int i = (c & 1) ? patch.m_ : 0, j = (c & 2) ? patch.n_ : 0;
                        known = std::max(known, sign * patch.points_(k, patch.index(i, j)));
                    }
                    if (depth >= 40) {
                        bound = std::max(bound, hullMax);
                        continue;
                    }
                    auto halves = patch.splitU(Scalar(0.5));
                    for (auto* h : {&halves.first, &halves.second}) {
                        auto q = h->splitV(Scalar(0.5));
                        stack.push_back({std::move(q.first), depth + 1});
                        stack.push_back({std::move(q.second), depth + 1});
                    }
                }
                bound = std::max(bound, known);
                if (side == 0) box.min()[k] = -bound; else box.max()[k] = bound;
            }
        }
        return box;
    }

    /// The point of the surface nearest to p, globally: the exact closest points of the four
    /// boundary curves (BezierCurve::closestPoint), and for the interior a best-first search over
    /// sub-patches (the distance to a sub-patch's control box is a lower bound; a sub-patch whose
    /// bound cannot beat the best point found is pruned) with a Newton iteration on
    /// (f - p) . f_u = (f - p) . f_v = 0 started in every sub-patch visited. At most maxNodes
    /// sub-patches are visited; near points that are (almost) equidistant from a large part of
    /// the surface the search may stop there with a point whose distance exceeds the minimum by
    /// at most the gap between it and the smallest unvisited lower bound.
    Closest closestPoint(const PointType& p, int maxNodes = 4096) const
    {
        Closest best{Scalar(0), Scalar(0), PointType(points_.col(0)), (PointType(points_.col(0)) - p).norm()};
        auto consider = [&](Scalar u, Scalar v, const PointType& q) {
            const Scalar dist = (q - p).norm();
            if (dist < best.distance) best = {u, v, q, dist};
        };
        {
            const auto c0 = curveAtU(Scalar(0)).closestPoint(p), c1 = curveAtU(Scalar(1)).closestPoint(p);
            const auto c2 = curveAtV(Scalar(0)).closestPoint(p), c3 = curveAtV(Scalar(1)).closestPoint(p);
            consider(Scalar(0), c0.t, c0.point);
            consider(Scalar(1), c1.t, c1.point);
            consider(c2.t, Scalar(0), c2.point);
            consider(c3.t, Scalar(1), c3.point);
        }
        const Scalar scale = controlBox().diagonal().norm() + (p - PointType(points_.col(0))).norm();
        const Scalar tol = Scalar(64) * std::numeric_limits<Scalar>::epsilon() * scale;
        struct Node {
            Scalar lower, u0, u1, v0, v1;
            int depth;
            BezierSurface patch;
        };
        auto lowerBound = [&](const BezierSurface& s) {
            return std::sqrt(s.controlBox().squaredExteriorDistance(p));
        };
        auto cmp = [](const Node& a, const Node& b) { return a.lower > b.lower; };
        std::priority_queue<Node, std::vector<Node>, decltype(cmp)> queue(cmp);
        queue.push({lowerBound(*this), Scalar(0), Scalar(1), Scalar(0), Scalar(1), 0, *this});
        int visited = 0;
        while (!queue.empty() && visited < maxNodes) {
            Node node = queue.top();
            queue.pop();
            if (node.lower >= best.distance - tol) break;
            ++visited;
            Scalar u = (node.u0 + node.u1) / 2, v = (node.v0 + node.v1) / 2;
            newtonClosest(p, u, v);
            consider(u, v, evaluate(u, v));
            if (node.depth >= 40) continue;
            const Scalar um = (node.u0 + node.u1) / 2, vm = (node.v0 + node.v1) / 2;
            auto halves = node.patch.splitU(Scalar(0.5));
            const Scalar us[2][2] = {{node.u0, um}, {um, node.u1}};
            const BezierSurface* hs[2] = {&halves.first, &halves.second};
            for (int a = 0; a < 2; ++a) {
                auto q = hs[a]->splitV(Scalar(0.5));
                const Scalar lq = lowerBound(q.first), lr = lowerBound(q.second);
                if (lq < best.distance - tol)
                    queue.push({lq, us[a][0], us[a][1], node.v0, vm, node.depth + 1, std::move(q.first)});
                if (lr < best.distance - tol)
                    queue.push({lr, us[a][0], us[a][1], vm, node.v1, node.depth + 1, std::move(q.second)});
            }
        }
        return best;
    }

private:
    /// A patch built from another's points by convex combinations (a split at t in [0, 1]) or by
    /// reordering them (transposed): the degrees and count hold, and the coordinates stay finite
    /// (the computed 1 - t and t may sum to 1 + 2^-53, which overflows only a coordinate within a
    /// few ulps of the largest double, as evaluating such a patch would), so the public
    /// constructor's checks are skipped (they were 2% of a part's meshing).
    struct Unchecked {};
    BezierSurface(int m, int n, Points points, Unchecked) : m_(m), n_(n), points_(std::move(points)) {}

    /// pieceU (alongU) or pieceV: each line of the net along that axis cut at b (keeping the left
    /// side of the de Casteljau triangle), then at a / b (keeping the right side).
    BezierSurface piece(Scalar a, Scalar b, bool alongU) const
    {
        BezierSurface out(m_, n_, Points(Dim, points_.cols()), Unchecked{});
        pieceInto(a, b, alongU, out);
        return out;
    }
    void pieceInto(Scalar a, Scalar b, bool alongU, BezierSurface& target) const
    {
        target.m_ = m_;
        target.n_ = n_;
        Points& out = target.points_;
        out.resize(Dim, points_.cols());
        const int d = alongU ? m_ : n_, lines = alongU ? n_ : m_;
        std::array<PointType, kMaxDegree + 1> w, l;
        for (int line = 0; line <= lines; ++line) {
            auto at = [&](int k) { return alongU ? index(k, line) : index(line, k); };
            for (int k = 0; k <= d; ++k) w[k] = points_.col(at(k));
            if (b < Scalar(1)) {
                const Scalar s = Scalar(1) - b;
                l[0] = w[0];
                for (int k = 1; k <= d; ++k) {
                    for (int i = 0; i <= d - k; ++i) w[i] = s * w[i] + b * w[i + 1];
                    l[k] = w[0];
                }
            } else {
                l = w;
            }
            if (a > Scalar(0)) {
                const Scalar t = a / b, s = Scalar(1) - t;
                out.col(at(d)) = l[d];
                for (int k = 1; k <= d; ++k) {
                    for (int i = 0; i <= d - k; ++i) l[i] = s * l[i] + t * l[i + 1];
                    out.col(at(d - k)) = l[d - k];
                }
            } else {
                for (int k = 0; k <= d; ++k) out.col(at(k)) = l[k];
            }
        }
    }

    /// splitU (alongU) or splitV.
    std::pair<BezierSurface, BezierSurface> split(Scalar t, bool alongU) const
    {
        BezierSurface left(m_, n_, Points(Dim, points_.cols()), Unchecked{}), right = *this;
        right.splitOff(t, alongU, left);
        if (!(t >= Scalar(0) && t <= Scalar(1))) // extrapolated: the points may overflow
            return {BezierSurface(m_, n_, std::move(left.points_)), BezierSurface(m_, n_, std::move(right.points_))};
        return {std::move(left), std::move(right)};
    }

    /// splitOffU (alongU) or splitOffV: each line's de Casteljau triangle, its left side into
    /// `left`, its right side back into this net (the line is read before it is written).
    void splitOff(Scalar t, bool alongU, BezierSurface& left)
    {
        left.m_ = m_;
        left.n_ = n_;
        left.points_.resize(Dim, points_.cols());
        const int d = alongU ? m_ : n_, lines = alongU ? n_ : m_;
        std::array<PointType, kMaxDegree + 1> w;
        const Scalar s = Scalar(1) - t;
        for (int line = 0; line <= lines; ++line) {
            auto at = [&](int k) { return alongU ? index(k, line) : index(line, k); };
            for (int k = 0; k <= d; ++k) w[k] = points_.col(at(k));
            left.points_.col(at(0)) = w[0];
            points_.col(at(d)) = w[d];
            for (int k = 1; k <= d; ++k) {
                for (int i = 0; i <= d - k; ++i) w[i] = s * w[i] + t * w[i + 1];
                left.points_.col(at(k)) = w[0];
                points_.col(at(d - k)) = w[d - k];
            }
        }
    }

    /// Whether a computed value `value` of f_u x f_v (or a Taylor coefficient of it) counts as
    /// zero: below sqrt(eps) times the sum of the magnitudes it was formed from, or (order 0)
    /// below 64 eps times the bound on |f_u| |f_v| from the control net, which catches edges that
    /// collapse up to rounding.
    bool negligible(Scalar value, Scalar magnitude, bool orderZero) const
    {
        const Scalar eps = std::numeric_limits<Scalar>::epsilon();
        if (value <= std::sqrt(eps) * magnitude) return true;
        if (orderZero) {
            const Scalar mu = netDerivativeBound(true), mv = netDerivativeBound(false);
            if (value <= Scalar(64) * eps * mu * mv) return true;
        }
        return !(value > Scalar(0));
    }

    /// max |f_u| <= m max |b_(i+1)j - b_ij| (u) or the same in v (convex hull of the hodograph).
    Scalar netDerivativeBound(bool inU) const
    {
        Scalar worst(0);
        for (int i = 0; i <= m_; ++i)
            for (int j = 0; j <= n_; ++j) {
                if (inU && i < m_) worst = std::max(worst, (points_.col(index(i + 1, j)) - points_.col(index(i, j))).norm());
                if (!inU && j < n_) worst = std::max(worst, (points_.col(index(i, j + 1)) - points_.col(index(i, j))).norm());
            }
        return worst * Scalar(inU ? m_ : n_);
    }

    /// The limit of (f_u x f_v)/|f_u x f_v| approaching (u, v) along the line towards the patch
    /// centre: the first coefficient c_k = sum_{r+s=k} U_r x V_s that does not vanish, with U_r,
    /// V_s the Taylor coefficients of f_u and f_v along the line (directional derivatives / r!).
    PointType limitNormal(Scalar u, Scalar v) const
        requires(Dim == 3)
    {
        Scalar du = Scalar(0.5) - u, dv = Scalar(0.5) - v;
        const Scalar dl = std::sqrt(du * du + dv * dv);
        if (dl > Scalar(0)) {
            du /= dl;
            dv /= dl;
        } else {
            du = dv = std::sqrt(Scalar(0.5));
        }
        const int top = m_ + n_; // f's partials vanish above total order m + n
        const Jet d = jet(u, v, top);
        std::vector<PointType> U(static_cast<std::size_t>(top)), V(static_cast<std::size_t>(top));
        Scalar factorial(1);
        // C(r, a) by Pascal's rule in Scalar: r reaches m + n - 1, past the exact table of binomial()
        // (kMaxDegree) when the two degrees sum to more than kMaxDegree + 1.
        std::vector<Scalar> pascal(static_cast<std::size_t>(top) + 1, Scalar(0));
        pascal[0] = Scalar(1);
        for (int r = 0; r < top; ++r) {
            if (r > 0) factorial *= Scalar(r);
            for (int a = r; a > 0; --a) pascal[static_cast<std::size_t>(a)] += pascal[static_cast<std::size_t>(a - 1)];
            PointType su = PointType::Zero(), sv = PointType::Zero();
            for (int a = 0; a <= r; ++a) {
                const Scalar w = pascal[static_cast<std::size_t>(a)] * powInt(du, a) * powInt(dv, r - a);
                su += w * d.col(jetIndex(a + 1, r - a));
                sv += w * d.col(jetIndex(a, r - a + 1));
            }
            U[static_cast<std::size_t>(r)] = su / factorial;
            V[static_cast<std::size_t>(r)] = sv / factorial;
        }
        for (int k = 0; k <= 2 * (top - 1); ++k) {
            PointType c = PointType::Zero();
            Scalar magnitude(0);
            for (int r = std::max(0, k - (top - 1)); r <= std::min(k, top - 1); ++r) {
                const PointType& a = U[static_cast<std::size_t>(r)];
                const PointType& b = V[static_cast<std::size_t>(k - r)];
                c += a.cross(b);
                magnitude += a.norm() * b.norm();
            }
            const Scalar len = c.norm();
            if (!negligible(len, magnitude, k == 0)) return c / len;
        }
        return PointType::Zero();
    }

    /// Newton on g(u,v) = |f - p|^2 / 2 in [0,1]^2 (clamped), with step halving so that the
    /// distance never grows; falls back to a gradient step where the Hessian is not positive.
    void newtonClosest(const PointType& p, Scalar& u, Scalar& v) const
    {
        Scalar dist2 = (evaluate(u, v) - p).squaredNorm();
        for (int iter = 0; iter < 32; ++iter) {
            const Jet d = jet(u, v, 2);
            const PointType r = d.col(0) - p, fu = d.col(1), fv = d.col(2);
            const Scalar gu = r.dot(fu), gv = r.dot(fv);
            const Scalar huu = fu.dot(fu) + r.dot(d.col(3)), huv = fu.dot(fv) + r.dot(d.col(4)),
                         hvv = fv.dot(fv) + r.dot(d.col(5));
            const Scalar det = huu * hvv - huv * huv;
            Scalar su, sv;
            if (huu > 0 && det > 0) {
                su = -(hvv * gu - huv * gv) / det;
                sv = -(huu * gv - huv * gu) / det;
            } else {
                const Scalar h = std::max(fu.squaredNorm() + fv.squaredNorm(), std::numeric_limits<Scalar>::min());
                su = -gu / h;
                sv = -gv / h;
            }
            bool moved = false;
            for (int half = 0; half < 30; ++half) {
                const Scalar nu = std::clamp(u + su, Scalar(0), Scalar(1)), nv = std::clamp(v + sv, Scalar(0), Scalar(1));
                const Scalar nd = (evaluate(nu, nv) - p).squaredNorm();
                if (nd < dist2) {
                    moved = std::abs(nu - u) + std::abs(nv - v) > Scalar(4) * std::numeric_limits<Scalar>::epsilon();
                    u = nu;
                    v = nv;
                    dist2 = nd;
                    break;
                }
                su /= 2;
                sv /= 2;
            }
            if (!moved) break;
        }
    }

    int m_, n_;
    Points points_;
};

// Declared here, defined for double 3D in src/surface/grid.cpp (the bulk kernel).
/// Positions and unit normals of a 3D double Bézier patch on a grid: ctrl is 3 x (m+1)(n+1)
/// column-major, point (iu, iv) of the output at column iu * nv + iv. normals may be null.
/// Writes needFallback[k] = 1 where f_u x f_v was too small to normalise (|f_u x f_v| <=
/// sqrt(eps) |f_u| |f_v| or <= zeroBound; the caller resolves those with the limit formula);
/// needFallback may be null only when normals is null.
void evaluateBezierPatchGrid(const double* ctrl, int m, int n, const double* us, int nu, const double* vs, int nv,
                             double* positions, double* normals, unsigned char* needFallback, double zeroBound);

template <typename Scalar, int Dim>
void BezierSurface<Scalar, Dim>::evaluateGrid(const std::vector<Scalar>& us, const std::vector<Scalar>& vs,
                                              Points& positions, Points* normals) const
{
    const int nu = static_cast<int>(us.size()), nv = static_cast<int>(vs.size());
    positions.resize(Dim, static_cast<Eigen::Index>(nu) * nv);
    if constexpr (Dim == 3 && std::is_same_v<Scalar, double>) {
        std::vector<unsigned char> fallback;
        if (normals) {
            normals->resize(3, positions.cols());
            fallback.assign(static_cast<std::size_t>(positions.cols()), 0);
        }
        const double zeroBound = 64 * std::numeric_limits<double>::epsilon() * netDerivativeBound(true) *
                                 netDerivativeBound(false);
        evaluateBezierPatchGrid(points_.data(), m_, n_, us.data(), nu, vs.data(), nv, positions.data(),
                                normals ? normals->data() : nullptr, normals ? fallback.data() : nullptr, zeroBound);
        if (normals)
            for (int iu = 0; iu < nu; ++iu)
                for (int iv = 0; iv < nv; ++iv)
                    if (fallback[static_cast<std::size_t>(iu * nv + iv)])
                        normals->col(static_cast<Eigen::Index>(iu) * nv + iv) = limitNormal(us[iu], vs[iv]);
        return;
    } else {
        // Generic path: basis tabulated per column of v, rows combined per u.
        std::vector<Scalar> bv(static_cast<std::size_t>(nv * (n_ + 1))), dbv(bv.size());
        std::vector<Scalar> scratch(static_cast<std::size_t>(std::max(m_, n_) + 1));
        for (int iv = 0; iv < nv; ++iv) {
            bernsteinAll(n_, vs[iv], &bv[static_cast<std::size_t>(iv * (n_ + 1))]);
            bernsteinDerivativeAll(n_, 1, vs[iv], &dbv[static_cast<std::size_t>(iv * (n_ + 1))], scratch.data());
        }
        if constexpr (Dim == 3) {
            if (normals) normals->resize(3, positions.cols());
        }
        std::vector<Scalar> bu(static_cast<std::size_t>(m_ + 1)), dbu(bu.size());
        std::vector<PointType> r(static_cast<std::size_t>(n_ + 1)), q(r.size());
        for (int iu = 0; iu < nu; ++iu) {
            bernsteinAll(m_, us[iu], bu.data());
            bernsteinDerivativeAll(m_, 1, us[iu], dbu.data(), scratch.data());
            for (int j = 0; j <= n_; ++j) {
                r[j].setZero();
                q[j].setZero();
                for (int i = 0; i <= m_; ++i) {
                    r[j] += bu[i] * points_.col(index(i, j));
                    q[j] += dbu[i] * points_.col(index(i, j));
                }
            }
            for (int iv = 0; iv < nv; ++iv) {
                const Scalar* b = &bv[static_cast<std::size_t>(iv * (n_ + 1))];
                const Scalar* db = &dbv[static_cast<std::size_t>(iv * (n_ + 1))];
                PointType f = PointType::Zero(), fu = PointType::Zero(), fv = PointType::Zero();
                for (int j = 0; j <= n_; ++j) {
                    f += b[j] * r[j];
                    fu += b[j] * q[j];
                    fv += db[j] * r[j];
                }
                const Eigen::Index k = static_cast<Eigen::Index>(iu) * nv + iv;
                positions.col(k) = f;
                if constexpr (Dim == 3) {
                    if (normals) {
                        const PointType c = fu.cross(fv);
                        const Scalar len = c.norm();
                        normals->col(k) = negligible(len, fu.norm() * fv.norm(), true) ? limitNormal(us[iu], vs[iv])
                                                                                        : PointType(c / len);
                    }
                }
            }
        }
    }
}

// Instantiated once in the library (src/surface/instantiations.cpp); user code links them.
extern template class BezierSurface<double, 3>;
#ifndef FREEFORM_DOUBLE_ONLY_INSTANTIATIONS // float and long double (docs/development.md)
extern template class BezierSurface<float, 3>;
extern template class BezierSurface<long double, 3>;
#endif

} // namespace freeform
