#include "apps/cli/report.h"

#include <unistd.h>

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
  char pattern[] = "/tmp/needle-report-XXXXXX";
  const char* dir = mkdtemp(pattern);
  if (!dir) throw std::runtime_error("report: cannot create a temporary folder for gnuplot");
  const std::filesystem::path folder(dir);
  for (const Series& s : data) {
    const std::string file = (folder / (s.name + ".dat")).string();
    std::ofstream out(file);
    out.precision(10);
    for (const auto& row : s.rows) {
      for (size_t i = 0; i < row.size(); ++i) out << (i ? " " : "") << row[i];
      out << '\n';
    }
    // Replace every $name with the quoted file name.
    const std::string key = "$" + s.name;
    for (size_t at = script.find(key); at != std::string::npos; at = script.find(key, at)) {
      script.replace(at, key.size(), "'" + file + "'");
      at += file.size() + 2;
    }
  }
  const std::string svg = (folder / "figure.svg").string();
  const std::string gp = (folder / "figure.gp").string();
  {
    std::ofstream out(gp);
    out << "set terminal svg size 860," << height_px << " font 'sans,12' background rgb 'white'\n"
        << "set output '" << svg << "'\nset grid\n"
        << script << "\nunset output\n";
  }
  const std::string command = "gnuplot '" + gp + "' 2>'" + (folder / "err.txt").string() + "'";
  const int status = std::system(command.c_str());
  std::ifstream in(svg);
  std::stringstream buffer;
  buffer << in.rdbuf();
  if (status != 0 || buffer.str().find("<svg") == std::string::npos) {
    std::ifstream err((folder / "err.txt").string());
    std::stringstream e;
    e << err.rdbuf();
    std::filesystem::remove_all(folder);
    throw std::runtime_error("gnuplot failed drawing \"" + caption + "\": " + e.str());
  }
  std::filesystem::remove_all(folder);
  std::string body = buffer.str();
  const auto start = body.find("<svg");  // drop the XML prologue for inline use
  parts_.push_back("<figure>" + body.substr(start) + "<figcaption>" + Escape(caption) +
                   "</figcaption></figure>");
  ++figures_;
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
  for (const std::string& p : parts_) out << p << '\n';
  out << "</body></html>\n";
  return out.str();
}

}  // namespace needle
