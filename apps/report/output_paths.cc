#include "apps/report/output_paths.h"

#include <stdlib.h>
#include <unistd.h>

#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "lib/case_error.h"
#include "lib/output.h"

namespace needle {
namespace {

namespace fs = std::filesystem;

bool SameFile(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  // Not both there yet: compare the normalised absolute paths.
  return fs::weakly_canonical(fs::absolute(a), ec) == fs::weakly_canonical(fs::absolute(b), ec);
}

// Whether a file can be made in `folder`, tried: access(W_OK) answers yes to root on a folder
// no one can write (sysfs, a read-only mount), and the command then failed only at its end,
// after its sweep (helper-51's trial with --out /sys/kernel). The probe is removed at once.
bool CanCreateIn(const fs::path& folder) {
  std::string probe = (folder / ".needle-probe-XXXXXX").string();
  const int fd = mkstemp(probe.data());
  if (fd < 0) return false;
  close(fd);
  unlink(probe.c_str());
  return true;
}

}  // namespace

void CheckOutputPaths(const std::vector<OutputPath>& outputs,
                      const std::vector<std::string>& inputs) {
  for (size_t i = 0; i < outputs.size(); ++i) {
    const OutputPath& o = outputs[i];
    auto fail = [&](const std::string& why) {
      throw CaseError(o.option + ": " + o.path + ": " + why);
    };
    if (o.path.empty()) fail("an empty path");
    std::error_code ec;
    if (fs::is_directory(o.path, ec)) fail("is a folder; expected a file name");
    if (fs::exists(o.path, ec) && !fs::is_regular_file(o.path, ec))
      fail("is not a regular file (a device or a pipe); expected a file name");
    fs::path folder = fs::path(o.path).parent_path();
    if (folder.empty()) folder = ".";
    if (!fs::is_directory(folder, ec)) fail("its folder " + folder.string() + " does not exist");
    if (!CanCreateIn(folder)) fail("its folder " + folder.string() + " is not writable");
    for (const std::string& in : inputs) {
      if (SameFile(o.path, in)) fail("is an input of this command; it would be overwritten");
    }
    for (size_t k = 0; k < i; ++k) {
      if (SameFile(o.path, outputs[k].path)) fail("is also the " + outputs[k].option + " output");
    }
  }
}

std::vector<std::string> CaseInputs(const std::string& path, const std::string& lift_source) {
  std::vector<std::string> in{path};
  if (lift_source.rfind("csv ", 0) == 0) in.push_back(lift_source.substr(4));
  return in;
}

namespace {

// The folders ReportPath made, deepest first (each level put in front as it is made): removed (when
// still empty) by a command that ends without its report, and by an interrupting signal
// (lib/output.h: rmdir, which leaves a folder that holds anything).
std::vector<std::pair<std::filesystem::path, int>>& MadeFolders() {
  static std::vector<std::pair<std::filesystem::path, int>> made;
  return made;
}

}  // namespace

void RemoveEmptyMadeFolders() {
  for (const auto& [folder, slot] : MadeFolders()) {
    std::error_code ignored;
    std::filesystem::remove(folder, ignored);  // rmdir: only a folder still empty goes
    UnregisterTemporary(slot);
  }
  MadeFolders().clear();
}

std::string ReportPath(const std::string& out_dir, const std::string& name) {
  std::error_code ec, unreachable;
  // A missing folder is made level by level (lexically normal: `a/../b` is b), each level this
  // call made registered, with the interrupting signals held, to go again if the command ends
  // without writing into it; a level that was there is never registered.
  std::error_code level_error;
  const std::filesystem::path folder =
      std::filesystem::absolute(out_dir, level_error).lexically_normal();
  std::filesystem::path level;
  for (const auto& part : folder) {
    level /= part;
    if (level_error || part.empty() || level == level.root_path()) continue;
    const SignalsHeld held;
    if (std::filesystem::create_directory(level, level_error))
      MadeFolders().emplace(MadeFolders().begin(), level, RegisterTemporary(level.string(), true));
  }
  // What is left to make (nothing, or where a level could not be made: its error as the message
  // gives it).
  std::filesystem::create_directories(out_dir, ec);
  // Without an error code, is_directory throws on a path it cannot reach (a symlink loop, a
  // folder it may not search): that was exit 3 with the raw message.
  if (!std::filesystem::is_directory(out_dir, unreachable)) {
    if (!ec) ec = unreachable;
    throw CaseError("--out: " + out_dir + " is not a folder and cannot be made one" +
                    (ec ? " (" + ec.message() + ")" : std::string()));
  }
  return (std::filesystem::path(out_dir) / name).string();
}

void WriteOutput(const OutputPath& output, const std::string& content) {
  // A folder ReportPath made may have been removed meanwhile by another needle that made it too
  // and ended without its report (runs started together on one new --out): made again.
  std::error_code ignored;
  const std::filesystem::path parent = std::filesystem::path(output.path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent, ignored);
  try {
    WriteFileAtomically(output.path, content);
  } catch (const std::runtime_error& e) {
    throw CaseError(output.option + ": " + e.what());
  }
}

template <typename F>
void StreamedCsv::Guard(F&& f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    throw CaseError(output_.option + ": " + e.what());
  }
}

StreamedCsv::StreamedCsv(const OutputPath& output, std::vector<Column> columns, int precision)
    : output_(output), columns_(std::move(columns)), precision_(precision) {
  Guard([&] {
    file_ = std::make_unique<AtomicFile>(output_.path);
    file_->Write(CsvHeader(columns_));
  });
}

void StreamedCsv::Row(const double* row_si) {
  line_.clear();
  AppendCsvRow(columns_, row_si, precision_, line_);
  Guard([&] { file_->Write(line_); });
}

void StreamedCsv::Commit() {
  Guard([&] { file_->Commit(); });
}

}  // namespace needle
