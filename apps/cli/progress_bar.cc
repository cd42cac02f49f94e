#include "apps/cli/progress_bar.h"

#include <unistd.h>

#include <algorithm>
#include <iostream>

namespace needle {
namespace {

// The longest a log waits for the next line, s.
constexpr double kLineIntervalS = 5.0;

}  // namespace

ProgressBar::ProgressBar(std::string label, std::string unit, bool quiet, bool estimated)
    : label_(std::move(label)),
      unit_(std::move(unit)),
      bar_(isatty(STDOUT_FILENO) && isatty(STDERR_FILENO)),
      lines_(!bar_ && !quiet),
      estimated_(estimated) {}

ProgressBar::~ProgressBar() {
  if (bar_) std::cerr << "\r" << std::string(label_.size() + 50, ' ') << "\r" << std::flush;
}

void ProgressBar::Update(int done, int total) {
  if (bar_) {
    const int width = 30, filled = std::min(width, width * done / std::max(1, total));
    std::cerr << "\r" << label_ << " [" << std::string(filled, '#')
              << std::string(width - filled, ' ') << "] " << done << " runs" << std::flush;
    return;
  }
  if (!lines_) return;
  const int tenth = std::min(10, 10 * done / std::max(1, total));
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_line_).count();
  if (tenth <= last_tenth_ && since < kLineIntervalS) return;
  last_tenth_ = std::max(last_tenth_, tenth);
  last_line_ = now;
  std::cerr << label_ << ": " << done << (estimated_ ? " of about " : "/") << std::max(done, total)
            << " " << unit_ << '\n'
            << std::flush;
}

}  // namespace needle
