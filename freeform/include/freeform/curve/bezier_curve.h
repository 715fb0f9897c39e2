#pragma once
// BezierCurve<Scalar, Dim>: f(t) = sum_{i=0..n} b_i B_i^n(t), t in [0, 1].
//
// Invariants: at least one control point, every coordinate finite, degree <= kMaxDegree. They are
// checked once, in the constructor (freeform::Error names what is wrong); everything after that is
// const and check-free. Structural operations (split, elevate, reduce, derivative, reversed,
// transformed) return new curves.
//
// Numerics: evaluate() is de Casteljau (convex combinations only, error <= ~n eps sum |b_i| B_i(t));
// bernsteinSum() is the basis sum with O(n) basis values; evaluateMany() is the batch path for
// many parameters (see curve/batch.h for how it stays as stable as de Casteljau).

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "freeform/core/bernstein.h"
#include "freeform/core/polynomial.h"
#include "freeform/core/quadrature.h"
#include "freeform/core/types.h"
#include "freeform/curve/batch.h"
#include "freeform/curve/least_squares.h"

namespace freeform {

template <typename Scalar, int Dim>
class BezierCurve {
    static_assert(Dim >= 1, "BezierCurve needs a fixed dimension of at least 1");

public:
    using PointType = Point<Scalar, Dim>;
    using Points = PointMatrix<Scalar, Dim>;
    using Linear = LinearMap<Scalar, Dim>;
    using BoxType = Box<Scalar, Dim>;

    /// Result of closestPoint().
    struct Closest {
        Scalar t;
        PointType point;
        Scalar distance;
    };

    /// Result of reduced(): the curve of one degree less and an upper bound of the distance
    /// max_t |reduced(t) - this(t)| (from the convex hull of the difference's control points).
    struct Reduction;

    /// Control points as columns (Dim x (n+1)). Throws Error if there are none, if one is not
    /// finite, or if the degree exceeds kMaxDegree.
    explicit BezierCurve(Points points) : points_(std::move(points))
    {
        if (points_.cols() < 1) throw Error("BezierCurve: needs at least one control point");
        requireDegree(static_cast<int>(points_.cols()) - 1, "BezierCurve");
        requireFinite(points_, "BezierCurve");
    }

    /// Control points from a list, e.g. BezierCurve<double,2>({{0,0},{1,2},{3,2},{4,0}}).
    BezierCurve(std::initializer_list<PointType> points) : BezierCurve(fromList(points)) {}

    int degree() const { return static_cast<int>(points_.cols()) - 1; }
    const Points& controlPoints() const { return points_; }
    PointType controlPoint(int i) const { return points_.col(i); }

    // ---------------------------------------------------------------- evaluation

    /// f(t) by de Casteljau (the default evaluator).
    PointType evaluate(Scalar t) const { return deCasteljau(t); }
    PointType operator()(Scalar t) const { return deCasteljau(t); }

    /// f(t) by the de Casteljau recursion b_i^k = (1-t) b_i^(k-1) + t b_(i+1)^(k-1).
    PointType deCasteljau(Scalar t) const
    {
        const int n = degree();
        Points w = points_;
        const Scalar s = Scalar(1) - t;
        for (int k = 1; k <= n; ++k)
            for (int i = 0; i <= n - k; ++i) w.col(i) = s * w.col(i) + t * w.col(i + 1);
        return w.col(0);
    }

    /// f(t) as sum b_i B_i^n(t), the basis values computed in O(n).
    PointType bernsteinSum(Scalar t) const
    {
        const int n = degree();
        Scalar basis[kMaxDegree + 1];
        bernsteinAll(n, t, basis);
        PointType p = PointType::Zero();
        for (int i = 0; i <= n; ++i) p += basis[i] * points_.col(i);
        return p;
    }

