#pragma once
/// @file
/// Internal to lib/'s local fit (lift_law.cc's pieces): a peak of s'' at a kink (s''' jumps: a
/// B-spline's knot, a junction of two laws that no break marks), found from the readings
/// (ReadingKinks, which the law passes through) or from the nodes (KinkPeaks, which the band
/// reaches).
///
/// A smooth law's s'' peaks smoothly; a kinked one's peaks at the kink, s''(ξ) reached from
/// both sides by laws that meet there with equal s, s', s''. Every window of the local fit that
/// holds ξ averages across it and rounds the peak off (a cubic B-spline with knots 8° apart, read
/// every 1.5°, comes out 2.5 % low in |a|; every 0.5° to 1e-3 mm, 7 % low). Near each extreme of
/// s'' the readings are split at every gap where a polynomial of degree d + 2 misfits the d + 2
/// readings on each side while each side's fit one of degree d (3, then 5); each side is then
/// fitted by the longest run of readings that a polynomial of degree d fits to the rounding (no
/// residual above q = √12 σ, the local fit's own test). Where the two sides' s'' meet in the gap,
/// with s and s' agreeing to their error, and s''' differing by more than its error (KinkOf has
/// the rules), the kink is there, and its s'' exact but for the sides' error: the rounding's,
/// q/2 Σ|g_i| (g_i the weights of s''(ξ) on the readings; its bound, taken as 95 %), and their
/// truncation's, the change from sides of half as many readings. On a rounded table no reading may
/// show a kink (each side, moved across it, still fits the rounding); there the sum of squares
/// tells it: a cubic kinked in the gap leaves far less of both sides' readings than a septic
/// through them, which misfits beyond the rounding (tried at the gaps above, and within a few
/// readings of the fit's own top at every gap).

#include <vector>

#include "lib/local_fit.h"

namespace needle {

/// The kinks of s'' near the fit's largest and least s'' (between the nodes beside either's node)
/// that peak beyond the fit there (a V whose top its windows round off) and reach the extreme
/// node's band, by angle, each as a node: x = ξ, s, s', s'' the sides' there, band2 their error,
/// window the readings of both sides. Only kinks the readings place (or their squares tell, as
/// above): one of s''' jump J shows in a side that reaches δ past it as J δ³/6, so no other of
/// its size hides inside a side where δ = (6q/J)^⅓ is under a step (a 9-decimal table's; 1e-3 mm
/// every 0.5°: δ ≈ 2°, and the sides may each hold one). (x, y): one piece's readings of an exact
/// or rounded table (σ the rounding's, q/√12), at most kLocalMaxNodes of them (none otherwise);
/// those `trim` leaves out of the fit's windows are left out here too.
std::vector<LocalNode> ReadingKinks(const std::vector<double>& x, const std::vector<double>& y,
                                    double sigma_m, const LocalFit& fit, LocalTrim trim = {});

/// The kinks ReadingKinks finds, made nodes of `fit` (in place of a node nearer than half its own
/// spacing, a quarter of its width: two nodes that close would carry their values' error into
/// s'' over the square of their spacing), its law made anew through them.
void AddReadingKinks(const std::vector<double>& x, const std::vector<double>& y, double sigma_m,
                     LocalTrim trim, LocalFit* fit);

/// A peak of s'' at a kink (s''' jumps: a B-spline's knot, a junction no break marks) between two
/// nodes rises above both, and the law between them rounds it off. A kink shows in the nodes'
/// second differences: those of the interval's two nodes, whose stencils straddle it, stand above
/// those beside them by kKinkContrast (a smooth peak's change slowly), and each of the two bends
/// off its neighbours' line by more than twice their half-widths; both nodes are of the narrowest
/// windows (kLocalMinimumPoints readings: an exact table's). There the secant through the
/// interval's left node and the one before it and the secant through its right node and the one
/// after it meet inside the interval above both its nodes, and the peak may reach that point
/// (exactly, for an s'' linear on each side of the kink; above it where s'' is concave on each
/// side). Returns each such point (of the largest sign·s'') as a node: x, s[2] the point's s'',
/// band2 the larger half-width of the interval's nodes (s, s' left 0 for the caller). Nodes with
/// the same angle are two pieces' ends at a break: four consecutive nodes are on one piece when
/// their angles increase strictly, so a kink in a piece's first or last interval is not seen.
std::vector<LocalNode> KinkPeaks(const std::vector<LocalNode>& nodes, double sign);

}  // namespace needle
