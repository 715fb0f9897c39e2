#pragma once
// Knot vectors and the B-spline basis (docs/nurbs.md, "Knot vectors" and "Cox-de Boor").
//
// A knot vector of degree p is a non-decreasing sequence u_0 <= ... <= u_m of finite numbers with
// m + 1 >= 2(p + 1); it carries n + 1 = m - p basis functions N_(i,p), and the curve or surface
// built on it is defined on its domain [u_p, u_(n+1)] (which must not be empty). No knot may
// appear more than p + 1 times (at p + 1 the curve may break at that knot; the ends of a clamped
// vector have exactly p + 1). Open (unclamped), clamped and periodic (uniform, with the first p
// control points repeated at the end) vectors are all accepted. Every check throws freeform::Error
// naming the knot by its index.
//
// Guarantees (tested in tests/test_nurbs_curve.cpp against a long-double Cox-de Boor recursion):
//   - findSpan(u) returns the index i in p..n with u_i <= u < u_(i+1) and u_i < u_(i+1) (u at the
//     right end of the domain gets the last non-empty span; u outside the domain is clamped);
//   - basisFunctions() computes the p+1 non-zero N_(i-p..i, p)(u) by the triangular scheme of
//     Cox-de Boor (non-negative terms only, partition of unity to rounding);
//   - basisDerivatives() computes their derivatives of orders 0..k (The NURBS Book, A2.3).

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "freeform/core/bernstein.h"
#include "freeform/core/error.h"
#include "freeform/core/format.h"

namespace freeform {

template <typename Scalar>
class KnotVector {
public:
    /// The knots of a spline in Bézier form over `breaks` (increasing): the ends with multiplicity
    /// degree + 1, every interior breakpoint with multiplicity degree.
    static std::vector<Scalar> bezierForm(const std::vector<Scalar>& breaks, int degree)
    {
        std::vector<Scalar> k(static_cast<std::size_t>(degree + 1), breaks.front());
        for (std::size_t i = 1; i + 1 < breaks.size(); ++i) k.insert(k.end(), static_cast<std::size_t>(degree), breaks[i]);
        k.insert(k.end(), static_cast<std::size_t>(degree + 1), breaks.back());
        return k;
    }

    /// Validates `knots` for `degree` (see the header comment); `what` names the owner in errors.
    KnotVector(std::vector<Scalar> knots, int degree, const std::string& what = "KnotVector")
        : knots_(std::move(knots)), degree_(degree)
    {
        requireDegree(degree, what);
        const int m = static_cast<int>(knots_.size()) - 1;
        if (m + 1 < 2 * (degree + 1))
            throw Error(what + ": " + std::to_string(knots_.size()) + " knots are too few for degree " +
                        std::to_string(degree) + " (needs at least " + std::to_string(2 * (degree + 1)) + ")");
        for (int i = 0; i <= m; ++i) {
            if (!std::isfinite(static_cast<long double>(knots_[i])))
                throw Error(what + ": knot " + std::to_string(i) + " is not finite");
            if (i > 0 && knots_[i] < knots_[i - 1])
                throw Error(what + ": knot " + std::to_string(i) + " (" + num(knots_[i]) + ") is less than knot " +
                            std::to_string(i - 1) + " (" + num(knots_[i - 1]) + "); knots must not decrease");
        }
        for (int i = 0; i <= m;) {
            int j = i;
            while (j + 1 <= m && knots_[j + 1] == knots_[i]) ++j;
            if (j - i + 1 > degree + 1)
                throw Error(what + ": knot " + std::to_string(i) + " (" + num(knots_[i]) + ") has multiplicity " +
                            std::to_string(j - i + 1) + ", more than degree + 1 = " + std::to_string(degree + 1));
            i = j + 1;
        }
        if (!(front() < back()))
            throw Error(what + ": the domain [knot " + std::to_string(degree) + ", knot " +
                        std::to_string(controlCount()) + "] is empty");
    }