    /// f at every t in ts, written to out (Dim x ts.size(), resized). The batch path.
    void evaluateMany(const Scalar* ts, std::size_t count, Points& out) const
    {
        out.resize(Dim, static_cast<Eigen::Index>(count));
        evaluateBezierBatch<Scalar, Dim>(points_.data(), degree(), ts, count, out.data());
    }
    Points evaluateMany(const std::vector<Scalar>& ts) const
    {
        Points out;
        evaluateMany(ts.data(), ts.size(), out);
        return out;
    }

    /// Position and derivatives up to order k in one call: column j is f^(j)(t), j = 0..k.
    /// Orders above the degree are zero vectors. Uses one de Casteljau run: the j-th derivative is
    /// n!/(n-j)! times the j-th forward difference of the level n-j points.
    Eigen::Matrix<Scalar, Dim, Eigen::Dynamic> derivatives(Scalar t, int k) const
    {
        if (k < 0) throw Error("BezierCurve::derivatives: order " + std::to_string(k) + " is negative");
        const int n = degree();
        Eigen::Matrix<Scalar, Dim, Eigen::Dynamic> result(Dim, k + 1);
        result.setZero();
        Points w = points_;
        const Scalar s = Scalar(1) - t;
        for (int level = 0; level <= n; ++level) {
            if (level > 0)
                for (int i = 0; i <= n - level; ++i) w.col(i) = s * w.col(i) + t * w.col(i + 1);
            const int order = n - level;
            if (order > k) continue;
            // Forward differences of w.col(0..order), in place on a copy.
            Points d = w.leftCols(order + 1);
            for (int r = 1; r <= order; ++r)
                for (int i = 0; i <= order - r; ++i) d.col(i) = d.col(i + 1) - d.col(i);
            Scalar factor(1);
            for (int r = 0; r < order; ++r) factor *= Scalar(n - r);
            result.col(order) = factor * d.col(0);
        }
        return result;
    }

    /// The k-th derivative as a curve (hodograph) of degree max(n-k, 0): control points
    /// n!/(n-k)! times the k-th forward differences. For k > n the zero curve of degree 0.
    BezierCurve derivative(int k = 1) const
    {
        if (k < 0) throw Error("BezierCurve::derivative: order " + std::to_string(k) + " is negative");
        const int n = degree();
        if (k > n) return BezierCurve(Points::Zero(Dim, 1));
        Points d = points_;
        Scalar factor(1);
        for (int r = 1; r <= k; ++r) {
            for (int i = 0; i <= n - r; ++i) d.col(i) = d.col(i + 1) - d.col(i);
            factor *= Scalar(n - r + 1);
        }
        return BezierCurve(Points(factor * d.leftCols(n - k + 1)));
    }

    /// Unit tangent. Where f'(t) vanishes (coincident control points) the direction of the first
    /// non-vanishing derivative is the limit and is returned; the zero vector only for a point.
    PointType tangent(Scalar t) const
    {
        const int n = degree();
        const auto d = derivatives(t, n);
        const Scalar scale = points_.cwiseAbs().maxCoeff() + Scalar(1);
        for (int j = 1; j <= n; ++j) {
            const Scalar len = d.col(j).norm();
            if (len > std::numeric_limits<Scalar>::epsilon() * 16 * scale) return d.col(j) / len;
        }
        return PointType::Zero();
    }

    /// Curvature |f' x f''| / |f'|^3; signed in 2D ((x'y'' - y'x'') / |f'|^3, positive turning
    /// left). 0 where f' vanishes.
    Scalar curvature(Scalar t) const
    {
        const auto d = derivatives(t, 2);
        const PointType d1 = d.col(1), d2 = d.col(2);
        const Scalar speed = d1.norm();
        if (speed == Scalar(0)) return Scalar(0);
        const Scalar d1d1 = d1.squaredNorm();
        Scalar cross;
        if constexpr (Dim == 2) {
            cross = d1.x() * d2.y() - d1.y() * d2.x();
        } else {
            // |d1 x d2| in any dimension via the Gram determinant (Lagrange's identity).
            cross = std::sqrt(std::max(Scalar(0), d1d1 * d2.squaredNorm() - d1.dot(d2) * d1.dot(d2)));
        }
        return cross / (speed * speed * speed);
    }

