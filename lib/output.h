#pragma once
/// @file
/// Output at the edges: files are written atomically (a temporary file beside the target,
/// flushed, then renamed over it), so an interrupted or failed run leaves either the old
/// file or the complete new one, never half a file.

#include <signal.h>
#include <sys/types.h>

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace needle {

/// Registers a temporary file (or, with `folder`, a folder) to be removed if SIGINT, SIGTERM or
/// SIGHUP ends the program (where it has no handler of its own): files first, then folders once
/// they are empty, innermost first. Returns its slot for UnregisterTemporary, or -1 when it
/// cannot be kept (128 at a time; paths under 4096 bytes). For the command-line program: its
/// registrations, removals and reaping happen while its worker threads are joined (a handler on
/// another thread could meet a slot being reused).
int RegisterTemporary(const std::string& path, bool folder = false);
void UnregisterTemporary(int slot);
/// Registers a child process that writes into registered temporaries (gnuplot): the signals
/// above end it (SIGKILL, then waited for) before removing them. Returns its slot, or -1 (8 at a
/// time).
int RegisterChildProcess(pid_t pid);
void UnregisterChildProcess(int slot);

/// SIGINT, SIGTERM and SIGHUP held back on this thread while it lives (delivered when it goes):
/// around making a temporary whose name is known only once it is made, and registering it.
class SignalsHeld {
 public:
  SignalsHeld();
  ~SignalsHeld();
  SignalsHeld(const SignalsHeld&) = delete;
  SignalsHeld& operator=(const SignalsHeld&) = delete;

 private:
  sigset_t before_;
};

/// A file written as it is produced and put in place atomically: the text goes to a temporary
/// file beside `path` (buffered), and Commit() flushes, syncs and renames it over `path`; an
/// AtomicFile destroyed before Commit() removes its temporary file, so a failed run writes
/// nothing. A symbolic link is written through (its target replaced, the link kept); the file
/// gets 0666 less the umask. SIGINT, SIGTERM or SIGHUP while it is written (where the program
/// has no handler of its own) remove the temporary file before the program ends as the signal
/// asks. Errors throw std::runtime_error naming the path and the failing
/// system call.
class AtomicFile {
 public:
  explicit AtomicFile(const std::string& path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  void Write(std::string_view text);
  void Commit();

 private:
  void Flush();
  [[noreturn]] void Fail(const char* call);

  std::string path_;    // as the user named it (messages)
  std::string target_;  // where it lands: a symbolic link's target, written through
  std::string tmp_;
  int fd_ = -1;
  int slot_ = -1;       // in the list an interrupting signal's handler removes
  std::string buffer_;  // written out at 1 MiB
};

/// Writes `content` to `path` atomically. Throws std::runtime_error naming the path and
/// the failing system call.
void WriteFileAtomically(const std::string& path, const std::string& content);

/// `value` with `decimals` digits after the point ("-0.000" is printed as "0.000").
std::string Fixed(double value, int decimals);

/// Fixed(value, decimals), or "none" for a value that is not finite.
std::string FixedOrNone(double value, int decimals);

/// The decimals that print `value` with at least `significant` significant digits, and never
/// fewer than `least`: 2 for 535.2 (least 2), 4 for 0.0043 (significant 2). `least` for 0 and
/// non-finite values.
int DecimalsFor(double value, int least, int significant);

/// At least `decimals`, and more (up to 12) while `value` and `limit` would print the same though
/// they differ: a surge ratio of 12.97 printed "13.0 below 13" and "13.0 (>= 13) -> FAIL".
int DecimalsApart(double value, double limit, int decimals);

/// The items as a sentence lists them: "a", "a and b", "a, b and c".
std::string ListText(const std::vector<std::string>& items);

/// `value` to `digits` significant digits, as a stream prints it ("0.001", "3.674", "1e+09").
std::string Significant(double value, int digits);

/// `a` and `b` to `digits` significant digits, and more (up to 17) while they would print the same
/// though they differ: "123.4567891 does not increase after 123.4567892", not "123.457 … 123.457".
std::pair<std::string, std::string> SignificantApart(double a, double b, int digits = 6);

}  // namespace needle
