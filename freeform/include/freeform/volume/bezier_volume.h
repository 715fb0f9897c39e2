#pragma once
// BezierVolume<Scalar>: the trivariate tensor-product Bézier volume
//     f(s,t,u) = sum_i sum_j sum_k b_ijk B_i^l(s) B_j^m(t) B_k^n(u),   (s,t,u) in [0,1]^3,
// with control point (i, j, k) at column i*(m+1)*(n+1) + j*(n+1) + k of a 3 x (l+1)(m+1)(n+1)
// matrix (the order of the document's lattice points).
//
// Invariants: degrees in 0..kMaxDegree, exactly (l+1)(m+1)(n+1) control points, all finite; checked
// once in the constructor (freeform::Error names what is wrong), evaluation is const and
// check-free. Structural operations (derivative volumes, degree elevation, subdivision, affine
// images) return new volumes and are exact up to rounding: elevation and subdivision leave the map
// unchanged, the derivative volume is the tensor hodograph. Parameters outside [0,1] evaluate the
// polynomial continued (extrapolation). Math: docs/ffd.md.

#include <array>
#include <string>
#include <utility>

#include "freeform/core/bernstein.h"
#include "freeform/core/types.h"
#include "freeform/curve/bezier_curve.h"

namespace freeform {

template <typename Scalar>
class BezierVolume {
public:
    using PointType = Point<Scalar, 3>;
    using Points = PointMatrix<Scalar, 3>;
    using Matrix3 = Eigen::Matrix<Scalar, 3, 3>;

    /// Point and first partial derivatives at one parameter (one call, as users need both).
    struct Jet {
        PointType point;
        PointType ds, dt, du;
        /// [f_s f_t f_u] as columns.
        Matrix3 jacobian() const
        {
            Matrix3 j;
            j << ds, dt, du;
            return j;
        }
    };

    /// Degrees (l, m, n) and the control points (3 x (l+1)(m+1)(n+1)). Throws Error on a degree
    /// outside 0..kMaxDegree, a wrong point count or a non-finite coordinate.
    BezierVolume(int l, int m, int n, Points points) : degree_{l, m, n}, points_(std::move(points))
    {
        requireDegree(l, "BezierVolume (degree l)");
        requireDegree(m, "BezierVolume (degree m)");
        requireDegree(n, "BezierVolume (degree n)");
        const Eigen::Index expected = Eigen::Index(l + 1) * (m + 1) * (n + 1);
        if (points_.cols() != expected)
            throw Error("BezierVolume: degrees (" + std::to_string(l) + ", " + std::to_string(m) + ", " +
                        std::to_string(n) + ") need " + std::to_string(expected) + " control points, found " +
                        std::to_string(points_.cols()));
        requireFinite(points_, "BezierVolume");
    }

    int degree(int axis) const { return degree_[static_cast<std::size_t>(axis)]; }
    const std::array<int, 3>& degrees() const { return degree_; }
    int pointCount() const { return static_cast<int>(points_.cols()); }
    const Points& controlPoints() const { return points_; }

    /// Column of control point (i, j, k).
    int index(int i, int j, int k) const { return (i * (degree_[1] + 1) + j) * (degree_[2] + 1) + k; }
    PointType controlPoint(int i, int j, int k) const { return points_.col(index(i, j, k)); }

    // ---------------------------------------------------------------- evaluation

    /// f(s,t,u) by de Casteljau along u, then t, then s (convex combinations only on [0,1]^3).
    PointType evaluate(Scalar s, Scalar t, Scalar u) const
    {
        const int l = degree_[0], m = degree_[1], n = degree_[2];
        Points w = points_;
        // Collapse k: each (i, j) line to one point, stored at column i*(m+1)+j.
        Points ij(3, (l + 1) * (m + 1));
        for (int a = 0; a < (l + 1) * (m + 1); ++a) ij.col(a) = casteljau(w.middleCols(a * (n + 1), n + 1), u);
        Points iOnly(3, l + 1);
        for (int i = 0; i <= l; ++i) iOnly.col(i) = casteljau(ij.middleCols(i * (m + 1), m + 1), t);
        return casteljau(iOnly, s);
    }
    PointType operator()(Scalar s, Scalar t, Scalar u) const { return evaluate(s, t, u); }