    // ---------------------------------------------------------------- structure

    /// The curve split at t into the pieces on [0, t] and [t, 1] (edges of the de Casteljau
    /// triangle).
    std::pair<BezierCurve, BezierCurve> split(Scalar t) const
    {
        const int n = degree();
        Points w = points_, left(Dim, n + 1), right(Dim, n + 1);
        const Scalar s = Scalar(1) - t;
        left.col(0) = w.col(0);
        right.col(n) = w.col(n);
        for (int k = 1; k <= n; ++k) {
            for (int i = 0; i <= n - k; ++i) w.col(i) = s * w.col(i) + t * w.col(i + 1);
            left.col(k) = w.col(0);
            right.col(n - k) = w.col(n - k);
        }
        return {BezierCurve(std::move(left)), BezierCurve(std::move(right))};
    }

    /// The piece of the curve over [a, b] (a > b gives it reversed), reparametrised to [0, 1].
    BezierCurve segment(Scalar a, Scalar b) const
    {
        if (a > b) return segment(b, a).reversed();
        BezierCurve right = split(a).second;
        if (b >= Scalar(1) || a >= Scalar(1)) return right;
        return right.split((b - a) / (Scalar(1) - a)).first;
    }

    /// The same curve with degree n + times: b'_i = i/(n+1) b_(i-1) + (1 - i/(n+1)) b_i, repeated.
    BezierCurve elevated(int times = 1) const
    {
        if (times < 0) throw Error("BezierCurve::elevated: count " + std::to_string(times) + " is negative");
        requireDegree(degree() + times, "BezierCurve::elevated");
        Points p = points_;
        for (int r = 0; r < times; ++r) {
            const int n = static_cast<int>(p.cols()) - 1;
            Points q(Dim, n + 2);
            q.col(0) = p.col(0);
            q.col(n + 1) = p.col(n);
            for (int i = 1; i <= n; ++i) {
                const Scalar a = Scalar(i) / Scalar(n + 1);
                q.col(i) = a * p.col(i - 1) + (Scalar(1) - a) * p.col(i);
            }
            p = std::move(q);
        }
        return BezierCurve(std::move(p));
    }

    /// Degree reduction by one, keeping both end points, the interior control points chosen by
    /// least squares so that elevating the result comes closest to this curve's control points.
    /// Exact (error 0 up to rounding) when the curve is a degree-elevated curve.
    Reduction reduced() const;

    /// The same curve run backwards: g(t) = f(1 - t).
    BezierCurve reversed() const { return BezierCurve(Points(points_.rowwise().reverse())); }

    /// The image under x -> A x + b (exact: Bézier curves are affinely invariant).
    BezierCurve transformed(const Linear& a, const PointType& b = PointType::Zero()) const
    {
        return BezierCurve(Points((a * points_).colwise() + b));
    }

    // ---------------------------------------------------------------- measures

    /// Tight axis-aligned bounding box: the end points and the curve at every root of each
    /// coordinate of the hodograph.
    BoxType boundingBox() const
    {
        BoxType box(controlPoint(0));
        box.extend(controlPoint(degree()));
        if (degree() < 2) return box;
        const BezierCurve d = derivative(1);
        for (int k = 0; k < Dim; ++k) {
            std::vector<Scalar> c(d.points_.cols());
            for (Eigen::Index i = 0; i < d.points_.cols(); ++i) c[i] = d.points_(k, i);
            for (Scalar t : bernsteinPolyRoots(c)) box.extend(evaluate(t));
        }
        return box;
    }

    /// Arc length of the piece over [a, b] (default the whole curve) to the absolute tolerance.
    Scalar arcLength(Scalar tolerance = defaultTolerance(), Scalar a = Scalar(0), Scalar b = Scalar(1)) const
    {
        const BezierCurve d = derivative(1);
        return integrate<Scalar>([&](Scalar t) { return d.evaluate(t).norm(); }, a, b, tolerance);
    }

