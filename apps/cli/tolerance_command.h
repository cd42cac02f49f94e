#pragma once
/// @file
/// `needle tolerance CASE [--samples N] [--seed S] [--first-sample K] [--threads T] [--out DIR]
/// [--json]`: a Monte-Carlo tolerance study (apps/study/tolerance_study.h) on all cores,
/// reproducible for a seed whatever the thread count: the distributions of what `check` reports,
/// the probability that the check fails (by item) and the inputs that drive it, with histograms in
/// DIR/tolerance-<case>.html. Exit 0; 2 on bad input.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>

#include "apps/report/output_format.h"

namespace needle {

struct ToleranceCommandOptions {
  std::string case_path;
  int samples = 1000;                  ///< N, [1, 1e6]
  uint64_t seed = 1;                   ///< the same seed, the same study
  int first_sample = 0;                ///< a shard: samples [first, first + N) of the study
  int threads = 0;                     ///< 0: all cores
  std::optional<std::string> out_dir;  ///< the report's folder; none: no report
  bool json = false;
  OutputFormat format = OutputFormat::kText;  ///< --format (json set for kJson, kMarkdown)
};

CLI::App* AddToleranceCommand(CLI::App& app, ToleranceCommandOptions& options);
int RunToleranceCommand(const ToleranceCommandOptions& options);

}  // namespace needle
