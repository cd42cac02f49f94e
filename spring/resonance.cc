#include "spring/resonance.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>
#include <unsupported/Eigen/FFT>

#include "lib/units.h"

namespace needle {

double ActiveSpringMassKg(const HelicalGeometry& g) {
  return g.density_kg_m3 * kPi * kPi * g.wire_m * g.wire_m * g.coil_m * g.active_coils / 4.0;
}

std::vector<double> ChainNaturalFrequenciesHz(double rate_N_m, double spring_mass_kg, int segments,
                                              int count) {
  if (!(rate_N_m > 0.0) || !(spring_mass_kg > 0.0)) {
    throw std::invalid_argument("ChainNaturalFrequenciesHz: rate and spring mass must be positive");
  }
  if (segments < 2 || count < 1 || count > segments - 1) {
    throw std::invalid_argument("ChainNaturalFrequenciesHz: " + std::to_string(segments) +
                                " segments have " + std::to_string(segments - 1) +
                                " interior modes, asked for " + std::to_string(count));
  }
  const int n = segments - 1;  // interior nodes
  const double k_seg = segments * rate_N_m, m_node = spring_mass_kg / segments;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);  // M⁻¹K, symmetric (M = m I)
  for (int i = 0; i < n; ++i) {
    a(i, i) = 2.0 * k_seg / m_node;
    if (i > 0) a(i, i - 1) = a(i - 1, i) = -k_seg / m_node;
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(a, Eigen::EigenvaluesOnly);
  if (solver.info() != Eigen::Success) {
    throw std::runtime_error("ChainNaturalFrequenciesHz: the eigensolver did not converge");
  }
  std::vector<double> f;
  for (int i = 0; i < count; ++i) f.push_back(std::sqrt(solver.eigenvalues()(i)) / (2.0 * kPi));
  return f;
}

double SurgeFrequencyHz(double rate_N_m, double spring_mass_kg, int mode) {
  return 0.5 * mode * std::sqrt(rate_N_m / spring_mass_kg);
}

CamHarmonics LiftHarmonics(const LiftLaw& law, double revolution_crank_rad, int orders,
                           double threshold) {
  constexpr int kSamples = 8192;
  if (orders < 1 || orders >= kSamples / 2) {
    throw std::invalid_argument("LiftHarmonics: orders must be in 1…" +
                                std::to_string(kSamples / 2 - 1));
  }
  if (!(threshold > 0.0 && threshold < 1.0)) {
    throw std::invalid_argument("LiftHarmonics: threshold must be in (0, 1)");
  }
  if (!law.HasAcceleration()) {
    throw std::invalid_argument("LiftHarmonics: the " + SplineKindName(law.kind()) +
                                " spline has no acceleration");
  }
  // ψ = 2π θ/revolution: u''(ψ) = (revolution/2π)² d²u/dθ².
  const double dtheta_dpsi = revolution_crank_rad / (2.0 * kPi);
  std::vector<double> u(kSamples), a(kSamples);
  const double start = law.start_rad();
  for (int k = 0; k < kSamples; ++k) {
    const double th = start + revolution_crank_rad * k / kSamples;
    const bool open = th <= law.end_rad();  // seated outside the open lift
    u[k] = open ? law.Lift(th) : 0.0;
    a[k] = open ? law.Derivative(th, 2) * dtheta_dpsi * dtheta_dpsi : 0.0;
  }
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> lift_spectrum, accel_spectrum;
  fft.fwd(lift_spectrum, u);
  fft.fwd(accel_spectrum, a);
  CamHarmonics h;
  h.threshold = threshold;
  double& largest = h.largest_acceleration_m_rad2;
  for (int i = 0; i <= orders; ++i) {
    const double scale = (i == 0 ? 1.0 : 2.0) / kSamples;
    h.lift_m.push_back(scale * std::abs(lift_spectrum[i]));
    h.acceleration_m_rad2.push_back(i == 0 ? 0.0 : scale * std::abs(accel_spectrum[i]));
    largest = std::max(largest, h.acceleration_m_rad2.back());
  }
  for (int i = 1; i <= orders; ++i) {
    if (h.acceleration_m_rad2[i] >= threshold * largest) h.highest_significant_order = i;
  }
  return h;
}

}  // namespace needle
