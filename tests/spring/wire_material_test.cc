// Wire grades and the fatigue check: a published worked example and closed forms.
#include "spring/wire_material.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lib/units.h"
#include "spring/helical_spring.h"

namespace needle {
namespace {

constexpr double kInch = 25.4e-3, kLbf = 4.4482216152605, kKpsi = 6.894757293168e6;

// Budynas & Nisbett, Shigley's Mechanical Engineering Design, 9th ed., Example 10-4: an
// as-wound music-wire spring, d = 0.092 in, OD = 9/16 in, free length 4 3/8 in, 21 active
// coils, squared and ground, unpeened; assembled at 5 lbf, 35 lbf at most in use. The book's
// solution: D = 0.4705 in, C = 5.11, K_B = 1.29, S_ut = 201/d^0.145 = 284.1 kpsi, S_su = 190.3
// kpsi, τ_a = 29.7 kpsi, τ_m = 39.6 kpsi; Gerber–Zimmerli n_f = 1.21; Goodman–Zimmerli
// S_se = 49.2 kpsi, S_a = 36.6 kpsi, n_f = 1.23. (Digits as we have them from the 9th
// edition; the book is not in this workplace's stored corpus, so they were not re-read
// this session: the computation below is checked to the digits printed there.)
HelicalGeometry Shigley104() {
  HelicalGeometry g;
  g.wire_m = 0.092 * kInch;
  g.coil_m = (9.0 / 16.0 - 0.092) * kInch;
  g.active_coils = 21;
  g.free_length_m = 4.375 * kInch;
  g.shear_modulus_Pa = 11.75e3 * kKpsi;                   // Table 10-5, music wire 0.064–0.125 in
  g.tensile_Pa = 201.0 / std::pow(0.092, 0.145) * kKpsi;  // A/d^m in the book's units
  g.ends = SpringEnds::kClosedGround;
  return g;
}

// The check of Shigley's spring by one criterion (5 lbf → 35 lbf).
FatigueCheck Shigley104Fatigue(FatigueCriterion criterion) {
  HelicalGeometry g = Shigley104();
  g.fatigue_criterion = criterion;
  const double max_lift = (35.0 - 5.0) * kLbf / HelicalRate(g);
  return CheckHelicalSpring(g, 5.0 * kLbf, max_lift, 1000.0, EngineCycle::kFourStroke).fatigue;
}

TEST(WireMaterialTest, ShigleyExample10_4FatigueToThePrintedDigits) {
  const HelicalGeometry g = Shigley104();
  EXPECT_NEAR(g.tensile_Pa / kKpsi, 284.1, 0.05);
  EXPECT_NEAR(g.coil_m / g.wire_m, 5.11, 0.005);
  EXPECT_NEAR(StressCorrection(g.coil_m / g.wire_m, StressFactor::kBergstrasser), 1.29,
              0.005);  // K_B
  const double rate = HelicalRate(g);
  const double max_lift = (35.0 - 5.0) * kLbf / rate;  // 5 lbf → 35 lbf
  const HelicalSpringCheck c =
      CheckHelicalSpring(g, 5.0 * kLbf, max_lift, 1000.0, EngineCycle::kFourStroke);
  const FatigueCheck& f = c.fatigue;
  EXPECT_TRUE(c.fatigue_judged);
  EXPECT_EQ(f.criterion, FatigueCriterion::kGoodmanZimmerli);  // the default
  EXPECT_NEAR(f.stress_amplitude_Pa / kKpsi, 29.7, 0.05);
  EXPECT_NEAR(f.stress_mean_Pa / kKpsi, 39.6, 0.05);
  EXPECT_NEAR(f.torsional_ultimate_Pa / kKpsi, 190.3, 0.05);
  EXPECT_NEAR(f.endurance_Pa / kKpsi, 49.2, 0.05);
  EXPECT_NEAR(f.limit_Pa / kKpsi, 36.6, 0.05);
  EXPECT_NEAR(f.safety_factor, 1.23, 0.005);
  EXPECT_TRUE(c.fatigue_ok);
  // Gerber–Zimmerli, the book's part (a): n_f = 1.21.
  EXPECT_NEAR(Shigley104Fatigue(FatigueCriterion::kGerber).safety_factor, 1.21, 0.005);
  // Sines–Zimmerli, its part (b): the mean stress has no effect, n_f = S_sa/τ_a = 35/29.7.
  const FatigueCheck sines = Shigley104Fatigue(FatigueCriterion::kSines);
  EXPECT_DOUBLE_EQ(sines.limit_Pa, 35.0 * kKpsi);
  EXPECT_NEAR(sines.safety_factor, 1.18, 0.005);
  // The same spring from the grade table: DH is music wire's R_m(d) (SI constants of the
  // same table, 2211 MPa·mm^0.145), within 0.3 % of the book's 284.1 kpsi.
  EXPECT_NEAR(TensileStrengthPa(WireGrade::kDH, g.wire_m) / g.tensile_Pa, 1.0, 3e-3);
}

// ASME-elliptic: no worked example of it was found in this workplace's stored pages, so it is
// held to its defining closed forms: the ellipse (S_a/S_se)² + (S_m/S_sy)² = 1 passes through
// Zimmerli's point (S_sm, S_sa) with S_sy = 0.45 S_ut, and n_f puts the working point on it.
TEST(WireMaterialTest, AsmeEllipticAndGerberLieOnTheirCurves) {
  const FatigueCheck a = Shigley104Fatigue(FatigueCriterion::kAsmeElliptic);
  const HelicalGeometry g = Shigley104();
  EXPECT_DOUBLE_EQ(a.yield_Pa, 0.45 * g.tensile_Pa);
  const auto ellipse = [&](double s_m, double s_a) {
    return std::pow(s_a / a.endurance_Pa, 2) + std::pow(s_m / a.yield_Pa, 2);
  };
  EXPECT_NEAR(ellipse(a.strength.mean_Pa, a.strength.amplitude_Pa), 1.0, 1e-12);
  const double n = a.safety_factor;
  EXPECT_NEAR(ellipse(n * a.stress_mean_Pa, n * a.stress_amplitude_Pa), 1.0, 1e-12);
  // Gerber's parabola S_a/S_se + (S_m/S_su)² = 1, through Zimmerli's point.
  const FatigueCheck b = Shigley104Fatigue(FatigueCriterion::kGerber);
  const auto parabola = [&](double s_m, double s_a) {
    return s_a / b.endurance_Pa + std::pow(s_m / b.torsional_ultimate_Pa, 2);
  };
  EXPECT_NEAR(parabola(b.strength.mean_Pa, b.strength.amplitude_Pa), 1.0, 1e-12);
  EXPECT_NEAR(parabola(b.safety_factor * b.stress_mean_Pa, b.limit_Pa), 1.0, 1e-12);
}

// V. B. Bhandari, Design of Machine Elements, Example 10.13, as computed by its public Scilab
// textbook companion (FOSSEE, book 764, EX10.13): 50 N → 150 N, d = 3 mm, D = 18 mm,
// S_ut = 1430 MPa; K_s = 1 + 0.5/C on the mean, Wahl's K on the amplitude, S'se = 0.22 S_ut,
// S_sy = 0.45 S_ut; printed factor of safety 1.26.
HelicalGeometry Bhandari1013() {
  HelicalGeometry g;
  g.wire_m = 3e-3;
  g.coil_m = 18e-3;
  g.active_coils = 10;  // not given: the factor does not depend on it
  g.free_length_m = 1.0;
  g.shear_modulus_Pa = 81370e6;
  g.tensile_Pa = 1430e6;
  g.fatigue_criterion = FatigueCriterion::kBhandari;
  return g;
}

FatigueCheck Bhandari1013Fatigue(const HelicalGeometry& g) {
  return CheckHelicalSpring(g, 50.0, 100.0 / HelicalRate(g), 1000.0, EngineCycle::kFourStroke)
      .fatigue;
}

TEST(WireMaterialTest, BhandariExample10_13ToThePrintedDigits) {
  const HelicalGeometry g = Bhandari1013();
  const FatigueCheck f = Bhandari1013Fatigue(g);
  const double per_N = 8.0 * 18.0 / (kPi * 27.0);  // 8D/(πd³), MPa per N
  EXPECT_NEAR(f.stress_mean_Pa * 1e-6, (1.0 + 0.5 / 6.0) * per_N * 100.0, 1e-9);
  EXPECT_NEAR(f.stress_amplitude_Pa * 1e-6, (23.0 / 20.0 + 0.615 / 6.0) * per_N * 50.0, 1e-9);
  EXPECT_DOUBLE_EQ(f.endurance_Pa, 0.22 * 1430e6);
  EXPECT_DOUBLE_EQ(f.yield_Pa, 0.45 * 1430e6);
  EXPECT_NEAR(f.safety_factor, 1.26, 0.005);
  // The case's own stress factor does not change Bhandari's: K_s and Wahl are his.
  HelicalGeometry wahl = g;
  wahl.stress_factor = StressFactor::kWahl;
  EXPECT_DOUBLE_EQ(Bhandari1013Fatigue(wahl).safety_factor, f.safety_factor);
  // The working point lies on his design line through A (S'se/2, S'se/2) and (S_sy/n, 0).
  const double half = 0.5 * f.endurance_Pa, n = f.safety_factor;
  EXPECT_NEAR(f.stress_amplitude_Pa / (f.yield_Pa / n - f.stress_mean_Pa),
              half / (f.yield_Pa - half), 1e-12);
  // Judged at any wire (his endurance is a fraction of S_ut, not Zimmerli's data).
  HelicalGeometry thick = g;
  thick.wire_m = 12e-3;
  thick.coil_m = 72e-3;
  EXPECT_TRUE(
      CheckHelicalSpring(thick, 50.0, 1e-3, 1000.0, EngineCycle::kFourStroke).fatigue_judged);
  // The finding: Goodman-Zimmerli (the default) rates this spring 2.07 with
  // Bergsträsser's factor and 2.05 with Wahl's, 1.6x the book's 1.26; a default limit of 1.5
  // passes it, the book's criterion does not.
  HelicalGeometry goodman = g;
  goodman.fatigue_criterion = FatigueCriterion::kGoodmanZimmerli;
  EXPECT_NEAR(Bhandari1013Fatigue(goodman).safety_factor, 2.07, 0.005);
  goodman.stress_factor = StressFactor::kWahl;
  EXPECT_NEAR(Bhandari1013Fatigue(goodman).safety_factor, 2.05, 0.005);
  // Patented cold-drawn wire (EN 10270-1) takes his 0.21 and 0.42.
  HelicalGeometry drawn = g;
  drawn.grade = WireGrade::kDH;
  const FatigueCheck d = Bhandari1013Fatigue(drawn);
  EXPECT_DOUBLE_EQ(d.endurance_Pa, 0.21 * 1430e6);
  EXPECT_DOUBLE_EQ(d.yield_Pa, 0.42 * 1430e6);
}

TEST(WireMaterialTest, DirectShearFactorIsBhandarisAndShigleysKs) {
  // K_s = 1 + 1/(2C) = (2C + 1)/(2C) (Shigley eq. 10-2; Bhandari's K_s; Khurmi & Gupta).
  EXPECT_DOUBLE_EQ(StressCorrection(6.0, StressFactor::kDirectShear), 13.0 / 12.0);
  EXPECT_DOUBLE_EQ(StressCorrection(10.0, StressFactor::kDirectShear), 1.05);
  // It is the curvature-free part: below both Wahl and Bergsträsser at every index.
  for (double w = 4; w <= 20; w += 0.5) {
    EXPECT_LT(StressCorrection(w, StressFactor::kDirectShear),
              StressCorrection(w, StressFactor::kWahl));
    EXPECT_LT(StressCorrection(w, StressFactor::kDirectShear),
              StressCorrection(w, StressFactor::kBergstrasser));
  }
  EXPECT_EQ(ParseStressFactor("direct-shear"), StressFactor::kDirectShear);
  EXPECT_EQ(StressFactorChoice(), "\"bergstrasser\", \"wahl\" or \"direct-shear\"");
}

TEST(WireMaterialTest, GoodmanLineClosedFormAndPeening) {
  // On the Goodman line τ_a/S_se + τ_m/S_su = 1/n_f: check the identity for a cycle.
  const double rm = 1800e6;
  const auto check = [rm](FatigueCriterion c, bool peened) {
    return CheckFatigue(c, 500e6, 200e6, rm, peened);  // 300 → 700 MPa
  };
  const FatigueCheck u = check(FatigueCriterion::kGoodmanZimmerli, false);
  const double ssu = 0.67 * rm;
  const double sse = 35 * kKpsi / (1 - 55 * kKpsi / ssu);
  EXPECT_NEAR(1.0 / u.safety_factor, u.stress_amplitude_Pa / sse + u.stress_mean_Pa / ssu, 1e-12);
  const FatigueCheck p = check(FatigueCriterion::kGoodmanZimmerli, true);
  EXPECT_GT(p.safety_factor, u.safety_factor);  // peening raises S_sa, S_sm
  EXPECT_DOUBLE_EQ(p.strength.amplitude_Pa, 57.5 * kKpsi);
  EXPECT_DOUBLE_EQ(p.strength.mean_Pa, 77.5 * kKpsi);
  // Gerber's parabola lies outside Goodman's line above Zimmerli's mean: a larger factor.
  EXPECT_GT(check(FatigueCriterion::kGerber, false).safety_factor, u.safety_factor);
  // No alternating stress: unbounded on every Zimmerli line.
  for (FatigueCriterion c : {FatigueCriterion::kGoodmanZimmerli, FatigueCriterion::kGerber,
                             FatigueCriterion::kAsmeElliptic, FatigueCriterion::kSines}) {
    EXPECT_TRUE(std::isinf(CheckFatigue(c, 500e6, 0.0, rm, false).safety_factor));
  }
  // A wire weaker than Zimmerli's mean strength has no endurance at all.
  EXPECT_EQ(
      CheckFatigue(FatigueCriterion::kGoodmanZimmerli, 100e6, 50e6, 500e6, false).safety_factor,
      0.0);
}

TEST(WireMaterialTest, CriteriaByNameWithTheirSources) {
  EXPECT_EQ(FatigueCriterionChoice(),
            "\"goodman-zimmerli\", \"gerber\", \"asme-elliptic\", \"sines\" or \"bhandari\"");
  for (const FatigueCriterionInfo& i : AllFatigueCriteria()) {
    EXPECT_EQ(ParseFatigueCriterion(i.name), i.criterion);
    EXPECT_STREQ(CriterionInfo(i.criterion).name, i.name);
    EXPECT_GT(std::string(i.source).size(), 20u);
  }
  EXPECT_FALSE(ParseFatigueCriterion("Goodman"));
}

TEST(WireMaterialTest, GradesByNameAndTheirDiameterRange) {
  EXPECT_EQ(WireGradeList(), "SH, DH, VDC, VDCrV, VDSiCr");
  for (WireGrade g : AllWireGrades()) EXPECT_EQ(ParseWireGrade(WireGradeName(g)), g);
  EXPECT_FALSE(ParseWireGrade("vdsicr"));
  // Thinner wire is stronger; the alloyed valve grades above the carbon one at 4 mm.
  EXPECT_GT(TensileStrengthPa(WireGrade::kVDSiCr, 2e-3),
            TensileStrengthPa(WireGrade::kVDSiCr, 5e-3));
  EXPECT_GT(TensileStrengthPa(WireGrade::kVDSiCr, 4e-3), TensileStrengthPa(WireGrade::kVDC, 4e-3));
  // Against EN 10270 rows visible in this workplace's stored pages: DH at 0.30 mm is
  // 2660–2940 MPa (the A228 fit gives 2633, 1 % under the minimum); VDSiCr at 4 mm from
  // A401: 1974/4^0.108 = 1700 MPa.
  EXPECT_NEAR(TensileStrengthPa(WireGrade::kDH, 0.30e-3) * 1e-6, 2633, 1);
  EXPECT_NEAR(TensileStrengthPa(WireGrade::kVDSiCr, 4e-3) * 1e-6, 1974 / std::pow(4.0, 0.108),
              1e-9);
  EXPECT_DOUBLE_EQ(GradeData(WireGrade::kVDSiCr).shear_modulus_Pa, 79.5e9);
  EXPECT_DOUBLE_EQ(GradeData(WireGrade::kSH).shear_modulus_Pa, 81.5e9);
  try {
    TensileStrengthPa(WireGrade::kVDSiCr, 16e-3);
    FAIL() << "expected a refusal";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "grade VDSiCr (R_m of A401 chrome-silicon) is tabulated for wire 1.60…9.50 mm, "
                 "got 16.000 mm; give tensile_MPa from the wire's certificate instead");
  }
}

TEST(WireMaterialTest, ThickWireIsNotJudgedForFatigue) {
  HelicalGeometry g = Shigley104();
  g.wire_m = 12e-3;
  g.coil_m = 80e-3;
  g.active_coils = 6;
  g.free_length_m = 200e-3;
  const HelicalSpringCheck c = CheckHelicalSpring(g, 1000.0, 5e-3, 300.0, EngineCycle::kFourStroke);
  EXPECT_FALSE(c.fatigue_judged);
  EXPECT_TRUE(c.fatigue_ok);
}

}  // namespace
}  // namespace needle
