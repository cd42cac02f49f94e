#pragma once
/// @file
/// Progress of a long sweep on stderr. Where stdout and stderr are both terminals, a bar drawn
/// in place and erased when it goes out of scope. Elsewhere (a pipe, a CI log) one line now and
/// then, "tolerance: 200/1000 samples" ("overspeed: 40 of about 173 speeds" where the total is
/// an estimate that moves as the sweep learns): each time another tenth is done, or 5 s after the
/// last line. Quiet (no lines; the bar of a terminal stays) under `--json`: a program reading the
/// JSON reads stderr as the place of errors and warnings, and no progress is mixed in.

#include <chrono>
#include <string>

namespace needle {

class ProgressBar {
 public:
  /// `label` begins every line ("overspeed"); `unit` names what is counted ("speeds").
  /// `quiet`: no lines when stderr or stdout is not a terminal (the command's --json).
  /// `estimated`: the totals given are estimates ("40 of about 173"), else exact ("40/173").
  explicit ProgressBar(std::string label, std::string unit = "runs", bool quiet = false,
                       bool estimated = false);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// `done` of about `total` (an estimate that may move).
  void Update(int done, int total);
  /// True when Update shows anything (a bar or lines).
  bool active() const { return bar_ || lines_; }

 private:
  std::string label_, unit_;
  bool bar_;            ///< both terminals: the bar
  bool lines_;          ///< otherwise, unless quiet: a line now and then
  bool estimated_;      ///< the totals are estimates
  int last_tenth_ = 0;  ///< the tenths done at the last line
  std::chrono::steady_clock::time_point last_line_ = std::chrono::steady_clock::now();
};

}  // namespace needle