    /// The parameter t with arcLength(tol, 0, t) = length (clamped to [0, total]) to the tolerance.
    /// Newton on s(t) - length, safeguarded by bisection.
    Scalar parameterAtLength(Scalar length, Scalar tolerance = defaultTolerance()) const
    {
        const Scalar total = arcLength(tolerance / 4);
        if (length <= Scalar(0)) return Scalar(0);
        if (length >= total) return Scalar(1);
        const BezierCurve d = derivative(1);
        Scalar lo(0), hi(1), t = length / total;
        for (int iter = 0; iter < 100; ++iter) {
            const Scalar s = arcLength(tolerance / 4, Scalar(0), t) - length;
            if (std::abs(s) <= tolerance) return t;
            if (s > 0) hi = t; else lo = t;
            const Scalar speed = d.evaluate(t).norm();
            Scalar next = speed > Scalar(0) ? t - s / speed : (lo + hi) / 2;
            if (!(next > lo && next < hi)) next = (lo + hi) / 2;
            t = next;
        }
        return t;
    }

    /// The point of the curve nearest to p, globally: all roots in [0,1] of the degree 2n-1
    /// polynomial (f(t) - p) . f'(t) are found (see core/polynomial.h) and compared with the end
    /// points.
    Closest closestPoint(const PointType& p) const
    {
        const int n = degree();
        Closest best{Scalar(0), controlPoint(0), (controlPoint(0) - p).norm()};
        auto consider = [&](Scalar t) {
            const PointType q = evaluate(t);
            const Scalar dist = (q - p).norm();
            if (dist < best.distance) best = {t, q, dist};
        };
        consider(Scalar(1));
        if (n == 0) return best;
        const BezierCurve d = derivative(1);
        std::vector<Scalar> g(static_cast<std::size_t>(2 * n), Scalar(0));
        for (int k = 0; k < Dim; ++k) {
            std::vector<Scalar> a(n + 1), b(n);
            for (int i = 0; i <= n; ++i) a[i] = points_(k, i) - p[k];
            for (int i = 0; i < n; ++i) b[i] = d.points_(k, i);
            const std::vector<Scalar> prod = bernsteinPolyProduct(a, b);
            for (std::size_t i = 0; i < g.size(); ++i) g[i] += prod[i];
        }
        for (Scalar t : bernsteinPolyRoots(g)) consider(t);
        return best;
    }

    // ---------------------------------------------------------------- sampling

    /// count >= 2 points at uniform parameters t_i = i / (count - 1).
    Points sampleUniform(int count) const
    {
        if (count < 2) throw Error("BezierCurve::sampleUniform: count " + std::to_string(count) + " is below 2");
        std::vector<Scalar> ts(static_cast<std::size_t>(count));
        for (int i = 0; i < count; ++i) ts[i] = Scalar(i) / Scalar(count - 1);
        ts.back() = Scalar(1);
        return evaluateMany(ts);
    }

    /// A polyline whose every segment is within `tolerance` of the curve piece it replaces:
    /// pieces are split at 1/2 until every control point lies within tolerance of the chord (the
    /// piece lies in the convex hull of its control points, so then within tolerance of the chord).
    /// Returns the parameters (sorted, from 0 to 1); the points are evaluate(t) of each.
    std::vector<Scalar> sampleAdaptive(Scalar tolerance, int maxDepth = 30) const
    {
        if (!(tolerance > Scalar(0)))
            throw Error("BezierCurve::sampleAdaptive: tolerance must be positive");
        std::vector<Scalar> ts{Scalar(0)};
        adaptiveStep(*this, Scalar(0), Scalar(1), tolerance, maxDepth, ts);
        return ts;
    }

