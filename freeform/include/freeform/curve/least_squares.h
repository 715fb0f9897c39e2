#pragma once
// The dense solves of the curve templates (BezierCurve::reduced, interpolateNurbs,
// approximateNurbs), compiled once in the library. Eigen's column-pivoted Householder QR and
// partial-pivoting LU, with their Householder and blocked-product kernels, are the costliest
// templates a curve instantiates. Written in the class templates, they were compiled again in
// every file that instantiates a curve, for each scalar, dimension and shape of right-hand side
// (BezierCurve<S, 4>, the homogeneous form of the rational curves in 3D, in both NURBS
// instantiation files); here they are instantiated once per scalar type and right-hand side shape
// (src/curve/least_squares.cpp). Each function is the Eigen expression it replaces, on the same
// types, so the results are the same to the bit (docs/development.md).

#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/QR>

namespace freeform::detail {

template <typename Scalar>
using DynamicMatrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

/// The least-squares solution x of a x = b (a: m x n, b: m x Cols): a.colPivHouseholderQr().solve(b).
template <typename Scalar, int Cols>
Eigen::Matrix<Scalar, Eigen::Dynamic, Cols> leastSquaresSolve(const DynamicMatrix<Scalar>& a,
                                                              const Eigen::Matrix<Scalar, Eigen::Dynamic, Cols>& b)
{
    return a.colPivHouseholderQr().solve(b);
}

/// The solution x of the square system a x = b: a.partialPivLu().solve(b).
template <typename Scalar>
DynamicMatrix<Scalar> linearSolve(const DynamicMatrix<Scalar>& a, const DynamicMatrix<Scalar>& b)
{
    return a.partialPivLu().solve(b);
}

// Instantiated once in the library (src/curve/least_squares.cpp): the fixed shapes (the curves'
// dimensions 2 and 3, and 4 for the homogeneous form of the rational curves in 3D) for every
// scalar of the curves' explicit instantiations; the dynamic ones for double, the only scalar
// interpolateNurbs and approximateNurbs are called with. Other scalars and shapes instantiate
// where they are used.
#define FREEFORM_LEAST_SQUARES_FIXED(prefix, S)                                                                  \
    prefix Eigen::Matrix<S, Eigen::Dynamic, 2> leastSquaresSolve<S, 2>(const DynamicMatrix<S>&,                  \
                                                                       const Eigen::Matrix<S, Eigen::Dynamic, 2>&); \
    prefix Eigen::Matrix<S, Eigen::Dynamic, 3> leastSquaresSolve<S, 3>(const DynamicMatrix<S>&,                  \
                                                                       const Eigen::Matrix<S, Eigen::Dynamic, 3>&); \
    prefix Eigen::Matrix<S, Eigen::Dynamic, 4> leastSquaresSolve<S, 4>(const DynamicMatrix<S>&,                  \
                                                                       const Eigen::Matrix<S, Eigen::Dynamic, 4>&);
#define FREEFORM_LEAST_SQUARES_DYNAMIC(prefix, S)                                                                \
    prefix DynamicMatrix<S> leastSquaresSolve<S, Eigen::Dynamic>(const DynamicMatrix<S>&, const DynamicMatrix<S>&); \
    prefix DynamicMatrix<S> linearSolve<S>(const DynamicMatrix<S>&, const DynamicMatrix<S>&);

FREEFORM_LEAST_SQUARES_FIXED(extern template, double)
#ifndef FREEFORM_DOUBLE_ONLY_INSTANTIATIONS // float and long double (docs/development.md)
FREEFORM_LEAST_SQUARES_FIXED(extern template, float)
FREEFORM_LEAST_SQUARES_FIXED(extern template, long double)
#endif
FREEFORM_LEAST_SQUARES_DYNAMIC(extern template, double)

} // namespace freeform::detail
