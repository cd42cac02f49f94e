#pragma once
/// @file
/// How many threads a compute-bound job takes (the overspeed sweep, a check's surge study beside
/// it, a tolerance study's samples): one rule.

#include <algorithm>
#include <thread>

namespace needle {

/// The threads asked (0: all cores), at most the machine's cores (the work is compute-bound:
/// more threads than cores do not help), at least 1.
inline int ThreadsToUse(int asked) {
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  return asked > 0 ? std::min(asked, cores) : cores;
}

}  // namespace needle
