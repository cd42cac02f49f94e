#pragma once
/// @file
/// A self-contained HTML report: sections of HTML and figures drawn by gnuplot (svg terminal),
/// embedded inline, written atomically as one file.

#include <string>
#include <vector>

namespace needle {

/// One data series for a figure: columns of numbers written to a temporary file.
struct Series {
  std::string name;
  std::vector<std::vector<double>> rows;
};

class Report {
 public:
  explicit Report(std::string title);

  void AddHtml(const std::string& html);
  /// Adds a figure, drawn with the others when the document is made (Html): `script` is gnuplot
  /// after the terminal is set; it reads the series as files named in `$name` placeholders
  /// ($lift, $force, …). `height_px`: the figure's height (860 px wide).
  void AddFigure(const std::string& caption, const std::vector<Series>& data, std::string script,
                 int height_px = 420);
  int figures() const { return figures_; }

  /// The whole HTML document; its figures are drawn here, all in one gnuplot process. Throws
  /// std::runtime_error naming gnuplot's failure and the figure it failed on.
  std::string Html() const;

 private:
  // A figure to draw: its caption, data and script, and its place in parts_.
  struct PendingFigure {
    std::string caption;
    std::vector<Series> data;
    std::string script;
    int height_px;
    size_t part;
  };
  std::vector<std::string> DrawFigures() const;  // parts_ with every figure drawn

  std::string title_;
  std::vector<std::string> parts_;
  std::vector<PendingFigure> pending_;
  int figures_ = 0;
};

/// True when gnuplot can be run.
bool GnuplotAvailable();
/// Throws std::runtime_error saying how to install gnuplot when it cannot be run (before a
/// command that draws a report computes anything).
void RequireGnuplot();

/// HTML-escapes text.
std::string Escape(const std::string& text);

}  // namespace needle
