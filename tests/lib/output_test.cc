#include "lib/output.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

namespace needle {
namespace {

// An empty folder of this name under the system's temporary folder.
std::filesystem::path FreshDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// The entries of a folder (a temporary file left behind counts).
std::ptrdiff_t Entries(const std::filesystem::path& dir) {
  return std::distance(std::filesystem::directory_iterator(dir), {});
}

// The first line of a file.
std::string FirstLine(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

TEST(OutputTest, WritesAtomicallyAndLeavesNoTemporaryFile) {
  const auto dir = FreshDir("needle_output_test");
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

// A write that fails half-way (here: the file-size limit, RLIMIT_FSIZE, in a child process,
// after 4 KiB of 64 KiB) must leave the old file whole and no temporary behind. A plain
// fopen/fwrite over the target would leave 4 KiB of the new content: this test tells.
TEST(OutputTest, AWriteThatFailsHalfWayLeavesTheOldFileWhole) {
  const auto dir = FreshDir("needle_output_half");
  const std::string path = (dir / "table.csv").string();
  WriteFileAtomically(path, "old\n");
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    signal(SIGXFSZ, SIG_IGN);  // the write returns EFBIG instead of killing the child
    struct rlimit limit {
      4096, 4096
    };
    setrlimit(RLIMIT_FSIZE, &limit);
    try {
      WriteFileAtomically(path, std::string(65536, 'x'));
    } catch (const std::runtime_error& e) {
      _exit(std::string(e.what()).find(": write failed: File too large") != std::string::npos ? 7
                                                                                              : 8);
    }
    _exit(9);  // no error: the limit did not bite
  }
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 7);
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  EXPECT_EQ(s.str(), "old\n");
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

// The acceleration of a table run at 1 rpm printed "0.00 ± 0.00 m/s^2" (stop 88's list): the
// decimals now show two significant digits, and never fewer than asked.
TEST(OutputTest, DecimalsForShowTheSignificantDigitsAsked) {
  EXPECT_EQ(DecimalsFor(535.2, 2, 2), 2);
  EXPECT_EQ(DecimalsFor(-18.13, 2, 2), 2);
  EXPECT_EQ(DecimalsFor(0.5, 2, 2), 2);
  EXPECT_EQ(DecimalsFor(0.0433, 2, 2), 3);
  EXPECT_EQ(DecimalsFor(-0.0012, 2, 2), 4);
  EXPECT_EQ(Fixed(-0.0012, DecimalsFor(-0.0012, 2, 2)), "-0.0012");
  EXPECT_EQ(DecimalsFor(0.0, 2, 2), 2);
  EXPECT_EQ(DecimalsFor(NAN, 2, 2), 2);
  EXPECT_EQ(DecimalsFor(1e-300, 2, 2), 15);
}

TEST(OutputTest, ListTextJoinsAsASentenceDoes) {
  EXPECT_EQ(ListText({}), "");
  EXPECT_EQ(ListText({"[needle]"}), "[needle]");
  EXPECT_EQ(ListText({"a", "b"}), "a and b");
  EXPECT_EQ(ListText({"a", "b", "c"}), "a, b and c");
}

// Two values that differ never print alike (a refusal of 123.4567891 after 123.4567892).
TEST(OutputTest, SignificantApartShowsTwoValuesApart) {
  EXPECT_EQ(SignificantApart(123.4567891, 123.4567892),
            std::make_pair(std::string("123.4567891"), std::string("123.4567892")));
  EXPECT_EQ(SignificantApart(2.0, 1.5), std::make_pair(std::string("2"), std::string("1.5")));
  EXPECT_EQ(SignificantApart(2.0, 2.0), std::make_pair(std::string("2"), std::string("2")));
  const auto [a, b] = SignificantApart(1.0, std::nextafter(1.0, 2.0));  // 17 digits at most
  EXPECT_NE(a, b);
}

// A value beside its limit never prints as the limit ("13.0 below 13" for 12.97).
TEST(OutputTest, DecimalsApartSetAValueApartFromItsLimit) {
  EXPECT_EQ(DecimalsApart(12.97, 13.0, 1), 2);
  EXPECT_EQ(DecimalsApart(12.5, 13.0, 1), 1);
  EXPECT_EQ(DecimalsApart(13.0, 13.0, 1), 1);
  EXPECT_EQ(DecimalsApart(30.55551, 30.55559, 2), 4);
  EXPECT_EQ(DecimalsApart(NAN, 13.0, 2), 2);
  EXPECT_EQ(DecimalsApart(13.0 - 1e-15, 13.0, 2), 12);
}

}  // namespace
}  // namespace needle

namespace needle {
namespace {

// A file written as it is produced: nothing at the path until Commit(), then all of it (here
// 3 MiB in pieces, past the 1 MiB buffer), and an AtomicFile given up leaves no file at all.
TEST(OutputTest, AnAtomicFileIsInPlaceOnlyOnceCommitted) {
  const auto dir = FreshDir("needle_output_stream");
  const std::string path = (dir / "series.csv").string();
  std::string expected;
  {
    AtomicFile file(path);
    for (int i = 0; i < 3 * 1024; ++i) {
      const std::string piece(1024, static_cast<char>('a' + i % 26));
      file.Write(piece);
      expected += piece;
    }
    EXPECT_FALSE(std::filesystem::exists(path));
    file.Commit();
  }
  EXPECT_EQ(std::filesystem::file_size(path), expected.size());
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(std::equal(expected.begin(), expected.end(), std::istreambuf_iterator<char>(in)));
  {
    AtomicFile abandoned((dir / "abandoned.csv").string());
    abandoned.Write(std::string(2 << 20, 'x'));
  }  // destroyed uncommitted: as if the run had failed
  EXPECT_EQ(Entries(dir), 1);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace needle

namespace needle {
namespace {

// An output named through a symbolic link is written through it: the link stays a link and its
// target gets the content (a user's test turned /dev/stdout into a regular file).
TEST(OutputTest, ASymbolicLinkIsWrittenThrough) {
  const auto dir = FreshDir("needle_output_link");
  std::filesystem::create_directories(dir / "other");
  WriteFileAtomically((dir / "other" / "real.csv").string(), "old\n");
  std::filesystem::create_symlink(std::filesystem::path("other") / "real.csv", dir / "via.csv");
  WriteFileAtomically((dir / "via.csv").string(), "new\n");
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "via.csv"));
  EXPECT_EQ(FirstLine(dir / "other" / "real.csv"), "new");
  EXPECT_EQ(Entries(dir / "other"), 1);
  // A dangling link is written through too: its target is made (issue 51: the link was replaced
  // by a file), and a target that cannot be written is an error, the link left as it was.
  std::filesystem::create_symlink(std::filesystem::path("other") / "new.csv", dir / "dangling.csv");
  WriteFileAtomically((dir / "dangling.csv").string(), "made\n");
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "dangling.csv"));
  EXPECT_EQ(FirstLine(dir / "other" / "new.csv"), "made");
  std::filesystem::create_symlink("/proc/needle-no-such/out.csv", dir / "nowhere.csv");
  EXPECT_ANY_THROW(WriteFileAtomically((dir / "nowhere.csv").string(), "lost\n"));
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "nowhere.csv"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace needle

namespace needle {
namespace {

// A run interrupted while it writes (SIGINT, SIGTERM, SIGHUP) leaves no temporary file and the
// old file whole, and still ends by the signal (a user's test found a 10 MB temporary left per
// interrupted run). Here a child process is stopped by SIGTERM in the middle of a file.
TEST(OutputTest, AnInterruptedWriteLeavesNoTemporaryFile) {
  const auto dir = FreshDir("needle_output_signal");
  const std::string path = (dir / "series.csv").string();
  WriteFileAtomically(path, "old\n");
  for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      AtomicFile file(path);
      file.Write(std::string(3 << 20, 'x'));  // past the buffer: the temporary is on disk
      raise(signal_number);
      _exit(9);  // not reached
    }
    int status = 0;
    waitpid(child, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << signal_number;
    EXPECT_EQ(WTERMSIG(status), signal_number);
  }
  EXPECT_EQ(Entries(dir), 1);
  EXPECT_EQ(FirstLine(path), "old");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace needle
