#include "apps/report/html_report.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <csignal>
#include <cstring>
#include <fstream>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "lib/case_error.h"
#include "lib/output.h"

extern char** environ;

namespace needle {

namespace {

std::string Slurp(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// Writes all of `text` to the pipe `fd`; false when the reader has gone (EPIPE: SIGPIPE is held
// back on this thread meanwhile and a pending one taken, so that the process is not killed).
bool WriteToPipe(int fd, const std::string& text) {
  sigset_t pipe_signal, old_mask;
  sigemptyset(&pipe_signal);
  sigaddset(&pipe_signal, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_signal, &old_mask);
  bool ok = true;
  for (size_t done = 0; done < text.size();) {
    const ssize_t n = write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      ok = false;
      break;
    }
    done += static_cast<size_t>(n);
  }
  if (!ok && errno == EPIPE) {
    const timespec now{0, 0};
    while (sigtimedwait(&pipe_signal, nullptr, &now) == SIGPIPE) {
    }
  }
  pthread_sigmask(SIG_SETMASK, &old_mask, nullptr);
  return ok;
}

// Writes `text` to the new file `path`; a full or failing disk is the machine's fault: CaseError
// naming the file (exit 2), not a figure gnuplot cannot read.
void WriteWhole(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  int error = out ? 0 : errno;  // before close() may change it
  out.close();
  if (!out) {
    if (error == 0) error = errno;
    throw CaseError("report: cannot write " + path.string() + " (" + std::strerror(error) +
                    "): a full or read-only temporary folder? ($TMPDIR, else /tmp)");
  }
}

// $TMPDIR, else /tmp (std::filesystem::temp_directory_path's rule, which reads TMP, TEMP and
// TEMPDIR too), made absolute (gnuplot's `cd` into one figure's folder stays for the next);
// /tmp where gnuplot's quoting could not hold it (a ' or a line break in it).
std::string TemporaryFolder() {
  std::error_code error;
  const std::filesystem::path folder =
      std::filesystem::absolute(std::filesystem::temp_directory_path(error), error);
  const std::string text = folder.string();
  if (error || text.find_first_of("'\n") != std::string::npos) return "/tmp";
  return text;
}

}  // namespace

Gnuplot::Gnuplot() {
  // The machine's faults, not needle's: one line, exit 2 (CaseError). gnuplot's messages go to
  // a file without a name (made and unlinked at once: nothing is left in /tmp by a command
  // interrupted while it computes); the figures' folder is made when the first figure is.
  const std::string temporary = TemporaryFolder();
  std::string pattern = temporary + "/needle-gnuplot-XXXXXX";
  {
    const SignalsHeld held;  // no interrupt between its making and its unlinking
    errors_ = mkostemp(pattern.data(), O_CLOEXEC);
    if (errors_ < 0) {
      throw CaseError("report: cannot make a temporary file for gnuplot in " + temporary + ": " +
                      std::strerror(errno));
    }
    unlink(pattern.c_str());
  }
  // gnuplot stays a zombie until reaped (Reap relies on it): a SIGCHLD ignored by whoever
  // started needle would let its pid go to another process while registered.
  struct sigaction child {};
  if (sigaction(SIGCHLD, nullptr, &child) == 0 &&
      (child.sa_handler == SIG_IGN || (child.sa_flags & SA_NOCLDWAIT))) {
    std::signal(SIGCHLD, SIG_DFL);
  }
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) {
    const std::string why = std::strerror(errno);
    close(errors_);
    throw CaseError("report: cannot make a pipe to gnuplot: " + why);
  }
  // gnuplot reads the pipe as its standard input and writes its messages to the file; nothing of
  // it reaches needle's standard output (a --json object).
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[0], 0);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, errors_, 2);
  // -d: no init file (~/.gnuplot, gnuplotrc) changes or breaks the figures.
  char name[] = "gnuplot", defaults[] = "-d";
  char* argv[] = {name, defaults, nullptr};
  const int spawned = posix_spawnp(&pid_, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  close(fds[0]);
  if (spawned != 0) {
    close(fds[1]);
    close(errors_);
    if (spawned == ENOENT) {
      throw CaseError(
          "gnuplot is not installed; the report's figures need it (apt-get install gnuplot-nox, "
          "or bash scripts/install-deps.sh)");
    }
    throw CaseError(std::string("report: cannot start gnuplot: ") + std::strerror(spawned));
  }
  input_ = fds[1];
  child_slot_ = RegisterChildProcess(pid_);
}

