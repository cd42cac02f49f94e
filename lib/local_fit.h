#pragma once
/// @file
/// Local polynomial regression of a lift table, the default reading of an exported table
/// (docs/lift-data.md, "Reading a table"). At every node t the readings near t are fitted by
/// weighted least squares with a polynomial of degree p = kLocalDegree,
///
///     min Σ_i c_i K((θ_i − t)/b) (s_i − Σ_k β_k (θ_i − t)^k)²,   s⁽ᵈ⁾(t) ≈ d! β_d,
///
/// K the tricube kernel, b the distance to the K-th nearest reading, c_i a reading's count (a
/// bin of a dense table holds several). Every estimate is linear in the readings,
/// s⁽ᵈ⁾(t) = Σ g_i s_i, so its standard deviation under white noise of σ per reading is
/// σ √(Σ g_i²/c_i). The window is chosen at each node by Lepski's rule: the widest of the
/// windows K_j = 7, 9, 11, … (×1.25) whose s'' agrees with every narrower one's within
/// kLepskiSigmas of the narrower one's standard deviation, so it grows while the noise shrinks
/// faster than the law's curvature bends the fit, and up to the first window whose polynomial
/// misfits its readings (a residual above q = √12 σ for rounding; Σ c_i r_i² above its χ² range
/// for white noise): it reaches past a junction no break marks (s''' jumps). Where the nearest
/// readings' window ends on such a misfit, the node also tries the readings on each side of it
/// alone and keeps the one-sided window that grows wider with a narrower band (LPA-ICI,
/// Katkovnik 2006). Where even the narrowest window misfits on an exact or rounded table, the
/// narrowest windows shifted to hold the node off-centre are tried (ENO), and the smoothest that
/// fits is taken where the junction shows (local_fit.cc, ShiftedNodeAt). An exact table (σ ≈ 0)
/// keeps the narrowest
/// window, a quintic through 7 readings (error O(h⁴) in s''); a rounded or measured one is
/// smoothed exactly as much as its σ asks. Windows never reach past the readings given, so a
/// piece between two junctions is fitted from its own data, one-sided at its ends.
///
/// The nodes, half their window's width apart (a closer node's values would carry their noise
/// into s'' over the square of the spacing), carry s, s', s'' and a 95 % half-width of s'' (1.96
/// standard deviations plus the largest change from the narrower windows of at least half its
/// size, the truncation's scale);
/// the last on the piece's last reading where less than half a step is left and its window
/// meets the node before's (half of each; else the pass steps on, and that node may stand
/// nearer the end than half a window; with no reading left past the node, as at a trimmed or
/// binned end, the last reading takes it whatever its window); between nodes the law is the quintic
/// Hermite interpolant of (s, s', s''), C². On an exact or rounded table a node is added where that
/// law misses a reading by far more than its nodes' error allows (local_fit.cc,
/// AddNodesWhereTheLawMisses), and where its s'' peaks between two nodes, unless the law then
/// strays past the three nodes' s'' and bands by more than a band (the node is then left out and
/// its neighbours' bands reach the stray: AddNodesAtExtremes). A table of more than kLocalMaxNodes
/// readings is first averaged in bins of consecutive readings (σ/√count each): the cost is O(n).

#include <array>
#include <cmath>
#include <vector>

#include "lib/piecewise_polynomial.h"

