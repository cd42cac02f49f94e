#include "apps/cli/compare_command.h"

#include <filesystem>
#include <iostream>

#include "apps/case/bound_case.h"
#include "apps/case/case_file.h"
#include "apps/cli/cli_checks.h"
#include "apps/cli/progress_bar.h"
#include "apps/report/command_output.h"
#include "apps/report/compare_writer.h"
#include "apps/report/html_report.h"
#include "apps/report/output_paths.h"
#include "apps/study/compare_checks.h"

namespace needle {

CLI::App* AddCompareCommand(CLI::App& app, CompareCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "compare", "Two designs side by side: every quantity and verdict of check, and the flips");
  cmd->add_option("A", o.a_path, "the design (case file)")->required();
  cmd->add_option("B", o.b_path, "the design set against it (case file)")->required();
  cmd->add_option("--out", o.out_dir, "folder for the report compare-A-B.html (default .)");
  AddSpeedOption(cmd, o.speed_rpm, "rated speed for both, rpm (default: each case's own)");
  cmd->add_flag("--json", o.json, "print one JSON object instead of the text");
  return cmd;
}

int RunCompareCommand(const CompareCommandOptions& o) {
  Case a = LoadCase(o.a_path), b = LoadCase(o.b_path);
  Gnuplot gnuplot;  // started now: its start-up runs beside the comparison
  const auto stem = [](const Case& c) { return std::filesystem::path(c.path).stem().string(); };
  const std::string path = ReportPath(o.out_dir, "compare-" + stem(a) + "-" + stem(b) + ".html");
  {
    std::vector<std::string> inputs = CaseInputs(a);
    for (const std::string& in : CaseInputs(b)) inputs.push_back(in);
    CheckOutputPaths({{"--out", path}}, inputs);
  }
  Comparison cmp;
  {
    ProgressBar bar("compare", "runs", o.json, true);
    BoundCase bound_a = Bind(a);  // A's problem first
    cmp = CompareCases(std::move(bound_a), Bind(b), o.speed_rpm,
                       [&](int done, int total) { bar.Update(done, total); });
  }
  WriteOutput({"--out", path}, CompareReport(cmp).Html(gnuplot));
  if (o.json) {
    std::cout << FormatObject(CompareJson(cmp, path), o.format) << std::flush;
  } else {
    PrintText(CompareText(cmp, path));
  }
  return cmp.status();
}

}  // namespace needle
