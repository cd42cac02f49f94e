// The spring check's fields: the preloads in kgf as Basu reads them, n_qs and the margins
// without a value where they are unbounded, the verdicts as yes/no.
#include "spring/spring_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "apps/case/case_file.h"
#include "apps/case/case_scene.h"
#include "lib/units.h"

namespace needle {
namespace {

const std::string kCases = std::string(NEEDLE_SOURCE_DIR) + "/cases/";

TEST(SpringCheckTest, FieldsShowTheCheckInKgfAndPercent) {
  const Case c = LoadCase(kCases + "basu-example1.toml");
  const LiftLaw law = MakeLiftLaw(c);
  SpringCheckResult r = CheckSpring(c, law, c.engine.speed_rpm);
  std::vector<Field> f = SpringCheckFields(r);
  EXPECT_EQ(*FieldAt(f, "actual_preload_kgf").Shown(), r.train.preload_N / kKgf);
  ASSERT_TRUE(r.basu_preload_N.has_value());
  EXPECT_EQ(*FieldAt(f, "deviation_percent").Shown(), *r.basu_deviation_percent);
  EXPECT_EQ(*FieldAt(f, "spring_rate_N_mm").Shown(), r.train.rate_N_m * 1e-3);
  EXPECT_EQ(*FieldAt(f, "liftoff_rpm_quasi_static").Shown(), r.liftoff_rpm_quasi_static);
  EXPECT_EQ(FieldAt(f, "pass").flag, r.pass);
  EXPECT_EQ(FieldAt(f, "gas_source").text, r.gas_source);
  // Unbounded: a needle that never decelerates has no n_qs, nothing required has no margin.
  r.liftoff_rpm_quasi_static = INFINITY;
  r.preload_margin_percent = INFINITY;
  f = SpringCheckFields(r);
  EXPECT_FALSE(FieldAt(f, "liftoff_rpm_quasi_static").Shown().has_value());
  EXPECT_FALSE(FieldAt(f, "preload_margin_percent").Shown().has_value());
}

}  // namespace
}  // namespace needle
