#pragma once
/// @file
/// The 95 % band of s'' of the splines that are not local fits (docs/lift-data.md, "Bands"),
/// as nodes (lib/local_fit.h LocalNode) the law's bands are read from, as a local fit's are.
///
/// An interpolating spline (natural, not-a-knot, clamped, quintic) is linear in the readings,
/// s''(x_j) = Σ_i g_ji s_i, so the rounding's σ makes s''(x_j) uncertain by σ‖g_j‖; its
/// truncation error, O(h²) in s'' for a cubic, is estimated from the same spline through every
/// other reading (both ends kept): twice the spacing makes four times the error, so the error
/// at the table's spacing is |s''_half − s''|/3 (Richardson; the larger of the two halves). A
/// sparse table (SplineOptions::sparse_table) is short of the h² regime: its error is taken to
/// fall as h^1.32, |s''_half − s''|/1.5.
///
///     band_j = 1.96 σ ‖g_j‖ + max over halves |s''_half(x_j) − s''(x_j)| / (3, or 1.5 sparse).
///
/// A smoothing spline (measured data) at the knots of its largest and smallest s'': for its λ
/// the fit is linear in the readings, γ = A⁻¹Qᵀy (lib/smoothing_spline.cc), so
/// sd(γ_j) = σ ‖Q A⁻¹ e_j‖; its bias, the peak the smoothing flattens, is estimated by smoothing
/// the fit once more (the bias of S applied to ŝ ≈ the bias of S applied to s):
///
///     band_j = 1.96 sd(γ_j) + |γ_j(S ŝ) − γ_j(ŝ)|.

#include <vector>

#include "lib/local_fit.h"
#include "lib/spline.h"

namespace needle {

/// Tables up to this many readings get an interpolating spline's band (26 splines built: O(n)).
constexpr int kInterpolationBandPoints = 2000;

/// The nodes of `law`, the spline of `options.kind` through (x, y), at every reading; none when
/// the kind is not an interpolating one with s'' (natural, not-a-knot, clamped, quintic), the
/// table has more than kInterpolationBandPoints readings, or too few for its halves.
std::vector<LocalNode> InterpolationNodes(const std::vector<double>& x,
                                          const std::vector<double>& y,
                                          const SplineOptions& options,
                                          const PiecewisePolynomial& law);

/// A local fit's bias that all its windows share (a rounded table's wide windows flatten its
/// peaks alike) is not in its nodes' bands: the fit through every other reading (both ends
/// kept), whose windows span twice the angle, differs from it by about three times that bias.
/// Adds that difference to each node's half-width, for tables of up to kLocalMaxNodes readings
/// (the coarse ones); `fit` is FitLocal's of (x, y) with `options`' σ.
void AddLocalFitBias(const std::vector<double>& x, const std::vector<double>& y,
                     const SplineOptions& options, LocalFit* fit, LocalTrim trim = {});

/// The smoothing spline through (x, y) (BuildSmoothingSpline) and its nodes at the knots of its
/// largest and smallest s'' (none when the fit is the least-squares line).
LocalFit BuildSmoothingFit(const std::vector<double>& x, const std::vector<double>& y,
                           const SplineOptions& options);

}  // namespace needle
