// The HTML report's figures: drawn by one gnuplot process started before the work, its failure
// named with the figure it failed on, its temporary folder gone either way.
#include "apps/report/html_report.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>

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
  const std::filesystem::path folder = gnuplot.folder();
  EXPECT_TRUE(std::filesystem::is_directory(folder));
  const std::string html = TwoFigures("plot $points with points").Html(gnuplot);
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
    folder = gnuplot.folder();
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

}  // namespace
}  // namespace needle

namespace needle {
namespace {

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

}  // namespace
}  // namespace needle

namespace needle {
namespace {

// A report given its gnuplot when made has each figure drawn as it is added: the same page as
// a report drawn at the end; finished with another gnuplot it is refused.
TEST(HtmlReportTest, FiguresGivenToGnuplotAsTheyAreAddedMakeTheSamePage) {
  const std::string at_end = TwoFigures("plot $points with points").Html();
  Gnuplot gnuplot;
  Report report("two figures", &gnuplot);
  report.AddHtml("<p>before</p>");
  report.AddFigure("a line", {Make("line", {{0.0, 1.0}, {1.0, 2.0}})}, "plot $line with lines");
  EXPECT_TRUE(std::filesystem::exists(gnuplot.folder() / "f0" / "figure.gp"));  // given already
  report.AddFigure("the second", {Make("points", {{0.0, 3.0}, {1.0, 4.0}})},
                   "plot $points with points");
  Gnuplot other;
  EXPECT_THROW(report.Html(other), std::logic_error);
  EXPECT_EQ(report.Html(), at_end);
}

}  // namespace
}  // namespace needle
