#pragma once
/// @file
/// The design page's computations (`needle serve`, docs/serve.md): a case with overrides in
/// case-file form, checked through the library exactly as `needle check --json` checks it.
///
///     overrides  {"spring": {"preload_N": 1700}, "train": {"play_mm": 0.3}}
///     merged     the case file's own lines, each key put under its section's header (a new
///                section at the end); a key replaces the section's lines of the same key and of
///                its quantity in another unit (preload_N replaces preload_kgf)
///     checked    ParseCase → Bind → CheckScene → CheckJson, the CLI's own code
///
/// Every bad override (not an object of objects of numbers, strings or booleans; a key the case
/// reader refuses) is the CLI's one-line message, returned with HTTP status 400.

#include <nlohmann/json.hpp>
#include <string>

namespace needle {

/// A reply: an HTTP status and its JSON body ({"error": line} when not 200).
struct ApiReply {
  int status = 200;
  std::string body;
};

/// The case file `case_text` with `overrides` merged, as TOML text. Throws CaseError naming
/// `where` (the case's path) and the override that is not a section of keys and scalars, or that
/// names a file ([lift] csv) unless `files` (`needle fit --case`: the table's path from where
/// the calibrated case goes; the design page opens no files).
std::string CaseWithOverrides(const std::string& case_text, const nlohmann::json& overrides,
                              const std::string& where, bool files = false);

/// One case the page designs: its file's text read once; every request merges its overrides
/// into it and reads it anew (a lift table in a CSV file is read again each time).
class DesignSession {
 public:
  /// Reads and validates `case_path` (throws CaseError as LoadCase does).
  explicit DesignSession(std::string case_path);

  /// POST /api/check: what `needle check --json` prints for the case with the overrides of
  /// `request_body` (an object; empty: none), its report path empty.
  ApiReply Check(const std::string& request_body) const;
  /// POST /api/design: {"check": Check's object, "series": the page's curves} — the lift,
  /// velocity and acceleration over the lift; the rated run's lift, cam and contact force and its
  /// impacts; the overspeed rows' least contact force.
  ApiReply Design(const std::string& request_body) const;
  /// POST /api/case: the merged case file as text (Save as case), in {"toml": text}.
  ApiReply SaveCase(const std::string& request_body) const;
  /// GET /api/case: the case file's sections as JSON (the page's inputs start from them).
  std::string CaseJson() const;

  const std::string& path() const { return path_; }

 private:
  // The case with the body's overrides merged, given to `reply`; a bad request (CaseError or
  // std::invalid_argument, as the CLI's exit 2) is its one line with 400.
  template <typename Reply>
  ApiReply Answer(const std::string& request_body, Reply reply) const;

  std::string path_;
  std::string text_;
};

}  // namespace needle
