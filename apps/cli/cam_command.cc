#include "apps/cli/cam_command.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/cli/output_paths.h"
#include "apps/scene/case_file.h"
#include "apps/scene/case_profile.h"
#include "dynamics/model/cam_input.h"
#include "lib/cam_profile.h"
#include "lib/cam_synthesis.h"
#include "lib/output.h"
#include "lib/units.h"

namespace needle {
namespace {

// The rise, with its mirrored fall when asked: S(2Φ − φ), S' negated, S'' kept, S''' negated.
SynthesizedLaw WithFall(const SynthesizedLaw& rise) {
  SynthesizedLaw law = rise;
  const double end = rise.phi.back();
  for (size_t k = rise.phi.size() - 1; k-- > 0;) {
    law.phi.push_back(2 * end - rise.phi[k]);
    law.s.push_back(rise.s[k]);
    law.s1.push_back(-rise.s1[k]);
    law.s2.push_back(rise.s2[k]);
    law.s3.push_back(-rise.s3[k + 1]);
  }
  return law;
}

// S, S', S'' between the steps, linearly; the base circle outside.
Displacement TableDisplacement(const SynthesizedLaw& law) {
  return [&law](double psi) {
    if (psi <= law.phi.front() || psi >= law.phi.back())
      return std::array<double, 3>{0.0, 0.0, 0.0};
    const size_t i = std::upper_bound(law.phi.begin(), law.phi.end(), psi) - law.phi.begin();
    const double w = (psi - law.phi[i - 1]) / (law.phi[i] - law.phi[i - 1]);
    auto lerp = [&](const std::vector<double>& v) { return v[i - 1] + w * (v[i] - v[i - 1]); };
    return std::array<double, 3>{lerp(law.s), lerp(law.s1), lerp(law.s2)};
  };
}

struct Extreme {
  double value = -INFINITY, at = 0.0;
};

}  // namespace

CLI::App* AddSynthCommand(CLI::App& app, SynthCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "synth", "Synthesize a cam law under derivative limits (constant-speed section)");
  cmd->add_option("SPEC", o.spec_path,
                  "synthesis file (TOML): [rise], [limits], [checks], [output]")
      ->required();
  cmd->add_flag("--json", o.json, "print one JSON object");
  cmd->add_option("--csv", o.csv,
                  "write the law (cam_deg, S_mm, S1_mm_rad, S2_mm_rad2, S3_mm_rad3)");
  cmd->add_option("--case", o.case_out, "write the law as a needle case file");
  return cmd;
}

