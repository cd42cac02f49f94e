// "Synthesize and verify a cam" as a library function: its checks against values computed
// here from the law, its failing lines, and its fields.
#include "apps/scene/synthesis_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "lib/units.h"

namespace needle {
namespace {

std::string MatecSpec() {
  std::ifstream in(std::string(NEEDLE_SOURCE_DIR) + "/cases/matec-2018-synth.toml");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The MATEC spec with a spring, a mass and a larger base circle (so that only the limits we
// set can fail).
SynthesisFile WithSpring(const std::string& extra) {
  std::string spec = MatecSpec();
  const std::string anchor = "max_pressure_angle_deg = 45\n";
  spec.insert(spec.find(anchor) + anchor.size(),
              "spring_preload_N = 2000\nspring_rate_N_mm = 50\nmoving_mass_kg = 0.3\n" + extra);
  spec.replace(spec.find("base_radius_mm = 10"), 19, "base_radius_mm = 60");
  return ParseSynthesisFile(spec, "s.toml");
}

bool Contains(const std::vector<std::string>& lines, const std::string& start) {
  for (const std::string& l : lines)
    if (l.rfind(start, 0) == 0) return true;
  return false;
}

TEST(SynthesisSceneTest, TheMatecCamUndercutsWithItsRoller) {
  const SynthesisResult r = SynthesizeCam(ParseSynthesisFile(MatecSpec(), "m.toml"));
  EXPECT_FALSE(r.pass);
  ASSERT_TRUE(r.profile);
  EXPECT_NEAR(r.profile->min_profile_radius_m * 1e3, -5.45, 0.005);
  ASSERT_EQ(r.failing.size(), 1u);
  EXPECT_TRUE(Contains(r.failing, "cam profile: the profile undercuts (least radius -5.450 mm"));
  EXPECT_EQ(r.law.phi.size(), 2 * r.rise.phi.size() - 1);  // the mirrored fall
  EXPECT_NEAR(r.max_s1.value, r.spec.speed_limit, 1e-12);  // the constant-speed section
}

// K = (P₀ + k·S)/(m·ω²·|S''|) at the cam's speed (half the crank's, four-stroke), least over
// the decelerating steps, computed here from the law.
TEST(SynthesisSceneTest, TheSpringReserveIsTheLeastRatioOverTheSteps) {
  const SynthesisResult r = SynthesizeCam(WithSpring(""));
  const double w = OmegaFromRpm(1000) / 2;
  double least = INFINITY;
  for (size_t i = 0; i < r.rise.phi.size(); ++i) {
    if (r.rise.s2[i] < 0)
      least = std::min(least, (2000 + 50e3 * r.rise.s[i]) / (0.3 * w * w * -r.rise.s2[i]));
  }
  ASSERT_TRUE(r.min_spring_reserve);
  EXPECT_NEAR(r.min_spring_reserve->value, least, 1e-12 * least);
  EXPECT_TRUE(r.pass) << (r.failing.empty() ? "" : r.failing[0]);
}

TEST(SynthesisSceneTest, EachLimitFailsByName) {
  // A reserve the law cannot meet steers S'' down; a contact stress limit of 1 MPa and a
  // pressure angle limit of 1° cannot hold.
  const SynthesisResult r =
      SynthesizeCam(WithSpring("contact_length_mm = 10\nmax_contact_stress_MPa = 1\n"));
  EXPECT_FALSE(r.pass);
  ASSERT_TRUE(r.max_contact_stress_Pa);
  EXPECT_TRUE(Contains(r.failing, "contact stress: ")) << r.failing.size();
  std::string spec = MatecSpec();
  // With an offset follower the caps do not steer (they assume a radial one), so the limit
  // is only checked.
  spec.replace(spec.find("max_pressure_angle_deg = 45"), 27, "max_pressure_angle_deg = 5");
  spec.replace(spec.find("base_radius_mm = 10"), 19, "base_radius_mm = 60");
  spec.replace(spec.find("offset_mm = 0"), 13, "offset_mm = 5");
  const SynthesisResult p = SynthesizeCam(ParseSynthesisFile(spec, "p.toml"));
  EXPECT_TRUE(Contains(p.failing, "pressure angle: the largest |angle| ")) << p.failing.size();
}

TEST(SynthesisSceneTest, FieldsAreTheResultInDisplayUnits) {
  const SynthesisResult r = SynthesizeCam(WithSpring(""));
  const std::vector<Field> f = SynthesisFields(r);
  auto at = [&](const std::string& key) {
    for (const Field& x : f)
      if (x.Key() == key) return x;
    ADD_FAILURE() << "no field " << key;
    return Field{};
  };
  EXPECT_EQ(*at("max_S1_mm_rad").Shown(), r.max_s1.value * 1e3);
  EXPECT_EQ(*at("max_S1_deg").Shown(), r.max_s1.at_rad / kDeg);
  EXPECT_EQ(*at("min_spring_reserve").Shown(), r.min_spring_reserve->value);
  EXPECT_FALSE(at("meet_speed_mm_rad").Shown());  // the speed limit is active: no meeting
  const auto rows = SynthesisRows(r.law);
  EXPECT_EQ(rows.size(), r.law.phi.size());
  EXPECT_EQ(CsvTable(SynthesisColumns(), {}, 6), "cam_deg,S_mm,S1_mm_rad,S2_mm_rad2,S3_mm_rad3\n");
}

}  // namespace
}  // namespace needle