    static constexpr Scalar defaultTolerance()
    {
        return std::numeric_limits<Scalar>::epsilon() * Scalar(1e4);
    }

private:
    static Points fromList(std::initializer_list<PointType> list)
    {
        Points p(Dim, static_cast<Eigen::Index>(list.size()));
        Eigen::Index i = 0;
        for (const PointType& q : list) p.col(i++) = q;
        return p;
    }

    static Scalar chordDeviation(const Points& p)
    {
        const PointType a = p.col(0), b = p.col(p.cols() - 1);
        const PointType ab = b - a;
        const Scalar len2 = ab.squaredNorm();
        Scalar worst(0);
        for (Eigen::Index i = 1; i + 1 < p.cols(); ++i) {
            const PointType ap = p.col(i) - a;
            Scalar u = len2 > Scalar(0) ? ap.dot(ab) / len2 : Scalar(0);
            u = std::clamp(u, Scalar(0), Scalar(1));
            worst = std::max(worst, (ap - u * ab).norm());
        }
        return worst;
    }

    static void adaptiveStep(const BezierCurve& piece, Scalar a, Scalar b, Scalar tol, int depth,
                             std::vector<Scalar>& ts)
    {
        if (depth == 0 || chordDeviation(piece.points_) <= tol) {
            ts.push_back(b);
            return;
        }
        const auto halves = piece.split(Scalar(0.5));
        const Scalar mid = (a + b) / 2;
        adaptiveStep(halves.first, a, mid, tol, depth - 1, ts);
        adaptiveStep(halves.second, mid, b, tol, depth - 1, ts);
    }

    Points points_;
};

template <typename Scalar, int Dim>
struct BezierCurve<Scalar, Dim>::Reduction {
    BezierCurve curve;
    Scalar errorBound;
};

template <typename Scalar, int Dim>
typename BezierCurve<Scalar, Dim>::Reduction BezierCurve<Scalar, Dim>::reduced() const
{
    const int n = degree();
    if (n == 0) throw Error("BezierCurve::reduced: a curve of degree 0 cannot be reduced");
    const int m = n - 1;
    // Elevation matrix E ((n+1) x n): row i mixes c_(i-1) and c_i.
    Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> e =
        Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>::Zero(n + 1, m + 1);
    for (int i = 0; i <= n; ++i) {
        const Scalar a = Scalar(i) / Scalar(n);
        if (i >= 1) e(i, i - 1) = a;
        if (i <= m) e(i, i) = Scalar(1) - a;
    }
    Points c(Dim, m + 1);
    c.col(0) = points_.col(0);
    c.col(m) = points_.col(n);
    if (m == 0) c.col(0) = (points_.col(0) + points_.col(1)) / Scalar(2); // a line to its midpoint
    if (m >= 2) {
        // Unknowns c_1..c_(m-1); the fixed ends move to the right-hand side.
        const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> a = e.block(0, 1, n + 1, m - 1);
        Eigen::Matrix<Scalar, Eigen::Dynamic, Dim> rhs = points_.transpose();
        rhs -= e.col(0) * points_.col(0).transpose() + e.col(m) * points_.col(n).transpose();
        const Eigen::Matrix<Scalar, Eigen::Dynamic, Dim> x = detail::leastSquaresSolve<Scalar, Dim>(a, rhs);
        c.middleCols(1, m - 1) = x.transpose();
    }
    const Points diff = c * e.transpose() - points_;
    Scalar bound(0);
    for (Eigen::Index i = 0; i < diff.cols(); ++i) bound = std::max(bound, diff.col(i).norm());
    return {BezierCurve(std::move(c)), bound};
}

// Instantiated once in the library (src/curve/instantiations.cpp); user code links them.
extern template class BezierCurve<double, 2>;
extern template class BezierCurve<double, 3>;
#ifndef FREEFORM_DOUBLE_ONLY_INSTANTIATIONS // float and long double (docs/development.md)
extern template class BezierCurve<float, 2>;
extern template class BezierCurve<float, 3>;
extern template class BezierCurve<long double, 2>;
extern template class BezierCurve<long double, 3>;
#endif

} // namespace freeform
