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
#include <Eigen/SparseCore>
#include <array>
#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "lib/spline.h"
#include "lib/spline_band.h"

namespace needle {
namespace {

// The discrepancy principle's root is taken where the residual is within this fraction of its
// target, N+1: below the χ² spread √(2(N+1)) for N < 2e8, and above the roundoff of the residual
// on a table of 1e6 readings (about ±200, ≈ 2e-4 of N: the root search there chased it).
constexpr double kDiscrepancyTolerance = 1e-4;

// Above this many readings the smoothing spline is fitted to bin means (ForSmoothing).
constexpr size_t kSmoothingMaxPoints = 20000;

struct Fit {
  Eigen::VectorXd f;      // fitted values
  Eigen::VectorXd gamma;  // second derivatives at all knots (0 at both ends)
  double residual;        // Σ ((y − f)/σ)²
};

class SmoothingProblem {
 public:
  // `relative`: each reading's variance over σ² (a bin's mean of k readings: 1/k); empty: 1.
  SmoothingProblem(const std::vector<double>& x, const std::vector<double>& y, double sigma,
                   std::vector<double> relative = {})
      : x_(x),
        n_(static_cast<int>(x.size()) - 1),
        sigma2_(sigma * sigma),
        relative_(std::move(relative)) {
    y_ = Eigen::Map<const Eigen::VectorXd>(y.data(), n_ + 1);
    h_.resize(n_);
    for (int i = 0; i < n_; ++i) h_[i] = x[i + 1] - x[i];
    inv_h_.resize(n_);
    for (int i = 0; i < n_; ++i) inv_h_[i] = 1.0 / h_[i];
    qty_ = QtTimes(y_);
  }

  // Qᵀ v for v of length N+1: (Qᵀv)_j = v_{j−1}/h_{j−1} − v_j(1/h_{j−1} + 1/h_j) + v_{j+1}/h_j.
  Eigen::VectorXd QtTimes(const Eigen::VectorXd& v) const {
    Eigen::VectorXd out(n_ - 1);
    for (int j = 1; j < n_; ++j) {
      out(j - 1) = v(j - 1) / h_[j - 1] - v(j) * (1.0 / h_[j - 1] + 1.0 / h_[j]) + v(j + 1) / h_[j];
    }
    return out;
  }

  // Q γ for γ of length N−1 (interior knots 1..N−1), into `out` (length N+1).
  void QTimes(const Eigen::VectorXd& g, Eigen::VectorXd& out) const {
    out.setZero(n_ + 1);
    for (int j = 1; j < n_; ++j) {
      const double a = g(j - 1) * inv_h_[j - 1], b = g(j - 1) * inv_h_[j];
      out(j - 1) += a;
      out(j) -= a + b;
      out(j + 1) += b;
    }
  }
  Eigen::VectorXd QTimes(const Eigen::VectorXd& g) const {
    Eigen::VectorXd out;
    QTimes(g, out);
    return out;
  }

  // Triplets of R + c QᵀQ (pentadiagonal), c = λσ² (W⁻¹ = σ² I); R left out if !with_r.
  std::vector<Eigen::Triplet<double>> Matrix(double c, bool with_r = true) const {
    std::vector<Eigen::Triplet<double>> a;
    a.reserve(8 * static_cast<size_t>(n_));
    const int m = n_ - 1;
    auto q = [&](int row, int col) -> double {  // Q_{row,col}, col = interior index 1..N−1
      if (row == col - 1) return 1.0 / h_[col - 1];
      if (row == col) return -1.0 / h_[col - 1] - 1.0 / h_[col];
      if (row == col + 1) return 1.0 / h_[col];
      return 0.0;
    };
    for (int j = 1; j <= m; ++j) {
      if (with_r) a.emplace_back(j - 1, j - 1, (h_[j - 1] + h_[j]) / 3.0);
      if (with_r && j < m) {
        a.emplace_back(j - 1, j, h_[j] / 6.0);
        a.emplace_back(j, j - 1, h_[j] / 6.0);
      }
      for (int k = std::max(1, j - 2); k <= std::min(m, j + 2); ++k) {
        double s = 0.0;  // (QᵀQ)_{jk} = Σ_r Q_{r,j} Q_{r,k}
        for (int r = std::max(0, j - 1); r <= std::min(n_, j + 1); ++r)
          s += q(r, j) * q(r, k) * Relative(r);  // (QᵀW⁻¹Q)/σ² when weighted
        if (s != 0.0) a.emplace_back(j - 1, k - 1, c * s);
      }
    }
    return a;
  }

