// The HTML report's figures: drawn by one gnuplot process started before the work, its failure
// named with the figure it failed on, its temporary folder gone either way.
#include "apps/report/html_report.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/case/case_file.h"
#include "apps/report/check_writers.h"
#include "apps/study/check_scene.h"

namespace needle {
namespace {

Series Make(const std::string& name, std::initializer_list<std::initializer_list<double>> rows) {
  Series s{name, {}};
  for (const auto& row : rows) s.rows.push_back(row);
  return s;
}

Report TwoFigures(const std::string& second_script) {
  Report report("two figures");
  report.AddHtml("<p>before</p>");
  report.AddFigure("a line", {Make("line", {{0.0, 1.0}, {1.0, 2.0}})}, "plot $line with lines");
  report.AddFigure("the second", {Make("points", {{0.0, 3.0}, {1.0, 4.0}})}, second_script);
  return report;
}

TEST(HtmlReportTest, FiguresAreDrawnInPlaceByTheGnuplotStartedBeforeTheWork) {
  Gnuplot gnuplot;
  const std::string html = TwoFigures("plot $points with points").Html(gnuplot);
  const std::filesystem::path folder = gnuplot.Folder();  // made for the first figure
  EXPECT_TRUE(std::filesystem::is_directory(folder / "f1"));
  const size_t before = html.find("<p>before</p>");
  const size_t first = html.find("<figure><svg");
  const size_t second = html.find("<figure><svg", first + 1);
  ASSERT_NE(second, std::string::npos) << html;
  EXPECT_LT(before, first);
  EXPECT_NE(html.find("</svg>\n\n<figcaption>a line</figcaption></figure>"), std::string::npos);
  EXPECT_NE(html.find("</svg>\n\n<figcaption>the second</figcaption></figure>"), std::string::npos);
  EXPECT_EQ(html.find(folder.string()), std::string::npos);  // no temporary path in the page
  EXPECT_THROW(gnuplot.Load(folder / "f0" / "figure.gp"), std::logic_error);  // finished
  EXPECT_THROW(gnuplot.Finish(), std::logic_error);
}

TEST(HtmlReportTest, AFigureGnuplotRefusesIsNamedWithGnuplotsMessageAndNothingIsLeft) {
  std::filesystem::path folder;
  try {
    Gnuplot gnuplot;
    folder = gnuplot.Folder();
    TwoFigures("plot no_such_function($points)").Html(gnuplot);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    // The first failing figure is named, with gnuplot's message as `gnuplot script` writes it
    // (the script's path and line first, not indented).
    EXPECT_EQ(what.rfind("gnuplot failed drawing \"the second\": \"" + folder.string() +
                             "/f1/figure.gp\" line ",
                         0),
              0u)
        << what;
    EXPECT_NE(what.find("undefined"), std::string::npos) << what;
  }
  EXPECT_FALSE(folder.empty());
  EXPECT_FALSE(std::filesystem::exists(folder));
}

TEST(HtmlReportTest, AReportWithoutFiguresNeedsNoGnuplot) {
  Report report("text only");
  report.AddHtml("<p>x</p>");
  EXPECT_EQ(report.figures(), 0);
  EXPECT_NE(report.Html().find("<p>x</p>"), std::string::npos);
}

TEST(HtmlReportTest, RowsAreAsWideAsTheFirst) {
  Rows rows;
  EXPECT_TRUE(rows.empty());
  rows.push_back({1.0, 2.0});
  rows.push_back({3.0, 4.0});
  EXPECT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows.width(), 2u);
  EXPECT_EQ(rows.row(1)[0], 3.0);
  try {
    rows.push_back({5.0});
    FAIL() << "no error";
  } catch (const std::logic_error& e) {
    EXPECT_STREQ(e.what(), "Rows::push_back: a row of 1 numbers in rows of 2");
  }
}

// A report given its gnuplot when made has each figure drawn as it is added: the same page as
// a report drawn at the end; finished with another gnuplot it is refused.
TEST(HtmlReportTest, FiguresGivenToGnuplotAsTheyAreAddedMakeTheSamePage) {
  const std::string at_end = TwoFigures("plot $points with points").Html();
  Gnuplot gnuplot;
  Report report("two figures", &gnuplot);
  report.AddHtml("<p>before</p>");
  report.AddFigure("a line", {Make("line", {{0.0, 1.0}, {1.0, 2.0}})}, "plot $line with lines");
  EXPECT_TRUE(std::filesystem::exists(gnuplot.Folder() / "f0" / "figure.gp"));  // given already
  report.AddFigure("the second", {Make("points", {{0.0, 3.0}, {1.0, 4.0}})},
                   "plot $points with points");
  Gnuplot other;
  EXPECT_THROW(report.Html(other), std::logic_error);
  EXPECT_EQ(report.Html(), at_end);
}

// A report made as its job runs: a place reserved for what is known later is filled in its
// order, left out when never filled (not even its line), filled once; a figure put in a place
// above one given to gnuplot before it is drawn there, and the first failing figure named is the
// first in the document, whichever gnuplot was given first. (The first figure a gnuplot draws
// differs from the later ones in one attribute of the SVG: both pages give theirs first.)
TEST(HtmlReportTest, PlacesReservedAreFilledInTheirOrderOrLeftOut) {
  const Series line = Make("line", {{0.0, 1.0}, {1.0, 2.0}});
  const Series points = Make("points", {{0.0, 3.0}, {1.0, 4.0}});
  const std::string b_script = "plot $points with points", c_script = "plot $line with points";
  Report in_order("three figures");
  in_order.AddHtml("<p>before</p>");
  in_order.AddFigure("a", {line}, "plot $line with lines");
  in_order.AddFigure("b", {points}, b_script);
  in_order.AddFigure("c", {line}, c_script);
  const auto out_of_order = [&](const std::string& b, const std::string& c) {
    Gnuplot gnuplot;
    Report report("three figures", &gnuplot);
    const size_t before = report.Reserve();
    report.AddFigure("a", {line}, "plot $line with lines");
    const size_t second = report.Reserve();
    const size_t never = report.Reserve();
    report.AddFigure("c", {line}, c);  // given to gnuplot before b
    report.FigureAt(second, "b", {points}, b);
    report.Fill(before, "<p>before</p>");
    EXPECT_THROW(report.Fill(before, "again"), std::logic_error);
    EXPECT_THROW(report.Fill(second, "taken"), std::logic_error);
    EXPECT_THROW(report.Fill(never + 2, "past the end"), std::logic_error);
    return report.Html(gnuplot);
  };
  EXPECT_EQ(out_of_order(b_script, c_script), in_order.Html());
  try {  // b and c fail; c was given to gnuplot first
    out_of_order("plot no_such_function($points)", "plot no_such_function($line)");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("gnuplot failed drawing \"b\"", 0), 0u) << e.what();
  }
}

