// The synthesized law's and the cam profile's JSON, text and CSV: cam_writer.h.
#include "apps/report/cam_writer.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/case/case_profile.h"
#include "apps/report/result_writers.h"
#include "lib/cam_synthesis.h"
#include "lib/output.h"
#include "lib/units.h"

namespace needle {

// The text of a synthesis (`needle synth` without --json), from its field table.
std::string SynthText(const SynthesisFile& f, const SynthesisResult& r,
                      const std::vector<Field>& fields) {
  const SynthesizedLaw& rise = r.rise;
  // v: the value alone; t: the value and its unit, both from the field table.
  const auto v = [&](const std::string& key) { return ValueText(FieldAt(fields, key)); };
  const auto t = [&](const std::string& key) { return FieldText(FieldAt(fields, key)); };
  std::ostringstream out;
  out << (f.title.empty() ? f.path : f.title) << '\n'
      << "rise " << t("lift_mm") << " in " << t("rise_deg") << " of cam, " << rise.phi.size() - 1
      << " steps; limits used at " << Fixed(100 * rise.scale, 2) << " %\n";
  if (rise.face_width_limited) {
    out << "constant-speed section at S' = the flat face's half-width "
        << Fixed(f.follower.face_half_width_m * 1e3, 3) << " mm/rad (S'max "
        << (f.rise.speed_limit < 1e299 ? Fixed(f.rise.speed_limit * 1e3, 3) + " mm/rad"
                                       : "not given")
        << ") from " << v("constant_speed_start_deg") << " to " << t("constant_speed_end_deg")
        << " (" << t("constant_speed_length_deg") << ")\n";
  } else if (rise.speed_limit_active) {
    out << "constant-speed section at S'max = " << Fixed(f.rise.speed_limit * 1e3, 3)
        << " mm/rad from " << v("constant_speed_start_deg") << " to " << t("constant_speed_end_deg")
        << " (" << t("constant_speed_length_deg") << ")\n";
  } else if (rise.meet_speed > 0.0) {
    out << "S' limit not active; the sides meet at S' = " << t("meet_speed_mm_rad")
        << " with S'' = 0 (lowered from where they would meet with a step in S'', "
           "to keep the jerk limit)\n";
  } else {
    out << "S' limit not active: no constant-speed section\n";
  }
  out << "max S' " << t("max_S1_mm_rad") << " at " << t("max_S1_deg") << "; S'' "
      << v("max_S2_mm_rad2") << " at " << t("max_S2_deg") << " and " << t("min_S2_mm_rad2")
      << " at " << t("min_S2_deg") << "; max |S'''| " << t("max_abs_S3_mm_rad3") << " at "
      << t("max_abs_S3_deg") << "\n";
  if (rise.backed_off_steps > 0)
    out << rise.backed_off_steps
        << " steps formed again with a lower S'' so that a later cap and the jerk limit both "
           "hold (back-off)\n";
  if (r.profile) {
    out << FollowerKindName(f.follower.kind) << " follower: ";
    if (f.follower.kind != FollowerKind::kRoller)
      out << "contact up to " << t("max_contact_offset_mm") << " off the axis at "
          << t("max_contact_offset_at_deg")
          << (f.follower.face_half_width_m > 0.0
                  ? " (face half-width " + Fixed(f.follower.face_half_width_m * 1e3, 3) + " mm)"
                  : "")
          << "; ";
    out << "entrainment speed min " << t("min_entrainment_speed_m_s") << " at "
        << t("min_entrainment_speed_at_deg")
        << (f.min_entrainment_m_s ? " (limit " + Fixed(*f.min_entrainment_m_s, 3) + ")" : "")
        << ", sliding max " << t("max_sliding_speed_m_s") << " at " << Fixed(f.speed_rpm, 0)
        << " rpm\n";
    out << "largest |pressure angle| " << t("max_abs_pressure_angle_deg") << " at "
        << t("max_pressure_angle_at_deg")
        << (f.max_pressure_angle_rad ? " (limit " + Fixed(*f.max_pressure_angle_rad / kDeg, 1) + ")"
                                     : "")
        << "; profile radius min " << t("min_profile_radius_mm") << "; "
        << (r.profile->undercut ? (f.follower.kind == FollowerKind::kFlat ? "CUSP" : "UNDERCUT")
                                : "no undercut")
        << '\n';
  }
  if (r.min_spring_reserve) {
    out << "spring reserve min " << Fixed(r.min_spring_reserve->value, 3) << " at "
        << t("min_spring_reserve_deg")
        << (f.min_spring_reserve
                ? " (limit " + Fixed(*f.min_spring_reserve, 2) + ", steering every step)"
                : "")
        << '\n';
  }
  if (r.max_contact_stress_Pa) {
    out << "contact (Hertz) stress max " << t("max_contact_stress_MPa") << " at cam "
        << t("max_contact_stress_deg")
        << (f.max_contact_stress_Pa ? " (limit " + Fixed(*f.max_contact_stress_Pa * 1e-6, 0) + ")"
                                    : "")
        << '\n';
  }
  for (const std::string& failing : r.failing) out << "fails: " << failing << '\n';
  out << (r.pass ? "checks pass\n" : "a check FAILS\n");
  return out.str();
}

CommandOutput WriteSynth(const SynthesisFile& f, const SynthesisResult& r, const CamWriting& w) {
  const SynthesizedLaw& rise = r.rise;
  const std::vector<Field> fields = SynthesisFields(r);
  CommandOutput result;
  result.status = r.pass ? 0 : 1;
  const std::vector<std::vector<double>> rows = SynthesisRows(r.law);
  result.columns = SiColumns(SynthesisColumns(), rows);
  if (w.csv) result.csv = CsvTable(SynthesisColumns(), rows, 12);
  if (w.case_file) result.case_file = SynthesizedCaseText(f, r.law);
  if (w.json) {
    nlohmann::json j;
    j["spec"] = f.path;
    PutFields(j, fields);
    j["speed_limit_active"] = rise.speed_limit_active;
    j["pressure_angle_cap_tighter"] = rise.pressure_angle_limited;
    j["curvature_cap_tighter"] = rise.curvature_limited;
    j["lubrication_cap_tighter"] = rise.lubrication_limited;
    j["contact_stress_cap_tighter"] = rise.stress_limited;
    j["face_width_limits_speed"] = rise.face_width_limited;
    j["backed_off_steps"] = rise.backed_off_steps;
    if (f.base_radius_m) j["follower"] = FollowerKindName(f.follower.kind);
    j["steps"] = rise.phi.size() - 1;
    if (r.profile) j["undercut"] = r.profile->undercut;
    if (r.min_spring_reserve) j["spring_reserve_cap_tighter"] = rise.spring_reserve_limited;
    j["pass"] = r.pass;
    j["failing"] = r.failing;
    result.json = std::move(j);
  } else {
    result.text = SynthText(f, r, fields);
  }
  return result;
}

CommandOutput WriteProfile(const CaseCamProfile& profile, const CamWriting& w) {
  const BoundCase& c = profile.c;
  const FollowerGeometry& g = profile.follower;
  const double play = profile.play_m, theta0 = profile.cam_zero_crank_rad;
  const CamProfile& p = profile.profile;
  const double cam_omega = profile.cam_omega_rad_s;
  CommandOutput result;
  result.status = p.undercut || p.off_face ? 1 : 0;
  std::vector<std::vector<double>> rows_si;
  rows_si.reserve(p.points.size());
  for (const ProfilePoint& q : p.points) rows_si.push_back(ProfileRowSi(q));
  result.columns = SiColumns(ProfileColumns(), rows_si);
  const std::vector<Field> follower = FollowerFields(g), extremes = CamProfileFields(p, cam_omega);
  const std::vector<Field> placing = {{"roller_play", display::kMm, play, 3},
                                      {"cam_angle_zero_crank", display::kDegree, theta0, 2}};
  // A cam angle, counted from the rise's foot, with the lift table's crank angle there.
  const auto at = [&](double cam_rad) { return CamAndCrank(c, theta0, cam_rad, 2, " deg"); };
  std::ostringstream out;
  if (w.json) {
    nlohmann::json j;
    j["case"] = c.path;
    PutFields(j, follower);
    PutFields(j, extremes);
    PutFields(j, placing);
    j["points"] = p.points.size();
    result.json = std::move(j);
  } else {
    out << (c.title.empty() ? c.path : c.title) << '\n'
        << FollowerKindName(g.kind) << " follower: base circle radius "
        << TextAt(follower, "base_radius_mm") << ", "
        << (g.kind == FollowerKind::kRoller
                ? "roller radius " + TextAt(follower, "roller_radius_mm") + ", "
            : g.kind == FollowerKind::kCurved
                ? "face radius " + TextAt(follower, "face_radius_mm") + ", "
                : std::string())
        << (g.face_half_width_m > 0.0
                ? "face half-width " + TextAt(follower, "face_half_width_mm") + ", "
                : std::string())
        << "offset " << TextAt(follower, "offset_mm") << ", lever "
        << TextAt(follower, "lever_ratio") << ", play " << TextAt(placing, "roller_play_mm")
        << "; cam 0 deg at crank " << TextAt(placing, "cam_angle_zero_crank_deg") << '\n'
        << "pressure angle largest |phi| "
        << FieldText({"", display::kDegree, std::abs(p.max_pressure_angle_rad), 3}) << " at "
        << at(p.max_pressure_angle_at_rad) << '\n'
        << "profile radius of curvature min " << TextAt(extremes, "min_profile_radius_mm") << " at "
        << at(p.min_profile_radius_at_rad) << "; "
        << (p.undercut ? (g.kind == FollowerKind::kFlat ? "CUSP" : "UNDERCUT") : "no undercut")
        << '\n';
    if (g.kind != FollowerKind::kRoller)
      out << "contact up to " << TextAt(extremes, "max_contact_offset_mm") << " off the axis at "
          << at(p.max_contact_offset_at_rad)
          << (g.face_half_width_m > 0.0 ? (p.off_face ? ": OFF THE FACE" : ": on the face")
                                        : std::string())
          << '\n';
    out << "at " << Fixed(c.engine.speed_rpm, 0) << " rpm: entrainment speed min "
        << TextAt(extremes, "min_entrainment_speed_m_s") << " at " << at(p.min_entrainment_at_rad)
        << ", sliding speed max " << TextAt(extremes, "max_sliding_speed_m_s") << '\n';
  }
  if (w.csv) {  // the CAD coordinates: the first three columns
    const std::vector<Column> xy(ProfileColumns().begin(), ProfileColumns().begin() + 3);
    std::vector<std::vector<double>> xy_si;
    xy_si.reserve(rows_si.size());
    for (const auto& row : rows_si) xy_si.emplace_back(row.begin(), row.begin() + 3);
    result.csv = CsvTable(xy, xy_si, 10);
  }
  result.text = out.str();
  return result;
}

}  // namespace needle
