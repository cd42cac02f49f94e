#pragma once
/// @file
/// Internal to LiftLaw (lib/lift_law.cc): the law of an open lift's readings built apart on the
/// pieces between LiftLawOptions::breaks_rad, each fitted from its own readings (a local fit,
/// a smoothing or an interpolating spline) and joined at the breaks, where s'' (and s' by the
/// pieces' error) jump; a dwell's piece is its lift, met where the pieces beside it reach it.
#include <functional>
#include <vector>

#include "lib/lift_law.h"
#include "lib/local_fit.h"
#include "lib/piecewise_polynomial.h"

namespace needle {
namespace lift_pieces {

/// The law through (x, y), x the open lift's angles (rad, increasing), y its lifts (m): built
/// apart on each piece between options.breaks_rad (each an x_i strictly inside), C⁰ for the
/// interpolating kinds; a local fit's two ends at a break are each piece's own estimate there
/// (its readings within the break's uncertainty left out). Every fit's nodes go to `nodes`.
/// Throws std::invalid_argument on a break that is no angle of the table or a piece with too
/// few readings for its kind.
PiecewisePolynomial BuildPieces(const std::vector<double>& x, const std::vector<double>& y,
                                const LiftLawOptions& options, LiftLawNodes* nodes);

/// Where the lift `s` (a law, or a law against a dwell's level; rad → m) leaves the seat between
/// the seat reading at `seat` and the next at `next` (either side of it): where it crosses zero,
/// or else touches it (its least value there).
double Foot(const std::function<double(double)>& s, double seat, double next);

/// `node`, put at `to` (rad) with `law`'s s, s' and s'' there.
void MoveNode(const PiecewisePolynomial& law, double to, LocalNode* node);

}  // namespace lift_pieces
}  // namespace needle
