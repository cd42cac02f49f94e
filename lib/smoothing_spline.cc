// Cubic smoothing spline (Reinsch; Green & Silverman §2.3, weighted). With weights
// w_i = 1/σ², f the fitted values and γ the interior second derivatives (natural ends),
// the minimiser of Σ w_i (y_i − f_i)² + λ∫f''² solves
//
//     (R + λ Qᵀ W⁻¹ Q) γ = Qᵀ y,     f = y − λ W⁻¹ Q γ,
//
// where Q (N+1 × N−1) has Q_{j−1,j} = 1/h_{j−1}, Q_{j,j} = −1/h_{j−1} − 1/h_j,
// Q_{j+1,j} = 1/h_j, and R (N−1 × N−1) is tridiagonal with R_jj = (h_{j−1} + h_j)/3,
// R_{j,j+1} = h_j/6. The weighted residual Σ w (y − f)² grows monotonically with λ from 0
// (interpolation) to that of the least-squares line (λ → ∞).
#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <stdexcept>

#include "lib/linear_solve.h"
#include "lib/spline.h"

namespace needle {
namespace {

struct Fit {
  Eigen::VectorXd f;      // fitted values
  Eigen::VectorXd gamma;  // second derivatives at all knots (0 at both ends)
  double residual;        // Σ ((y − f)/σ)²
};

class SmoothingProblem {
 public:
  SmoothingProblem(const std::vector<double>& x, const std::vector<double>& y, double sigma)
      : x_(x), n_(static_cast<int>(x.size()) - 1), sigma2_(sigma * sigma) {
    y_ = Eigen::Map<const Eigen::VectorXd>(y.data(), n_ + 1);
    h_.resize(n_);
    for (int i = 0; i < n_; ++i) h_[i] = x[i + 1] - x[i];
  }

  // Qᵀ v for v of length N+1: (Qᵀv)_j = v_{j−1}/h_{j−1} − v_j(1/h_{j−1} + 1/h_j) + v_{j+1}/h_j.
  Eigen::VectorXd QtTimes(const Eigen::VectorXd& v) const {
    Eigen::VectorXd out(n_ - 1);
    for (int j = 1; j < n_; ++j) {
      out(j - 1) = v(j - 1) / h_[j - 1] - v(j) * (1.0 / h_[j - 1] + 1.0 / h_[j]) + v(j + 1) / h_[j];
    }
    return out;
  }

  // Q γ for γ of length N−1 (interior knots 1..N−1).
  Eigen::VectorXd QTimes(const Eigen::VectorXd& g) const {
    Eigen::VectorXd out = Eigen::VectorXd::Zero(n_ + 1);
    for (int j = 1; j < n_; ++j) {
      out(j - 1) += g(j - 1) / h_[j - 1];
      out(j) -= g(j - 1) * (1.0 / h_[j - 1] + 1.0 / h_[j]);
      out(j + 1) += g(j - 1) / h_[j];
    }
    return out;
  }

  // Triplets of R + λ Qᵀ W⁻¹ Q (pentadiagonal), W⁻¹ = σ² I.
  std::vector<Eigen::Triplet<double>> Matrix(double lambda) const {
    std::vector<Eigen::Triplet<double>> a;
    const int m = n_ - 1;
    auto q = [&](int row, int col) -> double {  // Q_{row,col}, col = interior index 1..N−1
      if (row == col - 1) return 1.0 / h_[col - 1];
      if (row == col) return -1.0 / h_[col - 1] - 1.0 / h_[col];
      if (row == col + 1) return 1.0 / h_[col];
      return 0.0;
    };
    for (int j = 1; j <= m; ++j) {
      a.emplace_back(j - 1, j - 1, (h_[j - 1] + h_[j]) / 3.0);
      if (j < m) {
        a.emplace_back(j - 1, j, h_[j] / 6.0);
        a.emplace_back(j, j - 1, h_[j] / 6.0);
      }
      for (int k = std::max(1, j - 2); k <= std::min(m, j + 2); ++k) {
        double s = 0.0;  // (QᵀQ)_{jk} = Σ_r Q_{r,j} Q_{r,k}
        for (int r = std::max(0, j - 1); r <= std::min(n_, j + 1); ++r) s += q(r, j) * q(r, k);
        if (s != 0.0) a.emplace_back(j - 1, k - 1, lambda * sigma2_ * s);
      }
    }
    return a;
  }

