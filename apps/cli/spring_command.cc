#include "apps/cli/spring_command.h"

#include "apps/case/bound_case.h"
#include "apps/case/case_file.h"
#include "apps/cli/cli_checks.h"
#include "apps/report/command_output.h"
#include "apps/report/output_paths.h"
#include "apps/report/spring_writer.h"
#include "apps/study/spring_job.h"

namespace needle {

CLI::App* AddSpringCommand(CLI::App& app, SpringCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "spring",
      "Spring check: Basu's formula, quasi-static lift-off, preload sizing, helical spring");
  cmd->add_option("CASE", o.case_path, "case file (TOML) with [needle] and [spring]")->required();
  AddSpeedOption(cmd, o.speed_rpm);
  cmd->add_flag("--json", o.json, "print one JSON object");
  return cmd;
}

int RunSpringCommand(const SpringCommandOptions& o) {
  return Emit(WriteSpring(CheckCaseSpring(Bind(LoadCase(o.case_path)), o.speed_rpm), o.json),
              o.format, std::nullopt);
}

CLI::App* AddDesignCommand(CLI::App& app, DesignCommandOptions& o) {
  CLI::App* cmd =
      app.add_subcommand("design", "Basu's design chain from engine data to cam, valve and spring");
  cmd->add_option("ENGINE", o.engine_path, "engine file (TOML) with [engine] and [design]")
      ->required();
  cmd->add_flag("--json", o.json, "print one JSON object, every quantity with its unit in the key");
  cmd->add_option("--case", o.case_out,
                  "write a complete case for `needle check`: the normal-curve lift, the needle, "
                  "Basu's spring, the cam profile, and each assumption marked as such");
  return cmd;
}

int RunDesignCommand(const DesignCommandOptions& o) {
  const DesignInputs in = LoadDesignInputs(o.engine_path);
  if (o.case_out) CheckOutputPaths({{"--case", *o.case_out}}, {in.path});
  const CommandOutput r = WriteDesign(in, DesignFromEngine(in), o.json, o.case_out);
  if (o.case_out) WriteOutput({"--case", *o.case_out}, r.case_file);
  return Emit(r, o.format, std::nullopt);
}

}  // namespace needle
