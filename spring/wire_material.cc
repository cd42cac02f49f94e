#include "spring/wire_material.h"

#include <cmath>
#include <stdexcept>

#include "lib/output.h"

namespace needle {
namespace {

struct GradeRow {
  WireGrade grade;
  const char* name;
  WireGradeData data;
};

// Shigley 9th ed. Table 10-4 (SI): A228 2211 MPa·mm^0.145 for 0.10–6.5 mm; A229 1855, 0.187,
// 0.5–12.7 mm; A232 2005, 0.168, 0.8–11.1 mm; A401 1974, 0.108, 1.6–9.5 mm. G: EN 13906-1.
// SH and DH (EN 10270-1's patented cold-drawn grades) both take A228's strengths.
const WireGradeData kMusicWire = {"EN 10270-1", "A228 music wire", 2211.0, 0.145, 0.10e-3, 6.5e-3,
                                  81.5e9};
const GradeRow kGrades[] = {
    {WireGrade::kSH, "SH", kMusicWire},
    {WireGrade::kDH, "DH", kMusicWire},
    {WireGrade::kVDC,
     "VDC",
     {"EN 10270-2", "A229/A230 oil-tempered", 1855.0, 0.187, 0.5e-3, 12.7e-3, 79.5e9}},
    {WireGrade::kVDCrV,
     "VDCrV",
     {"EN 10270-2", "A232 chrome-vanadium", 2005.0, 0.168, 0.8e-3, 11.1e-3, 79.5e9}},
    {WireGrade::kVDSiCr,
     "VDSiCr",
     {"EN 10270-2", "A401 chrome-silicon", 1974.0, 0.108, 1.6e-3, 9.5e-3, 79.5e9}},
};

const GradeRow& Row(WireGrade g) {
  for (const GradeRow& r : kGrades) {
    if (r.grade == g) return r;
  }
  throw std::logic_error("WireGrade without a row");
}

}  // namespace

const std::vector<WireGrade>& AllWireGrades() {
  static const std::vector<WireGrade> all = [] {
    std::vector<WireGrade> v;
    for (const GradeRow& r : kGrades) v.push_back(r.grade);
    return v;
  }();
  return all;
}

std::string WireGradeName(WireGrade g) { return Row(g).name; }

std::optional<WireGrade> ParseWireGrade(const std::string& name) {
  for (const GradeRow& r : kGrades) {
    if (name == r.name) return r.grade;
  }
  return std::nullopt;
}

std::string WireGradeList() {
  std::string s;
  for (const GradeRow& r : kGrades) s += (s.empty() ? "" : ", ") + std::string(r.name);
  return s;
}

const WireGradeData& GradeData(WireGrade g) { return Row(g).data; }

double TensileStrengthPa(WireGrade g, double wire_m) {
  const WireGradeData& d = GradeData(g);
  if (!(wire_m >= d.min_wire_m && wire_m <= d.max_wire_m)) {
    throw std::invalid_argument("grade " + WireGradeName(g) + " (R_m of " + d.astm +
                                ") is tabulated for wire " + Fixed(d.min_wire_m * 1e3, 2) + "…" +
                                Fixed(d.max_wire_m * 1e3, 2) + " mm, got " +
                                Fixed(wire_m * 1e3, 3) +
                                " mm; give tensile_MPa from the "
                                "wire's certificate instead");
  }
  return d.a_MPa_mm * std::pow(wire_m * 1e3, -d.m) * 1e6;  // A / d^m, d in mm, MPa → Pa
}

FatigueStrength ZimmerliStrength(bool shot_peened) {
  constexpr double kKpsi = 6.894757293168e6;  // Zimmerli's data are in kpsi
  return shot_peened ? FatigueStrength{57.5 * kKpsi, 77.5 * kKpsi}
                     : FatigueStrength{35.0 * kKpsi, 55.0 * kKpsi};
}

namespace {

// The one table of the criteria: name, title, line, source.
const std::vector<FatigueCriterionInfo> kCriteria = {
    {FatigueCriterion::kGoodmanZimmerli, "goodman-zimmerli", "Goodman",
     "S_se = S_sa/(1 - S_sm/S_su); S_a = r S_se S_su/(r S_su + S_se); n_f = S_a/tau_a",
     "Budynas & Nisbett, Shigley's MED 9th ed., sec. 10-9 and Ex. 10-4; Zimmerli (1957)"},
    {FatigueCriterion::kGerber, "gerber", "Gerber",
     "S_se = S_sa/(1 - (S_sm/S_su)^2); S_a = r^2 S_su^2/(2 S_se) (-1 + sqrt(1 + (2 S_se/(r "
     "S_su))^2)); n_f = S_a/tau_a",
     "Budynas & Nisbett, Shigley's MED 9th ed., sec. 10-9 and Ex. 10-4"},
    {FatigueCriterion::kAsmeElliptic, "asme-elliptic", "ASME-elliptic",
     "S_se = S_sa/sqrt(1 - (S_sm/S_sy)^2); S_a = r S_se S_sy/sqrt(S_se^2 + r^2 S_sy^2); "
     "S_sy = 0.45 S_ut; n_f = S_a/tau_a",
     "Budynas & Nisbett, Shigley's MED 9th ed., sec. 10-9; S_sy from Table 10-6"},
    {FatigueCriterion::kSines, "sines", "Sines",
     "S_a = S_sa (the mean stress has no effect); n_f = S_sa/tau_a",
     "Budynas & Nisbett, Shigley's MED 9th ed., sec. 10-9 and Ex. 10-4"},
    {FatigueCriterion::kBhandari, "bhandari", "Bhandari",
     "tau_m with K_s = 1 + 1/(2C), tau_a with Wahl's K; line from (S'se/2, S'se/2) to (S_sy, "
     "0): 1/n_f = (tau_a (S_sy - S'se/2)/(S'se/2) + tau_m)/S_sy; S'se = 0.22 S_ut, S_sy = 0.45 "
     "S_ut (0.21, 0.42 patented cold-drawn)",
     "V. B. Bhandari, Design of Machine Elements, ch. 10, Ex. 10.13"},
};

// S_a where the load line r = τ_a/τ_m meets a Zimmerli criterion through (S_sm, S_sa).
void ZimmerliLine(FatigueCheck& f, double r) {
  const double ssu = f.torsional_ultimate_Pa, ssa = f.strength.amplitude_Pa,
               ssm = f.strength.mean_Pa, sy = f.yield_Pa;
  switch (f.criterion) {
    case FatigueCriterion::kGoodmanZimmerli:
      f.endurance_Pa = ssa / (1.0 - ssm / ssu);
      f.limit_Pa = r * f.endurance_Pa * ssu / (r * ssu + f.endurance_Pa);
      break;
    case FatigueCriterion::kGerber: {
      f.endurance_Pa = ssa / (1.0 - (ssm / ssu) * (ssm / ssu));
      const double q = 2.0 * f.endurance_Pa / (r * ssu);
      f.limit_Pa = r * r * ssu * ssu / (2.0 * f.endurance_Pa) * (-1.0 + std::sqrt(1.0 + q * q));
      break;
    }
    case FatigueCriterion::kAsmeElliptic:
      f.endurance_Pa = ssa / std::sqrt(1.0 - (ssm / sy) * (ssm / sy));
      f.limit_Pa =
          r * f.endurance_Pa * sy / std::sqrt(f.endurance_Pa * f.endurance_Pa + r * r * sy * sy);
      break;
    case FatigueCriterion::kSines:
      f.endurance_Pa = f.limit_Pa = ssa;
      break;
    case FatigueCriterion::kBhandari:
      break;
  }
}

}  // namespace

const std::vector<FatigueCriterionInfo>& AllFatigueCriteria() { return kCriteria; }

const FatigueCriterionInfo& CriterionInfo(FatigueCriterion c) {
  for (const FatigueCriterionInfo& i : kCriteria)
    if (i.criterion == c) return i;
  throw std::logic_error("FatigueCriterion without a row");
}

std::optional<FatigueCriterion> ParseFatigueCriterion(const std::string& name) {
  for (const FatigueCriterionInfo& i : kCriteria)
    if (name == i.name) return i.criterion;
  return std::nullopt;
}

std::string FatigueCriterionChoice() {
  std::string s;
  for (size_t i = 0; i < kCriteria.size(); ++i) {
    if (i > 0) s += i + 1 == kCriteria.size() ? " or " : ", ";
    s += "\"" + std::string(kCriteria[i].name) + "\"";
  }
  return s;
}

BhandariFractions BhandariFractionsFor(std::optional<WireGrade> grade) {
  if (grade && GradeData(*grade).standard == "EN 10270-1") return {0.21, 0.42};
  return {0.22, 0.45};
}

FatigueCheck CheckFatigue(FatigueCriterion criterion, double stress_mean_Pa,
                          double stress_amplitude_Pa, double tensile_Pa, bool shot_peened,
                          std::optional<WireGrade> grade) {
  FatigueCheck f;
  f.criterion = criterion;
  f.stress_amplitude_Pa = stress_amplitude_Pa;
  f.stress_mean_Pa = stress_mean_Pa;
  f.torsional_ultimate_Pa = 0.67 * tensile_Pa;  // S_su = 0.67 R_m
  if (criterion == FatigueCriterion::kBhandari) {
    const BhandariFractions b = BhandariFractionsFor(grade);
    const double half = 0.5 * b.endurance * tensile_Pa;  // S'se/2
    f.yield_Pa = b.yield * tensile_Pa;
    f.strength = {half, half};
    f.endurance_Pa = 2.0 * half;
    if (!(stress_amplitude_Pa > 0.0) && !(stress_mean_Pa > 0.0)) {  // no stress at all
      f.limit_Pa = f.endurance_Pa;
      f.safety_factor = INFINITY;
      return f;
    }
    // 1/n = (τ_a (S_sy − S'se/2)/(S'se/2) + τ_m) / S_sy
    f.safety_factor =
        f.yield_Pa / (stress_amplitude_Pa * (f.yield_Pa - half) / half + stress_mean_Pa);
    f.limit_Pa = f.safety_factor * stress_amplitude_Pa;
    return f;
  }
  f.strength = ZimmerliStrength(shot_peened);
  if (criterion == FatigueCriterion::kAsmeElliptic) f.yield_Pa = kAsmeYieldFraction * tensile_Pa;
  const double ceiling =
      criterion == FatigueCriterion::kAsmeElliptic ? f.yield_Pa : f.torsional_ultimate_Pa;
  if (criterion != FatigueCriterion::kSines && !(ceiling > f.strength.mean_Pa)) {
    f.safety_factor = 0.0;  // a wire weaker than Zimmerli's mean strength: no endurance at all
    return f;
  }
  if (!(stress_amplitude_Pa > 0.0)) {
    ZimmerliLine(f, 1.0);
    f.limit_Pa = f.endurance_Pa;
    f.safety_factor = INFINITY;
    return f;
  }
  ZimmerliLine(f, stress_amplitude_Pa / stress_mean_Pa);  // the load line r = τ_a/τ_m
  f.safety_factor = f.limit_Pa / stress_amplitude_Pa;
  return f;
}

}  // namespace needle
