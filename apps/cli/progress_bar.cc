#include "apps/cli/progress_bar.h"

#include <unistd.h>

#include <algorithm>
#include <iostream>

namespace needle {

ProgressBar::ProgressBar(std::string label)
    : label_(std::move(label)), active_(isatty(STDOUT_FILENO) && isatty(STDERR_FILENO)) {}

ProgressBar::~ProgressBar() {
  if (active_) std::cerr << "\r" << std::string(label_.size() + 50, ' ') << "\r" << std::flush;
}

void ProgressBar::Update(int done, int total) {
  if (!active_) return;
  const int width = 30, filled = std::min(width, width * done / std::max(1, total));
  std::cerr << "\r" << label_ << " [" << std::string(filled, '#')
            << std::string(width - filled, ' ') << "] " << done << " runs" << std::flush;
}

}  // namespace needle
