// "Synthesize and verify a cam" as a library function: its checks against values computed
// here from the law, its failing lines, and its fields.
#include "apps/scene/synthesis_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
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
  // A contact-stress limit of 1 MPa steers S'' to nothing: the law cannot be formed, and the
  // refusal names the cap.
  try {
    SynthesizeCam(WithSpring("contact_length_mm = 10\nmax_contact_stress_MPa = 1\n"));
    ADD_FAILURE() << "a 1 MPa stress limit was met";
  } catch (const CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("the caps that bound S' or S'': contact stress"),
              std::string::npos)
        << e.what();
  }
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

// The MATEC spec with a flat face on a large base circle and its rise angle changed.
SynthesisFile FlatSpec(const std::string& rise_deg, const std::string& extra) {
  std::string spec = MatecSpec();
  auto swap = [&](const std::string& from, const std::string& to) {
    spec.replace(spec.find(from), from.size(), to);
  };
  swap("follower = \"curved\"", "follower = \"flat\"");
  swap("face_radius_mm = 8.25", extra);
  swap("base_radius_mm = 10", "base_radius_mm = 200");
  swap("angle_deg = 63", "angle_deg = " + rise_deg);
  swap("max_pressure_angle_deg = 45", "min_profile_radius_mm = 0");
  return ParseSynthesisFile(spec, "flat.toml");
}

TEST(SynthesisSceneTest, AFlatFacesHalfWidthMakesTheConstantSpeedSection) {
  // S'max 7.6 mm/rad, but the face reaches 7.5 mm either side of the axis, and the contact lies
  // S' off it: the face is the speed limit, the section runs at 7.5 mm/rad, and the largest
  // contact offset reported on the profile is the half-width.
  const SynthesisResult r = SynthesizeCam(FlatSpec("70", "face_half_width_mm = 7.5"));
  EXPECT_TRUE(r.rise.face_width_limited);
  EXPECT_TRUE(r.rise.speed_limit_active);
  EXPECT_GT(r.rise.constant_length_rad(), 50 * kDeg);
  ASSERT_TRUE(r.profile);
  EXPECT_NEAR(r.max_s1.value, 7.5e-3, 1e-12);
  EXPECT_NEAR(r.profile->max_contact_offset_m, 7.5e-3, 1e-9);
  EXPECT_LE(r.profile->max_contact_offset_m, 7.5e-3 * (1 + 1e-12));
  EXPECT_FALSE(r.profile->off_face);
  EXPECT_TRUE(r.pass) << (r.failing.empty() ? "" : r.failing[0]);
  // The same law under a narrower face (checked, not steered: a roller has none, so take the
  // law as it is and the face from the profile) runs off it.
  FollowerGeometry g;
  g.kind = FollowerKind::kFlat;
  g.base_radius_m = 0.2;
  g.face_half_width_m = 7.0e-3;
  const CamProfile narrow = MakeCamProfile(
      [&](double psi) {
        const SynthesizedLaw& law = r.law;
        if (psi <= 0.0 || psi >= law.phi.back()) return std::array<double, 3>{0.0, 0.0, 0.0};
        const size_t i = std::upper_bound(law.phi.begin(), law.phi.end(), psi) - law.phi.begin();
        return std::array<double, 3>{law.s[i], law.s1[i], law.s2[i]};
      },
      g, 3600);
  EXPECT_TRUE(narrow.off_face);
}

