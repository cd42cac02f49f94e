#include "lib/output.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace needle {
namespace {

TEST(OutputTest, WritesAtomicallyAndLeavesNoTemporaryFile) {
  const auto dir = std::filesystem::temp_directory_path() / "needle_output_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "table.csv").string();
  WriteFileAtomically(path, "old\n");
  WriteFileAtomically(path, "a,b\n1,2\n");
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  EXPECT_EQ(s.str(), "a,b\n1,2\n");
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 1);
  std::filesystem::remove_all(dir);
}

TEST(OutputTest, FailsOnAMissingDirectoryNamingThePath) {
  try {
    WriteFileAtomically("/nonexistent-dir/x.csv", "x");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("/nonexistent-dir/x.csv: cannot create a temporary", 0),
              0u);
  }
}

TEST(OutputTest, FixedNeverPrintsNegativeZero) {
  EXPECT_EQ(Fixed(-0.0001, 2), "0.00");
  EXPECT_EQ(Fixed(-1.005, 1), "-1.0");
  EXPECT_EQ(Fixed(3.14159, 3), "3.142");
}

}  // namespace
}  // namespace needle
