// What synth and profile compute and print: ComputeSynth and ComputeProfile
// (cam_command.h).
#include <algorithm>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/cli/cam_command.h"
#include "apps/cli/command_output.h"
#include "apps/cli/output_paths.h"
#include "apps/cli/result_writers.h"
#include "apps/scene/case_file.h"
#include "apps/scene/case_profile.h"
#include "apps/scene/synthesis_scene.h"
#include "dynamics/model/cam_input.h"
#include "lib/cam_profile.h"
#include "lib/cam_synthesis.h"
#include "lib/output.h"
#include "lib/units.h"

namespace needle {

CommandOutput ComputeSynth(const SynthesisFile& f, const SynthCommandOptions& o) {
  const SynthesisResult r = SynthesizeCam(f);
  const SynthesizedLaw& rise = r.rise;
  const std::vector<Field> fields = SynthesisFields(r);
  // v: the value alone; t: the value and its unit, both from the field table.
  const auto v = [&](const std::string& key) { return ValueText(FieldAt(fields, key)); };
  const auto t = [&](const std::string& key) { return FieldText(FieldAt(fields, key)); };
  CommandOutput result;
  result.status = r.pass ? 0 : 1;
  const std::vector<std::vector<double>> rows = SynthesisRows(r.law);
  result.columns = SiColumns(SynthesisColumns(), rows);
  if (o.csv) result.csv = CsvTable(SynthesisColumns(), rows, 12);
  if (o.case_out) result.case_file = SynthesizedCaseText(f, r.law);
  std::ostringstream out;
  if (o.json) {
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
    if (f.base_radius_m) j["follower"] = FollowerKindName(f.follower);
    j["steps"] = rise.phi.size() - 1;
    if (r.profile) j["undercut"] = r.profile->undercut;
    if (r.min_spring_reserve) j["spring_reserve_cap_tighter"] = rise.spring_reserve_limited;
    j["pass"] = r.pass;
    j["failing"] = r.failing;
    result.json = std::move(j);
  } else {
    out << (f.title.empty() ? f.path : f.title) << '\n'
        << "rise " << t("lift_mm") << " in " << t("rise_deg") << " of cam, " << rise.phi.size() - 1
        << " steps; limits used at " << Fixed(100 * rise.scale, 2) << " %\n";
    if (rise.face_width_limited) {
      out << "constant-speed section at S' = the flat face's half-width "
          << Fixed(*f.face_half_width_m * 1e3, 3) << " mm/rad (S'max "
          << (f.speed_limit < 1e299 ? Fixed(f.speed_limit * 1e3, 3) + " mm/rad" : "not given")
          << ") from " << v("constant_speed_start_deg") << " to " << t("constant_speed_end_deg")
          << " (" << t("constant_speed_length_deg") << ")\n";
    } else if (rise.speed_limit_active) {
      out << "constant-speed section at S'max = " << Fixed(f.speed_limit * 1e3, 3)
          << " mm/rad from " << v("constant_speed_start_deg") << " to "
          << t("constant_speed_end_deg") << " (" << t("constant_speed_length_deg") << ")\n";
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
      out << FollowerKindName(f.follower) << " follower: ";
      if (f.follower != FollowerKind::kRoller)
        out << "contact up to " << t("max_contact_offset_mm") << " off the axis at "
            << t("max_contact_offset_at_deg")
            << (f.face_half_width_m
                    ? " (face half-width " + Fixed(*f.face_half_width_m * 1e3, 3) + " mm)"
                    : "")
            << "; ";
      out << "entrainment speed min " << t("min_entrainment_speed_m_s") << " at "
          << t("min_entrainment_speed_at_deg")
          << (f.min_entrainment_m_s ? " (limit " + Fixed(*f.min_entrainment_m_s, 3) + ")" : "")
          << ", sliding max " << t("max_sliding_speed_m_s") << " at " << Fixed(f.speed_rpm, 0)
          << " rpm\n";
      out << "largest |pressure angle| " << t("max_abs_pressure_angle_deg") << " at "
          << t("max_pressure_angle_at_deg")
          << (f.max_pressure_angle_rad
                  ? " (limit " + Fixed(*f.max_pressure_angle_rad / kDeg, 1) + ")"
                  : "")
          << "; profile radius min " << t("min_profile_radius_mm") << "; "
          << (r.profile->undercut ? (f.follower == FollowerKind::kFlat ? "CUSP" : "UNDERCUT")
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
  }
  result.text = out.str();
  return result;
}

CommandOutput ComputeProfile(const Case& c, const ProfileCommandOptions& o) {
  if (!c.profile)
    throw CaseError(c.path + ": [profile] base_radius_mm: section [profile] is missing");
  const LiftLaw law = MakeLiftLaw(c);
  const FollowerGeometry g = CaseFollower(c);
  const double play = c.train ? c.train->play_m : 0.0;
  double theta0 = 0.0;
  const CamProfile p = MakeCaseProfile(c, law, &theta0);
  // The cam's speed at the rated engine speed (four-stroke: half the crank's).
  const double cam_omega = OmegaFromRpm(c.engine.speed_rpm) / CrankTurnsPerCycle(c.engine.cycle);
  CommandOutput result;
  result.status = p.undercut || p.off_face ? 1 : 0;
  for (const ProfilePoint& q : p.points) {
    result.columns["cam_rad"].push_back(q.cam_rad);
    result.columns["x_m"].push_back(q.x_m);
    result.columns["y_m"].push_back(q.y_m);
    result.columns["pressure_angle_rad"].push_back(q.pressure_angle_rad);
    result.columns["profile_radius_m"].push_back(q.profile_radius_m);
    result.columns["contact_offset_m"].push_back(q.contact_offset_m);
  }
  std::ostringstream out;
  if (o.json) {
    nlohmann::json j;
    j["case"] = c.path;
    j["follower"] = FollowerKindName(g.kind);
    j["base_radius_mm"] = g.base_radius_m * 1e3;
    if (g.kind == FollowerKind::kRoller) j["roller_radius_mm"] = g.roller_radius_m * 1e3;
    if (g.kind == FollowerKind::kCurved) j["face_radius_mm"] = g.face_radius_m * 1e3;
    if (g.face_half_width_m > 0.0) j["face_half_width_mm"] = g.face_half_width_m * 1e3;
    j["max_contact_offset_mm"] = p.max_contact_offset_m * 1e3;
    j["max_contact_offset_at_cam_deg"] = p.max_contact_offset_at_rad / kDeg;
    j["off_face"] = p.off_face;
    j["min_entrainment_speed_m_s"] = p.min_entrainment_m_rad * cam_omega;
    j["min_entrainment_speed_at_cam_deg"] = p.min_entrainment_at_rad / kDeg;
    j["max_sliding_speed_m_s"] = p.max_sliding_m_rad * cam_omega;
    j["offset_mm"] = g.offset_m * 1e3;
    j["lever_ratio"] = g.lever_ratio;
    j["roller_play_mm"] = play * 1e3;
    j["cam_angle_zero_crank_deg"] = theta0 / kDeg;
    j["max_pressure_angle_deg"] = p.max_pressure_angle_rad / kDeg;
    j["max_pressure_angle_at_cam_deg"] = p.max_pressure_angle_at_rad / kDeg;
    j["min_profile_radius_mm"] = p.min_profile_radius_m * 1e3;
    j["min_profile_radius_at_cam_deg"] = p.min_profile_radius_at_rad / kDeg;
    j["undercut"] = p.undercut;
    j["points"] = p.points.size();
    result.json = std::move(j);
  } else {
    out << (c.title.empty() ? c.path : c.title) << '\n'
        << FollowerKindName(g.kind) << " follower: base circle radius "
        << Fixed(g.base_radius_m * 1e3, 2) << " mm, "
        << (g.kind == FollowerKind::kRoller
                ? "roller radius " + Fixed(g.roller_radius_m * 1e3, 2) + " mm, "
            : g.kind == FollowerKind::kCurved
                ? "face radius " + Fixed(g.face_radius_m * 1e3, 2) + " mm, "
                : std::string())
        << (g.face_half_width_m > 0.0
                ? "face half-width " + Fixed(g.face_half_width_m * 1e3, 2) + " mm, "
                : std::string())
        << "offset " << Fixed(g.offset_m * 1e3, 2) << " mm, lever " << Fixed(g.lever_ratio, 3)
        << ", play " << Fixed(play * 1e3, 3) << " mm; cam 0 deg at crank "
        << Fixed(theta0 / kDeg, 2) << " deg\n"
        << "pressure angle largest |phi| " << Fixed(std::abs(p.max_pressure_angle_rad) / kDeg, 3)
        << " deg at cam " << Fixed(p.max_pressure_angle_at_rad / kDeg, 2) << " deg\n"
        << "profile radius of curvature min " << Fixed(p.min_profile_radius_m * 1e3, 3)
        << " mm at cam " << Fixed(p.min_profile_radius_at_rad / kDeg, 2) << " deg; "
        << (p.undercut ? (g.kind == FollowerKind::kFlat ? "CUSP" : "UNDERCUT") : "no undercut")
        << '\n';
    if (g.kind != FollowerKind::kRoller)
      out << "contact up to " << Fixed(p.max_contact_offset_m * 1e3, 3)
          << " mm off the axis at cam " << Fixed(p.max_contact_offset_at_rad / kDeg, 2) << " deg"
          << (g.face_half_width_m > 0.0 ? (p.off_face ? ": OFF THE FACE" : ": on the face")
                                        : std::string())
          << '\n';
    out << "at " << Fixed(c.engine.speed_rpm, 0) << " rpm: entrainment speed min "
        << Fixed(p.min_entrainment_m_rad * cam_omega, 3) << " m/s at cam "
        << Fixed(p.min_entrainment_at_rad / kDeg, 2) << " deg, sliding speed max "
        << Fixed(p.max_sliding_m_rad * cam_omega, 3) << " m/s\n";
  }
  if (o.csv) {
    std::ostringstream csv;
    csv.precision(10);
    csv << "cam_deg,x_mm,y_mm\n";
    for (const ProfilePoint& q : p.points)
      csv << q.cam_rad / kDeg << ',' << q.x_m * 1e3 << ',' << q.y_m * 1e3 << '\n';
    result.csv = csv.str();
  }
  result.text = out.str();
  return result;
}

}  // namespace needle