    /// Point and the three first partial derivatives (Bernstein values and their derivatives per
    /// axis, one pass over the control points).
    Jet derivatives(Scalar s, Scalar t, Scalar u) const
    {
        const int l = degree_[0], m = degree_[1], n = degree_[2];
        Scalar bs[kMaxDegree + 1], bt[kMaxDegree + 1], bu[kMaxDegree + 1];
        Scalar ds[kMaxDegree + 1], dt[kMaxDegree + 1], du[kMaxDegree + 1], scratch[kMaxDegree + 1];
        bernsteinAll(l, s, bs);
        bernsteinAll(m, t, bt);
        bernsteinAll(n, u, bu);
        bernsteinDerivativeAll(l, 1, s, ds, scratch);
        bernsteinDerivativeAll(m, 1, t, dt, scratch);
        bernsteinDerivativeAll(n, 1, u, du, scratch);
        Jet jet{PointType::Zero(), PointType::Zero(), PointType::Zero(), PointType::Zero()};
        for (int i = 0; i <= l; ++i) {
            PointType a = PointType::Zero(), b = PointType::Zero(), c = PointType::Zero();
            for (int j = 0; j <= m; ++j) {
                PointType p = PointType::Zero(), q = PointType::Zero();
                for (int k = 0; k <= n; ++k) {
                    const PointType x = points_.col(index(i, j, k));
                    p += bu[k] * x;
                    q += du[k] * x;
                }
                a += bt[j] * p; // f without the s factor
                b += dt[j] * p; // d/dt
                c += bt[j] * q; // d/du
            }
            jet.point += bs[i] * a;
            jet.ds += ds[i] * a;
            jet.dt += bs[i] * b;
            jet.du += bs[i] * c;
        }
        return jet;
    }

    /// [f_s f_t f_u] at (s, t, u).
    Matrix3 jacobian(Scalar s, Scalar t, Scalar u) const { return derivatives(s, t, u).jacobian(); }

    // ---------------------------------------------------------------- structure

    /// The partial derivative along `axis` (0: s, 1: t, 2: u) as a volume whose degree along that
    /// axis is one less (the tensor hodograph: degree times the forward differences). A volume of
    /// degree 0 along the axis gives the zero volume of degree 0 there.
    BezierVolume derivative(int axis) const
    {
        requireAxis(axis, "BezierVolume::derivative");
        const int d = degree(axis);
        return mapLines(axis, d == 0 ? 0 : d - 1, [](const Points& line) {
            return BezierCurve<Scalar, 3>(line).derivative(1).controlPoints();
        });
    }

    /// The same map with the degree along `axis` raised by `times` (repeated degree elevation of
    /// every control-point line along that axis).
    BezierVolume elevated(int axis, int times = 1) const
    {
        requireAxis(axis, "BezierVolume::elevated");
        if (times < 0) throw Error("BezierVolume::elevated: count " + std::to_string(times) + " is negative");
        requireDegree(degree(axis) + times, "BezierVolume::elevated");
        if (times == 0) return *this;
        return mapLines(axis, degree(axis) + times, [times](const Points& line) {
            return BezierCurve<Scalar, 3>(line).elevated(times).controlPoints();
        });
    }

    /// Elevation by (dl, dm, dn) in the three directions.
    BezierVolume elevated(int dl, int dm, int dn) const { return elevated(0, dl).elevated(1, dm).elevated(2, dn); }

    /// Subdivision: the volume split at parameter `at` of `axis` into the pieces over [0, at] and
    /// [at, 1] of that parameter, each reparametrised to [0, 1] (de Casteljau on every line).
    std::pair<BezierVolume, BezierVolume> split(int axis, Scalar at) const
    {
        requireAxis(axis, "BezierVolume::split");
        auto first = mapLines(axis, degree(axis), [at](const Points& line) {
            return BezierCurve<Scalar, 3>(line).split(at).first.controlPoints();
        });
        auto second = mapLines(axis, degree(axis), [at](const Points& line) {
            return BezierCurve<Scalar, 3>(line).split(at).second.controlPoints();
        });
        return {std::move(first), std::move(second)};
    }

