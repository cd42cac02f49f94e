#include "apps/report/html_report.h"

#include <unistd.h>

#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace needle {

bool GnuplotAvailable() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

void RequireGnuplot() {
  if (!GnuplotAvailable()) {
    throw std::runtime_error(
        "gnuplot is not installed; the report's figures need it (apt-get install gnuplot-nox, "
        "or bash scripts/install-deps.sh)");
  }
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

Report::Report(std::string title) : title_(std::move(title)) {}

void Report::AddHtml(const std::string& html) { parts_.push_back(html); }

void Report::AddFigure(const std::string& caption, const std::vector<Series>& data,
                       std::string script, int height_px) {
  parts_.emplace_back();  // the figure's place, filled when the report is drawn
  pending_.push_back({caption, data, std::move(script), height_px, parts_.size() - 1});
  ++figures_;
}

namespace {

// A temporary folder, removed with everything in it when the owner goes.
class TempFolder {
 public:
  TempFolder() {
    char pattern[] = "/tmp/needle-report-XXXXXX";
    const char* dir = mkdtemp(pattern);
    if (!dir) throw std::runtime_error("report: cannot create a temporary folder for gnuplot");
    path_ = dir;
  }
  ~TempFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

std::string Slurp(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace

std::vector<std::string> Report::DrawFigures() const {
  std::vector<std::string> parts = parts_;
  if (pending_.empty()) return parts;
  // Every figure in one gnuplot process: each in its own folder (its data files named as the
  // series, so the SVG's titles name no temporary path), `reset session` between them.
  const TempFolder folder;
  std::ostringstream gp;
  for (size_t k = 0; k < pending_.size(); ++k) {
    const PendingFigure& f = pending_[k];
    const std::filesystem::path dir = folder.path() / ("f" + std::to_string(k));
    std::filesystem::create_directory(dir);
    std::string script = f.script;
    for (const Series& s : f.data) {
      const std::string file = s.name + ".dat";
      // Ten significant digits, %g style, as a stream with precision 10 writes them; by
      // std::to_chars (a stream took some 3000 instructions a number: a third of a check).
      std::string text;
      char number[64];
      for (const auto& row : s.rows) {
        for (size_t i = 0; i < row.size(); ++i) {
          if (i) text += ' ';
          const auto end =
              std::to_chars(number, number + sizeof number, row[i], std::chars_format::general, 10);
          text.append(number, end.ptr);
        }
        text += '\n';
      }
      std::ofstream(dir / file) << text;
      // Replace every $name with the quoted file name.
      const std::string key = "$" + s.name;
      for (size_t at = script.find(key); at != std::string::npos; at = script.find(key, at)) {
        script.replace(at, key.size(), "'" + file + "'");
        at += file.size() + 2;
      }
    }
    gp << "reset session\ncd '" << dir.string() << "'\n"
       << "set terminal svg size 860," << f.height_px << " font 'sans,12' background rgb 'white'\n"
       << "set output 'figure.svg'\nset grid\n"
       << script << "\nunset output\n";
  }
  {
    std::ofstream out(folder.path() / "figures.gp");
    out << gp.str();
  }
  const std::string command = "gnuplot '" + (folder.path() / "figures.gp").string() + "' 2>'" +
                              (folder.path() / "err.txt").string() + "'";
  const int status = std::system(command.c_str());
  for (size_t k = 0; k < pending_.size(); ++k) {
    const PendingFigure& f = pending_[k];
    const std::string body = Slurp(folder.path() / ("f" + std::to_string(k)) / "figure.svg");
    const auto start = body.find("<svg");  // drop the XML prologue for inline use
    if (start == std::string::npos || body.find("</svg>") == std::string::npos) {
      throw std::runtime_error("gnuplot failed drawing \"" + f.caption +
                               "\": " + Slurp(folder.path() / "err.txt"));
    }
    parts[f.part] = "<figure>" + body.substr(start) + "<figcaption>" + Escape(f.caption) +
                    "</figcaption></figure>";
  }
  if (status != 0) {
    throw std::runtime_error("gnuplot failed drawing the report's figures: " +
                             Slurp(folder.path() / "err.txt"));
  }
  return parts;
}

std::string Report::Html() const {
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
  for (const std::string& p : DrawFigures()) out << p << '\n';
  out << "</body></html>\n";
  return out.str();
}

}  // namespace needle