  Fit Solve(double lambda) const {
    Eigen::VectorXd g;
    if (n_ - 1 <= kDense) {
      // Small tables: R and QᵀQ are formed once; each λ is one Cholesky of a dense SPD matrix.
      if (r_.size() == 0) FormDense();
      const Eigen::MatrixXd a = r_ + (lambda * sigma2_) * qtq_;
      const Eigen::LLT<Eigen::MatrixXd> llt(a);
      if (llt.info() != Eigen::Success) throw std::runtime_error("smoothing spline: LLT failed");
      g = llt.solve(qty_);
    } else {
      // Large tables: R and QᵀQ are formed once, sparse and of one pattern; each λ is one
      // factorisation of the pentadiagonal SPD matrix by LDLᵀ in its natural order (no fill
      // outside the band: O(N)), its symbolic analysis done once.
      if (a_.size() == 0) FormSparse();
      const double c = lambda * sigma2_;
      for (Eigen::Index k = 0; k < a_.nonZeros(); ++k)
        a_.valuePtr()[k] = r_values_[k] + c * q_values_[k];
      ldlt_.factorize(a_);
      if (ldlt_.info() != Eigen::Success) throw std::runtime_error("smoothing spline: LDLT failed");
      g = ldlt_.solve(qty_);
      if (!g.allFinite()) throw std::runtime_error("smoothing spline: the solution is not finite");
    }

    Fit fit;
    fit.f = y_ - lambda * sigma2_ * QTimes(g);  // f = y − λW⁻¹Qγ
    fit.gamma = Eigen::VectorXd::Zero(n_ + 1);
    fit.gamma.segment(1, n_ - 1) = g;
    fit.residual = (y_ - fit.f).squaredNorm() / sigma2_;
    return fit;
  }

  // Generalised cross-validation score N·RSS/(N − tr A)², A = I − λσ²Q(R + λσ²QᵀQ)⁻¹Qᵀ.
  double Gcv(double lambda) const {
    const int m = n_ - 1;
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(m, m);
    for (const auto& t : Matrix(lambda)) a(t.row(), t.col()) += t.value();
    Eigen::MatrixXd q = Eigen::MatrixXd::Zero(n_ + 1, m);
    for (int j = 0; j < m; ++j) {
      Eigen::VectorXd e = Eigen::VectorXd::Zero(m);
      e(j) = 1.0;
      q.col(j) = QTimes(e);
    }
    const Eigen::MatrixXd s = q * a.ldlt().solve(q.transpose());  // Q (…)⁻¹ Qᵀ
    const double trace_a = (n_ + 1) - lambda * sigma2_ * s.trace();
    const double rss = Solve(lambda).residual * sigma2_;
    const double denom = (n_ + 1) - trace_a;
    return (n_ + 1) * rss / (denom * denom);
  }

  // λ → ∞ limit: the weighted least-squares straight line.
  PiecewisePolynomial Line() const {
    const Eigen::VectorXd xs = Eigen::Map<const Eigen::VectorXd>(x_.data(), n_ + 1);
    Eigen::MatrixXd design(n_ + 1, 2);
    design.col(0).setOnes();
    design.col(1) = xs.array() - x_[0];
    const Eigen::Vector2d beta = design.colPivHouseholderQr().solve(y_);
    Eigen::MatrixXd c = Eigen::MatrixXd::Zero(n_, 4);
    for (int i = 0; i < n_; ++i) {
      c(i, 0) = beta(0) + beta(1) * (x_[i] - x_[0]);
      c(i, 1) = beta(1);
    }
    return PiecewisePolynomial(x_, std::move(c), 2);
  }

  double LineResidual() const {
    const PiecewisePolynomial line = Line();
    double r = 0.0;
    for (int i = 0; i <= n_; ++i) r += std::pow(y_(i) - line.Evaluate(x_[i]), 2) / sigma2_;
    return r;
  }

  PiecewisePolynomial Spline(const Fit& fit) const {
    Eigen::MatrixXd c(n_, 4);
    for (int i = 0; i < n_; ++i) {
      const double delta = (fit.f(i + 1) - fit.f(i)) / h_[i];
      c(i, 0) = fit.f(i);
      c(i, 1) = delta - h_[i] * (2.0 * fit.gamma(i) + fit.gamma(i + 1)) / 6.0;
      c(i, 2) = 0.5 * fit.gamma(i);
      c(i, 3) = (fit.gamma(i + 1) - fit.gamma(i)) / (6.0 * h_[i]);
    }
    return PiecewisePolynomial(x_, std::move(c), 2);
  }

