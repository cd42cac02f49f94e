// The tolerance study's writers over a study with a refused sample (the model refused its
// perturbed case: no outputs): the report's histograms leave it out. Before, `tolerance --out`
// ended in "needle: error: map::at" (exit 3) once any sample was refused.
#include "apps/report/tolerance_writer.h"

#include <gtest/gtest.h>

#include <string>

namespace needle {
namespace {

TEST(ToleranceWriterTest, AReportLeavesRefusedSamplesOutOfItsHistograms) {
  BoundCase c;
  c.path = "valve.toml";
  ToleranceResult r;
  const std::string key = "spring.liftoff_rpm_quasi_static";
  for (double n : {600.0, 640.0}) {
    ToleranceSample s;
    s.outputs[key] = n;
    s.pass = true;
    r.samples.push_back(s);
  }
  ToleranceSample refused;
  refused.refused = "case refused";
  refused.failing = {"case refused"};
  r.samples.push_back(refused);
  r.distributions[key] = Describe({600.0, 640.0});
  r.options.threads = 1;
  Report report("");
  EXPECT_NO_THROW(report = ToleranceReport(c, r, 1));
  EXPECT_GE(report.figures(), 1);  // the histogram of the two samples that have the output
  EXPECT_NE(ToleranceJson(c, r)["sample_results"][2]["refused"], nullptr);
}

// A scatter within round-off (a user's preload_percent = 1e-13) has no histogram: its bin width
// printed to 12 decimals was 0, gnuplot refused the figure and the study ended in exit 3. The
// report's title is escaped once (it was twice: "&amp;amp;").
TEST(ToleranceWriterTest, AScatterWithinRoundOffHasNoHistogramAndTheTitleIsEscapedOnce) {
  BoundCase c;
  c.path = "valve.toml";
  c.title = "Cam A & B <v2>";
  ToleranceResult r;
  const std::string key = "spring.liftoff_rpm_quasi_static";
  for (double n : {600.0, 600.0 * (1 + 1e-13), 600.0 * (1 + 2e-13)}) {
    ToleranceSample s;
    s.outputs[key] = n;
    s.pass = true;
    r.samples.push_back(s);
  }
  r.distributions[key] = Describe({600.0, 600.0 * (1 + 1e-13), 600.0 * (1 + 2e-13)});
  r.options.threads = 1;
  const Report report = ToleranceReport(c, r, 1);
  EXPECT_EQ(report.figures(), 0);
  const std::string html = report.Html();
  EXPECT_NE(html.find("<title>needle tolerance: Cam A &amp; B &lt;v2&gt;</title>"),
            std::string::npos);
  EXPECT_EQ(html.find("&amp;amp;"), std::string::npos);
}

}  // namespace
}  // namespace needle
