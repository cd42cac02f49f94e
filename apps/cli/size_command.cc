#include "apps/cli/size_command.h"

#include <optional>

#include "apps/case/bound_case.h"
#include "apps/cli/cli_checks.h"
#include "apps/report/output_paths.h"
#include "apps/report/size_writer.h"
#include "apps/study/spring_sizing_scene.h"
#include "lib/input_file.h"

namespace needle {

CLI::App* AddSizeCommand(CLI::App& app, SizeCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "size", "Size the valve spring: the lightest that passes every limit, verified end to end");
  cmd->add_option("CASE", o.case_path, "case file with [needle] and [spring] (and [sizing])")
      ->required();
  cmd->add_option("--case", o.case_out, "write the case with the sized spring");
  cmd->add_option("--threads", o.sizing.threads,
                  "threads of the verification's sweeps (0: all cores)")
      ->transform(WholeIn(kThreadsRange, "a number of threads"));
  cmd->add_flag("--json", o.json, "print one JSON object");
  return cmd;
}

int RunSizeCommand(const SizeCommandOptions& o) {
  const Case loaded = LoadCase(o.case_path);
  if (o.case_out) CheckOutputPaths({{"--case", *o.case_out}}, CaseInputs(loaded));
  const BoundCase c = Bind(loaded);
  SizeWriting writing{o.json, std::nullopt};
  if (o.case_out) writing.case_text = ReadInputFile(o.case_path, "case file");
  const CommandOutput r = WriteSize(c, SizeCase(c, *c.lift.law, o.sizing), writing);
  if (o.case_out && !r.case_file.empty()) WriteOutput({"--case", *o.case_out}, r.case_file);
  return Emit(r, o.format, std::nullopt);
}

}  // namespace needle
