#include "apps/cli/program_start.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#if defined(__GLIBC__)
#include <sys/auxv.h>
#include <sys/stat.h>
#endif
#include <unistd.h>

namespace needle {
namespace {

constexpr char kHugePages[] = "glibc.malloc.hugetlb=1";
constexpr char kRestarted[] = "NEEDLE_RESTARTED_WITH_HUGE_PAGES";  // our mark, set for one exec
constexpr char kFitServe[] = "needle-fit-serve";

// This program's own file, when /proc/self/exe is one of the two needle programs (not a
// valgrind tool or the dynamic loader that started it); empty otherwise.
std::filesystem::path OwnExecutable() {
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) return {};
  const std::string name = self.filename().string();
  return name == "needle" || name == kFitServe ? self : std::filesystem::path();
}

}  // namespace

// A dense table's reading (a file argument of 4 MiB or more: some 2e5 rows and up) touches a
// few hundred MB of fresh heap, and on 4 kB pages each first touch is a fault: 1e6 rows, 40,000
// to 57,000 faults and a third of the run. glibc puts its heap in transparent huge pages when
// GLIBC_TUNABLES asks (read once, at start), so the program starts itself again with it set
// (~20 ms, against 0.3-0.4 s saved), marked so that it never restarts twice (a glibc that drops
// GLIBC_TUNABLES for a privileged program would otherwise loop). A user's own GLIBC_TUNABLES is
// left alone, and so is a privileged run (glibc ignores tunables there) or one whose
// /proc/self/exe is not needle (valgrind's tool, the dynamic loader); a failed exec runs on.
void RestartWithHugePages(int argc, char** argv) {
#if defined(__GLIBC__)
  if (std::getenv(kRestarted)) {  // ours: neither kept for children nor done again
    ::unsetenv(kRestarted);
    ::unsetenv("GLIBC_TUNABLES");
    return;
  }
  if (std::getenv("GLIBC_TUNABLES") || ::getauxval(AT_SECURE)) return;
  bool large = false;
  for (int i = 2; i < argc && !large; ++i) {
    struct stat st;
    large = ::stat(argv[i], &st) == 0 && S_ISREG(st.st_mode) && st.st_size >= (4 << 20);
  }
  if (!large) return;
  const std::filesystem::path self = OwnExecutable();  // read only when needed: not every start's
  if (self.empty()) return;
  if (::setenv(kRestarted, "1", 1) != 0 || ::setenv("GLIBC_TUNABLES", kHugePages, 1) != 0) {
    ::unsetenv(kRestarted);
    return;
  }
  ::execv(self.c_str(), argv);
  ::unsetenv(kRestarted);
  ::unsetenv("GLIBC_TUNABLES");
#else
  static_cast<void>(argc);
  static_cast<void>(argv);
#endif
}

// `needle fit` and `needle serve` run as `needle-fit-serve` with the same arguments: found beside
// this program (the build tree), else in NEEDLE_LIBEXEC_FROM_BIN from it (an install). This
// program is /proc/self/exe, or where argv[0] names it (run under valgrind or the dynamic
// loader). Returns only when neither could be started: an installation's fault, exit 3.
int RunInFitServe(char** argv) {
  std::filesystem::path self = OwnExecutable();
  if (self.empty() && std::strchr(argv[0], '/')) self = std::filesystem::absolute(argv[0]);
  if (self.empty()) {
    std::cerr << "needle: error: `needle " << argv[1] << "` runs " << kFitServe
              << " from needle's own folder, which is unknown here (started as " << argv[0]
              << ")\n";
    return 3;
  }
  const std::filesystem::path here = self.parent_path();
  const std::filesystem::path tried[] = {
      here / kFitServe, (here / NEEDLE_LIBEXEC_FROM_BIN / kFitServe).lexically_normal()};
  int failure = ENOENT;
  for (const std::filesystem::path& path : tried) {
    ::execv(path.c_str(), argv);
    if (errno != ENOENT) failure = errno;
  }
  std::cerr << "needle: error: `needle " << argv[1] << "` runs " << kFitServe
            << ", which could not be started from " << tried[0].string() << " or "
            << tried[1].string() << " (" << std::strerror(failure) << ")\n";
  return 3;
}

}  // namespace needle