// LineEnvelope keeps, of each column's run of rows, the first, lowest, highest and last, in
// their order: every column shows the same extent and the curve enters and leaves it where the
// whole series does.
TEST(LineEnvelopeTest, EachColumnKeepsItsFirstLowestHighestAndLast) {
  Rows rows;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const double x = 10.0 * i / (n - 1);
    rows.push_back({x, std::sin(37.0 * x) + 0.3 * std::sin(911.0 * x)});  // a ringing curve
  }
  const int columns = 200;
  const Rows out = LineEnvelope(rows, 0.0, 10.0, columns);
  EXPECT_LE(out.size(), 4u * (columns + 1));
  EXPECT_GT(out.size(), 2u * columns);
  // Every kept row is a row of the series, in the series' order.
  size_t at = 0;
  for (size_t k = 0; k < out.size(); ++k) {
    while (at < rows.size() && (rows.row(at)[0] != out.row(k)[0])) ++at;
    ASSERT_LT(at, rows.size()) << k;
    EXPECT_EQ(rows.row(at)[1], out.row(k)[1]);
    ++at;  // each row of the series kept once at most
  }
  // Each column: the same first, last, least and largest y.
  const auto column = [&](double x) { return static_cast<int>(std::floor(x * (columns / 10.0))); };
  const auto extents = [&](const Rows& r) {
    std::vector<std::array<double, 4>> e(columns + 1, {NAN, NAN, INFINITY, -INFINITY});
    for (size_t i = 0; i < r.size(); ++i) {
      auto& c = e[column(r.row(i)[0])];
      if (std::isnan(c[0])) c[0] = r.row(i)[1];
      c[1] = r.row(i)[1];
      c[2] = std::min(c[2], r.row(i)[1]);
      c[3] = std::max(c[3], r.row(i)[1]);
    }
    return e;
  };
  const auto a = extents(rows), b = extents(out);
  for (int c = 0; c <= columns; ++c) {
    for (int j = 0; j < 4; ++j) {
      EXPECT_TRUE(a[c][j] == b[c][j] || (std::isnan(a[c][j]) && std::isnan(b[c][j])))
          << "column " << c << " item " << j;
    }
  }
}

// Rows of two curves (the report's force figure: the dynamic force, and the quasi-static one only
// inside the lift, NaN outside): each curve's extent in each column is kept, and a curve's gap
// keeps the rows at its ends.
TEST(LineEnvelopeTest, EveryCurveOfARowKeepsItsExtentAndItsGaps) {
  Rows rows;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double x = 10.0 * i / (n - 1);
    rows.push_back({x, std::sin(53.0 * x), x > 3.0 && x < 7.0 ? std::cos(71.0 * x) : NAN});
  }
  const int columns = 100;
  const Rows out = LineEnvelope(rows, 0.0, 10.0, columns);
  EXPECT_LE(out.size(), 6u * (columns + 2));
  for (size_t curve = 1; curve <= 2; ++curve) {
    std::vector<double> lo_a(columns + 1, INFINITY), hi_a(columns + 1, -INFINITY);
    std::vector<double> lo_b = lo_a, hi_b = hi_a;
    const auto extents = [&](const Rows& r, std::vector<double>& lo, std::vector<double>& hi) {
      for (size_t i = 0; i < r.size(); ++i) {
        const double y = r.row(i)[curve];
        if (!std::isfinite(y)) continue;
        const int c = static_cast<int>(std::floor(r.row(i)[0] * (columns / 10.0)));
        lo[c] = std::min(lo[c], y);
        hi[c] = std::max(hi[c], y);
      }
    };
    extents(rows, lo_a, hi_a);
    extents(out, lo_b, hi_b);
    EXPECT_EQ(lo_a, lo_b) << "curve " << curve;
    EXPECT_EQ(hi_a, hi_b) << "curve " << curve;
  }
  // The second curve's gap: the last row before it and the first inside it are both kept.
  size_t first_in = 0;
  while (!std::isfinite(rows.row(first_in)[2])) ++first_in;
  bool before = false, inside = false;
  for (size_t k = 0; k < out.size(); ++k) {
    before = before || out.row(k)[0] == rows.row(first_in - 1)[0];
    inside = inside || out.row(k)[0] == rows.row(first_in)[0];
  }
  EXPECT_TRUE(before);
  EXPECT_TRUE(inside);
}

