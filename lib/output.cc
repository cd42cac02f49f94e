#include "lib/output.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <mutex>
#include <sstream>
#include <stdexcept>

namespace needle {

namespace {

// Where a write to `path` lands: a symbolic link is written through (its target replaced, the
// link kept), not replaced by a file, also where the target does not exist yet (a dangling
// link: weakly_canonical left it, and the link was replaced while its unwritable target went
// unreported). Links are followed link by link, a relative one from its own folder.
std::string WriteTarget(const std::string& path) {
  std::error_code error;
  std::filesystem::path p = path;
  for (int hop = 0; hop < 40 && std::filesystem::is_symlink(p, error); ++hop) {
    const std::filesystem::path to = std::filesystem::read_symlink(p, error);
    if (error) break;
    p = to.is_absolute() ? to : p.parent_path() / to;
  }
  return p == path ? path : p.lexically_normal().string();
}

// The temporary files and folders, removed by the handler of an interrupting signal (SIGINT,
// SIGTERM, SIGHUP: a run stopped from the terminal or by its scheduler leaves no temporary file):
// the files first (unlink), then the folders, innermost first (rmdir, repeated: a folder goes
// once it is empty); both are async-signal-safe. A slot is taken by storing its path and kind,
// then its flag.
constexpr int kSlots = 128;
char g_temporary[kSlots][4096];
bool g_folder[kSlots];
std::atomic<bool> g_taken[kSlots];
constexpr int kFolderDepth = 4;  // folders inside registered folders, at most
// Child processes that write into them (gnuplot), ended first (kill and waitpid are
// async-signal-safe too): else one still drawing would write after the removal.
constexpr int kChildSlots = 8;
std::atomic<pid_t> g_child[kChildSlots];
static_assert(std::atomic<pid_t>::is_always_lock_free && std::atomic<bool>::is_always_lock_free,
              "the interrupt handler reads these: they must be lock-free");

extern "C" void RemoveTemporariesAndDie(int signal_number) {
  for (int i = 0; i < kChildSlots; ++i) {
    const pid_t pid = g_child[i].load();
    if (pid > 0) {
      kill(pid, SIGKILL);
      waitpid(pid, nullptr, 0);
    }
  }
  for (int i = 0; i < kSlots; ++i)
    if (g_taken[i].load() && !g_folder[i]) unlink(g_temporary[i]);
  for (int pass = 0; pass < kFolderDepth; ++pass)
    for (int i = 0; i < kSlots; ++i)
      if (g_taken[i].load() && g_folder[i]) rmdir(g_temporary[i]);
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

// The handler, where the program has none of its own, once.
void InstallRemovalHandler() {
  static std::once_flag installed;
  std::call_once(installed, [] {
    // Each of the three held while the handler runs for another (one pass of removal).
    struct sigaction removal {};
    removal.sa_handler = RemoveTemporariesAndDie;
    sigemptyset(&removal.sa_mask);
    for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&removal.sa_mask, s);
    for (int s : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction now {};
      if (sigaction(s, nullptr, &now) == 0 && now.sa_handler == SIG_DFL)
        sigaction(s, &removal, nullptr);
    }
  });
}

}  // namespace

int RegisterTemporary(const std::string& path, bool folder) {
  InstallRemovalHandler();
  if (path.size() >= sizeof g_temporary[0]) return -1;
  static std::mutex mutex;
  std::lock_guard<std::mutex> lock(mutex);
  for (int i = 0; i < kSlots; ++i) {
    if (g_taken[i].load()) continue;
    std::memcpy(g_temporary[i], path.c_str(), path.size() + 1);
    g_folder[i] = folder;
    g_taken[i].store(true);
    return i;
  }
  return -1;
}

void UnregisterTemporary(int slot) {
  if (slot >= 0) g_taken[slot].store(false);
}

int RegisterChildProcess(pid_t pid) {
  InstallRemovalHandler();
  for (int i = 0; i < kChildSlots; ++i) {
    pid_t free = 0;
    if (g_child[i].compare_exchange_strong(free, pid)) return i;
  }
  return -1;
}

void UnregisterChildProcess(int slot) {
  if (slot >= 0) g_child[slot].store(0);
}

SignalsHeld::SignalsHeld() {
  sigset_t interrupting;
  sigemptyset(&interrupting);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&interrupting, s);
  pthread_sigmask(SIG_BLOCK, &interrupting, &before_);
}

