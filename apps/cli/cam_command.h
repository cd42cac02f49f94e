#pragma once
/// @file
/// `needle synth SPEC [--json] [--csv FILE] [--case FILE]`: a rise law under derivative limits
/// (MATEC 2018), with its constant-speed section; `needle profile CASE [--json] [--csv FILE]`:
/// the cam profile for a roller follower with its pressure angle, curvature and undercut check.

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "apps/case/case_file.h"
#include "apps/report/output_format.h"

namespace needle {

struct SynthCommandOptions {
  std::string spec_path;
  bool json = false;
  OutputFormat format = OutputFormat::kText;  ///< --format (json set for kJson, kMarkdown)
  std::optional<std::string> csv, case_out;
};
CLI::App* AddSynthCommand(CLI::App& app, SynthCommandOptions& options);
/// Exit 1 when a check of [checks] fails.
int RunSynthCommand(const SynthCommandOptions& options);

struct ProfileCommandOptions {
  std::string case_path;
  bool json = false;
  OutputFormat format = OutputFormat::kText;  ///< --format (json set for kJson, kMarkdown)
  std::optional<std::string> csv;
};
CLI::App* AddProfileCommand(CLI::App& app, ProfileCommandOptions& options);
/// Exit 1 when the profile undercuts.
int RunProfileCommand(const ProfileCommandOptions& options);

}  // namespace needle
