#pragma once
/// @file
/// Solves the sparse, banded systems A·x = b that spline construction produces.
/// Small systems (n ≤ 32) go to a dense LU with partial pivoting, larger ones to Eigen's
/// SparseLU: both O(n) memory per row of band and fast where each is used.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

namespace needle {

/// Solves A·x = b where A is n×n given by (row, col, value) triplets (duplicates add).
/// Throws std::runtime_error naming `what` when A is singular or the solution not finite.
Eigen::VectorXd SolveSparse(int n, const std::vector<Eigen::Triplet<double>>& entries,
                            const Eigen::VectorXd& rhs, const std::string& what);

}  // namespace needle
