#pragma once
/// @file
/// Internal to lib/'s local fit (lift_pieces.cc): a step of s'' that no break marks, or a kink,
/// near an extreme of the fit, that the band of that extreme must reach.
///
/// A step of s'' of size J at ξ moves each reading δ past it by J δ²/2. Where that is at the
/// rounding's level (a 2-3 cubic rise and return of 0.05 mm read every 1° to 1e-4 mm: J δ²/2 is
/// 0.7 of a digit at δ = 1°), the break search cannot find it, and the local fit's windows grow
/// across it: they fit the readings to the rounding and read the mean of the step's sides (that
/// table: a_min −12.7 against −15.5 m/s², its band stopping at −13.6). So near each extreme the
/// band reaches what two cubics meeting at ξ read there, wherever the readings favour them:
///
///     y_i = p(θ_i) + b₂ (θ_i − ξ)²₊ + b₃ (θ_i − ξ)³₊,  p cubic,
///     s''(ξ−) = p''(ξ),  s''(ξ+) = p''(ξ) + 2 b₂,
///
/// fitted to the widest of 8, 16, 32 and 64 readings each side of ξ that they fit to the
/// rounding's bound (the more readings, the less each side's s'' is in doubt), and taken where
/// one cubic misfits those readings and the two leave at most kStepSquaresRatio times the
/// squares of a quintic through them (a smooth law of as many coefficients) and kStepOverKink
/// times those of a cubic kinked within kKinkSteps steps of ξ (s''' jumping, s'' not). ξ is tried
/// at each reading and each gap's middle within kStepGaps readings of the fit's extreme node.
/// Each side's s''(ξ) and its error (q/2 Σ|g_i| for a rounded table, 1.96 σ ‖g‖ otherwise; g its
/// weights on the readings) is a value the band of the extreme it was found near reaches on its
/// unsafe side (LiftLawNodes::reach); near the least s'', n_qs's band and the preload's unsafe end
/// reach it too.
///
/// A kink (s''' jumps, s'' not: a cubic B-spline's knot) hides the same way where the squares do
/// not tell it (lib/reading_kinks.h): every window holding it rounds its peak off. At the same ξ
/// and windows, one cubic kinked there, y_i = p(θ_i) + b₃ (θ_i − ξ)³₊, fitted to the widest run
/// it fits to the rounding's bound, reads s''(ξ) = p''(ξ), and the band reaches it where one
/// cubic misfits those readings and the kinked one leaves no more than kKinkOverQuintic times a
/// quintic's squares (the B-spline of the lift bench, 3 mm over 24° every 0.1–0.5° to 1e-3 mm and
/// 0.25° to 1e-4 mm: a_min 2.4–5.0 % short, the truth beyond its band).

#include <array>
#include <vector>

#include "lib/local_fit.h"

namespace needle {

/// The fewest readings each side of a step tried (then twice, four and eight times as many).
constexpr size_t kStepSideReadings = 8;
/// The readings ξ is tried at (and the gaps' middles after them), at most this many from the
/// fit's extreme node either way.
constexpr size_t kStepGaps = 8;

/// The sides' s'' (and errors) at each step (and kink) the readings favour near the largest s''
/// of `fit` ([1]) and the least ([0]), FitLocal's of one piece's readings (x, y) with `sigma_m`
/// (> 0, the rounding's when `quantized`) and `trim`; none for tables of more than
/// kLocalMaxNodes readings. Each node: x = ξ, s and s' the cubics' there, s[2] a side's s''(ξ),
/// band2 its error (the rounding's alone: a side whose readings reach past another junction is
/// biased beyond it, which is why each extreme's band takes only the nodes found near it).
std::array<std::vector<LocalNode>, 2> HiddenSteps(const std::vector<double>& x,
                                                  const std::vector<double>& y, double sigma_m,
                                                  bool quantized, const LocalFit& fit,
                                                  LocalTrim trim = {});

}  // namespace needle
