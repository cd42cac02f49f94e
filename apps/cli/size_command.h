#pragma once
/// @file
/// `needle size CASE [--case FILE] [--json] [--threads N]`: the lightest valve spring (or the
/// shortest, or the least stressed: [sizing] objective) that passes every rule of the spring
/// check in closed form, the best few then checked end to end as `needle check` would
/// (apps/study/spring_sizing_scene.h). Prints the spring, its rules with margins, the check's
/// limits table, the next best springs and the front between mass and fatigue safety factor;
/// `--case FILE` writes the case with the sized spring. Exit 1 when no spring fits, naming the
/// binding rule, by how much, and the best spring.

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "apps/case/case_file.h"
#include "apps/report/output_format.h"
#include "apps/study/spring_sizing_scene.h"

namespace needle {

struct SizeCommandOptions {
  std::string case_path;
  bool json = false;
  OutputFormat format = OutputFormat::kText;  ///< --format (json set for kJson, kMarkdown)
  std::optional<std::string> case_out;        ///< --case: write the sized case
  SizeOptions sizing;                         ///< --threads
};

CLI::App* AddSizeCommand(CLI::App& app, SizeCommandOptions& options);
int RunSizeCommand(const SizeCommandOptions& options);

}  // namespace needle
