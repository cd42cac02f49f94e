// One rule for the threads of a compute-bound job: the overspeed sweep, a check's surge study
// beside it, a tolerance study.
#include "lib/threads.h"

#include <gtest/gtest.h>

#include <thread>

namespace needle {
namespace {

TEST(ThreadsTest, AskedAtMostTheCoresAtLeastOneAndZeroIsAll) {
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  EXPECT_EQ(ThreadsToUse(0), cores);
  EXPECT_EQ(ThreadsToUse(-1), cores);
  EXPECT_EQ(ThreadsToUse(1), 1);
  EXPECT_EQ(ThreadsToUse(cores), cores);
  EXPECT_EQ(ThreadsToUse(cores + 7), cores);
}

}  // namespace
}  // namespace needle
