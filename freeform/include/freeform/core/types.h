#pragma once
// Point and matrix types shared by curves, surfaces and volumes.
//
// Dimension and scalar are compile-time parameters (Geometric Tools' habit): a BezierCurve<double, 3>
// stores its control points as the columns of an Eigen matrix with 3 fixed rows.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <string>
#include <string_view>
#include <type_traits>

#include "freeform/core/error.h"

namespace freeform {

template <typename Scalar, int Dim>
using Point = Eigen::Matrix<Scalar, Dim, 1>;

/// Control points as columns: Dim x (count).
template <typename Scalar, int Dim>
using PointMatrix = Eigen::Matrix<Scalar, Dim, Eigen::Dynamic>;

template <typename Scalar, int Dim>
using LinearMap = Eigen::Matrix<Scalar, Dim, Dim>;

template <typename Scalar, int Dim>
using Box = Eigen::AlignedBox<Scalar, Dim>;

/// Throws Error("<what>: point <i> coordinate <k> is not finite") for the first non-finite entry.
/// `what` is a view: a caller's literal costs no string unless the check fails (curves are built
/// and split in the inner loops of tessellation).
template <typename Derived>
void requireFinite(const Eigen::MatrixBase<Derived>& points, std::string_view what)
{
    if constexpr (std::is_floating_point_v<typename Derived::Scalar>) {
        if (points.allFinite()) return;
    }
    for (Eigen::Index i = 0; i < points.cols(); ++i) {
        for (Eigen::Index k = 0; k < points.rows(); ++k) {
            if (!std::isfinite(static_cast<long double>(points(k, i)))) {
                throw Error(std::string(what) + ": point " + std::to_string(i) + " coordinate " +
                            std::to_string(k) + " is not finite");
            }
        }
    }
}

} // namespace freeform