    /// The sub-volume over [s0,s1] x [t0,t1] x [u0,u1], reparametrised to [0,1]^3.
    BezierVolume subVolume(Scalar s0, Scalar s1, Scalar t0, Scalar t1, Scalar u0, Scalar u1) const
    {
        const Scalar lo[3] = {s0, t0, u0}, hi[3] = {s1, t1, u1};
        BezierVolume v = *this;
        for (int axis = 0; axis < 3; ++axis) {
            const Scalar a = lo[axis], b = hi[axis];
            v = v.mapLines(axis, v.degree(axis), [a, b](const Points& line) {
                return BezierCurve<Scalar, 3>(line).segment(a, b).controlPoints();
            });
        }
        return v;
    }

    /// The image under x -> A x + b (exact: Bézier volumes are affinely invariant).
    BezierVolume transformed(const Matrix3& a, const PointType& b = PointType::Zero()) const
    {
        return BezierVolume(degree_[0], degree_[1], degree_[2], Points((a * points_).colwise() + b));
    }

private:
    [[noreturn]] static void badAxis(int axis, const char* what)
    {
        throw Error(std::string(what) + ": axis " + std::to_string(axis) + " is not 0 (s), 1 (t) or 2 (u)");
    }
    static void requireAxis(int axis, const char* what)
    {
        if (axis < 0 || axis > 2) badAxis(axis, what);
    }

    static PointType casteljau(Points w, Scalar t)
    {
        const Eigen::Index n = w.cols() - 1;
        const Scalar s = Scalar(1) - t;
        for (Eigen::Index k = 1; k <= n; ++k)
            for (Eigen::Index i = 0; i <= n - k; ++i) w.col(i) = s * w.col(i) + t * w.col(i + 1);
        return w.col(0);
    }

    /// Applies `fn` (a line of degree(axis)+1 points -> a line of newDegree+1 points) to every line
    /// of control points along `axis`.
    template <typename Fn>
    BezierVolume mapLines(int axis, int newDegree, Fn&& fn) const
    {
        std::array<int, 3> nd = degree_;
        nd[static_cast<std::size_t>(axis)] = newDegree;
        const auto oldIndex = [&](int i, int j, int k) { return index(i, j, k); };
        const auto newIndex = [&](int i, int j, int k) { return (i * (nd[1] + 1) + j) * (nd[2] + 1) + k; };
        Points out(3, Eigen::Index(nd[0] + 1) * (nd[1] + 1) * (nd[2] + 1));
        const int a = (axis + 1) % 3, b = (axis + 2) % 3; // the two other axes
        const int len = degree(axis) + 1;
        Points line(3, len);
        for (int p = 0; p <= degree_[static_cast<std::size_t>(a)]; ++p) {
            for (int q = 0; q <= degree_[static_cast<std::size_t>(b)]; ++q) {
                int ijk[3] = {0, 0, 0};
                ijk[a] = p;
                ijk[b] = q;
                for (int r = 0; r < len; ++r) {
                    ijk[axis] = r;
                    line.col(r) = points_.col(oldIndex(ijk[0], ijk[1], ijk[2]));
                }
                const Points mapped = fn(line);
                for (int r = 0; r <= newDegree; ++r) {
                    ijk[axis] = r;
                    out.col(newIndex(ijk[0], ijk[1], ijk[2])) = mapped.col(r);
                }
            }
        }
        return BezierVolume(nd[0], nd[1], nd[2], std::move(out));
    }

    std::array<int, 3> degree_;
    Points points_;
};

// Instantiated once in the library (src/volume/instantiations.cpp); user code links them.
extern template class BezierVolume<double>;
#ifndef FREEFORM_DOUBLE_ONLY_INSTANTIATIONS // float and long double (docs/development.md)
extern template class BezierVolume<float>;
extern template class BezierVolume<long double>;
#endif

} // namespace freeform
