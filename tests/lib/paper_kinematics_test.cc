// NACA TM 477 reproduced: the velocity table of cams 1-4 at 400 rpm and Example 1's
// acceleration. Basu differentiated by hand (graphically), so these tests assert what a
// careful computation shows about his numbers, not that we match them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "apps/case/case_file.h"
#include "lib/kinematics.h"
#include "lib/units.h"

namespace needle {
namespace {

const std::string kCases = std::string(NEEDLE_SOURCE_DIR) + "/cases/";

// Mean | |v| − v_paper | over the paper's angles, m/s.
double MeanVelocityDeviation(const std::string& name, SplineKind kind) {
  Case c = LoadCase(kCases + name);
  c.lift.spline.kind = kind;
  c.lift.spline.start_slope = c.lift.spline.end_slope = 0.0;
  const LiftLaw law = MakeLiftLaw(c);
  const Kinematics kin(law, c.engine.speed_rpm);
  double sum = 0;
  for (size_t i = 0; i < c.paper->crank_rad.size(); ++i) {
    sum +=
        std::abs(std::abs(kin.At(c.paper->crank_rad[i]).velocity_m_s) - c.paper->velocity_m_s[i]);
  }
  return sum / c.paper->crank_rad.size();
}

TEST(PaperKinematicsTest, VelocityTableDeviationPerCamAndSpline) {
  const char* cams[] = {"basu-cam1b.toml", "basu-cam2b.toml", "basu-cam3.toml",
                        "basu-cam3-alt.toml", "basu-cam4.toml"};
  for (const char* cam : cams) {
    const double clamped = MeanVelocityDeviation(cam, SplineKind::kClamped);
    const double not_a_knot = MeanVelocityDeviation(cam, SplineKind::kNotAKnot);
    std::printf("%-20s mean |dev| dcm/s: clamped at-rest %.2f, not-a-knot %.2f\n", cam,
                10 * clamped, 10 * not_a_knot);
    // Basu's curves start and end at rest (velocity 0 at the first and last angle): the
    // at-rest clamped spline is the end condition that agrees with him, on every cam but
    // cam 2 (whose tabulated positions are not the Fig. 10 curve he differentiated), where
    // the two are within 0.05 dcm/s of each other.
    EXPECT_LT(clamped, not_a_knot + 0.005) << cam;
    // And no cam is off by more than half a dcm/s on average: the order of a hand
    // differentiation's error, 10 % of the 4-5 dcm/s peaks.
    EXPECT_LT(clamped, 0.05) << cam;
  }
}

TEST(PaperKinematicsTest, Cam3VelocityTableFitsTheLiftReadAs005) {
  // The lift at −5° is printed 0.50 mm; the velocity table (0.45 dcm/s there) fits 0.05.
  EXPECT_LT(MeanVelocityDeviation("basu-cam3-alt.toml", SplineKind::kClamped),
            MeanVelocityDeviation("basu-cam3.toml", SplineKind::kClamped));
}

TEST(PaperKinematicsTest, Cam4MaximumVelocityIsBasusThirtyCentimetresPerSecond) {
  // "reaches its maximum value of about 30 cm per second and remains constant up to 13°".
  Case c = LoadCase(kCases + "basu-cam4.toml");
  c.lift.spline.kind = SplineKind::kClamped;
  const LiftLaw law = MakeLiftLaw(c);
  const KinematicsSummary s = Kinematics(law, 400).Summarize();
  EXPECT_NEAR(s.max_velocity_m_s, 0.30, 0.02);
  EXPECT_GT(s.max_velocity_rad / kDeg, 5.0);
  EXPECT_LT(s.max_velocity_rad / kDeg, 13.0);
}

TEST(PaperKinematicsTest, Example1AccelerationBesideBasus67) {
  // Basu: 67.6 m/s² (× 11.5 kg = 79.5 kg). Two different accelerations are in play:
  // - the deceleration over the crest, which the table fixes by itself: its central second
  //   difference, (3.38 − 2·3.67 + 3.22) mm / (5°)² at 125 rpm, is −16.6 m/s², and every C²
  //   spline agrees within 15 %;
  // - the acceleration that brings the needle to rest on its seat at 40°, which depends on
  //   the end condition: the table falls 0.954 mm in the last 5°, so a curve drawn, like
  //   Basu's velocity curves, to zero velocity at 40° (clamped at-rest) needs ≈ 70 m/s²
  //   there, within 5 % of his 67.6; the free end conditions need 18–24 m/s².
  // So Basu's 67.6 m/s² is matched by the at-rest end condition, and it is the landing, not
  // the crest, that sets it. We report both; nothing is tuned to his value.
  const Case c = LoadCase(kCases + "basu-example1.toml");
  const double omega = OmegaFromRpm(125);
  const double h = 5 * kDeg;
  const double second_difference = (3.38 - 2 * 3.67 + 3.22) * 1e-3 / (h * h) * omega * omega;
  EXPECT_NEAR(second_difference, -16.6, 0.05);
  for (SplineKind kind : {SplineKind::kNatural, SplineKind::kNotAKnot, SplineKind::kClamped,
                          SplineKind::kQuintic, SplineKind::kSmoothing}) {
    Case k = c;
    k.lift.spline.kind = kind;
    const LiftLaw law = MakeLiftLaw(k);
    const KinematicsSummary s = Kinematics(law, 125).Summarize();
    const bool max_wins = std::abs(*s.max_acceleration_m_s2) > std::abs(*s.min_acceleration_m_s2);
    const double a_max = max_wins ? *s.max_acceleration_m_s2 : -*s.min_acceleration_m_s2;
    const double a_deg = (max_wins ? *s.max_acceleration_rad : *s.min_acceleration_rad) / kDeg;
    std::printf(
        "Example 1 %-11s max |a| %6.2f m/s^2 at %5.1f deg (x 11.5 kg = %5.2f kgf); min a "
        "%6.2f m/s^2 at %5.1f deg. Basu: 67.6 m/s^2, 79.5 kgf\n",
        SplineKindName(kind).c_str(), a_max, a_deg, 11.5 * a_max / kStandardGravity,
        *s.min_acceleration_m_s2, *s.min_acceleration_rad / kDeg);
    const double a_crest = *Kinematics(law, 125).At(20 * kDeg).acceleration_m_s2;
    std::printf("          a(20 deg) = %6.2f m/s^2 against the second difference %6.2f\n", a_crest,
                second_difference);
    EXPECT_NEAR(a_crest, second_difference, 0.15 * std::abs(second_difference))
        << SplineKindName(kind);
    if (kind == SplineKind::kClamped) {
      EXPECT_NEAR(a_max, *c.paper->max_acceleration_m_s2, 0.05 * *c.paper->max_acceleration_m_s2);
      EXPECT_NEAR(a_deg, 40.0, 1e-9);
    } else {
      EXPECT_LT(a_max, 25.0) << SplineKindName(kind);
    }
  }
}

// The summary's fields are its SI values shown in their units, under the keys every writer
// uses; a C¹ spline's acceleration extremes are fields without a value.
TEST(PaperKinematicsTest, SummaryFieldsShowTheSummaryInTheirUnits) {
  Case c = LoadCase(kCases + "basu-example1.toml");
  const LiftLaw law = MakeLiftLaw(c);
  const KinematicsSummary s = Kinematics(law, c.engine.speed_rpm).Summarize();
  const std::vector<Field> fields = KinematicsFields(s);
  const auto shown = [&](const std::string& key) { return FieldAt(fields, key).Shown(); };
  EXPECT_EQ(*shown("max_lift_mm"), s.max_lift_m * 1e3);
  EXPECT_EQ(*shown("max_lift_deg"), s.max_lift_rad / kDeg);
  EXPECT_EQ(*shown("injection_period_s"), s.injection_period_s);
  EXPECT_EQ(*shown("rho"), s.rho);
  EXPECT_EQ(*shown("min_acceleration_m_s2"), *s.min_acceleration_m_s2);
  // The two 95 % bands of the extremes: the sparse table's cubic carries them (lib/spline_band.h).
  EXPECT_EQ(fields.size(), 17u);
  const Field& band = FieldAt(fields, "max_acceleration_band_m_s2");
  ASSERT_EQ(band.list_si.size(), 2u);
  EXPECT_LT(band.list_si[0], *s.max_acceleration_m_s2);
  EXPECT_GT(band.list_si[1], *s.max_acceleration_m_s2);

  c.lift.spline.kind = SplineKind::kPchip;
  const LiftLaw c1 = MakeLiftLaw(c);
  for (const Field& f : KinematicsFields(Kinematics(c1, c.engine.speed_rpm).Summarize())) {
    if (f.name.find("acceleration") != std::string::npos) {
      EXPECT_FALSE(f.Shown().has_value()) << f.Key();
    }
  }
}

}  // namespace
}  // namespace needle

namespace needle {
namespace {

// The text shows the band the JSON holds: symmetric as "± h", else both reaches (a user's trial
// read "51.96 ± 32.17" where the JSON band was [19.79, 51.96]).
TEST(PaperKinematicsTest, TheTextShowsTheBandTheJsonHolds) {
  EXPECT_EQ(PlusMinus(51.96, ExtremumBand{19.79, 51.96}, 2), " +0.00/-32.17");
  EXPECT_EQ(PlusMinus(10.0, ExtremumBand{9.0, 11.0}, 2), " ± 1.00");
  EXPECT_EQ(PlusMinus(10.0, ExtremumBand{9.5, 11.0}, 1), " +1.0/-0.5");
  EXPECT_EQ(PlusMinus(10.0, std::nullopt, 2), "");
}

}  // namespace
}  // namespace needle