    /// Clamped vector with uniform interior knots on [a, b] for `count` control points.
    static KnotVector clampedUniform(int degree, int count, Scalar a = Scalar(0), Scalar b = Scalar(1))
    {
        requireDegree(degree, "KnotVector::clampedUniform");
        if (count < degree + 1)
            throw Error("KnotVector::clampedUniform: " + std::to_string(count) + " control points are too few for degree " +
                        std::to_string(degree));
        std::vector<Scalar> k;
        const int spans = count - degree;
        for (int i = 0; i <= degree; ++i) k.push_back(a);
        for (int i = 1; i < spans; ++i) k.push_back(a + (b - a) * Scalar(i) / Scalar(spans));
        for (int i = 0; i <= degree; ++i) k.push_back(b);
        return KnotVector(std::move(k), degree, "KnotVector::clampedUniform");
    }

    /// Uniform (unclamped) vector 0, 1, ..., count + degree for `count` control points.
    static KnotVector uniform(int degree, int count)
    {
        std::vector<Scalar> k;
        for (int i = 0; i <= count + degree; ++i) k.push_back(Scalar(i));
        return KnotVector(std::move(k), degree, "KnotVector::uniform");
    }

    int degree() const { return degree_; }
    const std::vector<Scalar>& knots() const { return knots_; }
    Scalar operator[](int i) const { return knots_[static_cast<std::size_t>(i)]; }
    int size() const { return static_cast<int>(knots_.size()); }
    /// n + 1 = m - p: the number of basis functions (control points).
    int controlCount() const { return size() - degree_ - 1; }
    /// Domain [u_p, u_(n+1)].
    Scalar front() const { return knots_[static_cast<std::size_t>(degree_)]; }
    Scalar back() const { return knots_[static_cast<std::size_t>(controlCount())]; }

    /// Clamped: the first p + 1 and the last p + 1 knots are equal.
    bool isClamped() const
    {
        const int m = size() - 1;
        for (int i = 1; i <= degree_; ++i)
            if (knots_[i] != knots_[0] || knots_[m - i] != knots_[m]) return false;
        return true;
    }

    /// How often u occurs among the knots (exact comparison).
    int multiplicity(Scalar u) const
    {
        return static_cast<int>(std::count(knots_.begin(), knots_.end(), u));
    }

    /// The distinct knots inside the domain, ends included.
    std::vector<Scalar> breakpoints() const
    {
        std::vector<Scalar> out;
        for (int i = degree_; i <= controlCount(); ++i)
            if (out.empty() || knots_[i] != out.back()) out.push_back(knots_[i]);
        return out;
    }

    /// Span index i in p..n with u_i <= u < u_(i+1) (see the header comment), by bisection.
    int findSpan(Scalar u) const
    {
        const int n = controlCount() - 1;
        if (!(u < knots_[n + 1])) { // right end (and beyond, and NaN): the last non-empty span
            int i = n;
            while (knots_[i] == knots_[i + 1]) --i;
            return i;
        }
        if (u <= knots_[degree_]) {
            int i = degree_;
            while (knots_[i] == knots_[i + 1]) ++i;
            return i;
        }
        int lo = degree_, hi = n + 1;
        while (hi - lo > 1) { // knots_[lo] <= u < knots_[hi]
            const int mid = (lo + hi) / 2;
            if (u < knots_[mid]) hi = mid; else lo = mid;
        }
        return lo;
    }

    /// N_(span-p+j, p)(u) for j = 0..p into out[0..p] (The NURBS Book, A2.2).
    void basisFunctions(int span, Scalar u, Scalar* out) const
    {
        const int p = degree_;
        Scalar left[kMaxDegree + 1], right[kMaxDegree + 1];
        out[0] = Scalar(1);
        for (int j = 1; j <= p; ++j) {
            left[j] = u - knots_[span + 1 - j];
            right[j] = knots_[span + j] - u;
            Scalar saved(0);
            for (int r = 0; r < j; ++r) {
                const Scalar temp = out[r] / (right[r + 1] + left[j - r]);
                out[r] = saved + right[r + 1] * temp;
                saved = left[j - r] * temp;
            }
            out[j] = saved;
        }
    }