  // γ = (R + λσ²QᵀQ)⁻¹ rhs, into g.
  void SolveSystem(double lambda, const Eigen::VectorXd& rhs, Eigen::VectorXd& g) const {
    if (n_ - 1 <= kDense) {
      // Small tables: R and QᵀQ are formed once; each λ is one Cholesky of a dense SPD matrix.
      if (r_.size() == 0) FormDense();
      const Eigen::MatrixXd a = r_ + (lambda * sigma2_) * qtq_;
      const Eigen::LLT<Eigen::MatrixXd> llt(a);
      if (llt.info() != Eigen::Success) throw std::runtime_error("smoothing spline: LLT failed");
      g = llt.solve(rhs);
    } else {
      // Large tables: R and QᵀQ are formed once as their three bands; each λ is one LDLᵀ of
      // the pentadiagonal SPD matrix in its natural order (Reinsch; no fill outside the band).
      if (band_r_[0].empty()) FormBands();
      SolveBanded(lambda * sigma2_, rhs, g);
      if (!g.allFinite()) throw std::runtime_error("smoothing spline: the solution is not finite");
    }
  }

  // The fit for λ, into `fit` (whose storage is reused: a large table's solves allocate once).
  void Solve(double lambda, Fit& fit) const {
    Eigen::VectorXd& g = g_;
    SolveSystem(lambda, qty_, g);
    QTimes(g, qg_);
    if (!relative_.empty()) qg_ = qg_.cwiseProduct(RelativeVector());  // W⁻¹/σ² Qγ
    fit.f = y_ - lambda * sigma2_ * qg_;                               // f = y − λW⁻¹Qγ
    fit.gamma.setZero(n_ + 1);
    fit.gamma.segment(1, n_ - 1) = g;
    fit.residual = relative_.empty()
                       ? (y_ - fit.f).squaredNorm() / sigma2_
                       : (y_ - fit.f).cwiseAbs2().cwiseQuotient(RelativeVector()).sum() / sigma2_;
  }
  Fit Solve(double lambda) const {
    Fit fit;
    Solve(lambda, fit);
    return fit;
  }

