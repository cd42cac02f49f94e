#pragma once
/// @file
/// A progress bar on stderr for long sweeps, drawn only when stdout and stderr are both
/// terminals (never in pipes or CI logs), and erased when it goes out of scope.

#include <string>

namespace needle {

class ProgressBar {
 public:
  explicit ProgressBar(std::string label);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// `done` runs of about `total`.
  void Update(int done, int total);
  bool active() const { return active_; }

 private:
  std::string label_;
  bool active_;
};

}  // namespace needle
