#pragma once
/// @file
/// A self-contained HTML report: sections of HTML and figures drawn by gnuplot (svg terminal),
/// embedded inline, written atomically as one file.

#include <sys/types.h>

#include <filesystem>
#include <initializer_list>
#include <string>
#include <vector>

namespace needle {

/// A gnuplot process, started when made, so that its start-up (some 10 ms of loading) runs
/// beside the work before the figures, and waiting on a pipe for the figures' scripts (Load, as
/// a Report adds or draws them). Throws CaseError (exit 2: the machine's fault, no bug) saying
/// how to install gnuplot when it is not there, or why it cannot be started; closes the pipe
/// (gnuplot then ends) and waits for it when it goes. Its standard output goes to /dev/null; it
/// reads no init file (-d). Its temporaries are in $TMPDIR, else /tmp.
class Gnuplot {
 public:
  Gnuplot();
  ~Gnuplot();
  Gnuplot(const Gnuplot&) = delete;
  Gnuplot& operator=(const Gnuplot&) = delete;

  /// A folder of its own for the figures' files, made when first asked (an interrupted command
  /// leaves none before its figures), removed with everything in it when it goes.
  const std::filesystem::path& Folder();
  /// Has gnuplot run the script file `script` (as `gnuplot script` runs it: stopping at the
  /// script's first error) once it has run the ones given before.
  void Load(const std::filesystem::path& script);
  /// Ends gnuplot's input, waits for it to end and returns its exit status (not 0 when a script
  /// failed); what it wrote to its standard error is in ErrorText(). Once only.
  int Finish();
  /// What gnuplot wrote to its standard error so far, as `gnuplot script` writes it.
  std::string ErrorText() const;
  /// Registers a file (or folder) of the figures to be removed if an interrupting signal ends the
  /// program (lib/output.h RegisterTemporary); all of Folder() goes when this does.
  void Temporary(const std::filesystem::path& path, bool folder = false);

 private:
  int Reap();  // waits for gnuplot to end: its wait status, or -1

  std::filesystem::path folder_;  // empty until Folder() makes it
  int input_ = -1;                // the write end of gnuplot's standard input
  int errors_ = -1;               // gnuplot's standard error: a file without a name
  std::vector<int> slots_;        // the registered temporaries (RegisterTemporary)
  int child_slot_ = -1;           // gnuplot, ended by an interrupt first (RegisterChildProcess)
  pid_t pid_ = -1;
};

/// A figure's rows of numbers, kept flat (a figure's thousands of points in one allocation):
/// every row as wide as the first.
class Rows {
 public:
  /// Appends one row; throws std::logic_error when it is not as wide as the first. (Named as a
  /// std::vector's, which its callers filled before.)
  void push_back(std::initializer_list<double> row);
  /// Appends the `width` numbers at `row` (another Rows' row).
  void push_back(const double* row, size_t width);
  bool empty() const { return values_.empty(); }
  size_t size() const { return width_ ? values_.size() / width_ : 0; }
  size_t width() const { return width_; }
  const double* row(size_t i) const { return values_.data() + i * width_; }

 private:
  std::vector<double> values_;
  size_t width_ = 0;
};

/// A figure's width in the report, px.
constexpr int kFigureWidthPx = 860;

/// The rows a line plot of `rows` (x in the first column, a curve's y in each other, in drawing
/// order) needs at `columns` columns over x in [x_from, x_to]: of each run of rows in one
/// column, the first, the last, and each curve's lowest and highest, in their order (M4: Jugel
/// et al., "M4: a visualization-oriented time series data aggregation", VLDB 2014). At a column
/// a pixel or more the curves are drawn to within a pixel of the whole series'. A run also
/// shares which numbers are finite (a curve's gap keeps the rows at its ends); rows without a
/// finite x are kept as they are, and rows narrower than two returned whole.
Rows LineEnvelope(const Rows& rows, double x_from, double x_to, int columns);

/// One data series for a figure: columns of numbers written to a temporary file.
struct Series {
  std::string name;
  Rows rows;
};

class Report {
 public:
  /// With `gnuplot`, each figure is given to it as it is added, so that gnuplot draws it while
  /// the report is built; Html() then finishes with the same gnuplot.
  explicit Report(std::string title, Gnuplot* gnuplot = nullptr);

  void AddHtml(const std::string& html);
  /// Adds a figure, given to the report's gnuplot now when it has one, else drawn with the others
  /// when the document is made (Html): `script` is gnuplot after the terminal is set; it reads the
  /// series as files named in `$name` placeholders
  /// ($lift, $force, …). `height_px`: the figure's height (kFigureWidthPx wide).
  void AddFigure(const std::string& caption, std::vector<Series> data, std::string script,
                 int height_px = 420);
  /// A place in the document for what is known later (a report made as its job runs, so that
  /// gnuplot draws the figures known first beside the rest of the job): filled once by Fill or
  /// FigureAt, and left out of the document if never filled. (gnuplot draws the figures in the
  /// order given; the first it draws differs from the later ones in one attribute of its SVG.)
  size_t Reserve();
  void Fill(size_t place, const std::string& html);
  /// The same with several parts, in the document as if each had been added (AddHtml).
  void Fill(size_t place, const std::vector<std::string>& htmls);
  void FigureAt(size_t place, const std::string& caption, std::vector<Series> data,
                std::string script, int height_px = 420);
  int figures() const { return figures_; }

  /// The whole HTML document, every figure drawn by one gnuplot process (the report's own, or one
  /// started here). Throws std::runtime_error naming gnuplot's failure and the first figure it
  /// failed on.
  std::string Html() const;
  /// The same, drawn by `gnuplot` (started before the work that made the report; the report's
  /// own when it has one).
  std::string Html(Gnuplot& gnuplot) const;

 private:
  // A figure to draw: its caption, data and script, and its place in parts_.
  struct PendingFigure {
    std::string caption;
    std::vector<Series> data;
    std::string script;
    int height_px;
    size_t part;
  };
  void SendFigure(Gnuplot& gnuplot, size_t k) const;  // writes figure k, has gnuplot draw it
  std::vector<std::string> DrawFigures(Gnuplot& gnuplot) const;       // parts_, every figure drawn
  std::string Document(const std::vector<std::string>& parts) const;  // the page around them

  std::string title_;
  std::vector<std::string> parts_;
  std::vector<bool> open_;  // parts_[i] reserved and not filled: left out of the document
  std::vector<PendingFigure> pending_;
  int figures_ = 0;
  Gnuplot* gnuplot_ = nullptr;  // draws each figure as it is added
};

/// HTML-escapes text.
std::string Escape(const std::string& text);

}  // namespace needle
