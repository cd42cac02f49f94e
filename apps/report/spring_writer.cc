// The spring check's and the design chain's JSON and text: spring_writer.h.
#include "apps/report/spring_writer.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/case/case_writer.h"
#include "apps/report/result_writers.h"
#include "lib/output.h"
#include "lib/units.h"

namespace needle {

namespace {

std::string PassFail(bool ok) { return ok ? "pass" : "FAIL"; }

// The helical check's fatigue line: the criterion's n_f, which the pass includes.
std::string FatigueLine(const BoundCase& c, const HelicalSpringCheck& h) {
  const HelicalGeometry& wire = *c.spring->helical;
  if (!h.fatigue_judged) {
    return "  fatigue not judged: wire " + Fixed(wire.wire_m * 1e3, 1) +
           " mm, Zimmerli's data cover wire below " + Fixed(kZimmerliMaxWire_m * 1e3, 0) + " mm\n";
  }
  const FatigueCheck& f = h.fatigue;
  const std::string basis =
      f.criterion == FatigueCriterion::kBhandari
          ? "S'se " + Fixed(f.endurance_Pa * 1e-6, 0) + " MPa, S_sy " +
                Fixed(f.yield_Pa * 1e-6, 0) + " MPa"
          : std::string("Zimmerli's data, ") + (wire.shot_peened ? "shot-peened" : "unpeened");
  const double n_f = f.safety_factor;
  return std::string("  fatigue (") + CriterionInfo(f.criterion).title + ", " + basis +
         ") safety factor " + (std::isfinite(n_f) ? Fixed(n_f, 2) : std::string("unbounded")) +
         " (>= 1) -> " + PassFail(h.fatigue_ok) + "\n";
}

}  // namespace

CommandOutput WriteSpring(const CaseSpringCheck& spring, bool json) {
  const BoundCase& c = spring.c;
  const double speed = spring.speed_rpm;
  const SpringCheckResult& check = spring.check;
  const KinematicsSummary& sum = check.kinematics;
  const RigidTrain& train = check.train;
  const std::optional<HelicalSpringCheck>& helical = check.helical;
  const std::optional<double>& basu_N = check.basu_preload_N;
  const double n_qs = check.liftoff_rpm_quasi_static;
  const bool preload_ok = check.preload_ok;
  const bool ok = check.pass;

  CommandOutput result;
  result.status = ok ? 0 : 1;
  std::ostringstream out;
  if (json) {
    nlohmann::json j;
    j["case"] = c.path;
    j["speed_rpm"] = speed;
    j["spline"] = SplineKindName(spring.spline);
    j["injection_period_s"] = sum.injection_period_s;
    PutFields(j, SpringCheckFields(check));
    j["safety_factor"] = c.spring->safety_factor;
    j["overspeed_factor"] = c.spring->overspeed_factor;
    j["failures"] = check.failures;
    j["warnings"] = check.warnings;
    if (helical) PutFields(j["helical"], HelicalFields(*helical));
    result.json = std::move(j);
  } else {
    const std::vector<Field> fields = SpringCheckFields(check);
    const auto t = [&](const char* key) { return FieldText(FieldAt(fields, key)); };
    const auto or_unbounded = [&](const char* key) {
      return FieldAt(fields, key).si ? t(key) : std::string("unbounded");
    };
    out << (c.title.empty() ? c.path : c.title) << '\n';
    out << "speed " << Fixed(speed, 1) << " rpm, spline " << SplineKindName(spring.spline)
        << ", injection period " << Fixed(sum.injection_period_s, 4) << " s\n\n";
    if (basu_N) {
      out << "Basu's formula (d = " << Fixed(*c.needle->diameter_m * 1e3, 1)
          << " mm): " << t("basu_preload_kgf") << "; the case's spring " << t("actual_preload_kgf")
          << " (" << t("deviation_percent") << "; tolerance " << t("basu_tolerance_percent")
          << ") -> " << PassFail(check.basu_ok) << '\n';
    }
    out << "combustion load F_g = "
        << FieldText({"gas_force", display::kKgForce, check.gas_force_N, 1}) << " ("
        << check.gas_source << "); preload against S x F_g: margin "
        << or_unbounded("combustion_margin_percent") << " -> " << PassFail(check.combustion_ok)
        << '\n';
    out << "inertia force m*max|a| = " << Fixed(train.mass_kg, 2) << " kg x "
        << t("max_abs_acceleration_m_s2") << " (at " << t("max_abs_acceleration_deg")
        << ") = " << t("inertia_force_kgf") << '\n';
    out << "quasi-static contact force: min " << t("min_quasi_static_force_N") << " at "
        << t("min_quasi_static_force_deg") << " (spring rate " << t("spring_rate_N_mm") << ")\n";
    out << "quasi-static lift-off speed n_qs = "
        << (std::isfinite(n_qs)
                ? Fixed(n_qs, 1) + PlusMinus(n_qs, check.liftoff_rpm_quasi_static_band, 1) +
                      " rpm (" + Fixed(n_qs / speed, 2) + " x rated)"
                : "none (never decelerates)")
        << '\n';
    out << "required preload (S = " << Fixed(c.spring->safety_factor, 2) << " at "
        << Fixed(c.spring->overspeed_factor, 2) << " x " << Fixed(speed, 0)
        << " rpm): " << t("required_preload_N") << " = " << t("required_preload_kgf")
        << "; margin of the case's spring "
        << (check.decelerates ? or_unbounded("preload_margin_percent") + PreloadMarginNote(check)
                              : std::string("undecided (the table never decelerates)"))
        << " -> " << PassFail(preload_ok) << '\n';
    if (helical) {
      const std::vector<Field> hf = HelicalFields(*helical);
      const auto ht = [&](const char* key) { return FieldText(FieldAt(hf, key)); };
      const auto pf = [&](const char* key) { return PassFail(FieldAt(hf, key).flag); };
      out << "\nhelical spring (" << StressFactorTitle(helical->stress_factor) << " correction "
          << ht("correction_factor") << ")\n"
          << "  rate " << ht("rate_N_mm") << ", index D/d " << ht("index") << ", total coils "
          << ht("total_coils") << '\n'
          << "  shear stress " << ht("stress_preload_MPa") << " at preload, "
          << ht("stress_full_lift_MPa") << " at full lift, allowable " << ht("allowable_stress_MPa")
          << " -> " << pf("stress_ok") << '\n'
          << "  length " << ht("length_preload_mm") << " at preload, " << ht("length_full_lift_mm")
          << " at full lift, solid " << ht("solid_length_mm") << "; coil gaps "
          << ht("clearance_full_lift_mm") << " against S_a " << ht("min_clearance_mm") << " -> "
          << pf("clearance_ok") << '\n'
          << "  surge " << ht("surge_hz") << ", cam " << ht("cam_hz") << ", ratio "
          << ht("surge_ratio") << " (>= 13) -> " << pf("surge_ok") << '\n'
          << FatigueLine(c, *helical) << "  sources: " << StressFactorTitle(helical->stress_factor)
          << " correction, " << StressFactorSource(helical->stress_factor) << "; "
          << CriterionInfo(helical->fatigue.criterion).title << " fatigue, "
          << CriterionInfo(helical->fatigue.criterion).source << '\n';
    }
    out << "\nspring check: " << (ok ? "pass" : "FAIL") << '\n';
    for (const std::string& f : check.failures) out << "  fails: " << f << '\n';
    for (const std::string& w : check.warnings) out << "  warns: " << w << '\n';
  }
  result.text = out.str();
  return result;
}

CommandOutput WriteDesign(const DesignInputs& in, const DesignResult& r, bool json,
                          const std::optional<std::string>& case_out) {
  CommandOutput result;
  std::ostringstream out;
  if (json) {
    nlohmann::json j;
    j["engine"] = in.path;
    PutFields(j, {{"power", display::kHp, in.power_W}});
    j["speed_rpm"] = in.speed_rpm;
    j["atomizer"] = in.atomizer;
    PutFields(j, DesignFields(r));
    j["passage_trials"] = RecordList(r.trials, PassageTrialFields);
    nlohmann::json table = nlohmann::json::array();
    for (size_t i = 0; i < r.lift_table.crank_rad.size(); ++i)
      table.push_back(
          RowObject(DesignLiftColumns(), {r.lift_table.crank_rad[i], r.lift_table.lift_m[i]}));
    j["lift_table"] = table;
    result.json = std::move(j);
  } else {
    const std::vector<Field> fields = DesignFields(r);
    const auto t = [&](const char* key) { return FieldText(FieldAt(fields, key)); };
    const auto v = [&](const char* key) { return ValueText(FieldAt(fields, key)); };
    out << (in.title.empty() ? in.path : in.title) << '\n'
        << ValueText({"power", display::kHp, in.power_W, 1}) << " HP_i per cylinder, "
        << Fixed(in.speed_rpm, 1) << " rpm, " << EngineCycleName(in.cycle) << ", " << in.atomizer
        << " atomizer\n\n"
        << "fuel per working cycle      " << t("fuel_per_cycle_g") << " = "
        << t("fuel_per_cycle_cm3") << '\n'
        << "mixing ratio                " << v("mixing_ratio")
        << (r.mixing_ratio_from_line ? " (Basu's line)" : " (given)") << '\n'
        << "injection air (p1, T1)      " << t("air_per_cycle_cm3") << '\n'
        << "expanded to p0              " << t("air_expanded_cm3") << "; mixture "
        << t("mixture_cm3") << '\n'
        << "outflow velocity w0         " << t("air_velocity_m_s")
        << " (p0/p1 = " << v("pressure_ratio") << ")\n"
        << "injection period            " << t("injection_period_s") << '\n'
        << "mean cross-section          " << t("mean_cross_section_mm2") << '\n';
    for (const PassageTrial& trial : r.trials) {
      const std::vector<Field> tf = PassageTrialFields(trial);
      out << "  passage " << FieldText(FieldAt(tf, "discharge_passage_mm")) << ": ";
      if (!FieldAt(tf, "mean_lift_mm").si) {
        out << "its largest cross-section is below the mean -> rejected\n";
        continue;
      }
      out << "mean lift " << FieldText(FieldAt(tf, "mean_lift_mm")) << ", max lift "
          << FieldText(FieldAt(tf, "max_lift_mm")) << " -> "
          << (trial.accepted ? "taken" : "rejected") << '\n';
    }
    out << "maximum lift (rho " << Fixed(in.rho, 2) << ")        " << t("max_lift_mm") << '\n'
        << "lift table (normal curve)  ";
    for (size_t i = 0; i < r.lift_table.crank_rad.size(); ++i) {
      out << ' ' << Fixed(r.lift_table.crank_rad[i] / kDeg, 0) << ":"
          << Fixed(r.lift_table.lift_m[i] * 1e3, 3);
    }
    out << "\ncam disk                    " << v("cam_disk_computed_mm") << " mm computed, "
        << t("cam_disk_mm") << " adopted; roller " << t("roller_mm") << '\n'
        << "discharge passage height    " << t("passage_height_mm") << '\n'
        << "needle diameter             " << t("needle_diameter_mm")
        << " (2d = " << t("needle_diameter_suggested_mm") << "); cage " << t("cage_diameter_mm")
        << '\n'
        << "spring preload (formula)    " << t("spring_preload_kgf") << " = "
        << t("spring_preload_N") << '\n'
        << "cross-section at max lift   " << t("max_lift_cross_section_mm2") << '\n'
        << "nozzle cross-section        " << t("nozzle_cross_section_mm2") << " in "
        << v("nozzle_holes") << " holes of " << t("nozzle_hole_mm") << '\n';
    if (case_out) out << "case written: " << *case_out << '\n';
  }
  if (case_out) result.case_file = DesignCaseText(in, r);
  result.text = out.str();
  return result;
}

}  // namespace needle
