#include "apps/cli/spring_command.h"

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/case/case_file.h"
#include "apps/case/case_scene.h"
#include "apps/cli/cli_checks.h"
#include "apps/report/command_output.h"
#include "apps/report/output_paths.h"
#include "apps/report/result_writers.h"
#include "lib/kinematics.h"
#include "lib/output.h"
#include "lib/units.h"
#include "spring/basu_formula.h"
#include "spring/design_chain.h"
#include "spring/helical_spring.h"
#include "spring/quasi_static.h"
#include "spring/spring_check.h"

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
  return Emit(ComputeSpring(LoadCase(o.case_path), o), o.format, std::nullopt);
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
  const CommandOutput r = ComputeDesign(in, o);
  if (o.case_out) WriteOutput({"--case", *o.case_out}, r.case_file);
  return Emit(r, o.format, std::nullopt);
}

}  // namespace needle
