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

FatigueCheck CheckFatigue(double stress_min_Pa, double stress_max_Pa, double tensile_Pa,
                          bool shot_peened) {
  FatigueCheck f;
  f.stress_amplitude_Pa = 0.5 * (stress_max_Pa - stress_min_Pa);
  f.stress_mean_Pa = 0.5 * (stress_max_Pa + stress_min_Pa);
  f.torsional_ultimate_Pa = 0.67 * tensile_Pa;  // S_su = 0.67 R_m
  f.strength = ZimmerliStrength(shot_peened);
  const double ssu = f.torsional_ultimate_Pa, ssa = f.strength.amplitude_Pa,
               ssm = f.strength.mean_Pa;
  if (!(ssu > ssm)) {  // a wire weaker than Zimmerli's mean strength: no endurance at all
    f.goodman_safety_factor = f.gerber_safety_factor = 0.0;
    return f;
  }
  f.goodman_endurance_Pa = ssa / (1.0 - ssm / ssu);
  if (!(f.stress_amplitude_Pa > 0.0)) {
    f.goodman_limit_Pa = f.goodman_endurance_Pa;
    f.goodman_safety_factor = f.gerber_safety_factor = INFINITY;
    return f;
  }
  const double r = f.stress_amplitude_Pa / f.stress_mean_Pa;  // the load line τ_a/τ_m
  const double sse = f.goodman_endurance_Pa;
  f.goodman_limit_Pa = r * sse * ssu / (r * ssu + sse);
  f.goodman_safety_factor = f.goodman_limit_Pa / f.stress_amplitude_Pa;
  const double sse_g = ssa / (1.0 - (ssm / ssu) * (ssm / ssu));
  const double q = 2.0 * sse_g / (r * ssu);
  const double gerber = r * r * ssu * ssu / (2.0 * sse_g) * (-1.0 + std::sqrt(1.0 + q * q));
  f.gerber_safety_factor = gerber / f.stress_amplitude_Pa;
  return f;
}

}  // namespace needle
