#pragma once
/// @file
/// `needle spring CASE [--rpm N] [--json]`: Basu's formula beside the case's spring, the
/// inertia force, the quasi-static contact force and lift-off speed, the preload sizing,
/// and the helical spring check. Exit 1 when the spring fails a check.
///
/// `needle design ENGINE [--json]`: Basu's design chain from engine data.

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "apps/case/case_file.h"
#include "apps/report/output_format.h"

namespace needle {

struct SpringCommandOptions {
  std::string case_path;
  std::optional<double> speed_rpm;  ///< overrides [engine] speed_rpm
  bool json = false;
  OutputFormat format = OutputFormat::kText;  ///< --format (json set for kJson, kMarkdown)
};

CLI::App* AddSpringCommand(CLI::App& app, SpringCommandOptions& options);
int RunSpringCommand(const SpringCommandOptions& options);

struct DesignCommandOptions {
  std::string engine_path;
  bool json = false;
  OutputFormat format = OutputFormat::kText;  ///< --format (json set for kJson, kMarkdown)
  std::optional<std::string> case_out;        ///< --case: write a complete case for `needle check`
};

CLI::App* AddDesignCommand(CLI::App& app, DesignCommandOptions& options);
int RunDesignCommand(const DesignCommandOptions& options);

}  // namespace needle
