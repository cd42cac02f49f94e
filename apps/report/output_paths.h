#pragma once
/// @file
/// Output paths are user input (issue 12): every one is checked before anything is computed or
/// written, and a failure is one CaseError line naming the option (exit 2), never a half set
/// of outputs or an "internal error".
///
///   - the path is not a folder, and its folder exists (or, for a folder option, can be made)
///     and is writable;
///   - it is not one of the command's inputs (`--csv case.toml` would overwrite the case);
///   - no two outputs of one run are the same file.

#include <memory>
#include <string>
#include <vector>

#include "apps/case/bound_case.h"
#include "lib/output.h"
#include "lib/result_fields.h"

namespace needle {

/// One output of a command: the option that named it and the path.
struct OutputPath {
  std::string option;  ///< "--csv", "--case", …
  std::string path;
};

/// Checks every output file before any is written. `inputs` are the files the command reads.
/// Throws CaseError "OPTION: PATH: what is wrong".
void CheckOutputPaths(const std::vector<OutputPath>& outputs,
                      const std::vector<std::string>& inputs);

/// The files a case reads: the case itself (`path`) and its lift CSV, if any (`lift_source`
/// "csv FILE").
std::vector<std::string> CaseInputs(const std::string& path, const std::string& lift_source);
/// The same of a case, loaded (case_file.h) or bound: checked before it is bound.
template <class AnyCase>
std::vector<std::string> CaseInputs(const AnyCase& c) {
  return CaseInputs(c.path, c.lift.source);
}

/// DIR/NAME, a report's path under the --out folder DIR, which is made when missing; throws
/// CaseError "--out: DIR is not a folder and cannot be made one" when it cannot be.
std::string ReportPath(const std::string& out_dir, const std::string& name);
/// Removes the folders ReportPath made that are still empty (a command that failed before its
/// report: nothing written, not even the folder).
void RemoveEmptyMadeFolders();

/// Writes `content` atomically (lib/output.h); a failure is a CaseError naming the option.
void WriteOutput(const OutputPath& output, const std::string& content);

/// A CSV output written row by row as a run makes them (memory independent of the row count)
/// and put in place by Commit(), atomically; destroyed uncommitted it leaves nothing. Failures
/// are CaseErrors naming the option.
class StreamedCsv {
 public:
  StreamedCsv(const OutputPath& output, std::vector<Column> columns, int precision);
  /// One row of columns().size() SI values.
  void Row(const double* row_si);
  void Commit();

 private:
  template <typename F>
  void Guard(F&& f);

  OutputPath output_;
  std::vector<Column> columns_;
  int precision_;
  std::unique_ptr<AtomicFile> file_;
  std::string line_;
};

}  // namespace needle
