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

// Example 2's case with its spring given by its rate alone (and `spring`'s preload line).
std::string RateOnlyExample2(const std::string& preload = "preload_kgf = 176") {
  std::string text = CaseText("basu-example2.toml");
  const size_t a = text.find("[spring]"), b = text.find("\n[", a + 1);
  return text.replace(a, b - a, "[spring]\n" + preload + "\nrate_N_mm = 46.02\n");
}

// V. B. Bhandari, Design of Machine Elements, Example 10.4 (a valve spring), as computed by its
// public Scilab textbook companion (FOSSEE, book 764, EX10.4): 150 N with the valve closed,
// 300 N open, 5 mm apart; ID at least 20 mm; tau at most 30 % of S_ut = 1370 MPa with Wahl's
// factor; G = 81 370 MPa; squared and ground ends; d from 3, 4, 5 mm with D = ID + d; N rounded
// up. Printed: d = 4 mm, D = 24 mm, N = 6.28 -> 7, Nt = 9.
TEST(SpringSizingSceneTest, BhandariExample10_4PosedAsADesignProblem) {
  const std::string text = RateOnlyExample2("preload_N = 150") +
                           "\n[sizing]\nclosed_load_N = 150\nopen_load_N = 300\nstroke_mm = 5\n"
                           "min_inner_diameter_mm = 20\nallowable_stress_fraction = 0.3\n"
                           "tensile_MPa = 1370\nshear_modulus_GPa = 81.37\nwire_mm = [3, 4, 5]\n"
                           "ends = \"closed-ground\"\nstress_correction = \"wahl\"\n"
                           "objective = \"diameter\"\ncoil_step_mm = 1\nactive_coil_step = 1\n"
                           "verify = 0\n";
  const Case c = ParseCase(text, "bhandari.toml");
  const SizeResult r = SizeCase(Bind(c), MakeLiftLaw(c), OneThread());
  ASSERT_TRUE(r.pass) << r.no_fit;
  ASSERT_FALSE(r.closed_form.best.empty());
  const SizedSpring& s = r.closed_form.best.front();
  EXPECT_EQ(s.geometry.wire_m, 4e-3);
  EXPECT_EQ(s.geometry.coil_m, 24e-3);
  EXPECT_EQ(s.geometry.active_coils, 7.0);
  EXPECT_EQ(s.total_coils, 9.0);
  EXPECT_EQ(s.preload_N, 150.0);
  EXPECT_EQ(s.preload_rule, "stated closed load P1");
  EXPECT_EQ(s.geometry.stress_factor, StressFactor::kWahl);
  EXPECT_EQ(s.geometry.tensile_Pa, 1370e6);
  // The book's own numbers: N = 6.28 at 30 N/mm, rounded up: the rate at most 30 N/mm.
  const double exact_n = 81370.0 * 256.0 * 5.0 / (8.0 * 13824.0 * 150.0);
  EXPECT_NEAR(exact_n, 6.278549, 5e-7);
  EXPECT_LE(s.rate_N_m, 30e3);
  // The 3 mm wire fails the book's stress rule; 5 mm fits a larger OD only.
  EXPECT_EQ(r.stroke_m, 5e-3);
  EXPECT_NE(r.space_note.find("the stated wire (R_m 1370 MPa, G 81.4 GPa)"), std::string::npos)
      << r.space_note;
  EXPECT_NE(r.space_note.find("ID >= 20.00 mm ([sizing])"), std::string::npos) << r.space_note;
  // Without the diameter objective the lightest spring of the same rules is another one: the
  // book's rule D = ID + d is what "diameter" poses.
  const Case mass = ParseCase(
      std::string(text).replace(text.find("objective = \"diameter\""), 22, "objective = \"mass\""),
      "bhandari.toml");
  const SizeResult m = SizeCase(Bind(mass), MakeLiftLaw(mass), OneThread());
  ASSERT_FALSE(m.closed_form.best.empty());
  EXPECT_LT(m.closed_form.best.front().mass_kg, s.mass_kg);
}

TEST(SpringSizingSceneTest, ARateOnlySpringIsSizedInASpaceFromTheNeedleAndSaysSo) {
  const Case c = ParseCase(RateOnlyExample2(), "rate.toml");
  const SizeResult r = SizeCase(Bind(c), MakeLiftLaw(c), OneThread());
  ASSERT_TRUE(r.space.max_outer_m && r.space.min_inner_m);
  EXPECT_NEAR(*r.space.max_outer_m, 4 * 12.8e-3, 1e-15);
  EXPECT_NEAR(*r.space.min_inner_m, 12.8e-3, 1e-15);
  EXPECT_NEAR(r.space.max_installed_m, 10 * 12.8e-3, 1e-15);
  EXPECT_NE(r.space_note.find("OD <= 51.20 mm (default from the needle's 12.8 mm diameter)"),
            std::string::npos)
      << r.space_note;
  EXPECT_NE(r.space_note.find("grades VDC, VDCrV, VDSiCr (default: EN 10270-2 valve spring wire"),
            std::string::npos)
      << r.space_note;
  EXPECT_TRUE(r.pass || !r.no_fit.empty());
  // Without a needle diameter there is nothing to derive it from: the key to give is named.
  std::string text = RateOnlyExample2();
  text.replace(text.find("diameter_mm = 12.8"), 18, "gas_force_N = 400");
  const Case bare = ParseCase(text, "bare.toml");
  try {
    (void)SizeCase(Bind(bare), MakeLiftLaw(bare), OneThread());
    FAIL() << "expected a refusal";
  } catch (const CaseError& e) {
    EXPECT_STREQ(e.what(),
                 "bare.toml: [sizing] max_outer_diameter_mm: the space needs a bound (the case's "
                 "spring has no helical geometry and [needle] no diameter_mm to derive one from)");
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
  EXPECT_EQ(Refusal("open_load_N = 300\n"),
            "t.toml: [sizing] open_load_N: needs closed_load_N (P1 at the installed length)");
  EXPECT_EQ(Refusal("closed_load_N = 300\nopen_load_N = 200\n"),
            "t.toml: [sizing] open_load_N: must be above closed_load_N (300 N): the spring is "
            "compressed further when open");
  EXPECT_EQ(Refusal("closed_load_N = 150\nopen_load_N = 300\nrate_N_mm = 30\n"),
            "t.toml: [sizing] open_load_N: give the open load or the rate, not both (the load "
            "pair sets the rate)");
  EXPECT_EQ(Refusal("tensile_MPa = 1370\n"),
            "t.toml: [sizing] tensile_MPa: a stated wire needs both tensile_MPa and "
            "shear_modulus_GPa");
  EXPECT_EQ(Refusal("tensile_MPa = 1370\nshear_modulus_GPa = 81\n"),
            "t.toml: [sizing] wire_mm: a stated wire needs the diameters to try (wire_mm, or "
            "min_wire_mm and max_wire_mm)");
  EXPECT_EQ(Refusal("stroke_mm = -5\n"), "t.toml: [sizing] stroke_mm: must be positive, got -5 mm");
  EXPECT_EQ(Refusal("fatigue_criterion = \"soderberg\"\n"),
            "t.toml: [sizing] fatigue_criterion: expected \"goodman-zimmerli\", \"gerber\", "
            "\"asme-elliptic\", \"sines\" or \"bhandari\", got \"soderberg\"");
  EXPECT_EQ(
      Refusal("objective = \"cost\"\n"),
      "t.toml: [sizing] objective: expected \"mass\", \"height\", \"stress\" or \"diameter\", "
      "got \"cost\"");
}

}  // namespace
}  // namespace needle
