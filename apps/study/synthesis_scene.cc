#include "apps/study/synthesis_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "lib/case_error.h"
#include "lib/output.h"
#include "lib/rigid_train.h"
#include "lib/units.h"

namespace needle {
namespace {

// The rise, with its mirrored fall: S(2Φ − φ), S' negated, S'' kept, S''' negated.
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

// The moving mass and the spring of [checks] (no gas load: the synthesis file states none).
// Call only when the file gives a preload and a mass.
RigidTrain TrainOf(const SynthesisFile& f) {
  RigidTrain train;
  train.mass_kg = *f.moving_mass_kg;
  train.preload_N = *f.spring_preload_N;
  train.rate_N_m = f.spring_rate_N_m.value_or(0.0);
  return train;
}

// The follower of [checks]. Call only when it gives base_radius_mm.
FollowerGeometry FollowerOf(const SynthesisFile& f) {
  FollowerGeometry g = f.follower;
  g.base_radius_m = *f.base_radius_m;
  g.offset_m = f.offset_m;
  return g;
}

SynthesisSpec SpecOf(const SynthesisFile& f, double cam_omega) {
  SynthesisSpec spec = f.rise;                 // [rise] and [limits] as read
  if (f.base_radius_m && f.offset_m == 0.0) {  // the steering caps assume a radial follower
    spec.follower = FollowerOf(f);
    spec.follower_limits.max_pressure_angle_rad = f.max_pressure_angle_rad.value_or(0.0);
    spec.follower_limits.min_profile_radius_m = f.min_profile_radius_m.value_or(-1.0);
    // |ū| ≥ u_min at ω  ⇔  |ū|/ω ≥ u_min/ω
    spec.follower_limits.min_entrainment_m_rad = f.min_entrainment_m_s.value_or(0.0) / cam_omega;
    if (f.max_contact_stress_Pa) {
      spec.max_contact_stress_Pa = *f.max_contact_stress_Pa;
      spec.contact_length_m = *f.contact_length_m;
      spec.elastic_modulus_Pa = f.elastic_modulus_Pa;
      spec.poisson = f.poisson;
    }
  }
  if (f.min_spring_reserve) spec.min_spring_reserve = *f.min_spring_reserve;
  if (f.min_spring_reserve || spec.max_contact_stress_Pa > 0.0) {
    spec.train = TrainOf(f);
    spec.cam_omega = cam_omega;
  }
  return spec;
}

}  // namespace

SynthesisResult SynthesizeCam(const SynthesisFile& f) {
  SynthesisResult r;
  // The cam turns at half the crank speed in a four-stroke engine.
  r.cam_omega = OmegaFromRpm(f.speed_rpm) / CrankTurnsPerCycle(f.cycle);
  r.spec = SpecOf(f, r.cam_omega);
  try {
    r.rise = SynthesizeRise(r.spec);
  } catch (const std::invalid_argument& e) {
    throw CaseError(f.path + ": [limits]: " + e.what());
  }
  r.law = f.mirror_fall ? WithFall(r.rise) : r.rise;
  const SynthesizedLaw& rise = r.rise;
  r.max_s1.value = r.max_s2.value = r.max_abs_s3.value = -INFINITY;
  r.min_s2.value = INFINITY;
  for (size_t i = 0; i < rise.phi.size(); ++i) {
    if (rise.s1[i] > r.max_s1.value) r.max_s1 = {rise.s1[i], rise.phi[i]};
    if (rise.s2[i] > r.max_s2.value) r.max_s2 = {rise.s2[i], rise.phi[i]};
    if (rise.s2[i] < r.min_s2.value) r.min_s2 = {rise.s2[i], rise.phi[i]};
    // Every step counts, the junction too: with a jerk limit the sides meet with S'' = 0, and
    // without one a step in S'' there is the law's, reported as it is.
    if (i > 0 && std::abs(rise.s3[i]) > r.max_abs_s3.value)
      r.max_abs_s3 = {std::abs(rise.s3[i]), rise.phi[i]};
  }

  if (f.base_radius_m) {
    const FollowerGeometry g = FollowerOf(f);
    r.profile = MakeCamProfile(TableDisplacement(r.law), g, 7200);
    const double angle = std::abs(r.profile->max_pressure_angle_rad);
    if (f.max_pressure_angle_rad && angle > *f.max_pressure_angle_rad) {
      r.failing.push_back("pressure angle: the largest |angle| " + Fixed(angle / kDeg, 2) +
                          " deg at cam " + Fixed(r.profile->max_pressure_angle_at_rad / kDeg, 2) +
                          " deg exceeds the limit " + Fixed(*f.max_pressure_angle_rad / kDeg, 2) +
                          " deg");
    }
    if (r.profile->undercut) {
      r.failing.push_back(std::string("cam profile: the profile ") +
                          (g.kind == FollowerKind::kFlat ? "has a cusp" : "undercuts") +
                          " (least radius " + Fixed(r.profile->min_profile_radius_m * 1e3, 3) +
                          " mm at cam " + Fixed(r.profile->min_profile_radius_at_rad / kDeg, 2) +
                          " deg)");
    }
    if (r.profile->off_face) {
      r.failing.push_back(
          "follower face: the contact runs " + Fixed(r.profile->max_contact_offset_m * 1e3, 3) +
          " mm off the axis at cam " + Fixed(r.profile->max_contact_offset_at_rad / kDeg, 2) +
          " deg, beyond the face half-width " + Fixed(g.face_half_width_m * 1e3, 3) + " mm");
    }
    if (f.min_entrainment_m_s) {
      const double u = r.profile->min_entrainment_m_rad * r.cam_omega;
      if (u < *f.min_entrainment_m_s * (1 - 1e-6))
        r.failing.push_back("lubrication: the entrainment velocity falls to " + Fixed(u, 3) +
                            " m/s at cam " + Fixed(r.profile->min_entrainment_at_rad / kDeg, 2) +
                            " deg, below the limit " + Fixed(*f.min_entrainment_m_s, 3) + " m/s");
    }
  }
  // The spring reserve where S'' < 0, and the Hertz line-contact stress with
  // F = m ω² S'' + P₀ + k S, 1/R* = 1/ρ + 1/r_r (ρ signed, + convex), E* = E/(2(1 − ν²)).
  if (f.spring_preload_N && f.moving_mass_kg) {
    const RigidTrain train = TrainOf(f);
    const double w2 = r.cam_omega * r.cam_omega;
    LawExtreme reserve{INFINITY, 0.0};
    for (size_t i = 0; i < rise.phi.size(); ++i) {
      const double k = train.SpringReserve(rise.s[i], w2 * rise.s2[i]);
      if (k < reserve.value) reserve = {k, rise.phi[i]};
    }
    r.min_spring_reserve = reserve;
    if (f.min_spring_reserve && reserve.value < *f.min_spring_reserve * (1 - 1e-9)) {
      r.failing.push_back("spring reserve: the least K " + Fixed(reserve.value, 3) + " at cam " +
                          Fixed(reserve.at_rad / kDeg, 2) + " deg is below the limit " +
                          Fixed(*f.min_spring_reserve, 2));
    }
    if (r.profile && f.contact_length_m) {
      const Displacement d = TableDisplacement(r.law);
      const FollowerGeometry follower = FollowerOf(f);
      LawExtreme hertz{-INFINITY, 0.0};
      for (const ProfilePoint& q : r.profile->points) {
        const auto sv = d(q.cam_rad);
        const double force = train.ContactForceN(sv[0], w2 * sv[2]);
        const double sigma =
            ContactStress(follower, q, force, f.elastic_modulus_Pa, f.poisson, *f.contact_length_m);
        if (sigma > hertz.value) hertz = {sigma, q.cam_rad};
      }
      if (std::isfinite(hertz.value) && hertz.value > 0) r.max_contact_stress_Pa = hertz;
      // The stress steered the steps at the rise's own points; between them (and at the
      // conservative look-ahead of side C) it may come out higher by round-off-sized amounts.
      if (f.max_contact_stress_Pa && hertz.value > *f.max_contact_stress_Pa * (1 + 1e-6)) {
        r.failing.push_back("contact stress: " + Fixed(hertz.value * 1e-6, 0) + " MPa at cam " +
                            Fixed(hertz.at_rad / kDeg, 2) + " deg exceeds the limit " +
                            Fixed(*f.max_contact_stress_Pa * 1e-6, 0) + " MPa");
      }
    }
  }
  r.pass = r.failing.empty();
  return r;
}

std::vector<Field> SynthesisFields(const SynthesisResult& r) {
  using namespace display;
  const SynthesizedLaw& rise = r.rise;
  std::vector<Field> f = {
      {"rise", kDegree, r.spec.rise_rad, 2},
      {"lift", kMm, r.spec.height_m, 3},
      {"limits_used_fraction", kNone, rise.scale, 4},
      {"constant_speed_start", kDegree, rise.constant_start_rad, 3},
      {"constant_speed_end", kDegree, rise.constant_end_rad, 3},
      {"constant_speed_length", kDegree, rise.constant_length_rad(), 3},
      {"max_S1", kMmPerRad, r.max_s1.value, 4},
      {"max_S1", kDegree, r.max_s1.at_rad, 2},
      {"max_S2", kMmPerRad2, r.max_s2.value, 2},
      {"max_S2", kDegree, r.max_s2.at_rad, 2},
      {"min_S2", kMmPerRad2, r.min_s2.value, 2},
      {"min_S2", kDegree, r.min_s2.at_rad, 2},
      {"max_abs_S3", kMmPerRad3, r.max_abs_s3.value, 1},
      {"max_abs_S3", kDegree, r.max_abs_s3.at_rad, 2},
      {"meet_speed", kMmPerRad,
       rise.meet_speed > 0.0 ? std::optional<double>(rise.meet_speed) : std::nullopt, 3},
  };
  if (r.profile) {
    // The largest |pressure angle| (its sign says on which flank: + rising, − falling).
    f.push_back(
        {"max_abs_pressure_angle", kDegree, std::abs(r.profile->max_pressure_angle_rad), 2});
    f.push_back({"max_pressure_angle", kDegree, r.profile->max_pressure_angle_rad, 2});
    f.push_back({"max_pressure_angle_at", kDegree, r.profile->max_pressure_angle_at_rad, 2});
    f.push_back({"min_profile_radius", kMm, r.profile->min_profile_radius_m, 3});
    f.push_back({"min_profile_radius_at", kDegree, r.profile->min_profile_radius_at_rad, 2});
    // The contact's largest distance from the axis along the face: the half-width it needs.
    f.push_back({"max_contact_offset", kMm, r.profile->max_contact_offset_m, 4});
    f.push_back({"max_contact_offset_at", kDegree, r.profile->max_contact_offset_at_rad, 2});
    f.push_back(
        {"min_entrainment_speed", kMPerS, r.profile->min_entrainment_m_rad * r.cam_omega, 3});
    f.push_back({"min_entrainment_speed_at", kDegree, r.profile->min_entrainment_at_rad, 2});
    f.push_back({"max_sliding_speed", kMPerS, r.profile->max_sliding_m_rad * r.cam_omega, 3});
  }
  if (r.min_spring_reserve) {
    const double k = r.min_spring_reserve->value;
    f.push_back({"min_spring_reserve", kNone,
                 std::isfinite(k) ? std::optional<double>(k) : std::nullopt, 3});
    f.push_back({"min_spring_reserve", kDegree, r.min_spring_reserve->at_rad, 2});
  }
  if (r.max_contact_stress_Pa) {
    f.push_back({"max_contact_stress", kMPa, r.max_contact_stress_Pa->value, 0});
    f.push_back({"max_contact_stress", kDegree, r.max_contact_stress_Pa->at_rad, 2});
  }
  return f;
}

std::vector<Column> SynthesisColumns() {
  using namespace display;
  return {{"cam", kDegree}, {"S", kMm}, {"S1", kMmPerRad}, {"S2", kMmPerRad2}, {"S3", kMmPerRad3}};
}

std::vector<std::vector<double>> SynthesisRows(const SynthesizedLaw& law) {
  std::vector<std::vector<double>> rows;
  rows.reserve(law.phi.size());
  for (size_t i = 0; i < law.phi.size(); ++i)
    rows.push_back({law.phi[i], law.s[i], law.s1[i], law.s2[i], law.s3[i]});
  return rows;
}

}  // namespace needle