namespace needle {

/// Degree of the local polynomial.
constexpr int kLocalDegree = 5;
/// Readings in the narrowest window: two more than the degree needs.
constexpr int kLocalMinimumPoints = kLocalDegree + 2;
/// The least readings the trims of a piece beside a break placed only to within some angle may
/// leave (LocalTrim::least): one window's and one more. Untrimmed, a short piece's fit followed
/// the readings its breaks' uncertainty says may be the neighbours' (a harmonic top rounded flat
/// to 1e-3 mm, its two junctions each found 1.2° off, left a piece of 12 readings, 8 after the
/// trims: a_min came out −8799 against −438 m/s²). Other trims (a seat reading, a break's added
/// reading) keep 2 kLocalMinimumPoints: a C∞ bump's foot trimmed to 8 readings read a_min 40 % off.
constexpr size_t kTrimmedLeastReadings = kLocalMinimumPoints + 1;
/// A piece of fewer readings than this has its windows' truncation measured by the quartic on
/// the same readings (no window can grow much wider; the reason names such a piece).
constexpr int kLocalFewReadings = 2 * kLocalMinimumPoints;
/// Lepski's agreement level, in standard deviations of the narrower window's s''.
constexpr double kLepskiSigmas = 2.5;
/// Above this many readings a piece is averaged in bins first (O(n) overall).
constexpr int kLocalMaxNodes = 1500;

/// The largest residual a polynomial fitted to rounded readings may show when it is the law's:
/// the rounding's bound q/2 = √3 σ, twice over (the fit adds its own error).
inline double RoundingMisfitBound(double sigma) { return 2.0 * std::sqrt(3.0) * sigma; }

/// Means of consecutive readings in bins (a dense table's, before a fit): angle, lift and count,
/// and each bin's spread: the central moments mean (θ − x̄)^j, j = 2 … 5, rad^j, that a fit
/// reads a bin's mean through (the mean of a polynomial over the bin is not its value at x̄: a
/// bin of other spacing than its neighbours', the table's last or one holding a break's reading,
/// would otherwise stand off their curve by s''·var/2). Empty when every bin is one reading.
struct BinMeans {
  std::vector<double> x, y, count;
  std::vector<std::array<double, 4>> moments;
};

/// The means of readings [from, to) in bins of `per` (≥ 1; the last bin may hold fewer).
BinMeans MeansOfBins(const std::vector<double>& x, const std::vector<double>& y, size_t from,
                     size_t to, size_t per);

/// One node of a local fit.
struct LocalNode {
  double x = 0.0;      ///< where, rad
  double s[3] = {};    ///< s, s', s'' there (m, m/rad, m/rad²)
  double band2 = 0.0;  ///< 95 % half-width of s'' there, m/rad², ≥ 0
  int window = 0;      ///< readings in its window (bins counted once)
  double width = 0.0;  ///< the span, rad, half of which spaces the next node (a window behind
                       ///< the node: the nearest readings' window's)
};

/// A local fit: the law and its nodes.
struct LocalFit {
  PiecewisePolynomial law;
  std::vector<LocalNode> nodes;
  bool trimmed = false;  ///< the trims asked were applied (not dropped for too few readings)
};

/// Fits (x, y), x strictly increasing, at least kLocalMinimumPoints readings, with σ ≥ 0 the
/// standard deviation of each reading, m. Nodes from the first reading to the last, half a
/// window's width apart. Throws std::invalid_argument on too few points.
/// `quantized`: the readings' errors are their rounding to q = √12 σ, bounded by q/2 and alike
/// within a bin, so an estimate's error is bounded by q/2 Σ|g_i| (taken as 1.96 standard
/// deviations) instead of σ √(Σ g_i²/c_i).
/// `trim`: readings within trim.front_rad of the first reading and trim.back_rad of the last
/// are left out of every window (a break placed only to within that angle: which side's law
/// they follow is not known), the nodes still reaching the piece's ends; no trim where it would
/// leave fewer than trim.least readings.
struct LocalTrim {
  double front_rad = 0.0, back_rad = 0.0;
  /// The least readings the trims may leave: 2 kLocalMinimumPoints, or kTrimmedLeastReadings
  /// where an end is a break placed only to within some angle (its readings may be the next
  /// piece's: better one window than a fit through them).
  size_t least = 2 * static_cast<size_t>(kLocalMinimumPoints);
};
LocalFit FitLocal(const std::vector<double>& x, const std::vector<double>& y, double sigma_m,
                  bool quantized = false, LocalTrim trim = {});

/// The half-width of s'' of the node nearest the angle `x` (rad; the first of two as near), 0
/// with no nodes.
double NearestHalfWidth(const std::vector<LocalNode>& nodes, double x);

/// The C² quintic Hermite interpolant of the nodes' (s, s', s'').
PiecewisePolynomial QuinticHermite(const std::vector<LocalNode>& nodes);

}  // namespace needle
