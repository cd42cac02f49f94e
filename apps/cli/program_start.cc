#include "apps/cli/program_start.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#if defined(__GLIBC__)
#include <sys/stat.h>
#endif
#include <unistd.h>

namespace needle {
namespace {
constexpr char kHugePages[] = "glibc.malloc.hugetlb=1";
constexpr char kFitServe[] = "needle-fit-serve";
}  // namespace

// A dense table's reading (a file argument of 4 MiB or more: some 2e5 rows and up) touches a
// few hundred MB of fresh heap, and on 4 kB pages each first touch is a fault: 1e6 rows, 40,000
// to 57,000 faults and a third of the run. glibc puts its heap in transparent huge pages when
// GLIBC_TUNABLES asks (read once, at start), so the program starts itself again with it set
// (~20 ms, against 0.3-0.4 s saved). A user's own GLIBC_TUNABLES is left alone; a failed exec
// runs on as it is.
void RestartWithHugePages(int argc, char** argv) {
#if defined(__GLIBC__)
  if (const char* set = std::getenv("GLIBC_TUNABLES")) {
    if (std::strcmp(set, kHugePages) == 0) ::unsetenv("GLIBC_TUNABLES");  // ours: not to children
    return;
  }
  bool large = false;
  for (int i = 2; i < argc && !large; ++i) {
    struct stat st;
    large = ::stat(argv[i], &st) == 0 && S_ISREG(st.st_mode) && st.st_size >= (4 << 20);
  }
  if (!large || ::setenv("GLIBC_TUNABLES", kHugePages, 0) != 0) return;
  ::execv("/proc/self/exe", argv);
  ::unsetenv("GLIBC_TUNABLES");
#else
  static_cast<void>(argc);
  static_cast<void>(argv);
#endif
}

// `needle fit` and `needle serve` run as `needle-fit-serve` with the same arguments: found beside
// this program (the build tree), else in NEEDLE_LIBEXEC_FROM_BIN from it (an install). Returns
// only when neither could be started: an installation's fault, exit 3.
int RunInFitServe(char** argv) {
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  const std::filesystem::path here = error ? std::filesystem::path(".") : self.parent_path();
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
