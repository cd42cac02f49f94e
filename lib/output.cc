#include "lib/output.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <stdexcept>

namespace needle {

namespace {

// Where a write to `path` lands: a symbolic link is written through (its target replaced, the
// link kept), not replaced by a file.
std::string WriteTarget(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_symlink(path, error)) return path;
  const std::filesystem::path target = std::filesystem::weakly_canonical(path, error);
  return error ? path : target.string();
}

// The temporary files being written, removed by the handler of an interrupting signal (SIGINT,
// SIGTERM, SIGHUP: a run stopped from the terminal or by its scheduler leaves no temporary
// file); unlink() is async-signal-safe. A slot is taken by storing its path, then its flag.
constexpr int kSlots = 16;
char g_temporary[kSlots][4096];
std::atomic<bool> g_taken[kSlots];

extern "C" void RemoveTemporariesAndDie(int signal_number) {
  for (int i = 0; i < kSlots; ++i)
    if (g_taken[i].load()) unlink(g_temporary[i]);
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

// The slot holding `path`, or -1 (no slot free, or a path too long: the file is then left as
// before, a temporary an interrupt may leave behind).
int Register(const std::string& path) {
  static std::once_flag installed;
  std::call_once(installed, [] {
    for (int s : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction now {};
      if (sigaction(s, nullptr, &now) == 0 && now.sa_handler == SIG_DFL)
        std::signal(s, RemoveTemporariesAndDie);
    }
  });
  if (path.size() >= sizeof g_temporary[0]) return -1;
  static std::mutex mutex;
  std::lock_guard<std::mutex> lock(mutex);
  for (int i = 0; i < kSlots; ++i) {
    if (g_taken[i].load()) continue;
    std::memcpy(g_temporary[i], path.c_str(), path.size() + 1);
    g_taken[i].store(true);
    return i;
  }
  return -1;
}

void Unregister(int slot) {
  if (slot >= 0) g_taken[slot].store(false);
}

// A new file's permissions: 0666 less the process's umask.
mode_t NewFileMode() {
  const mode_t mask = umask(0);
  umask(mask);
  return 0666 & ~mask;
}

}  // namespace

AtomicFile::AtomicFile(const std::string& path)
    : path_(path), target_(WriteTarget(path)), tmp_(target_ + ".tmp.XXXXXX") {
  fd_ = mkstemp(tmp_.data());
  if (fd_ < 0) {
    throw std::runtime_error(path_ +
                             ": cannot create a temporary file beside it: " + std::strerror(errno));
  }
  slot_ = Register(tmp_);
}

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) {
    close(fd_);
    std::remove(tmp_.c_str());
  }
  Unregister(slot_);
}

void AtomicFile::Fail(const char* call) {
  const std::string reason = std::strerror(errno);
  if (fd_ >= 0) close(fd_);
  fd_ = -1;
  std::remove(tmp_.c_str());
  Unregister(slot_);
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
    Unregister(slot_);
    slot_ = -1;
    throw std::runtime_error(path_ + ": close failed: " + reason);
  }
  const bool renamed = std::rename(tmp_.c_str(), target_.c_str()) == 0;
  const std::string reason = renamed ? "" : std::strerror(errno);
  if (!renamed) std::remove(tmp_.c_str());
  Unregister(slot_);
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

}  // namespace needle
