#pragma once
/// @file
/// What a command computes from a loaded case, apart from where it goes. The `needle` command
/// prints it and writes its files (Emit); the Python module (apps/python) returns the same JSON
/// object as a dict and the columns as NumPy arrays. The Compute functions of the commands
/// (kinematics_command.h, …) read no file and write none.

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "apps/report/output_format.h"

namespace needle {

struct CommandOutput {
  int status = 0;         ///< the exit status: 0, or 1 when a check fails
  nlohmann::json json;    ///< the --json object (built when the options ask for JSON)
  std::string text;       ///< the text report (built when they do not)
  std::string csv;        ///< the --csv file's content (built when the options name a file)
  std::string case_file;  ///< synth's --case file's content (when asked)
  /// The command's table as columns in SI, each key with its unit (crank_rad, lift_m, …);
  /// NaN where a value is missing.
  std::map<std::string, std::vector<double>> columns;
};

/// Writes `r.csv` to `csv_path` (when given, atomically, as the --csv option), then prints the
/// JSON object in `format` (json or markdown) or, for text, the text to stdout; returns
/// `r.status`.
int Emit(const CommandOutput& r, OutputFormat format, const std::optional<std::string>& csv_path);

/// Prints a text report to stdout with its control characters escaped (EscapeControls: a title
/// or a path typed with an escape sequence does not drive the terminal), and flushes.
void PrintText(const std::string& text);

}  // namespace needle