    /// Derivatives of orders 0..k of the p+1 non-zero basis functions at u: ders[r * (p+1) + j] is
    /// d^r/du^r N_(span-p+j, p)(u) (zero for r > p). `ders` must hold (k+1)(p+1) values.
    void basisDerivatives(int span, Scalar u, int k, Scalar* ders) const
    {
        const int p = degree_;
        const int P = p + 1;
        std::vector<Scalar> ndu(static_cast<std::size_t>(P * P)), a(static_cast<std::size_t>(2 * P));
        std::vector<Scalar> left(static_cast<std::size_t>(P)), right(static_cast<std::size_t>(P));
        auto NDU = [&](int i, int j) -> Scalar& { return ndu[static_cast<std::size_t>(i * P + j)]; };
        NDU(0, 0) = Scalar(1);
        for (int j = 1; j <= p; ++j) {
            left[j] = u - knots_[span + 1 - j];
            right[j] = knots_[span + j] - u;
            Scalar saved(0);
            for (int r = 0; r < j; ++r) {
                NDU(j, r) = right[r + 1] + left[j - r]; // lower triangle: knot differences
                const Scalar temp = NDU(r, j - 1) / NDU(j, r);
                NDU(r, j) = saved + right[r + 1] * temp; // upper triangle: basis functions
                saved = left[j - r] * temp;
            }
            NDU(j, j) = saved;
        }
        for (int j = 0; j <= p; ++j) ders[j] = NDU(j, p);
        for (int r = 1; r <= k; ++r)
            for (int j = 0; j <= p; ++j) ders[r * P + j] = Scalar(0);
        for (int r = 0; r <= p; ++r) {
            int s1 = 0, s2 = 1;
            auto A = [&](int s, int j) -> Scalar& { return a[static_cast<std::size_t>(s * P + j)]; };
            A(0, 0) = Scalar(1);
            for (int kk = 1; kk <= std::min(k, p); ++kk) {
                Scalar d(0);
                const int rk = r - kk, pk = p - kk;
                if (r >= kk) {
                    A(s2, 0) = A(s1, 0) / NDU(pk + 1, rk);
                    d = A(s2, 0) * NDU(rk, pk);
                }
                const int j1 = rk >= -1 ? 1 : -rk;
                const int j2 = (r - 1 <= pk) ? kk - 1 : p - r;
                for (int j = j1; j <= j2; ++j) {
                    A(s2, j) = (A(s1, j) - A(s1, j - 1)) / NDU(pk + 1, rk + j);
                    d += A(s2, j) * NDU(rk + j, pk);
                }
                if (r <= pk) {
                    A(s2, kk) = -A(s1, kk - 1) / NDU(pk + 1, r);
                    d += A(s2, kk) * NDU(r, pk);
                }
                ders[kk * P + r] = d;
                std::swap(s1, s2);
            }
        }
        Scalar factor = Scalar(p);
        for (int kk = 1; kk <= std::min(k, p); ++kk) {
            for (int j = 0; j <= p; ++j) ders[kk * P + j] *= factor;
            factor *= Scalar(p - kk);
        }
    }

    /// The Bézier extraction operator of knot span `span` over [a, b] = [u_span, u_(span+1)]: the
    /// (p+1) x (p+1) matrix E with Bézier point i of that span = sum_j E(i, j) P_(span-p+j). Row i
    /// is the blossom at (a^(p-i), b^i) applied to unit control points (de Boor's algorithm with a
    /// different argument at each level).
    Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> extractionOperator(int span) const
    {
        const int p = degree_;
        const Scalar a = knots_[span], b = knots_[span + 1];
        Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> e(p + 1, p + 1);
        std::vector<Eigen::Matrix<Scalar, Eigen::Dynamic, 1>> d(static_cast<std::size_t>(p + 1));
        for (int i = 0; i <= p; ++i) {
            for (int j = 0; j <= p; ++j) d[j] = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>::Unit(p + 1, j);
            for (int r = 1; r <= p; ++r) {
                const Scalar x = r - 1 < p - i ? a : b;
                for (int j = p; j >= r; --j) {
                    const int k = span - p + j;
                    const Scalar al = (x - knots_[k]) / (knots_[k + p + 1 - r] - knots_[k]);
                    d[j] = (Scalar(1) - al) * d[j - 1] + al * d[j];
                }
            }
            e.row(i) = d[p].transpose();
        }
        return e;
    }

private:
    static std::string num(Scalar x) { return formatNumber(x); }

    std::vector<Scalar> knots_;
    int degree_;
};

extern template class KnotVector<double>;
#ifndef FREEFORM_DOUBLE_ONLY_INSTANTIATIONS // float and long double (docs/development.md)
extern template class KnotVector<float>;
extern template class KnotVector<long double>;
#endif

} // namespace freeform
