#pragma once
/// @file
/// The lift law s(θ) of the needle (docs/model.md §2, docs/model.md): a spline through a table of
/// crank angle θ_i (rad, strictly increasing) and lift s_i (m), closed (s = 0) outside the open
/// lift [θ_open, θ_close] ⊆ [θ_0, θ_N]:
///
///     s(θ) = spline(θ) on [θ_open, θ_close],  0 elsewhere;   dᵏs/dθᵏ from the spline, exact.
///
/// The open lift of an exact table (closed level 0) runs from the last zero before the rise to
/// the first zero after the fall, and the spline is built on that part of the table only, so
/// padded zeros neither count nor shape it. For measured data (closed level h > 0, the noise
/// band of the seated needle) the spline is built on the whole table and the open lift runs
/// from the first to the last crossing of h. A case may state θ_open and θ_close itself.

#include <array>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "lib/local_fit.h"
#include "lib/piecewise_polynomial.h"
#include "lib/spline.h"

namespace needle {

/// A lift table in SI: crank angle θ_i in rad (negative before dead center), lift s_i in m.
struct LiftTable {
  std::vector<double> crank_rad;
  std::vector<double> lift_m;
};

/// Basu's normal curve (NACA TM 477), lift in percent of maximum at −15…40° in 5° steps.
/// Returns it scaled to `max_lift_m` (> 0).
LiftTable BasuNormalCurve(double max_lift_m);

/// Where a derivative of s takes its largest or smallest value.
struct Extremum {
  double crank_rad = 0.0;  ///< angle of the extremum, rad
  double value = 0.0;      ///< dᵏs/dθᵏ there, m/radᵏ
};

/// A 95 % band of an extreme, [low, high], in its units.
struct ExtremumBand {
  double low = 0.0, high = 0.0;
};

/// How a lift law is built from its table. Every field has a default.
/// A dwell inside the open lift (lib/lift_data.h FindDwells): the table's readings from
/// from_rad to to_rad, all at lift_m, the readings beside it lower (a top) or higher.
struct LiftDwell {
  double from_rad = 0.0, to_rad = 0.0;  ///< its first and last reading, rad
  double lift_m = 0.0;                  ///< its lift, m
  bool top = true;                      ///< the readings beside it lower
  bool jumps_before = false;            ///< s'' jumps where the readings before it meet it
  bool jumps_after = false;             ///< s'' jumps where the readings after it meet it
};

struct LiftLawOptions {
  /// The spline and its options.
  SplineOptions spline;
  /// Closed level h, m, ≥ 0: 0 for an exact table (open from its last leading zero to its first
  /// trailing zero); > 0 for measured data (open where the fitted curve exceeds h).
  double closed_level_m = 0.0;
  /// Readings down to −allowance, m (≥ 0), are accepted as noise of a seated needle; below that
  /// a reading is an error. 0 for exact tables.
  double negative_allowance_m = 0.0;
  /// The allowance in σ, for messages (lib/lift_data.h TailSigmas: 4 up to 316 readings).
  double negative_sigmas = 4.0;
  /// θ_open and θ_close stated by the case, rad, inside [θ_0, θ_N]; detected when absent.
  std::optional<double> open_rad, close_rad;
  /// Angles where s'' may jump (a cam of circular arcs), rad, increasing: the spline is built
  /// apart on each piece of the open lift between them, so the jumps are kept, not smeared.
  /// Each must be an angle of the table strictly inside the open lift (inside the table, for
  /// measured data).
  std::vector<double> breaks_rad;
  /// How far from its true place a break may lie, rad (≥ 0, found breaks: LiftLawChoice's
  /// break_uncertainty_rad): a local fit leaves the readings that near a break out of its
  /// windows (lib/local_fit.h LocalTrim).
  double break_uncertainty_rad = 0.0;
  /// Which breaks_rad have a reading added at them whose lift is an estimate (a found break
  /// between readings: the sides' cubics' mean there), left out of a local fit's windows, each
  /// piece's end there its own; empty: none.
  std::vector<bool> break_estimated;
  /// Dwells, each one's first and last reading among breaks_rad: the law is the dwell's lift
  /// from where the piece before it reaches that lift (between the dwell's first reading and
  /// the one before) to where the piece after it leaves it. A local fit's only.
  std::vector<LiftDwell> dwells;
};

/// Internal to LiftLaw: a fit's nodes, ready (a local fit's, a smoothing spline's) or deferred
/// (an interpolating spline's band, lib/spline_band.h), and all of them once asked.
struct LiftLawNodes {
  /// Whether a local fit left the open lift's first (last) reading, a seat reading the law does
  /// not start on, out of its windows.
  bool seat_left_out[2] = {false, false};
  /// Values s'' may take that the fit does not read, each with its band: a short end piece's at a
  /// seat between readings (lift_pieces.cc ShortSeatBand; both extremes') and a step's or kink's
  /// of s'' that no break marks near the largest s'' ([1]) or the least ([0]; lib/reading_steps.h).
  /// The extreme's band (the least's: n_qs's and the preload's too) reaches them on its unsafe
  /// side only.
  std::array<std::vector<LocalNode>, 2> reach;
  std::vector<LocalNode> ready;
  std::vector<std::function<std::vector<LocalNode>()>> deferred;
  std::once_flag once;
  std::vector<LocalNode> all;
};

/// A lift law: table plus spline. Immutable after construction.
class LiftLaw {
 public:
  /// Builds the spline of `options.kind` through the table, as an exact table. Throws
  /// std::invalid_argument when the table is invalid for that kind (see BuildSpline) or a lift
  /// is negative.
  LiftLaw(LiftTable table, const SplineOptions& options);
  /// Builds the law as `options` say (see LiftLawOptions). Throws std::invalid_argument naming
  /// the entry or the angle when the table does not fit them.
  LiftLaw(LiftTable table, const LiftLawOptions& options);

