#pragma once
// The quartic triangular Bézier nets of the certified tessellation of Loop cages
// (certified_tessellation_loop.cpp; docs/subdivision.md, "Loop cages"), defined in loop_bezier.cpp
// with the public part (freeform/subdivision/loop_bezier.h). Private to src/subdivision/ (never
// installed).

#include <Eigen/Core>

#include <array>

namespace freeform::detail::loop {

/// A quartic triangular Bézier net: b[j][k] is the point of multi-index (4 - j - k, j, k), i.e.
/// weight (1-s-t)^i s^j t^k in the local coordinates (s, t) of the cell's corners 0, 1, 2.
using Net = std::array<std::array<Eigen::Vector3d, 5>, 5>;

/// The quartic box spline of OpenSubdiv's LOOP patch (its 12 points in the patch table's order) in
/// Bézier form, times 24: row (j, k) in the order j = 0..4, k = 0..4-j. Derived by evaluating
/// OpenSubdiv's Loop basis at the 15 domain points (j/4, k/4) and solving (docs/subdivision.md,
/// "Loop cages"); every row is non-negative and sums to 24. tests/test_subdivision_tessellation_loop.cpp
/// checks it against OpenSubdiv's patch evaluation.
inline constexpr int kLoopToBezier[15][12] = {
    {2, 2, 0, 2, 12, 2, 0, 2, 2, 0, 0, 0},  {0, 1, 0, 1, 12, 3, 0, 3, 4, 0, 0, 0}, {0, 0, 0, 0, 8, 4, 0, 4, 8, 0, 0, 0},
    {0, 0, 0, 0, 4, 3, 0, 3, 12, 1, 1, 0},  {0, 0, 0, 0, 2, 2, 0, 2, 12, 2, 2, 2}, {1, 3, 0, 0, 12, 4, 0, 1, 3, 0, 0, 0},
    {0, 1, 0, 0, 10, 6, 0, 1, 6, 0, 0, 0},  {0, 0, 0, 0, 6, 6, 0, 1, 10, 1, 0, 0}, {0, 0, 0, 0, 3, 4, 0, 1, 12, 3, 0, 1},
    {0, 4, 0, 0, 8, 8, 0, 0, 4, 0, 0, 0},   {0, 1, 0, 0, 6, 10, 0, 0, 6, 1, 0, 0}, {0, 0, 0, 0, 4, 8, 0, 0, 8, 4, 0, 0},
    {0, 3, 1, 0, 4, 12, 0, 0, 3, 1, 0, 0},  {0, 1, 0, 0, 3, 12, 1, 0, 4, 3, 0, 0}, {0, 2, 2, 0, 2, 12, 2, 0, 2, 2, 0, 0},
};

/// The net of the sub-triangle with corners q0, q1, q2 (barycentric in the parent).
Net subNet(const Net& net, const Eigen::Vector3d& q0, const Eigen::Vector3d& q1, const Eigen::Vector3d& q2);

/// The certified bound of the net's triangle (loop_bezier.cpp, docs/subdivision.md "Loop cages").
double netBound(const Net& net);

/// The unit normal of the net at corner k (tangents along its two sides, counter-clockwise).
Eigen::Vector3d cornerNormal(const Net& b, int k);

} // namespace freeform::detail::loop