  // Generalised cross-validation score N·RSS/(N − tr A)², A = I − λσ²Q(R + λσ²QᵀQ)⁻¹Qᵀ. On a
  // large table tr A comes from the band of (R + λσ²QᵀQ)⁻¹ (BandedTrace): O(N) per λ.
  double Gcv(double lambda) const {
    const int m = n_ - 1;
    if (m > kDense) {
      Fit fit;
      Solve(lambda, fit);  // factors R + λσ²QᵀQ (SolveBanded keeps L and D)
      const double trace_a = (n_ + 1) - lambda * sigma2_ * BandedTrace();
      const double denom = (n_ + 1) - trace_a;
      return (n_ + 1) * fit.residual * sigma2_ / (denom * denom);
    }
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(m, m);
    for (const auto& t : Matrix(lambda * sigma2_)) a(t.row(), t.col()) += t.value();
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
    for (int i = 0; i <= n_; ++i)
      r += std::pow(y_(i) - line.Evaluate(x_[i]), 2) / (sigma2_ * Relative(i));
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

  // γ of the fit smoothed once more, S f: its difference from the fit's γ is the bias's scale.
  Eigen::VectorXd SmoothedAgain(double lambda, const Fit& fit) const {
    Eigen::VectorXd again;
    SolveSystem(lambda, QtTimes(fit.f), again);
    return again;
  }

  // A node at interior knot j of the fit for λ: s'' = γ_j, and its 95 % half-width
  // 1.96 σ‖Q A⁻¹ e_j‖ + |γ_j(S f) − γ_j| (lib/spline_band.h), `again` = SmoothedAgain.
  LocalNode Node(double lambda, const Fit& fit, const Eigen::VectorXd& again,
                 const PiecewisePolynomial& law, int j) const {
    Eigen::VectorXd unit = Eigen::VectorXd::Zero(n_ - 1), g, qg;
    unit(j - 1) = 1.0;
    SolveSystem(lambda, unit, g);
    QTimes(g, qg);
    LocalNode node;
    node.x = x_[j];
    node.s[0] = fit.f(j);
    node.s[1] = law.Evaluate(x_[j], 1);
    node.s[2] = fit.gamma(j);
    if (!relative_.empty()) qg = qg.cwiseProduct(RelativeVector().cwiseSqrt());
    node.band2 = 1.96 * std::sqrt(sigma2_) * qg.norm() + std::abs(again(j - 1) - fit.gamma(j));
    node.window = 1;
    return node;
  }

 private:
  static constexpr int kDense = 64;

  void FormDense() const {
    const int m = n_ - 1;
    r_ = Eigen::MatrixXd::Zero(m, m);
    qtq_ = Eigen::MatrixXd::Zero(m, m);
    for (const auto& t : Matrix(0.0)) r_(t.row(), t.col()) += t.value();  // R alone
    Eigen::MatrixXd q(n_ + 1, m);
    for (int j = 0; j < m; ++j) q.col(j) = QTimes(Eigen::VectorXd::Unit(m, j));
    qtq_ = relative_.empty() ? Eigen::MatrixXd(q.transpose() * q)
                             : Eigen::MatrixXd(q.transpose() * RelativeVector().asDiagonal() * q);
  }

  // R's and QᵀQ's diagonals 0, 1 and 2 below the main one: band[d][j] = A(j, j − d).
  void FormBands() const {
    const int m = n_ - 1;
    for (int d = 0; d < 3; ++d) {
      band_r_[d].assign(m, 0.0);
      band_q_[d].assign(m, 0.0);
    }
    for (const auto& t : Matrix(0.0))
      if (t.row() >= t.col()) band_r_[t.row() - t.col()][t.row()] += t.value();
    for (const auto& t : Matrix(1.0, false))
      if (t.row() >= t.col()) band_q_[t.row() - t.col()][t.row()] += t.value();
  }

  // Solves (R + c QᵀQ) γ = rhs by LDLᵀ of the pentadiagonal matrix, into g: O(N).
  void SolveBanded(double c, const Eigen::VectorXd& rhs, Eigen::VectorXd& g) const {
    const int m = n_ - 1;
    // D (as its inverse) and L's two subdiagonals; row j: l2_j = a2_j / d_{j−2},
    // l1_j = (a1_j − l2_j l1_{j−1} d_{j−2}) / d_{j−1}, d_j = a0_j − l1_j² d_{j−1} − l2_j² d_{j−2}.
    std::vector<double>&inv_d = dd_, &l1 = l1_, &l2 = l2_;
    inv_d.assign(m + 2, 0.0);  // two leading zero rows stand for j − 1, j − 2 < 0
    l1.assign(m + 2, 0.0);
    l2.assign(m + 2, 0.0);
    double d1 = 0.0, d2 = 0.0;  // d_{j−1}, d_{j−2}
    for (int j = 0; j < m; ++j) {
      const int r = j + 2;
      const double a0 = band_r_[0][j] + c * band_q_[0][j];
      const double a1 = band_r_[1][j] + c * band_q_[1][j];  // 0 for j < 1
      const double a2 = band_r_[2][j] + c * band_q_[2][j];  // 0 for j < 2
      l2[r] = a2 * inv_d[r - 2];
      l1[r] = (a1 - l2[r] * l1[r - 1] * d2) * inv_d[r - 1];
      const double d = a0 - l1[r] * l1[r] * d1 - l2[r] * l2[r] * d2;
      if (d == 0.0 || !std::isfinite(d)) throw std::runtime_error("smoothing spline: LDLT failed");
      inv_d[r] = 1.0 / d;
      d2 = d1;
      d1 = d;
    }
    g.resize(m);
    double z1 = 0.0, z2 = 0.0;
    for (int j = 0; j < m; ++j) {  // L z = b, then D⁻¹ z
      const double z = rhs(j) - l1[j + 2] * z1 - l2[j + 2] * z2;
      z2 = z1;
      z1 = z;
      g(j) = z * inv_d[j + 2];
    }
    if (m >= 2) g(m - 2) -= l1[m + 1] * g(m - 1);  // Lᵀ x = D⁻¹ z
    for (int j = m - 3; j >= 0; --j) {
      g(j) -= l1[j + 3] * g(j + 1) + l2[j + 4] * g(j + 2);
    }
  }

  // tr((R + cQᵀQ)⁻¹ QᵀQ) from the last SolveBanded's LDLᵀ: the five central diagonals of the
  // inverse Σ by Hutchinson and de Hoog's recursion, Σ = D⁻¹L⁻¹ + (I − Lᵀ)Σ from the last row
  // up (Σ_ij for j − i ≤ 2 needs only Σ's band below-right of it), against QᵀQ's band.
  double BandedTrace() const {
    const int m = n_ - 1;
    const std::vector<double>&inv_d = dd_, &l1 = l1_, &l2 = l2_;
    // L_{i+1,i} = l1[i + 3], L_{i+2,i} = l2[i + 4]; Σ_{i,i}, Σ_{i,i+1}, Σ_{i,i+2} in s0, s1, s2.
    std::vector<double> s0(m + 2, 0.0), s1(m + 2, 0.0), s2(m + 2, 0.0);
    double trace = 0.0;
    for (int i = m - 1; i >= 0; --i) {
      const double a = i + 1 < m ? l1[i + 3] : 0.0, b = i + 2 < m ? l2[i + 4] : 0.0;
      s2[i] = -a * s1[i + 1] - b * s0[i + 2];
      s1[i] = -a * s0[i + 1] - b * s1[i + 1];
      s0[i] = inv_d[i + 2] - a * s1[i] - b * s2[i];
      trace += s0[i] * band_q_[0][i];
      if (i + 1 < m) trace += 2.0 * s1[i] * band_q_[1][i + 1];
      if (i + 2 < m) trace += 2.0 * s2[i] * band_q_[2][i + 2];
    }
    return trace;
  }

  mutable Eigen::MatrixXd r_, qtq_;
  Eigen::VectorXd qty_;  // Qᵀy
  mutable std::array<std::vector<double>, 3> band_r_, band_q_;
  mutable std::vector<double> dd_, l1_, l2_;  // SolveBanded's factors, kept between solves
  mutable Eigen::VectorXd g_, qg_;            // γ and Qγ of the last solve

  std::vector<double> x_;
  int n_;
  double sigma2_;
  std::vector<double> relative_;  // each reading's variance over σ²; empty: all 1

  double Relative(int i) const { return relative_.empty() ? 1.0 : relative_[i]; }
  Eigen::VectorXd RelativeVector() const {
    return Eigen::Map<const Eigen::VectorXd>(relative_.data(), n_ + 1);
  }
  Eigen::VectorXd y_;
  std::vector<double> h_, inv_h_;  // knot spacings and their inverses
};

// The λ the options' rule chooses and its fit; `line` when even the least-squares line fits
// the readings within σ (λ → ∞).
struct Chosen {
  bool line = false;
  double lambda = 0.0;
  Fit fit;
};

Chosen ChooseLambda(const SmoothingProblem& problem, const SplineOptions& options) {
  const double scale = problem.Scale();
  Chosen c;
  if (options.smoothing_rule == SmoothingRule::kGcv) {
    // Minimise GCV over log10(λ/scale) in [−12, 12] (Brent).
    auto score = [&](double log_lambda) { return problem.Gcv(scale * std::pow(10.0, log_lambda)); };
    const auto best = boost::math::tools::brent_find_minima(score, -12.0, 12.0, 40);
    c.lambda = scale * std::pow(10.0, best.first);
    c.fit = problem.Solve(c.lambda);
    return c;
  }
  const double target = problem.points();  // discrepancy principle: Σ((y − f)/σ)² = N+1
  if (problem.LineResidual() <= target) {  // even a line fits within σ
    c.line = true;
    return c;
  }
  // A residual within kDiscrepancyTolerance of the target is the root (TOMS 748 stops at an
  // exact zero).
  const double tolerance = kDiscrepancyTolerance * target;
  double last_log_lambda = std::numeric_limits<double>::quiet_NaN();
  auto excess = [&](double log_lambda) {  // c.fit: the fit of the λ solved last
    problem.Solve(scale * std::pow(10.0, log_lambda), c.fit);
    last_log_lambda = log_lambda;
    const double e = c.fit.residual - target;
    return std::abs(e) <= tolerance ? 0.0 : e;
  };
  auto found = [&](double log_lambda) {
    c.lambda = scale * std::pow(10.0, log_lambda);
    if (log_lambda != last_log_lambda) c.fit = problem.Solve(c.lambda);
    return c;
  };
  // Bracket the root in log10(λ/scale), then TOMS 748.
  double lo = -2.0, hi = 2.0, e_lo = excess(lo), e_hi = 0.0;
  int guard = 0;
  while (e_lo > 0.0 && guard++ < 60) e_lo = excess(lo -= 2.0);
  if (e_lo == 0.0) return found(lo);
  e_hi = excess(hi);
  while (e_hi < 0.0 && guard++ < 120) e_hi = excess(hi += 2.0);
  if (guard >= 120) throw std::runtime_error("smoothing spline: could not bracket λ");
  if (e_hi == 0.0) return found(hi);
  std::uintmax_t iterations = 100;
  const auto root = boost::math::tools::toms748_solve(
      excess, lo, hi, e_lo, e_hi, boost::math::tools::eps_tolerance<double>(40), iterations);
  return found(0.5 * (root.first + root.second));
}

// The readings the smoothing spline is fitted to: all of them up to kSmoothingMaxPoints; above,
// the first and last kept and the others averaged in bins of equal count k (a bin's mean has
// σ²/k; its angle the mean of its readings'). The smoothing system of 1e6 readings is too
// ill-conditioned for double precision (a 1e6-row trace with 1 µm of noise came out 16 % high
// in a_max, its band excluding the truth; at 1e5 bins a steeper law's 7.5e5-row trace was still
// 33 % high, at 2e4 within its band), and its solves cost a fiftieth.
struct Readings {
  std::vector<double> x, y, relative;  // relative: each one's variance over σ²; empty: all 1
};

Readings ForSmoothing(const std::vector<double>& x, const std::vector<double>& y) {
  const size_t n = x.size();
  if (n <= kSmoothingMaxPoints) return {x, y, {}};
  const size_t k = (n - 2 + kSmoothingMaxPoints - 3) / (kSmoothingMaxPoints - 2);
  const BinMeans bins = MeansOfBins(x, y, 1, n - 1, k);
  Readings r{{x.front()}, {y.front()}, {1.0}};
  r.x.insert(r.x.end(), bins.x.begin(), bins.x.end());
  r.y.insert(r.y.end(), bins.y.begin(), bins.y.end());
  for (const double count : bins.count) r.relative.push_back(1.0 / count);
  r.x.push_back(x.back());
  r.y.push_back(y.back());
  r.relative.push_back(1.0);
  return r;
}

}  // namespace

PiecewisePolynomial BuildSmoothingSpline(const std::vector<double>& x, const std::vector<double>& y,
                                         const SplineOptions& options) {
  Readings r = ForSmoothing(x, y);
  const SmoothingProblem problem(r.x, r.y, options.sigma, std::move(r.relative));
  const Chosen c = ChooseLambda(problem, options);
  return c.line ? problem.Line() : problem.Spline(c.fit);
}

LocalFit BuildSmoothingFit(const std::vector<double>& x_given, const std::vector<double>& y_given,
                           const SplineOptions& options) {
  Readings r = ForSmoothing(x_given, y_given);
  const std::vector<double>& x = r.x;
  const SmoothingProblem problem(r.x, r.y, options.sigma, std::move(r.relative));
  const Chosen c = ChooseLambda(problem, options);
  if (c.line) return {problem.Line(), {}};
  LocalFit out{problem.Spline(c.fit), {}};
  const Eigen::Index n = c.fit.gamma.size();
  if (n < 3) return out;
  Eigen::Index j_max = 1, j_min = 1;  // interior knots: the natural ends hold s'' = 0
  for (Eigen::Index j = 1; j + 1 < n; ++j) {
    if (c.fit.gamma(j) > c.fit.gamma(j_max)) j_max = j;
    if (c.fit.gamma(j) < c.fit.gamma(j_min)) j_min = j;
  }
  const Eigen::VectorXd again = problem.SmoothedAgain(c.lambda, c.fit);
  for (const Eigen::Index j : {std::min(j_max, j_min), std::max(j_max, j_min)}) {
    if (!out.nodes.empty() && out.nodes.back().x == x[j]) continue;
    out.nodes.push_back(problem.Node(c.lambda, c.fit, again, out.law, static_cast<int>(j)));
  }
  return out;
}

}  // namespace needle
