#pragma once
/// @file
/// The two end nodes of a local fit at a break of s'' (lib/local_fit.h): their bands from one
/// fit of both sides with the slope shared.

#include <vector>

#include "lib/local_fit.h"

namespace needle {

/// At a break t of s'' between two pieces (s and s' continuous there, s'' not), the two end
/// nodes' bands reach what one weighted fit of both sides' windows reads: one s and s' shared,
/// each side its own s'' … s⁽⁵⁾ terms and tricube weights (`left`: the last left->window readings
/// of (xl, yl), which ends at t; `right`: the first right->window of (xr, yr), which starts at t),
/// narrowed by Lepski's factor until its polynomials fit the readings as a window's must
/// (Misfits). Each side's window alone leaves s' free, and a one-sided quintic's s'' at its end
/// carries that error: a harmonic return over 30° straight from a harmonic rise, every 2° to
/// 1e-4 mm, read −1.7 % at its start, the truth past the band's unsafe end (a spring 0.7 % short
/// of its need passed); joined, −0.4 %. Each node keeps its own value: a junction a fraction of a
/// step off the reading, which the readings cannot tell (the break finder's own estimate
/// is off by 0.03–0.15 of a step on such junctions, by 0.04 on one exactly at the reading), makes
/// one shared s' wrong (a double harmonic at 0.3° to 1e-4 mm, its junction 0.09 of a step before
/// the reading: joined, a_min 18 % off instead of 1.2 %). Its band reaches the joint s'' with the
/// joint fit's noise and what its own band held beyond its own window's noise (truncation, the
/// half-density fit's bias). False (bands untouched) where either piece is binned (over
/// kLocalMaxNodes readings), a node is not at t, or no joint fit fits.
/// (A widened band also enters KinkPeaks' test of a bend, lib/reading_kinks.h, which could then
/// pass over a kink in the piece's second interval; none of the trials shows it.)
bool JoinAtBreak(const std::vector<double>& xl, const std::vector<double>& yl,
                 const std::vector<double>& xr, const std::vector<double>& yr, double sigma_m,
                 bool quantized, LocalNode* left, LocalNode* right);

}  // namespace needle
