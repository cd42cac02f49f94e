#include "apps/cli/check_command.h"

#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>

#include "apps/case/case_file.h"
#include "apps/cli/cli_checks.h"
#include "apps/cli/progress_bar.h"
#include "apps/report/check_writers.h"
#include "apps/report/html_report.h"
#include "apps/report/output_paths.h"
#include "apps/study/check_scene.h"
#include "dynamics/overspeed.h"
#include "lib/output.h"

namespace needle {
namespace {

std::string Num(double v, int digits) {
  return std::isfinite(v) ? Fixed(v, digits) : std::string("none");
}

}  // namespace

CLI::App* AddCheckCommand(CLI::App& app, CheckCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "check", "The main job: check a scene end to end and write an HTML report");
  cmd->add_option("CASE", o.case_path, "case file (TOML)")->required();
  cmd->add_option("--out", o.out_dir, "folder for the report (default: the current folder)");
  AddSpeedOption(cmd, o.speed_rpm, "rated speed in rpm (default: [engine] speed_rpm)");
  cmd->add_flag("--json", o.json,
                "print one JSON object (the verdict, every failing item, what was skipped and the "
                "numbers behind them) instead of the text summary");
  return cmd;
}

int RunCheckCommand(const CheckCommandOptions& o) {
  const Case c = LoadCase(o.case_path);
  const std::string path =
      ReportPath(o.out_dir, std::filesystem::path(c.path).stem().string() + ".html");
  CheckOutputPaths({{"--out", path}}, CaseInputs(c));
  RequireGnuplot();
  CheckOptions options;
  options.speed_rpm = o.speed_rpm;
  const CaseLift lift = ResolveLift(c);
  const LiftLaw& law = *lift.law;
  CheckResult result;
  {
    ProgressBar bar("overspeed", "speeds", o.json);
    options.progress = [&](int done, int total) { bar.Update(done, total); };
    result = CheckScene(c, lift, options);
  }
  const Report report = CheckReport(c, law, result);
  WriteOutput({"--out", path}, report.Html());
  if (o.json) {
    std::cout << FormatObject(CheckJson(c, law, result, path), o.format);
    return result.pass ? 0 : 1;
  }
  std::cout << (c.title.empty() ? c.path : c.title) << '\n';
  for (const auto& k : result.skipped) std::cout << "skipped: " << k << '\n';
  if (result.spring)
    std::cout << "spring check: " << (result.spring->pass ? "pass" : "FAIL") << '\n';
  if (result.profile)
    std::cout << "cam profile: " << (result.profile->undercut ? "UNDERCUT" : "no undercut") << '\n';
  if (result.run)
    std::cout << "lift-off at " << Fixed(result.speed_rpm, 0)
              << " rpm: " << (result.run->liftoff() ? "YES" : "no") << '\n';
  if (result.sweep) {
    std::cout << "n_qs " << Num(result.n_qs_rpm, 1) << " rpm, n_dyn "
              << OverspeedOutcome(*result.sweep) << '\n';
  }
  if (!result.limits.empty()) {
    std::cout << "limits (value, limit, margin, verdict):\n";
    for (const LimitRow& x : result.limits) {
      const std::string u = x.UnitSuffix();
      std::cout << "  " << x.name << ": "
                << (x.verdict == "not judged"
                        ? "not judged (" + x.note + ")"
                        : Num(x.value, 2) + u + (x.at_most ? " <= " : " >= ") + Num(x.limit, 2) +
                              u + ", margin " + Num(x.margin, 2) + u + ", " + x.verdict)
                << '\n';
    }
  }
  for (const auto& w : result.warnings) std::cout << "warns: " << w << '\n';
  for (const auto& f : result.failing) std::cout << "fails: " << f << '\n';
  std::cout << "report: " << path << " (" << report.figures() << " figures)\n"
            << "overall: " << (result.pass ? "pass" : "FAIL") << '\n';
  return result.pass ? 0 : 1;
}

}  // namespace needle