Gnuplot::~Gnuplot() {
  if (input_ >= 0) close(input_);  // gnuplot reads the end of its input and ends
  if (pid_ > 0) Reap();
  close(errors_);
  if (!folder_.empty()) {
    std::error_code ignored;
    std::filesystem::remove_all(folder_, ignored);
  }
  for (int slot : slots_) UnregisterTemporary(slot);
}

void Gnuplot::Temporary(const std::filesystem::path& path, bool folder) {
  slots_.push_back(RegisterTemporary(path.string(), folder));
}

const std::filesystem::path& Gnuplot::Folder() {
  if (folder_.empty()) {
    const std::string temporary = TemporaryFolder();
    std::string pattern = temporary + "/needle-report-XXXXXX";
    const SignalsHeld held;  // made and registered for removal with no interrupt in between
    if (!mkdtemp(pattern.data())) {
      throw CaseError("report: cannot make a temporary folder for gnuplot in " + temporary + ": " +
                      std::strerror(errno));
    }
    folder_ = pattern;
    slots_.push_back(RegisterTemporary(folder_.string(), true));
  }
  return folder_;
}

void Gnuplot::Load(const std::filesystem::path& script) {
  if (input_ < 0) throw std::logic_error("Gnuplot::Load: gnuplot has finished");
  // `load` stops at the script's first error, as `gnuplot script` does (gnuplot reading its
  // input would go on to the next line); the next script is read after it either way.
  WriteToPipe(input_, "load '" + script.string() + "'\n");  // a gone gnuplot: its status says
}

