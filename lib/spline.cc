#include "lib/spline.h"

#include <cmath>
#include <stdexcept>

#include "lib/local_fit.h"
#include "lib/name_table.h"

namespace needle {

void SplineOptions::Validate() const {
  if (!std::isfinite(start_slope)) {
    throw std::invalid_argument("SplineOptions.start_slope = " + std::to_string(start_slope) +
                                ": must be finite");
  }
  if (!std::isfinite(end_slope)) {
    throw std::invalid_argument("SplineOptions.end_slope = " + std::to_string(end_slope) +
                                ": must be finite");
  }
  if (!(sigma > 0.0) || !std::isfinite(sigma)) {
    throw std::invalid_argument("SplineOptions.sigma = " + std::to_string(sigma) +
                                ": must be positive and finite (the table's resolution/√12)");
  }
}

namespace {

// The one name table, in the order AllSplineKinds lists the kinds.
constexpr NameRow<SplineKind> kSplineNames[] = {
    {SplineKind::kNatural, "natural"},     {SplineKind::kNotAKnot, "not-a-knot"},
    {SplineKind::kClamped, "clamped"},     {SplineKind::kQuintic, "quintic"},
    {SplineKind::kPchip, "pchip"},         {SplineKind::kMakima, "makima"},
    {SplineKind::kSmoothing, "smoothing"}, {SplineKind::kLocal, "local"},
};

}  // namespace

std::string SplineKindName(SplineKind kind) { return NameOf(kSplineNames, kind); }

std::vector<SplineKind> AllSplineKinds() {
  std::vector<SplineKind> out;
  for (const NameRow<SplineKind>& row : kSplineNames) out.push_back(row.value);
  return out;
}

std::optional<SplineKind> ParseSplineKind(const std::string& name) {
  for (SplineKind kind : AllSplineKinds()) {
    if (SplineKindName(kind) == name) return kind;
  }
  return std::nullopt;
}

std::string SplineKindList() {
  std::string out;
  for (SplineKind kind : AllSplineKinds()) out += (out.empty() ? "" : ", ") + SplineKindName(kind);
  return out;
}

int MinimumPoints(SplineKind kind) {
  switch (kind) {
    case SplineKind::kNotAKnot:
      return 4;  // two distinct not-a-knot conditions
    case SplineKind::kQuintic:
      return 6;  // four distinct not-a-knot conditions
    case SplineKind::kSmoothing:
      return 3;  // at least one interior curvature
    case SplineKind::kLocal:
      return kLocalMinimumPoints;
    default:
      return 2;
  }
}

bool HasAcceleration(SplineKind kind) {
  return kind != SplineKind::kPchip && kind != SplineKind::kMakima;
}

void CheckSplineInputs(const std::vector<double>& x, const std::vector<double>& y,
                       const SplineOptions& options) {
  options.Validate();
  const std::string kind = SplineKindName(options.kind);
  if (x.size() != y.size()) {
    throw std::invalid_argument(kind + " spline: " + std::to_string(x.size()) + " abscissae but " +
                                std::to_string(y.size()) + " values");
  }
  const int need = MinimumPoints(options.kind);
  if (static_cast<int>(x.size()) < need) {
    throw std::invalid_argument(kind + " spline needs at least " + std::to_string(need) +
                                " points, got " + std::to_string(x.size()));
  }
  for (size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i])) {
      throw std::invalid_argument(kind + " spline: point " + std::to_string(i) + " is not finite");
    }
    if (i > 0 && !(x[i] > x[i - 1])) {
      throw std::invalid_argument(kind + " spline: abscissae must increase strictly; point " +
                                  std::to_string(i) + " is not above point " +
                                  std::to_string(i - 1));
    }
  }
}

PiecewisePolynomial BuildSpline(const std::vector<double>& x, const std::vector<double>& y,
                                const SplineOptions& options) {
  CheckSplineInputs(x, y, options);
  switch (options.kind) {
    case SplineKind::kNatural:
    case SplineKind::kNotAKnot:
    case SplineKind::kClamped:
      return BuildCubicSpline(x, y, options);
    case SplineKind::kQuintic:
      return BuildQuinticSpline(x, y);
    case SplineKind::kPchip:
      return BuildPchip(x, y);
    case SplineKind::kMakima:
      return BuildMakima(x, y);
    case SplineKind::kSmoothing:
      return BuildSmoothingSpline(x, y, options);
    case SplineKind::kLocal:
      return FitLocal(x, y, options.sigma, options.quantized).law;
  }
  throw std::logic_error("BuildSpline: unhandled kind");
}

PiecewisePolynomial CubicHermite(const std::vector<double>& x, const std::vector<double>& y,
                                 const std::vector<double>& slopes, int continuity) {
  const int n = static_cast<int>(x.size()) - 1;
  Eigen::MatrixXd c(n, 4);
  for (int i = 0; i < n; ++i) {
    const double h = x[i + 1] - x[i];
    const double delta = (y[i + 1] - y[i]) / h;  // δ = Δy/h
    c(i, 0) = y[i];
    c(i, 1) = slopes[i];
    c(i, 2) = (3.0 * delta - 2.0 * slopes[i] - slopes[i + 1]) / h;  // (3δ − 2d_i − d_{i+1})/h
    c(i, 3) = (slopes[i] + slopes[i + 1] - 2.0 * delta) / (h * h);  // (d_i + d_{i+1} − 2δ)/h²
  }
  return PiecewisePolynomial(x, std::move(c), continuity);
}

}  // namespace needle
