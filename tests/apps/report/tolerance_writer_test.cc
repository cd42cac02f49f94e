// The tolerance study's writers over a study with a refused sample (the model refused its
// perturbed case: no outputs): the report's histograms leave it out. Before, `tolerance --out`
// ended in "needle: error: map::at" (exit 3) once any sample was refused.
#include "apps/report/tolerance_writer.h"

#include <gtest/gtest.h>

#include <string>

namespace needle {
namespace {

TEST(ToleranceWriterTest, AReportLeavesRefusedSamplesOutOfItsHistograms) {
  Case c;
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

}  // namespace
}  // namespace needle
