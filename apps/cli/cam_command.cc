#include "apps/cli/cam_command.h"

#include <vector>

#include "apps/case/bound_case.h"
#include "apps/case/case_file.h"
#include "apps/report/cam_writer.h"
#include "apps/report/command_output.h"
#include "apps/report/output_paths.h"
#include "apps/study/profile_job.h"
#include "apps/study/synthesis_scene.h"

namespace needle {

CLI::App* AddSynthCommand(CLI::App& app, SynthCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "synth", "Synthesize a cam law under derivative limits (constant-speed section)");
  cmd->add_option("SPEC", o.spec_path,
                  "synthesis file (TOML): [rise], [limits], [checks], [output]")
      ->required();
  cmd->add_flag("--json", o.json, "print one JSON object");
  cmd->add_option("--csv", o.csv,
                  "write the law (cam_deg, S_mm, S1_mm_rad, S2_mm_rad2, S3_mm_rad3)");
  cmd->add_option("--case", o.case_out, "write the law as a needle case file");
  return cmd;
}

int RunSynthCommand(const SynthCommandOptions& o) {
  const SynthesisFile f = LoadSynthesisFile(o.spec_path);
  {
    std::vector<OutputPath> outputs;
    if (o.csv) outputs.push_back({"--csv", *o.csv});
    if (o.case_out) outputs.push_back({"--case", *o.case_out});
    CheckOutputPaths(outputs, {o.spec_path});
  }
  const CommandOutput r =
      WriteSynth(f, SynthesizeCam(f), {o.json, o.csv.has_value(), o.case_out.has_value()});
  if (o.case_out) WriteOutput({"--case", *o.case_out}, r.case_file);
  return Emit(r, o.format, o.csv);
}

CLI::App* AddProfileCommand(CLI::App& app, ProfileCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "profile",
      "Cam profile for a roller, flat-face or curved-face follower: coordinates, pressure angle, "
      "undercut, contact on the face, entrainment and sliding");
  cmd->add_option("CASE", o.case_path, "case file with [lift] and [profile] (and [train] play)")
      ->required();
  cmd->add_flag("--json", o.json, "print one JSON object");
  cmd->add_option("--csv", o.csv, "write cam_deg, x_mm, y_mm for manufacture");
  return cmd;
}

int RunProfileCommand(const ProfileCommandOptions& o) {
  const Case loaded = LoadCase(o.case_path);
  if (o.csv) CheckOutputPaths({{"--csv", *o.csv}}, CaseInputs(loaded));
  const BoundCase c = Bind(loaded);
  return Emit(WriteProfile(ProfileOfCase(c), {o.json, o.csv.has_value(), false}), o.format, o.csv);
}

}  // namespace needle