int RunSynthCommand(const SynthCommandOptions& o) {
  const SynthesisFile f = LoadSynthesisFile(o.spec_path);
  {
    std::vector<OutputPath> outputs;
    if (o.csv) outputs.push_back({"--csv", *o.csv});
    if (o.case_out) outputs.push_back({"--case", *o.case_out});
    CheckOutputPaths(outputs, {o.spec_path});
  }
  SynthesisSpec spec;
  spec.rise_rad = f.rise_rad;
  spec.height_m = f.height_m;
  spec.step_rad = f.step_rad;
  spec.speed_limit = f.speed_limit;
  spec.accel_limit = f.accel_limit;
  spec.decel_limit = f.decel_limit;
  spec.jerk_limit = f.jerk_limit;
  if (f.base_radius_m && f.offset_m == 0.0) {  // the steering caps assume a radial follower
    spec.base_radius_m = *f.base_radius_m;
    spec.roller_radius_m = f.roller_radius_m.value_or(0.0);
    spec.max_pressure_angle_rad = f.max_pressure_angle_rad.value_or(0.0);
    spec.min_profile_radius_m = f.min_profile_radius_m.value_or(-1.0);
  }
  // The cam turns at half the crank speed in a four-stroke engine.
  const double cam_omega = OmegaFromRpm(f.speed_rpm) / (f.cycle == "four-stroke" ? 2.0 : 1.0);
  if (f.min_spring_reserve) {
    spec.min_spring_reserve = *f.min_spring_reserve;
    spec.spring_preload_N = *f.spring_preload_N;
    spec.spring_rate_N_m = f.spring_rate_N_m.value_or(0.0);
    spec.moving_mass_kg = *f.moving_mass_kg;
    spec.cam_omega = cam_omega;
  }

  SynthesizedLaw rise;
  try {
    rise = SynthesizeRise(spec);
  } catch (const std::invalid_argument& e) {
    throw CaseError(f.path + ": [limits]: " + e.what());
  }
  const SynthesizedLaw law = f.mirror_fall ? WithFall(rise) : rise;
  Extreme s1, s2, s2n, s3;
  for (size_t i = 0; i < rise.phi.size(); ++i) {
    if (rise.s1[i] > s1.value) s1 = {rise.s1[i], rise.phi[i]};
    if (rise.s2[i] > s2.value) s2 = {rise.s2[i], rise.phi[i]};
    if (-rise.s2[i] > s2n.value) s2n = {-rise.s2[i], rise.phi[i]};
    // Every step counts, the junction too: with a jerk limit the sides meet with S'' = 0, and
    // without one a step in S'' there is the law's, reported as it is.
    if (i > 0 && std::abs(rise.s3[i]) > s3.value) s3 = {std::abs(rise.s3[i]), rise.phi[i]};
  }
  std::optional<CamProfile> profile;
  bool ok = true;
  if (f.base_radius_m) {
    FollowerGeometry g;
    g.base_radius_m = *f.base_radius_m;
    g.roller_radius_m = f.roller_radius_m.value_or(0.0);
    g.offset_m = f.offset_m;
    profile = MakeCamProfile(TableDisplacement(law), g, 7200);
    if (f.max_pressure_angle_rad &&
        std::abs(profile->max_pressure_angle_rad) > *f.max_pressure_angle_rad)
      ok = false;
    if (profile->undercut) ok = false;
  }
  // Spring reserve K = (P₀ + k S)/(m ω² |S''|) where S'' < 0, and the Hertz line-contact stress
  // σ = √(F E*/(π L R*)), F = P₀ + k S + m ω² S'', 1/R* = 1/ρ + 1/r_r (ρ signed, + convex),
  // E* = E/(2(1 − ν²)) for two bodies of the same steel.
  Extreme reserve{INFINITY, 0.0}, hertz;
  const bool have_spring = f.spring_preload_N && f.moving_mass_kg;
  if (have_spring) {
    const double p0 = *f.spring_preload_N, k = f.spring_rate_N_m.value_or(0.0),
                 m = *f.moving_mass_kg;
    for (size_t i = 0; i < rise.phi.size(); ++i) {
      if (rise.s2[i] >= 0.0) continue;
      const double factor = (p0 + k * rise.s[i]) / (m * cam_omega * cam_omega * -rise.s2[i]);
      if (factor < reserve.value) reserve = {factor, rise.phi[i]};
    }
    if (f.min_spring_reserve && reserve.value < *f.min_spring_reserve * (1 - 1e-9)) ok = false;
    if (profile && f.contact_length_m) {
      const Displacement d = TableDisplacement(law);
      const double rr = f.roller_radius_m.value_or(0.0);
      for (const ProfilePoint& q : profile->points) {
        const auto sv = d(q.cam_rad);
        const double force =
            p0 + k * sv[0] + m * cam_omega * cam_omega * sv[2];  // F = P₀ + kS + mω²S''
        const double sigma = HertzLineStress(force, q.profile_radius_m, rr > 0.0 ? rr : INFINITY,
                                             f.elastic_modulus_Pa, f.poisson, *f.contact_length_m);
        if (sigma > hertz.value) hertz = {sigma, q.cam_rad};
      }

      if (f.max_contact_stress_Pa && hertz.value > *f.max_contact_stress_Pa) ok = false;
    }
  }
  std::ostringstream out;
  const double mm = 1e3;
  if (o.json) {
    nlohmann::json j;
    j["spec"] = f.path;
    j["rise_deg"] = f.rise_rad / kDeg;
    j["lift_mm"] = f.height_m * mm;
    j["limits_used_fraction"] = rise.scale;
    j["speed_limit_active"] = rise.speed_limit_active;
    j["pressure_angle_cap_tighter"] = rise.pressure_angle_limited;
    j["curvature_cap_tighter"] = rise.curvature_limited;

    j["constant_speed_start_deg"] = rise.constant_start_rad / kDeg;
    j["constant_speed_end_deg"] = rise.constant_end_rad / kDeg;
    j["constant_speed_length_deg"] = rise.constant_length_rad() / kDeg;
    j["max_S1_mm_rad"] = s1.value * mm;
    j["max_S1_deg"] = s1.at / kDeg;
    j["max_S2_mm_rad2"] = s2.value * mm;
    j["max_S2_deg"] = s2.at / kDeg;
    j["min_S2_mm_rad2"] = -s2n.value * mm;
    j["min_S2_deg"] = s2n.at / kDeg;
    j["max_abs_S3_mm_rad3"] = s3.value * mm;
    j["max_abs_S3_deg"] = s3.at / kDeg;
    j["steps"] = rise.phi.size() - 1;
    j["meet_speed_mm_rad"] =
        rise.meet_speed > 0.0 ? nlohmann::json(rise.meet_speed * mm) : nlohmann::json(nullptr);
    if (profile) {
      // The largest |pressure angle| (its sign says on which flank: + rising, − falling).
      j["max_abs_pressure_angle_deg"] = std::abs(profile->max_pressure_angle_rad) / kDeg;
      j["max_pressure_angle_deg"] = profile->max_pressure_angle_rad / kDeg;
      j["max_pressure_angle_at_deg"] = profile->max_pressure_angle_at_rad / kDeg;
      j["min_profile_radius_mm"] = profile->min_profile_radius_m * mm;
      j["min_profile_radius_at_deg"] = profile->min_profile_radius_at_rad / kDeg;
      j["undercut"] = profile->undercut;
    }
    if (have_spring) {
      j["min_spring_reserve"] =
          std::isfinite(reserve.value) ? nlohmann::json(reserve.value) : nlohmann::json(nullptr);
      j["min_spring_reserve_deg"] = reserve.at / kDeg;
      j["spring_reserve_cap_tighter"] = rise.spring_reserve_limited;
    }
    if (std::isfinite(hertz.value) && hertz.value > 0) {
      j["max_contact_stress_MPa"] = hertz.value * 1e-6;
      j["max_contact_stress_deg"] = hertz.at / kDeg;
    }
    j["pass"] = ok;
    out << j.dump(2) << '\n';
  } else {
    out << (f.title.empty() ? f.path : f.title) << '\n'
        << "rise " << Fixed(f.height_m * mm, 3) << " mm in " << Fixed(f.rise_rad / kDeg, 2)
        << " deg of cam, " << rise.phi.size() - 1 << " steps; limits used at "
        << Fixed(100 * rise.scale, 2) << " %\n";
    if (rise.speed_limit_active) {
      out << "constant-speed section at S'max = " << Fixed(f.speed_limit * mm, 3) << " mm/rad from "
          << Fixed(rise.constant_start_rad / kDeg, 3) << " to "
          << Fixed(rise.constant_end_rad / kDeg, 3) << " deg ("
          << Fixed(rise.constant_length_rad() / kDeg, 3) << " deg)\n";
    } else if (rise.meet_speed > 0.0) {
      out << "S' limit not active; the sides meet at S' = " << Fixed(rise.meet_speed * mm, 3)
          << " mm/rad with S'' = 0 (lowered from where they would meet with a step in S'', "
             "to keep the jerk limit)\n";
    } else {
      out << "S' limit not active: no constant-speed section\n";
    }
    out << "max S' " << Fixed(s1.value * mm, 4) << " mm/rad at " << Fixed(s1.at / kDeg, 2)
        << " deg; S'' " << Fixed(s2.value * mm, 2) << " at " << Fixed(s2.at / kDeg, 2)
        << " deg and " << Fixed(-s2n.value * mm, 2) << " mm/rad2 at " << Fixed(s2n.at / kDeg, 2)
        << " deg; max |S'''| " << Fixed(s3.value * mm, 1) << " mm/rad3 at "
        << Fixed(s3.at / kDeg, 2) << " deg\n";
    if (profile) {
      out << "largest |pressure angle| "
          << Fixed(std::abs(profile->max_pressure_angle_rad) / kDeg, 2) << " deg at "
          << Fixed(profile->max_pressure_angle_at_rad / kDeg, 2) << " deg"
          << (f.max_pressure_angle_rad
                  ? " (limit " + Fixed(*f.max_pressure_angle_rad / kDeg, 1) + ")"
                  : "")
          << "; "
          << "profile radius min " << Fixed(profile->min_profile_radius_m * mm, 3) << " mm; "
          << (profile->undercut ? "UNDERCUT" : "no undercut") << '\n';
    }
    if (have_spring) {
      out << "spring reserve min " << Fixed(reserve.value, 3) << " at "
          << Fixed(reserve.at / kDeg, 2) << " deg"
          << (f.min_spring_reserve
                  ? " (limit " + Fixed(*f.min_spring_reserve, 2) + ", steering every step)"
                  : "")
          << '\n';
    }
    if (std::isfinite(hertz.value) && hertz.value > 0) {
      out << "contact (Hertz) stress max " << Fixed(hertz.value * 1e-6, 0) << " MPa at cam "
          << Fixed(hertz.at / kDeg, 2) << " deg"
          << (f.max_contact_stress_Pa ? " (limit " + Fixed(*f.max_contact_stress_Pa * 1e-6, 0) + ")"
                                      : "")
          << '\n';
    }
    out << (ok ? "checks pass\n" : "a check FAILS\n");
  }
  if (o.csv) {
    std::ostringstream csv;
    csv.precision(12);
    csv << "cam_deg,S_mm,S1_mm_rad,S2_mm_rad2,S3_mm_rad3\n";
    for (size_t i = 0; i < law.phi.size(); ++i) {
      csv << law.phi[i] / kDeg << ',' << law.s[i] * mm << ',' << law.s1[i] * mm << ','
          << law.s2[i] * mm << ',' << law.s3[i] * mm << '\n';
    }
    WriteOutput({"--csv", *o.csv}, csv.str());
  }
  if (o.case_out) {
    // Every 10th step (and the last), as crank angles: ×2 for a four-stroke cam.
    const double k = f.cycle == "four-stroke" ? 2.0 : 1.0;
    std::ostringstream c, angles, lifts;
    angles.precision(10);
    lifts.precision(10);
    for (size_t i = 0; i < law.phi.size(); i += 10) {
      angles << (i ? ", " : "") << (f.crank_start_rad + k * law.phi[i]) / kDeg;
      lifts << (i ? ", " : "") << std::max(0.0, law.s[i]) * mm;
    }
    if ((law.phi.size() - 1) % 10 != 0) {
      angles << ", " << (f.crank_start_rad + k * law.phi.back()) / kDeg;
      lifts << ", " << std::max(0.0, law.s.back()) * mm;
    }
    c << "# Written by `needle synth " << f.path << "`.\n"
      << "title = \"" << (f.title.empty() ? "synthesized law" : f.title)
      << "\"\n\n[engine]\nspeed_rpm = " << f.speed_rpm << "\ncycle = \"" << f.cycle
      << "\"\n\n[lift]\ncrank_deg = [" << angles.str() << "]\nlift_mm = [" << lifts.str()
      << "]\nspline = \"not-a-knot\"\nresolution_mm = 0.000001\n";
    if (f.base_radius_m) {
      c << "\n[profile]\nbase_radius_mm = " << *f.base_radius_m * mm
        << "\nroller_radius_mm = " << f.roller_radius_m.value_or(0.0) * mm
        << "\noffset_mm = " << f.offset_m * mm << "\n";
    }
    // Every [checks] input the synthesis used goes on into the case, so that `needle check` on
    // it runs the spring check and the dynamics (issue 11). What the synthesis file does not
    // say and the dynamics needs is stated as an assumption, marked as such.
    if (f.moving_mass_kg && f.spring_preload_N) {
      std::ostringstream v;
      v.precision(12);
      v << "\n[needle]\nmass_kg = " << *f.moving_mass_kg
        << "\ngas_force_N = 0  # ASSUMED: the synthesis file states no gas load\n"
        << "\n[spring]\npreload_N = " << *f.spring_preload_N
        << "\nrate_N_mm = " << f.spring_rate_N_m.value_or(0.0) * 1e-3 << "\n"
        << "\n# ASSUMED (not in the synthesis file): a stiff steel roller-on-cam contact and "
           "seat,\n"
           "# no roller play. State your own train before trusting the dynamics.\n"
        << "[train]\ncontact_stiffness_N_m = 2e8\ncontact_damping_ratio = 0.1\n"
           "seat_stiffness_N_m = 2e8\nseat_damping_ratio = 0.1\nplay_mm = 0\n";
      c << v.str();
    }
    WriteOutput({"--case", *o.case_out}, c.str());
  }
  std::cout << out.str() << std::flush;
  return ok ? 0 : 1;
}

