#pragma once
// Internal to src/document: the parameter checks and the Evaluation layout that evaluate.cpp (the
// curves, surfaces, lattices and subdivision surfaces) and part_ops.cpp (trimmed surfaces and
// parts) share, so `freeform eval` words its errors and orders its derivatives one way for every
// kind (docs/cli.md, "eval"); gridEdges for the control nets (model.cpp).

#include <Eigen/Core>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "freeform/document/operations.h"

namespace freeform::detail {

/// Error unless `at` holds `count` numbers: "WHAT: the parameter is FORM (COUNT numbers), got N".
void expectCount(const std::string& what, const std::vector<double>& at, std::size_t count, const char* form);

/// Error unless a <= t <= b: "WHAT: NAME = T is outside the KIND's domain [A, B]".
void inDomain(const std::string& what, const char* name, double t, double a, double b, const char* kind);

/// A curve's point and derivatives 1..order from the columns of its derivative matrix.
Evaluation curveEvaluation(const Eigen::Ref<const Eigen::MatrixXd>& derivatives, int order);

/// A surface's point, normal and partial derivatives of orders 1..order from its jet (columns by
/// BezierSurface::jetIndex), keyed "u", "v", "uu", "uv", "vv", ... (u-order first).
Evaluation surfaceEvaluation(const Eigen::Ref<const Eigen::MatrixXd>& jet, const Eigen::Vector3d& normal, int order);

/// The edges of a rows x cols grid of points (index i * cols + j): along each row and each column.
void gridEdges(std::vector<std::pair<int, int>>& edges, int rows, int cols);

} // namespace freeform::detail
