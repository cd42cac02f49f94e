#include "lib/output.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace needle {

AtomicFile::AtomicFile(const std::string& path) : path_(path), tmp_(path + ".tmp.XXXXXX") {
  fd_ = mkstemp(tmp_.data());
  if (fd_ < 0) {
    throw std::runtime_error(path_ +
                             ": cannot create a temporary file beside it: " + std::strerror(errno));
  }
}

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) {
    close(fd_);
    std::remove(tmp_.c_str());
  }
}

void AtomicFile::Fail(const char* call) {
  const std::string reason = std::strerror(errno);
  if (fd_ >= 0) close(fd_);
  fd_ = -1;
  std::remove(tmp_.c_str());
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
  if (fchmod(fd_, 0644) != 0) Fail("fchmod");
  if (fsync(fd_) != 0) Fail("fsync");
  const int fd = fd_;
  fd_ = -1;
  if (close(fd) != 0) {
    const std::string reason = std::strerror(errno);
    std::remove(tmp_.c_str());
    throw std::runtime_error(path_ + ": close failed: " + reason);
  }
  if (std::rename(tmp_.c_str(), path_.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    std::remove(tmp_.c_str());
    throw std::runtime_error(path_ + ": rename failed: " + reason);
  }
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

}  // namespace needle
