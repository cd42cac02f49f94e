#include "apps/cli/kinematics_command.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/case/case_file.h"
#include "apps/case/case_scene.h"
#include "apps/cli/cli_checks.h"
#include "apps/report/command_output.h"
#include "apps/report/kinematics_writer.h"
#include "apps/report/output_paths.h"
#include "lib/kinematics.h"
#include "lib/output.h"
#include "lib/units.h"

namespace needle {

CLI::App* AddKinematicsCommand(CLI::App& app, KinematicsCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "kinematics", "Velocity and acceleration table of a lift law (like NACA TM 477's)");
  cmd->add_option("CASE", o.case_path, "case file (TOML)")->required();
  AddSpeedOption(cmd, o.table.speed_rpm);
  cmd->add_option("--step", o.table.step_deg,
                  "table spacing in crank degrees, 0.001 to 90 (default 5; at most 100000 rows)")
      ->check(InRange(kTableStepRange, "a spacing in crank degrees"));
  cmd->add_option("--spline", o.spline,
                  "spline kind (default: [lift] spline): " + SplineKindList());
  cmd->add_option("--units", o.units,
                  "table units: paper (mm, dcm/s, m/s^2) or si (m, m/s, m/s^2, m/s^3)")
      ->check(CLI::IsMember({"paper", "si"}));
  cmd->add_flag("--json", o.json, "print one JSON object instead of the table");
  cmd->add_option("--csv", o.csv, "also write the table to this CSV file (atomically)");
  cmd->add_option("--cycle", o.cycle, "a bare CSV table: four-stroke (default) or two-stroke")
      ->check(CLI::IsMember({"four-stroke", "two-stroke"}));
  cmd->add_option("--noise-mm", o.noise_mm,
                  "a bare CSV table: standard deviation of its readings in mm (default: "
                  "estimated)")
      ->check(InRange(kNoiseOptionRange, "a noise in mm"));
  return cmd;
}

int RunKinematicsCommand(const KinematicsCommandOptions& o) {
  const bool bare_csv = IsCsvPath(o.case_path);
  if (bare_csv && !o.table.speed_rpm) {
    throw CaseError("--rpm: " + o.case_path +
                    " is a bare CSV lift table with no [engine] speed_rpm; give --rpm");
  }
  if (!bare_csv && o.cycle)
    throw CaseError("--cycle: applies to a bare CSV table; a case file states [engine] cycle");
  if (!bare_csv && o.noise_mm)
    throw CaseError("--noise-mm: only for a bare CSV table; a case states [lift] noise_mm");
  Case c = bare_csv
               ? CaseFromLiftCsv(o.case_path, *ParseEngineCycle(o.cycle.value_or("four-stroke")))
               : LoadCase(o.case_path);
  if (o.csv) CheckOutputPaths({{"--csv", *o.csv}}, CaseInputs(c));
  if (o.noise_mm) c.lift.noise_m = *o.noise_mm * 1e-3;
  if (o.spline) c = WithSpline(std::move(c), *o.spline, "--spline");
  const KinematicsTable table = MakeKinematicsTable(Bind(c), o.table);
  return Emit(WriteKinematics(table, {o.json, o.csv.has_value(), o.units == "paper"}), o.format,
              o.csv);
}

}  // namespace needle