CLI::App* AddProfileCommand(CLI::App& app, ProfileCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "profile", "Cam profile for a roller follower: coordinates, pressure angle, undercut");
  cmd->add_option("CASE", o.case_path, "case file with [lift] and [profile] (and [train] play)")
      ->required();
  cmd->add_flag("--json", o.json, "print one JSON object");
  cmd->add_option("--csv", o.csv, "write cam_deg, x_mm, y_mm for manufacture");
  return cmd;
}

int RunProfileCommand(const ProfileCommandOptions& o) {
  const Case c = LoadCase(o.case_path);
  if (o.csv) CheckOutputPaths({{"--csv", *o.csv}}, CaseInputs(c));
  if (!c.profile)
    throw CaseError(c.path + ": [profile] base_radius_mm: section [profile] is missing");
  const LiftLaw law = MakeLiftLaw(c);
  const FollowerGeometry g = CaseFollower(c);
  const double play = c.train ? c.train->play_m : 0.0;
  double theta0 = 0.0;
  const CamProfile p = MakeCaseProfile(c, law, &theta0);
  std::ostringstream out;
  if (o.json) {
    nlohmann::json j;
    j["case"] = c.path;
    j["base_radius_mm"] = g.base_radius_m * 1e3;
    j["roller_radius_mm"] = g.roller_radius_m * 1e3;
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
    out << j.dump(2) << '\n';
  } else {
    out << (c.title.empty() ? c.path : c.title) << '\n'
        << "base circle radius " << Fixed(g.base_radius_m * 1e3, 2) << " mm, roller radius "
        << Fixed(g.roller_radius_m * 1e3, 2) << " mm, offset " << Fixed(g.offset_m * 1e3, 2)
        << " mm, lever " << Fixed(g.lever_ratio, 3) << ", play " << Fixed(play * 1e3, 3)
        << " mm; cam 0 deg at crank " << Fixed(theta0 / kDeg, 2) << " deg\n"
        << "pressure angle largest |phi| " << Fixed(std::abs(p.max_pressure_angle_rad) / kDeg, 3)
        << " deg at cam " << Fixed(p.max_pressure_angle_at_rad / kDeg, 2) << " deg\n"
        << "profile radius of curvature min " << Fixed(p.min_profile_radius_m * 1e3, 3)
        << " mm at cam " << Fixed(p.min_profile_radius_at_rad / kDeg, 2) << " deg; "
        << (p.undercut ? "UNDERCUT" : "no undercut") << '\n';
  }
  if (o.csv) {
    std::ostringstream csv;
    csv.precision(10);
    csv << "cam_deg,x_mm,y_mm\n";
    for (const ProfilePoint& q : p.points)
      csv << q.cam_rad / kDeg << ',' << q.x_m * 1e3 << ',' << q.y_m * 1e3 << '\n';
    WriteOutput({"--csv", *o.csv}, csv.str());
  }
  std::cout << out.str() << std::flush;
  return p.undercut ? 1 : 0;
}

}  // namespace needle