TEST(LineEnvelopeTest, RowsItCannotJudgeAreKeptAsTheyAre) {
  Rows gap;
  for (double x : {0.0, 0.1, 0.2}) gap.push_back({x, x});
  gap.push_back({NAN, NAN});
  for (double x : {0.3, 0.4, 0.5}) gap.push_back({x, -x});
  const Rows out = LineEnvelope(gap, 0.0, 1.0, 1);  // one column: the gap splits its run
  ASSERT_EQ(out.size(), 5u);
  EXPECT_EQ(out.row(1)[0], 0.2);
  EXPECT_TRUE(std::isnan(out.row(2)[0]));
  EXPECT_EQ(out.row(3)[0], 0.3);
  EXPECT_EQ(out.row(4)[0], 0.5);
  Rows narrow;
  for (double x : {0.0, 0.1, 0.2, 0.3}) narrow.push_back({x});
  EXPECT_EQ(LineEnvelope(narrow, 0.0, 1.0, 1).size(), 4u);        // one number a row: no curve
  EXPECT_EQ(LineEnvelope(gap, 1.0, 1.0, 10).size(), gap.size());  // no x range
}

// A figure stops at its first error (a later line that would draw does not make it drawn), a
// figure that fails inside a multiplot does not fail the ones after it, and the first failing
// figure is the one named.
TEST(HtmlReportTest, AFigureStopsAtItsFirstErrorAndTheNextIsStillDrawn) {
  Gnuplot gnuplot;
  Report report("three figures", &gnuplot);
  report.AddFigure("stops", {Make("a", {{0.0, 1.0}, {1.0, 2.0}})},
                   "plot no_such_function($a)\nplot $a with lines");
  report.AddFigure("multiplot", {Make("b", {{0.0, 1.0}, {1.0, 2.0}})},
                   "set multiplot layout 2,1\nplot $b with lines\nplot no_such_function($b)\n"
                   "unset multiplot");
  report.AddFigure("fine", {Make("c", {{0.0, 1.0}, {1.0, 2.0}})}, "plot $c with lines");
  try {
    report.Html();
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("gnuplot failed drawing \"stops\": ", 0), 0u) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(gnuplot.Folder() / "f0" / "drawn"));
  EXPECT_FALSE(std::filesystem::exists(gnuplot.Folder() / "f1" / "drawn"));
  EXPECT_TRUE(std::filesystem::exists(gnuplot.Folder() / "f2" / "drawn"));
  const std::string svg = [&] {
    std::ifstream in(gnuplot.Folder() / "f2" / "figure.svg");
    return std::string(std::istreambuf_iterator<char>(in), {});
  }();
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
}

// `check` makes its report as the check runs (the kinematics figure first, the rated run's when
// it ends): the same page as the report made from the result, on a scene with every figure, on
// one with its surge figure left out (no coil geometry: a rate-only spring) and on a kinematics
// case without dynamics.
TEST(CheckReportWriterTest, TheReportMadeAsTheCheckRunsIsTheResultsToTheByte) {
  for (const char* name : {"basu-example1.toml", "basu-cam4-light-spring.toml", "basu-cam4.toml"}) {
    const BoundCase c = Bind(LoadCase(std::string(NEEDLE_SOURCE_DIR) + "/cases/" + name));
    Gnuplot gnuplot;
    CheckReportWriter writer(c, *c.lift.law, c.lift.choice, c.engine.speed_rpm, &gnuplot);
    int calls = 0;
    CheckOptions options;
    options.rated_run_done = [&](const SpringCheckResult& spring, const SimulationResult& run,
                                 const SimulationOptions& sim) {
      ++calls;
      writer.RatedRun(spring, run, sim);
    };
    const CheckResult result = CheckScene(c, options);
    EXPECT_EQ(calls, result.run ? 1 : 0) << name;
    const std::string as_it_ran = writer.Finish(result).Html(gnuplot);
    EXPECT_EQ(as_it_ran, CheckReport(c, *c.lift.law, result).Html()) << name;
    EXPECT_NE(as_it_ran.find("<svg"), std::string::npos) << name;
  }
}

}  // namespace
}  // namespace needle
