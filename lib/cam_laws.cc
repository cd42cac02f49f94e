#include "lib/cam_laws.h"

#include <cmath>
#include <stdexcept>

#include "lib/units.h"

namespace needle {

CamLaw::CamLaw(CamLawKind kind, double height, double beta)
    : kind_(kind), height_(height), beta_(beta) {
  if (!(beta > 0.0) || !std::isfinite(height)) {
    throw std::invalid_argument("CamLaw: need beta > 0 and a finite height; got beta = " +
                                std::to_string(beta) + ", height = " + std::to_string(height));
  }
}

std::string CamLaw::name() const {
  switch (kind_) {
    case CamLawKind::kCycloidal:
      return "cycloidal";
    case CamLawKind::kHarmonic:
      return "harmonic";
    case CamLawKind::kPoly345:
      return "3-4-5 polynomial";
  }
  return "?";
}

double CamLaw::Derivative(double theta, int order) const {
  if (theta < 0.0 || theta > beta_) {  // at rest outside; the ends belong to the rise
    if (order > 0) return 0.0;
    return theta < 0.0 ? 0.0 : height_;
  }
  const double u = theta / beta_;
  const double scale = height_ / std::pow(beta_, order);  // d/dθ = (1/β) d/du
  switch (kind_) {
    case CamLawKind::kCycloidal: {
      const double w = 2.0 * kPi;
      switch (order) {
        case 0:
          return scale * (u - std::sin(w * u) / w);
        case 1:
          return scale * (1.0 - std::cos(w * u));
        case 2:
          return scale * w * std::sin(w * u);
        case 3:
          return scale * w * w * std::cos(w * u);
      }
      break;
    }
    case CamLawKind::kHarmonic: {
      switch (order) {
        case 0:
          return scale * 0.5 * (1.0 - std::cos(kPi * u));
        case 1:
          return scale * 0.5 * kPi * std::sin(kPi * u);
        case 2:
          return scale * 0.5 * kPi * kPi * std::cos(kPi * u);
        case 3:
          return -scale * 0.5 * kPi * kPi * kPi * std::sin(kPi * u);
      }
      break;
    }
    case CamLawKind::kPoly345: {
      const double u2 = u * u;
      switch (order) {
        case 0:
          return scale * (10.0 * u2 * u - 15.0 * u2 * u2 + 6.0 * u2 * u2 * u);
        case 1:
          return scale * (30.0 * u2 - 60.0 * u2 * u + 30.0 * u2 * u2);
        case 2:
          return scale * (60.0 * u - 180.0 * u2 + 120.0 * u2 * u);
        case 3:
          return scale * (60.0 - 360.0 * u + 360.0 * u2);
      }
      break;
    }
  }
  throw std::invalid_argument("CamLaw::Derivative: order must be 0..3, got " +
                              std::to_string(order));
}

}  // namespace needle