TEST(SynthesisSceneTest, TheLubricationLimitSteersTheCrest) {
  // A flat tappet loses its film where the entrainment (r_b + S + 2S'')ω/2 passes through zero:
  // a nose with |S''| > (r_b + S)/2. With 0.5 m/s asked for at 1000 rpm, the crest is formed
  // so that the least entrainment is the limit, and the check passes; without it, the same
  // rise's crest takes the entrainment through zero.
  const SynthesisResult r = SynthesizeCam(FlatSpec("64.2", "min_entrainment_speed_m_s = 0.5"));
  EXPECT_TRUE(r.rise.lubrication_limited);
  ASSERT_TRUE(r.profile);
  const double least = r.profile->min_entrainment_m_rad * r.cam_omega;
  EXPECT_GE(least, 0.5 * (1 - 1e-6));
  EXPECT_LT(least, 0.5 * 1.01);  // binding
  EXPECT_TRUE(r.pass) << (r.failing.empty() ? "" : r.failing[0]);
  const SynthesisResult free = SynthesizeCam(FlatSpec("64.2", ""));
  EXPECT_EQ(free.profile->min_entrainment_m_rad, 0.0);
}

TEST(SynthesisSceneTest, TheContactStressSteersTheSteps) {
  // Unsteered, this cam reaches 1306 MPa (checked only, before issue 15); with a 1290 MPa limit
  // steering S'' the law is formed within it and passes.
  const SynthesisResult free = SynthesizeCam(WithSpring("contact_length_mm = 10\n"));
  ASSERT_TRUE(free.max_contact_stress_Pa);
  EXPECT_NEAR(free.max_contact_stress_Pa->value * 1e-6, 1306, 1);
  const SynthesisResult r =
      SynthesizeCam(WithSpring("contact_length_mm = 10\nmax_contact_stress_MPa = 1290\n"));
  EXPECT_TRUE(r.rise.stress_limited);
  EXPECT_LE(r.max_contact_stress_Pa->value, 1290e6 * (1 + 1e-6));
  EXPECT_GT(r.max_contact_stress_Pa->value, 1289e6);
  EXPECT_TRUE(r.pass) << (r.failing.empty() ? "" : r.failing[0]);
}

// The table of the paper's case in docs/synthesis.md, one row per follower kind: what the law as formed
// does to each, and, steered to a profile radius ≥ 0, what would have to change.
TEST(SynthesisSceneTest, ThePapersCaseForEachFollowerKind) {
  struct Row {
    std::string kind, radius_key;
    double least_radius_mm, contact_offset_mm;
    std::string shortest, least_smax, least_base;
  };
  const Row rows[] = {
      {"roller", "roller_radius_mm = 8.25", -5.450, 0.0, "takes 65.38", "is 7.94", "is 26.66"},
      {"curved", "face_radius_mm = 8.25", -5.450, 3.145, "takes 65.38", "is 7.94", "is 26.66"},
      {"flat", "", -202.86, 7.6, "takes 73.85", "is 10.28", "is 173.5"},
  };
  for (const Row& row : rows) {
    std::string spec = MatecSpec();
    auto swap = [&](const std::string& from, const std::string& to) {
      spec.replace(spec.find(from), from.size(), to);
    };
    swap("follower = \"curved\"", "follower = \"" + row.kind + "\"");
    swap("face_radius_mm = 8.25", row.radius_key);
    const SynthesisResult r = SynthesizeCam(ParseSynthesisFile(spec, "k.toml"));
    ASSERT_TRUE(r.profile);
    EXPECT_TRUE(r.profile->undercut) << row.kind;
    EXPECT_NEAR(r.profile->min_profile_radius_m * 1e3, row.least_radius_mm, 0.01) << row.kind;
    EXPECT_NEAR(r.profile->max_contact_offset_m * 1e3, row.contact_offset_mm, 0.001) << row.kind;
    EXPECT_FALSE(r.pass);
    swap("max_pressure_angle_deg = 45", "min_profile_radius_mm = 0");
    try {
      SynthesizeCam(ParseSynthesisFile(spec, "k.toml"));
      ADD_FAILURE() << row.kind << ": the paper's numbers fit";
    } catch (const CaseError& e) {
      const std::string m = e.what();
      for (const std::string& part : {row.shortest, row.least_smax, row.least_base})
        EXPECT_NE(m.find(part), std::string::npos) << row.kind << ": " << part << " in " << m;
    }
  }
}

}  // namespace
}  // namespace needle
