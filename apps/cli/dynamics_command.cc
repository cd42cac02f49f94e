#include "apps/cli/dynamics_command.h"

#include <array>
#include <optional>

#include "apps/case/bound_case.h"
#include "apps/case/case_file.h"
#include "apps/cli/cli_checks.h"
#include "apps/cli/progress_bar.h"
#include "apps/report/command_output.h"
#include "apps/report/dynamics_writer.h"
#include "apps/report/output_paths.h"
#include "dynamics/simulation.h"

namespace needle {

CLI::App* AddSimulateCommand(CLI::App& app, SimulateCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "simulate", "Dynamic run: lift-off episodes, impacts, forces, energy audit");
  cmd->add_option("CASE", o.case_path, "case file with [needle], [spring] and [train]")->required();
  AddSpeedOption(cmd, o.run.speed_rpm);
  AddMethodOptions(cmd, o.run.method, o.run.rtol);
  cmd->add_option("--cycles", o.run.cycles,
                  "cam revolutions run back to back, the state carried over, until the state "
                  "repeats (default: [solver] cycles or 1)")
      ->transform(WholeIn(kCyclesRange, "a number of cam revolutions"));
  cmd->add_flag("--dynamic", o.run.dynamic,
                "run the dynamics even where the rigid answer would be reported");
  cmd->add_flag("--json", o.json, "print one JSON object");
  cmd->add_option("--csv", o.csv, "write the time series to this CSV file (atomically)");
  return cmd;
}

int RunSimulateCommand(const SimulateCommandOptions& o) {
  const Case loaded = LoadCase(o.case_path);
  SimulateJobOptions job = o.run;
  job.quasi_static = o.json;  // n_qs: the JSON object's, not the text's
  if (!o.csv)
    return Emit(WriteSimulate(SimulateCase(Bind(loaded), job), o.json), o.format, std::nullopt);
  // The series streamed to the CSV as the run makes it, put in place once the run is done.
  CheckOutputPaths({{"--csv", *o.csv}}, CaseInputs(loaded));
  StreamedCsv csv({"--csv", *o.csv}, SeriesColumns(), kSeriesCsvPrecision);
  const CaseRun run = SimulateCase(Bind(loaded), job, [&csv](const SeriesPoint& p) {
    const std::array<double, 7> row = SeriesRow(p);
    csv.Row(row.data());
  });
  if (run.result.skipped)
    throw CaseError("--csv: no time series to write, " + run.result.method_reason);
  csv.Commit();
  return Emit(WriteSimulate(run, o.json), o.format, std::nullopt);
}

CLI::App* AddOverspeedCommand(CLI::App& app, OverspeedCommandOptions& o) {
  CLI::App* cmd =
      app.add_subcommand("overspeed", "Search the dynamic lift-off speed n_dyn beside n_qs");
  cmd->add_option("CASE", o.case_path, "case file with [needle], [spring] and [train]")->required();
  cmd->add_option("--from", o.search.from_rpm,
                  "start of the sweep, rpm (default: [overspeed] from_rpm or the rated speed)")
      ->check(SpeedRpm());
  cmd->add_option(
         "--to", o.search.to_rpm,
         "end of the sweep, rpm (default: [overspeed] to_rpm, else the larger of 2 x n_qs and 2 x "
         "the rated speed)")
      ->check(SpeedRpm());
  AddMethodOptions(cmd, o.search.method, o.search.rtol);
  cmd->add_option("--threads", o.search.threads,
                  "threads (default and 0: all cores, which is also the most)")
      ->transform(WholeIn(kThreadsRange, "a number of threads"));
  cmd->add_option("--step-rpm", o.search.step_rpm,
                  "scan step where the contact force gives no guidance (default 2.5 % of --from, "
                  "at least 1 rpm); elsewhere the force leads the steps (docs/model.md section 6)")
      ->check(InRange(kSpeedStepRange, "a speed step in rpm"));
  cmd->add_flag("--json", o.json, "print one JSON object");
  return cmd;
}

int RunOverspeedCommand(const OverspeedCommandOptions& o) {
  const BoundCase c = Bind(LoadCase(o.case_path));
  CommandOutput r;
  {
    ProgressBar bar("overspeed", "speeds", o.json, true);
    r = WriteOverspeed(
        OverspeedOfCase(c, o.search, [&](int done, int total) { bar.Update(done, total); }),
        o.json);
  }
  return Emit(r, o.format, std::nullopt);
}

}  // namespace needle
