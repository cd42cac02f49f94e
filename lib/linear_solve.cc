#include "lib/linear_solve.h"

#include <Eigen/Dense>
#include <Eigen/SparseLU>
#include <stdexcept>

namespace needle {

namespace {
// Below this many unknowns a dense LU beats SparseLU's set-up (measured: needle-bench kinematics).
constexpr int kDenseLimit = 32;
}  // namespace

Eigen::VectorXd SolveSparse(int n, const std::vector<Eigen::Triplet<double>>& entries,
                            const Eigen::VectorXd& rhs, const std::string& what) {
  Eigen::VectorXd x;
  if (n <= kDenseLimit) {
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
    for (const auto& t : entries) a(t.row(), t.col()) += t.value();
    Eigen::PartialPivLU<Eigen::MatrixXd> lu(a);
    if (!(lu.rcond() > 1e-15)) {  // reciprocal condition estimate; NaN also fails
      throw std::runtime_error(what + ": the linear system is singular (check the knots)");
    }
    x = lu.solve(rhs);
  } else {
    Eigen::SparseMatrix<double> a(n, n);
    a.setFromTriplets(entries.begin(), entries.end());
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
    lu.compute(a);
    if (lu.info() != Eigen::Success) {
      throw std::runtime_error(what + ": SparseLU factorization failed: " + lu.lastErrorMessage());
    }
    x = lu.solve(rhs);
  }
  if (!x.allFinite()) throw std::runtime_error(what + ": the solution is not finite");
  return x;
}

}  // namespace needle
