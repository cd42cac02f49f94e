#pragma once
/// @file
/// The kinematics job: a lift law's velocity and acceleration table, like NACA TM 477's,
///
///   v(θ) = ω · ds/dθ,   a(θ) = ω² · d²s/dθ²,   j(θ) = ω³ · d³s/dθ³,   ω = 2π n / 60,
///
/// at every multiple of a step over the lift table, with the paper's published velocities
/// beside it where the case gives them. `needle kinematics` and the Python module call it; the
/// writer is apps/report/kinematics_writer.h.

#include <optional>
#include <string>
#include <vector>

#include "apps/case/bound_case.h"
#include "lib/kinematics.h"
#include "lib/lift_data.h"
#include "lib/lift_law.h"

namespace needle {

/// What the table is made with. Messages name the command's options (--rpm, --step); a
/// --spline is the case's, set before it is bound (WithSpline, apps/case/case_scene.h).
struct KinematicsTableOptions {
  std::optional<double> speed_rpm;  ///< crank speed, rpm (default: [engine] speed_rpm)
  double step_deg = 5.0;            ///< row spacing, crank deg, in kTableStepRange
};

/// How far the table's |v| lies from the paper's published velocities.
struct PaperVelocityDeviation {
  int points = 0;               ///< the paper's velocity points
  double mean_abs_m_s = 0.0;    ///< mean | |v| − v_paper |, m/s
  double largest_m_s = 0.0;     ///< the largest, m/s
  double largest_at_rad = 0.0;  ///< where, crank rad
};

struct KinematicsTable {
  BoundCase c;                                  ///< the case, with the spline asked for
  double speed_rpm = 0.0;                       ///< the speed of the table, rpm
  LiftLawChoice choice;                         ///< the spline chosen, and why
  LiftLaw law;                                  ///< the lift law
  KinematicsSummary summary;                    ///< extremes, open lift, injection period
  std::vector<KinematicsPoint> rows;            ///< the rows, by crank angle
  std::optional<PaperVelocityDeviation> paper;  ///< when the case gives the paper's velocities
};

/// The table of a bound case. Throws CaseError on bad input (an option out of range, more than
/// 100 000 rows).
KinematicsTable MakeKinematicsTable(const BoundCase& c, const KinematicsTableOptions& options);

}  // namespace needle
