#include "apps/report/command_output.h"

#include <iostream>

#include "apps/report/output_paths.h"
#include "lib/case_error.h"

namespace needle {

int Emit(const CommandOutput& r, OutputFormat format, const std::optional<std::string>& csv_path) {
  if (csv_path) WriteOutput({"--csv", *csv_path}, r.csv);
  if (format != OutputFormat::kText) {
    std::cout << FormatObject(r.json, format) << std::flush;
  } else {
    PrintText(r.text);
  }
  return r.status;
}

void PrintText(const std::string& text) { std::cout << EscapeControls(text, true) << std::flush; }

}  // namespace needle