  /// Lift s(θ), m; 0 outside [θ_0, θ_N].
  double Lift(double crank_rad) const;
  /// dᵏs/dθᵏ in m/radᵏ, k = 0..3; 0 outside [θ_0, θ_N]. For k = 2, 3 only meaningful when
  /// HasAcceleration() (C¹ kinds have a second derivative that jumps at the knots).
  double Derivative(double crank_rad, int order) const;
  /// Derivative(crank_rad, k) into out[k] for k = 0 … count − 1, bit for bit, in one lookup.
  void Derivatives(double crank_rad, int count, double* out) const;
  /// True when s'' is continuous (all kinds but pchip and makima), between the breaks if any.
  bool HasAcceleration() const { return needle::HasAcceleration(kind_); }

  /// θ_open and θ_close, rad: where the needle leaves and reaches its seat.
  double start_rad() const { return open_rad_; }
  double end_rad() const { return close_rad_; }
  /// θ_0 and θ_N of the table, rad.
  double table_start_rad() const { return table_.crank_rad.front(); }
  double table_end_rad() const { return table_.crank_rad.back(); }
  /// The closed level h the open lift was detected with, m (0: exact table).
  double closed_level_m() const { return closed_level_m_; }
  /// How far the spline dips below zero inside the open lift, m (0 when it does not), and where.
  double undershoot_m() const { return undershoot_m_; }
  double undershoot_rad() const { return undershoot_rad_; }
  /// Mean lift over the open lift: (1/(θ_close − θ_open)) ∫ s dθ, m.
  double MeanLift() const;
  /// Largest and smallest dᵏs/dθᵏ on [θ_open, θ_close], k = 0..2, located to ~1e-12 rad.
  Extremum Max(int order) const;
  Extremum Min(int order) const;
  /// The 95 % band of the largest (`largest`) or smallest s'' over the open lift, m/rad²: the
  /// extreme of the nodes' bands (lib/local_fit.h, lib/spline_band.h), and always holding
  /// Max(2) (Min(2)), its unsafe end reaching a local fit's peak on a kink between nodes
  /// (KinkNodes); none for a law without nodes (pchip, makima, a table too short or too long
  /// for an interpolating spline's band).
  std::optional<ExtremumBand> AccelerationBand(bool largest) const;
  /// The largest (smallest) s'' as a node: where it is, s, s', s'' there, and the half-width of
  /// the node nearest it (the extreme may lie between nodes). Meaningful only with nodes.
  LocalNode ExtremeNode(bool largest) const;
  /// A local fit's peaks of s'' (the largest, or the smallest) on kinks between its nodes
  /// (lib/reading_kinks.h KinkPeaks) as nodes whose band spans the law's s'' there and the peak:
  /// s'' their mean, the half-width half their distance plus the interval's nodes'. Empty for
  /// the other kinds (an interpolating spline's nodes, one a reading, are too far apart on a
  /// sparse table to tell a kink from a smooth peak).
  std::vector<LocalNode> KinkNodes(bool largest) const;
  /// The law at `crank_rad` as a node: s, s', s'' there and the half-width of the node nearest
  /// it (a quantity read from s'' may be most unsafe between nodes). Meaningful only with nodes.
  LocalNode NodeAt(double crank_rad) const;
  /// The values the largest (`largest`) or least s'' may take that no node carries, on its unsafe
  /// side only (LiftLawNodes::reach).
  const std::vector<LocalNode>& ReachNodes(bool largest) const { return nodes_->reach[largest]; }
  /// The nodes inside the open lift that carry the band of s'' (empty when there is none). An
  /// interpolating spline's are computed when first asked (26 splines a piece: a scene that
  /// reads no band never pays for them); thread-safe.
  const std::vector<LocalNode>& nodes() const;

  const LiftTable& table() const { return table_; }
  const PiecewisePolynomial& spline() const { return spline_; }
  SplineKind kind() const { return kind_; }

 private:
  std::pair<Extremum, Extremum> Extrema(int order) const;

  LiftTable table_;
  SplineKind kind_;
  double closed_level_m_ = 0.0;
  double open_rad_ = 0.0, close_rad_ = 0.0;  // set by spline_'s initialiser: declared before it
  std::shared_ptr<LiftLawNodes> nodes_ =
      std::make_shared<LiftLawNodes>();  // set by spline_'s initialiser: declared before it
  PiecewisePolynomial spline_;           // restricted to [θ_open, θ_close]
  double undershoot_m_ = 0.0, undershoot_rad_ = 0.0;
};

}  // namespace needle