SignalsHeld::~SignalsHeld() { pthread_sigmask(SIG_SETMASK, &before_, nullptr); }

namespace {

// A new file's permissions: 0666 less the process's umask.
mode_t NewFileMode() {
  const mode_t mask = umask(0);
  umask(mask);
  return 0666 & ~mask;
}

}  // namespace

AtomicFile::AtomicFile(const std::string& path)
    : path_(path), target_(WriteTarget(path)), tmp_(target_ + ".tmp.XXXXXX") {
  // Made and registered with the interrupting signals held: one arriving in between would leave
  // the file.
  const SignalsHeld held;
  fd_ = mkstemp(tmp_.data());
  if (fd_ < 0) {
    throw std::runtime_error(path_ +
                             ": cannot create a temporary file beside it: " + std::strerror(errno));
  }
  slot_ = RegisterTemporary(tmp_);
}

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) {
    close(fd_);
    std::remove(tmp_.c_str());
  }
  UnregisterTemporary(slot_);
}

void AtomicFile::Fail(const char* call) {
  const std::string reason = std::strerror(errno);
  if (fd_ >= 0) close(fd_);
  fd_ = -1;
  std::remove(tmp_.c_str());
  UnregisterTemporary(slot_);
  slot_ = -1;
  throw std::runtime_error(path_ + ": " + call + " failed: " + reason);
}

void AtomicFile::Flush() {
  size_t written = 0;
  while (written < buffer_.size()) {
    const ssize_t n = write(fd_, buffer_.data() + written, buffer_.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      Fail("write");
    }
    written += static_cast<size_t>(n);
  }
  buffer_.clear();
}

void AtomicFile::Write(std::string_view text) {
  if (fd_ < 0) throw std::logic_error(path_ + ": written after it was committed or failed");
  buffer_.append(text);
  if (buffer_.size() >= (1u << 20)) Flush();
}

void AtomicFile::Commit() {
  if (fd_ < 0) throw std::logic_error(path_ + ": committed twice or after a failure");
  Flush();
  if (fchmod(fd_, NewFileMode()) != 0) Fail("fchmod");
  if (fsync(fd_) != 0) Fail("fsync");
  const int fd = fd_;
  fd_ = -1;
  if (close(fd) != 0) {
    const std::string reason = std::strerror(errno);
    std::remove(tmp_.c_str());
    UnregisterTemporary(slot_);
    slot_ = -1;
    throw std::runtime_error(path_ + ": close failed: " + reason);
  }
  const bool renamed = std::rename(tmp_.c_str(), target_.c_str()) == 0;
  const std::string reason = renamed ? "" : std::strerror(errno);
  if (!renamed) std::remove(tmp_.c_str());
  UnregisterTemporary(slot_);
  slot_ = -1;
  if (!renamed) throw std::runtime_error(path_ + ": rename failed: " + reason);
}

void WriteFileAtomically(const std::string& path, const std::string& content) {
  AtomicFile file(path);
  file.Write(content);
  file.Commit();
}

std::string Fixed(double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  std::string s(buffer);
  // Avoid "-0.00": a value that rounds to zero prints without a sign.
  if (s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
  return s;
}

std::string FixedOrNone(double value, int decimals) {
  return std::isfinite(value) ? Fixed(value, decimals) : std::string("none");
}

int DecimalsApart(double value, double limit, int decimals) {
  if (!std::isfinite(value) || !std::isfinite(limit)) return decimals;
  int d = decimals;
  while (d < 12 && value != limit && Fixed(value, d) == Fixed(limit, d)) ++d;
  return d;
}

int DecimalsFor(double value, int least, int significant) {
  if (!std::isfinite(value) || value == 0.0) return least;
  const int magnitude = static_cast<int>(std::floor(std::log10(std::abs(value))));
  return std::max(least, std::min(15, significant - 1 - magnitude));
}

std::string ListText(const std::vector<std::string>& items) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i)
    out += (i == 0 ? "" : i + 1 == items.size() ? " and " : ", ") + items[i];
  return out;
}

std::string Significant(double value, int digits) {
  std::ostringstream out;
  out << std::setprecision(digits) << value;
  return out.str();
}

std::pair<std::string, std::string> SignificantApart(double a, double b, int digits) {
  std::pair<std::string, std::string> text{Significant(a, digits), Significant(b, digits)};
  while (a != b && text.first == text.second && digits < 17) {
    ++digits;
    text = {Significant(a, digits), Significant(b, digits)};
  }
  return text;
}

}  // namespace needle
