// `needle size` as a library: Basu's examples and the new engine sized, the sized cases checked
// end to end, the no-fit diagnosis, and [sizing]'s refusals.
#include "apps/study/spring_sizing_scene.h"

#include <gtest/gtest.h>

#include <cmath>

#include "apps/case/case_scene.h"
#include "lib/input_file.h"
#include "lib/kinematics.h"
#include "lib/units.h"
#include "spring/basu_formula.h"

namespace needle {
namespace {

const std::string kCases = std::string(NEEDLE_SOURCE_DIR) + "/cases/";

std::string CaseText(const std::string& name) { return ReadInputFile(kCases + name, "case file"); }

SizeOptions OneThread() {
  SizeOptions o;
  o.threads = 1;
  return o;
}

// The sized case, written and read back, passes `needle check`'s CheckScene, and its spring is
// the one sized.
void ExpectWrittenCasePasses(const Case& c, const std::string& text, const SizeResult& r) {
  ASSERT_TRUE(r.winner);
  const SizedSpring& s = r.verified[*r.winner].spring;
  const BoundCase sized = CaseWithSpring(Bind(c), s, r.space, r.mass_without_spring_kg);
  const std::string written = SizedCaseText(text, sized.needle->mass_kg, s, r.space);
  const Case back = ParseCase(written, "sized.toml");
  ASSERT_TRUE(back.spring && back.spring->helical);
  EXPECT_EQ(back.spring->preload_N, s.preload_N);
  EXPECT_EQ(back.spring->helical->wire_m, s.geometry.wire_m);
  EXPECT_EQ(back.spring->helical->coil_m, s.geometry.coil_m);
  EXPECT_EQ(back.spring->helical->active_coils, s.geometry.active_coils);
  EXPECT_NEAR(back.spring->helical->free_length_m, s.geometry.free_length_m, 1e-9);
  EXPECT_NEAR(back.needle->mass_kg, r.mass_without_spring_kg + s.active_mass_kg / 3, 1e-15);
  CheckOptions o;
  o.threads = 1;
  o.record_series = false;
  const CheckResult check = CheckScene(Bind(back), o);
  EXPECT_TRUE(check.pass) << (check.failing.empty() ? "" : check.failing.front());
  for (const LimitRow& x : check.limits) EXPECT_NE(x.verdict, "fail") << x.name;
}

TEST(SpringSizingSceneTest, Example2InItsOwnSpaceHasNoSpringAndSaysWhichRuleBinds) {
  // The case's spring fails the Goodman row (1.46 < 1.5); no spring of its space (OD ≤ 47 mm,
  // ID ≥ 33 mm, installed ≤ 87.49 mm, the case's 1600 MPa wire at R40 sizes) reaches 1.5.
  const Case c = LoadCase(kCases + "basu-example2.toml");
  const SizeResult r = SizeCase(Bind(c), MakeLiftLaw(c), OneThread());
  EXPECT_FALSE(r.pass);
  EXPECT_TRUE(r.closed_form.best.empty());
  EXPECT_TRUE(r.verified.empty());
  ASSERT_TRUE(r.closed_form.binding && r.closed_form.closest);
  EXPECT_EQ(r.closed_form.binding->key, "fatigue");
  EXPECT_NEAR(r.closed_form.binding->value, 1.4046, 5e-5);
  EXPECT_EQ(r.closed_form.closest->geometry.wire_m, 6.7e-3);
  EXPECT_EQ(r.closed_form.closest->geometry.coil_m, 40e-3);
  EXPECT_EQ(r.closed_form.closest->geometry.active_coils, 9.0);
  EXPECT_NE(r.no_fit.find("OD <= 47.00 mm (the case's spring)"), std::string::npos) << r.no_fit;
  EXPECT_NE(r.no_fit.find("reaches the spring fatigue safety factor (Goodman) of at least 1.50; "
                          "best 1.40 (short by 0.10) at case wire d = 6.70 mm, D = 40.0 mm, "
                          "9.0 active coils"),
            std::string::npos)
      << r.no_fit;
}

TEST(SpringSizingSceneTest, Example2SizedInAWiderSpacePassesTheCheckAndIsLighter) {
  const std::string text =
      CaseText("basu-example2.toml") + "\n[sizing]\nmax_outer_diameter_mm = 52\n";
  const Case c = ParseCase(text, "ex2.toml");
  const LiftLaw law = MakeLiftLaw(c);
  const SizeResult r = SizeCase(Bind(c), law, OneThread());
  ASSERT_TRUE(r.pass) << r.no_fit;
  ASSERT_TRUE(r.winner);
  const SizedSpring& s = r.verified[*r.winner].spring;
  // Basu's formula less its 10 % sets the preload (above S F_g and the inertia sizing).
  const double basu = BasuPreloadN(12.8e-3, Kinematics(law, 400).Summarize().injection_period_s);
  EXPECT_NEAR(s.preload_N, std::ceil(0.9 * basu * 10.0) / 10.0, 1e-9);
  EXPECT_EQ(s.preload_rule, "Basu's formula less its tolerance");
  EXPECT_EQ(s.geometry.wire_m, 8e-3);
  EXPECT_EQ(s.geometry.coil_m, 41e-3);
  EXPECT_EQ(s.geometry.active_coils, 3.0);
  // Lighter than the paper's case spring (7 mm wire, 40 mm coil, 8 + 2 coils: 0.380 kg).
  ASSERT_TRUE(r.case_spring_mass_kg);
  EXPECT_NEAR(*r.case_spring_mass_kg, 7850 * kPi * kPi * 49e-6 * 0.04 * 10 / 4, 1e-12);
  EXPECT_LT(s.mass_kg, *r.case_spring_mass_kg);
  EXPECT_NEAR(s.mass_kg, 0.2541, 1e-4);
  // Each stage says what it kept.
  ASSERT_EQ(r.stages.size(), 2u);
  EXPECT_EQ(r.stages[0].in, r.closed_form.candidates);
  EXPECT_EQ(r.stages[0].kept, 5);
  EXPECT_EQ(r.stages[1].kept, 1);
  ExpectWrittenCasePasses(c, text, r);
}

TEST(SpringSizingSceneTest, Example1AndTheNewEngineSizedTheSameWay) {
  {
    const std::string text = CaseText("basu-example1.toml");
    const Case c = ParseCase(text, "ex1.toml");
    const SizeResult r = SizeCase(Bind(c), MakeLiftLaw(c), OneThread());
    ASSERT_TRUE(r.pass) << r.no_fit;
    EXPECT_LT(r.verified[*r.winner].spring.mass_kg, *r.case_spring_mass_kg);
    ExpectWrittenCasePasses(c, text, r);
  }
  {
    // No helical spring in the case: [sizing] states the space.
    const std::string text =
        CaseText("new-engine-weak-spring.toml") +
        "\n[sizing]\ngrades = [\"VDC\", \"VDCrV\", \"VDSiCr\"]\nmax_outer_diameter_mm = 55\n"
        "min_inner_diameter_mm = 30\nmax_installed_length_mm = 90\n";
    const Case c = ParseCase(text, "new.toml");
    const SizeResult r = SizeCase(Bind(c), MakeLiftLaw(c), OneThread());
    ASSERT_TRUE(r.pass) << r.no_fit;
    EXPECT_EQ(r.mass_note, "[needle] mass_kg (the case's spring has no geometry to take out)");
    ExpectWrittenCasePasses(c, text, r);
  }
}

std::string Refusal(const std::string& sizing) {
  const std::string text = CaseText("basu-example2.toml") + "\n[sizing]\n" + sizing;
  try {
    const Case c = ParseCase(text, "t.toml");
    (void)SizeCase(Bind(c), MakeLiftLaw(c), OneThread());
  } catch (const CaseError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(SpringSizingSceneTest, SizingKeysAreValidatedNamingTheKey) {
  EXPECT_EQ(Refusal("colour = \"red\"\n"), "t.toml: [sizing] colour: unknown key in this section");
  EXPECT_EQ(Refusal("wire_size_mm = 4\n"),
            "t.toml: [sizing] wire_size_mm: unit suffix 'size_mm' is not a unit of length "
            "(expected wire_mm or wire_cm or wire_m or wire_um)");
  EXPECT_EQ(Refusal("grades = [\"VD\"]\n"),
            "t.toml: [sizing] grades: unknown grade \"VD\"; expected SH, DH, VDC, VDCrV, VDSiCr "
            "or \"case\"");
  EXPECT_EQ(Refusal("min_installed_length_mm = 90\nmax_installed_length_mm = 80\n"),
            "t.toml: [sizing] min_installed_length_mm: is above max_installed_length_mm: the range "
            "is empty");
  EXPECT_EQ(Refusal("installed_length_mm = 80\nmax_installed_length_mm = 90\n"),
            "t.toml: [sizing] installed_length_mm: give it or its range "
            "(min_/max_installed_length), not both");
  EXPECT_EQ(Refusal("min_index = 6\nmax_index = 5\n"),
            "t.toml: [sizing] min_index: is above max_index: the range is empty");
  EXPECT_EQ(Refusal("max_index = 25\n"), "t.toml: [sizing] max_index: must be in [4, 20], got 25");
  EXPECT_EQ(Refusal("wire_mm = [7]\nmin_index = 5\nmax_index = 5\nmin_active_coils = 8\n"
                    "max_active_coils = 8\n"),
            "t.toml: [sizing] wire_mm: one wire, one index and one coil count leave nothing to "
            "choose; `needle check` judges a given spring");
  EXPECT_EQ(Refusal("candidates = 2\nverify = 3\n"),
            "t.toml: [sizing] verify: verifies 3 springs but only 2 candidates are kept");
  EXPECT_EQ(Refusal("max_outer_diameter = 50\n")
                .rfind("t.toml: [sizing] max_outer_diameter: needs a unit suffix: ", 0),
            0u);
  EXPECT_EQ(
      Refusal("max_outer_diameter_mm = 10\nmin_inner_diameter_mm = 5\n")
          .rfind("t.toml: [sizing] max_outer_diameter_mm: no coil diameter of any wire fits the "
                 "space (",
                 0),
      0u);
  EXPECT_EQ(
      Refusal("objective = \"cost\"\n"),
      "t.toml: [sizing] objective: expected \"mass\", \"height\", \"stress\" or \"diameter\", "
      "got \"cost\"");
}

}  // namespace
}  // namespace needle