  // Natural scale of λ where the two terms balance: R ~ h, λσ²QᵀQ ~ λσ²/h² → λ ~ h³/σ².
  double Scale() const {
    const double h = (x_.back() - x_.front()) / n_;
    return h * h * h / sigma2_;
  }

  int points() const { return n_ + 1; }

 private:
  static constexpr int kDense = 64;

  void FormDense() const {
    const int m = n_ - 1;
    r_ = Eigen::MatrixXd::Zero(m, m);
    qtq_ = Eigen::MatrixXd::Zero(m, m);
    for (const auto& t : Matrix(0.0)) r_(t.row(), t.col()) += t.value();  // R alone
    Eigen::MatrixXd q(n_ + 1, m);
    for (int j = 0; j < m; ++j) q.col(j) = QTimes(Eigen::VectorXd::Unit(m, j));
    qtq_ = q.transpose() * q;

    qty_ = QtTimes(y_);
  }

  // A = R + λσ²QᵀQ's pattern, and R's and QᵀQ's values in its storage order.
  void FormSparse() const {
    const int m = n_ - 1;
    const std::vector<Eigen::Triplet<double>> r = Matrix(0.0), rq = Matrix(1.0 / sigma2_);
    a_.resize(m, m);
    a_.setFromTriplets(r.begin(), r.end());  // R, with QᵀQ's pattern held as zeros
    r_values_.assign(a_.valuePtr(), a_.valuePtr() + a_.nonZeros());
    a_.setFromTriplets(rq.begin(), rq.end());  // R + QᵀQ: the same triplets' positions
    q_values_.resize(r_values_.size());
    for (size_t k = 0; k < q_values_.size(); ++k) q_values_[k] = a_.valuePtr()[k] - r_values_[k];
    ldlt_.analyzePattern(a_);
    qty_ = QtTimes(y_);
  }

  mutable Eigen::MatrixXd r_, qtq_;
  mutable Eigen::VectorXd qty_;
  mutable Eigen::SparseMatrix<double> a_;
  mutable std::vector<double> r_values_, q_values_;
  mutable Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower,
                                Eigen::NaturalOrdering<int>>
      ldlt_;

  std::vector<double> x_;
  int n_;
  double sigma2_;
  Eigen::VectorXd y_;
  std::vector<double> h_;
};

}  // namespace

PiecewisePolynomial BuildSmoothingSpline(const std::vector<double>& x, const std::vector<double>& y,
                                         const SplineOptions& options) {
  const SmoothingProblem problem(x, y, options.sigma);
  const double scale = problem.Scale();
  if (options.smoothing_rule == SmoothingRule::kGcv) {
    // Minimise GCV over log10(λ/scale) in [−12, 12] (Brent).
    auto score = [&](double log_lambda) { return problem.Gcv(scale * std::pow(10.0, log_lambda)); };
    const auto best = boost::math::tools::brent_find_minima(score, -12.0, 12.0, 40);
    return problem.Spline(problem.Solve(scale * std::pow(10.0, best.first)));
  }
  const double target = problem.points();  // discrepancy principle: Σ((y − f)/σ)² = N+1
  if (problem.LineResidual() <= target) return problem.Line();  // even a line fits within σ
  auto excess = [&](double log_lambda) {
    return problem.Solve(scale * std::pow(10.0, log_lambda)).residual - target;
  };
  // Bracket the root in log10(λ/scale), then TOMS 748.
  double lo = -2.0, hi = 2.0;
  int guard = 0;
  while (excess(lo) > 0.0 && guard++ < 60) lo -= 2.0;
  while (excess(hi) < 0.0 && guard++ < 120) hi += 2.0;
  if (guard >= 120) throw std::runtime_error("smoothing spline: could not bracket λ");
  std::uintmax_t iterations = 100;
  const auto root = boost::math::tools::toms748_solve(
      excess, lo, hi, boost::math::tools::eps_tolerance<double>(40), iterations);
  return problem.Spline(problem.Solve(scale * std::pow(10.0, 0.5 * (root.first + root.second))));
}

}  // namespace needle