int Gnuplot::Finish() {
  if (input_ < 0) throw std::logic_error("Gnuplot::Finish: gnuplot has finished");
  close(input_);
  input_ = -1;
  const int status = Reap();
  if (status < 0) throw std::runtime_error("report: lost the gnuplot process");
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

int Gnuplot::Reap() {
  // Waited for without reaping first, then taken off the interrupt's list, then reaped: its pid
  // stays its own (a zombie's) until the interrupt can no longer kill it.
  siginfo_t info;
  while (waitid(P_PID, pid_, &info, WEXITED | WNOWAIT) < 0 && errno == EINTR) {
  }
  UnregisterChildProcess(child_slot_);
  child_slot_ = -1;
  int status = 0;
  pid_t reaped = -1;
  while ((reaped = waitpid(pid_, &status, 0)) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  return reaped < 0 ? -1 : status;
}

std::string Gnuplot::ErrorText() const {
  // A loaded script's messages come indented by the 9 columns of gnuplot's prompt: each line as
  // `gnuplot script` writes it.
  std::string all;
  char buffer[4096];
  for (off_t at = 0;;) {
    const ssize_t n = pread(errors_, buffer, sizeof buffer, at);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    all.append(buffer, static_cast<size_t>(n));
    at += n;
  }
  std::istringstream in(all);
  std::string text, line;
  while (std::getline(in, line)) {
    size_t indent = 0;
    while (indent < 9 && indent < line.size() && line[indent] == ' ') ++indent;
    text += line.substr(indent) + '\n';
  }
  return text;
}

std::string Escape(const std::string& text) {
  std::string out;
  for (char ch : text) {
    switch (ch) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += ch;
    }
  }
  return out;
}

Report::Report(std::string title, Gnuplot* gnuplot) : title_(std::move(title)), gnuplot_(gnuplot) {}

void Report::AddHtml(const std::string& html) {
  parts_.push_back(html);
  open_.push_back(false);
}

void Rows::push_back(const double* row, size_t width) {
  if (width_ == 0) width_ = width;
  if (width != width_) {
    throw std::logic_error("Rows::push_back: a row of " + std::to_string(width) +
                           " numbers in rows of " + std::to_string(width_));
  }
  values_.insert(values_.end(), row, row + width);
}

void Rows::push_back(std::initializer_list<double> row) {
  if (width_ == 0) width_ = row.size();
  if (row.size() != width_) {
    throw std::logic_error("Rows::push_back: a row of " + std::to_string(row.size()) +
                           " numbers in rows of " + std::to_string(width_));
  }
  values_.insert(values_.end(), row.begin(), row.end());
}

Rows LineEnvelope(const Rows& rows, double x_from, double x_to, int columns) {
  const size_t width = rows.width();
  if (width < 2 || width > 32 || !std::isfinite(x_from) || !std::isfinite(x_to) ||
      !(x_to > x_from) || columns < 1)
    return rows;  // (a row's finite numbers are a bit each of 32)
  const double per_x = columns / (x_to - x_from);
  // Which of a row's numbers are finite, a bit each: a run shares its pattern (a curve with a
  // gap keeps the rows at the gap's ends).
  const auto pattern = [&rows, width](size_t i) {
    unsigned bits = 0;
    for (size_t j = 0; j < width; ++j) bits |= std::isfinite(rows.row(i)[j]) ? 1u << j : 0u;
    return bits;
  };
  const auto column = [&](size_t i) { return std::floor((rows.row(i)[0] - x_from) * per_x); };
  Rows out;
  std::vector<size_t> kept;
  for (size_t i = 0; i < rows.size();) {
    const unsigned bits = pattern(i);
    if (!(bits & 1u)) {  // no x: kept as it is
      kept = {i++};
    } else {
      const double c = column(i);
      std::vector<size_t> low(width, i), high(width, i);
      size_t end = i + 1;
      for (; end < rows.size() && pattern(end) == bits && column(end) == c; ++end) {
        for (size_t j = 1; j < width; ++j) {
          if (!(bits & (1u << j))) continue;
          if (rows.row(end)[j] < rows.row(low[j])[j]) low[j] = end;
          if (rows.row(end)[j] > rows.row(high[j])[j]) high[j] = end;
        }
      }
      kept = {i, end - 1};
      for (size_t j = 1; j < width; ++j) kept.insert(kept.end(), {low[j], high[j]});
      std::sort(kept.begin(), kept.end());
      kept.erase(std::unique(kept.begin(), kept.end()), kept.end());
      i = end;
    }
    for (size_t k : kept) out.push_back(rows.row(k), width);
  }
  return out;
}

void Report::AddFigure(const std::string& caption, std::vector<Series> data, std::string script,
                       int height_px) {
  FigureAt(Reserve(), caption, std::move(data), std::move(script), height_px);
}

size_t Report::Reserve() {
  parts_.emplace_back();
  open_.push_back(true);
  return parts_.size() - 1;
}

void Report::Fill(size_t place, const std::string& html) {
  if (!(place < parts_.size() && open_[place]))
    throw std::logic_error("Report: place " + std::to_string(place) + " is not an open one");
  parts_[place] = html;
  open_[place] = false;
}

void Report::Fill(size_t place, const std::vector<std::string>& htmls) {
  std::string joined;  // one place: Document ends each part with a line
  for (size_t i = 0; i < htmls.size(); ++i) joined += (i ? "\n" : "") + htmls[i];
  Fill(place, joined);
}

void Report::FigureAt(size_t place, const std::string& caption, std::vector<Series> data,
                      std::string script, int height_px) {
  Fill(place, "");  // the figure's place, filled when the report is drawn
  pending_.push_back({caption, std::move(data), std::move(script), height_px, place});
  ++figures_;
  if (gnuplot_) {
    SendFigure(*gnuplot_, pending_.size() - 1);
    pending_.back().data.clear();  // in its files now
  }
}

void Report::SendFigure(Gnuplot& gnuplot, size_t k) const {
  // Each figure in its own folder (its data files named as the series, so the SVG's titles name
  // no temporary path) with its script, `reset session` first; given to gnuplot as soon as it is
  // written, so that gnuplot draws it while the next one is made.
  const PendingFigure& f = pending_[k];
  const std::filesystem::path dir = gnuplot.Folder() / ("f" + std::to_string(k));
  // Each file registered before it is made (an interrupt removes it), gnuplot's own too.
  gnuplot.Temporary(dir, true);
  std::error_code made;
  if (!std::filesystem::create_directory(dir, made) && made) {
    throw CaseError("report: cannot make " + dir.string() + ": " + made.message());
  }
  for (const char* own : {"figure.gp", "figure.svg", "drawn"}) gnuplot.Temporary(dir / own);
  std::string script = f.script;
  for (const Series& s : f.data) {
    const std::string file = s.name + ".dat";
    // Ten significant digits, %g style, as a stream with precision 10 writes them; by
    // std::to_chars (a stream took some 3000 instructions a number: a third of a check).
    std::string text;
    char number[64];
    text.reserve(s.rows.size() * s.rows.width() * 12);
    for (size_t n = 0; n < s.rows.size(); ++n) {
      const double* row = s.rows.row(n);
      for (size_t i = 0; i < s.rows.width(); ++i) {
        if (i) text += ' ';
        const auto end =
            std::to_chars(number, number + sizeof number, row[i], std::chars_format::general, 10);
        text.append(number, end.ptr);
      }
      text += '\n';
    }
    gnuplot.Temporary(dir / file);
    WriteWhole(dir / file, text);
    // Replace every $name with the quoted file name.
    const std::string key = "$" + s.name;
    for (size_t at = script.find(key); at != std::string::npos; at = script.find(key, at)) {
      script.replace(at, key.size(), "'" + file + "'");
      at += file.size() + 2;
    }
  }
  // `unset multiplot` first: a figure that failed inside a multiplot leaves gnuplot in it (and
  // `reset session` does not end it). Its last line marks the figure drawn: a failed figure has
  // none, whatever its SVG holds.
  std::ostringstream gp;
  gp << "unset multiplot\nreset session\ncd '" << dir.string() << "'\n"
     << "set terminal svg size " << kFigureWidthPx << "," << f.height_px
     << " font 'sans,12' background rgb 'white'\n"
     << "set output 'figure.svg'\nset grid\n"
     << script << "\nunset output\nset print 'drawn'\nprint 1\nunset print\n";
  WriteWhole(dir / "figure.gp", gp.str());
  gnuplot.Load(dir / "figure.gp");
}

std::vector<std::string> Report::DrawFigures(Gnuplot& gnuplot) const {
  if (gnuplot_ && gnuplot_ != &gnuplot)
    throw std::logic_error("Report: its figures were given to another gnuplot");
  std::vector<std::string> parts = parts_;
  if (pending_.empty()) return parts;
  // Every figure in one gnuplot process: a report with its own gave each as it was added.
  if (!gnuplot_)
    for (size_t k = 0; k < pending_.size(); ++k) SendFigure(gnuplot, k);
  const std::filesystem::path& folder = gnuplot.Folder();
  const int status = gnuplot.Finish();
  // gnuplot's messages, or what little is known without them.
  const auto why = [&] {
    const std::string text = gnuplot.ErrorText();
    return text.empty()
               ? "gnuplot wrote no message and ended with status " + std::to_string(status) + "\n"
               : text;
  };
  // In the document's order (a figure may have been given to gnuplot before one above it): the
  // first that failed is named.
  std::vector<size_t> order(pending_.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return pending_[a].part < pending_[b].part; });
  for (size_t k : order) {
    const PendingFigure& f = pending_[k];
    const std::filesystem::path dir = folder / ("f" + std::to_string(k));
    const std::string body = Slurp(dir / "figure.svg");
    const auto start = body.find("<svg");  // drop the XML prologue for inline use
    if (!std::filesystem::exists(dir / "drawn") || start == std::string::npos ||
        body.find("</svg>") == std::string::npos) {
      throw std::runtime_error("gnuplot failed drawing \"" + f.caption + "\": " + why());
    }
    parts[f.part] = "<figure>" + body.substr(start) + "<figcaption>" + Escape(f.caption) +
                    "</figcaption></figure>";
  }
  if (status != 0) {
    throw std::runtime_error("gnuplot failed drawing the report's figures: " + why());
  }
  return parts;
}

std::string Report::Html() const {
  if (gnuplot_) return Html(*gnuplot_);
  if (pending_.empty()) return Document(parts_);
  Gnuplot gnuplot;
  return Html(gnuplot);
}

std::string Report::Html(Gnuplot& gnuplot) const { return Document(DrawFigures(gnuplot)); }

std::string Report::Document(const std::vector<std::string>& parts) const {
  std::ostringstream out;
  out << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>"
      << Escape(title_)
      << "</title>\n<style>body{font-family:sans-serif;max-width:960px;margin:2em auto;color:#222}"
         "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #bbb;padding:.3em "
         ".6em;text-align:left}"
         "th{background:#eee}.pass{color:#070;font-weight:bold}.fail{color:#b00;font-weight:bold}"
         "figure{margin:1.5em "
         "0}figcaption{font-size:.9em;color:#555}svg{max-width:100%;height:auto}"
         ".skip{color:#555}</style></head>\n<body>\n<h1>"
      << Escape(title_) << "</h1>\n";
  for (size_t i = 0; i < parts.size(); ++i)
    if (!open_[i]) out << parts[i] << '\n';
  out << "</body></html>\n";
  return out.str();
}

}  // namespace needle
