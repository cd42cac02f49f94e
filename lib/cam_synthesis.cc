#include "lib/cam_synthesis.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "lib/units.h"

namespace needle {
namespace {

struct Point {
  double s = 0.0, s1 = 0.0, s2 = 0.0;
};

// Caps on S' and |S''| at a point of a side (s_abs: the displacement from the base circle;
// convex: the side where S'' < 0), and which limit set the |S''| cap.
struct Caps {
  double vmax = 1e300, amax = 1e300;
  enum Source { kNone, kReserve, kCurvature, kLubrication, kStress } source = kNone;
  void Lower(double v, Source why) {
    if (v < amax) {
      amax = v;
      source = why;
    }
  }
};

// The largest |S''| ≤ a_user at which the Hertz stress stays within its limit, by bisection on
// |S''| (the stress is not affine in S''; it is taken to cross its limit once, from below).
double StressCap(const SynthesisSpec& spec, double s_abs, double s1, bool convex, double a_user) {
  const double w2 = spec.cam_omega * spec.cam_omega;
  auto over = [&](double a) {
    const double s2 = convex ? -a : a;
    const ProfilePoint q = FollowerContact(spec.follower, 0.0, {s_abs, s1, s2});
    return ContactStress(spec.follower, q, spec.train.ContactForceN(s_abs, w2 * s2),
                         spec.elastic_modulus_Pa, spec.poisson,
                         spec.contact_length_m) > spec.max_contact_stress_Pa;
  };
  if (!over(a_user)) return 1e300;
  if (over(0.0)) return 0.0;
  double lo = 0.0, hi = a_user;
  for (int k = 0; k < 60 && hi - lo > 1e-12 * hi; ++k)
    (over(0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
  return lo;
}

Caps GeometryCaps(const SynthesisSpec& spec, double s_abs, double s1, bool convex, double a_user) {
  Caps c;
  if (convex && spec.min_spring_reserve > 0.0) {
    // (P₀ + k S) ≥ K m ω² |S''|  ⇔  |S''| ≤ (P₀ + k S)/(K m ω²)
    c.Lower(spec.train.SpringForceN(s_abs) /
                (spec.min_spring_reserve * spec.train.mass_kg * spec.cam_omega * spec.cam_omega),
            Caps::kReserve);
  }
  if (!(spec.follower.base_radius_m > 0.0)) return c;
  c.vmax = SpeedCap(spec.follower, spec.follower_limits, s_abs);
  const AccelerationCap a =
      AccelerationCapAt(spec.follower, spec.follower_limits, s_abs, s1, convex);
  c.Lower(a.value, a.source == CapSource::kLubrication ? Caps::kLubrication : Caps::kCurvature);
  if (spec.max_contact_stress_Pa > 0.0)
    c.Lower(StressCap(spec, s_abs, s1, convex, std::min(a_user, c.amax)), Caps::kStress);
  return c;
}

// The largest S''_i that keeps S'_i + S''_i²/(2j) ≤ vmax (so that S'' can come back to zero
// exactly at vmax), with S'_i = S'_{i−1} + h(S''_{i−1} + S''_i)/2:
// S''²/(2j) + (h/2) S'' + (S'_{i−1} + h S''_{i−1}/2 − vmax) ≤ 0. +∞ without vmax.
double SpeedRoot(const Point& p, double j, double vmax, double h) {
  if (!(vmax < 1e299)) return 1e300;
  const double qa = (j < 1e299) ? 1.0 / (2.0 * j) : 0.0;
  const double qb = 0.5 * h;
  const double qc = p.s1 + 0.5 * h * p.s2 - vmax;
  if (qa > 0.0) {
    const double disc = qb * qb - 4.0 * qa * qc;
    return disc >= 0.0 ? (-qb + std::sqrt(disc)) / (2.0 * qa) : -1e300;
  }
  return -qc / qb;
}

// One side formed from rest with limits (a, j, vmax): the next point.
Point Advance(const Point& p, double a, double j, double vmax, double h) {
  double s2 = std::min(a, p.s2 + j * h);  // largest S'' allowed by |S''| ≤ a and the jerk
  if (vmax < 1e299) {
    s2 = std::min(s2, SpeedRoot(p, j, vmax, h));
    s2 = std::max({s2, p.s2 - j * h, 0.0});  // cannot come down faster than the jerk allows
  }
  Point n;
  n.s2 = s2;
  n.s1 = p.s1 + 0.5 * h * (p.s2 + s2);  // trapezoidal (2)
  if (vmax < 1e299) n.s1 = std::min(n.s1, vmax);
  n.s = p.s + 0.5 * h * (p.s1 + n.s1);  // trapezoidal (3)
  return n;
}

struct Formed {
  // Which caps were the tighter limit somewhere.
  bool v_bound = false, a_bound = false, reserve_bound = false, lube_bound = false,
       stress_bound = false;
  size_t backed_off = 0;    // steps formed again (back-off)
  std::vector<Point> a, c;  // side A forward, side C backward (from the end of the rise)

  double constant_rad = 0.0;  // constant-speed length
  double total_rad = 0.0;
  bool speed_active = false;
  double meet_speed = 0.0;  // > 0: the sides were made to meet at this S' (FormSmooth)
};

// Forms both sides with the limits scaled by alpha; the rise angle comes out. Gives up with
// total_rad = +∞ once the sides are longer than `give_up_rad`.
Formed Form(const SynthesisSpec& spec, double alpha, double vmax, double h,
            double give_up_rad = INFINITY) {
  Formed f;
  f.a.push_back({});
  f.c.push_back({});
  const double aa = alpha * spec.accel_limit, ac = alpha * spec.decel_limit;
  const double j = spec.jerk_limit < 1e299 ? alpha * spec.jerk_limit : 1e300;
  const size_t budget =
      std::isfinite(give_up_rad) ? static_cast<size_t>(give_up_rad / h) + 3 : 50000000;
  auto at_speed = [&](const Point& p) {
    return vmax < 1e299 && p.s1 >= vmax * (1 - 1e-12) && p.s2 <= 0.0;
  };
  // Ceilings on |S''| per step index, set by back-off: a step whose cap lies more than j·h
  // below the step before makes that step be formed again with S'' ≤ cap + j·h.
  std::vector<double> ceil_a, ceil_c;
  // A safeguard on back-off (steps formed again): 64 per step of the rise, whatever the give-up
  // angle; beyond it a cap that still cannot be met within the jerk limit is let off.
  const size_t backoff_budget = 64 * (static_cast<size_t>(spec.rise_rad / h) + 3);
  while (f.a.size() + f.c.size() < budget) {
    const Point& pa = f.a.back();
    const Point& pc = f.c.back();
    if (pa.s + pc.s >= spec.height_m) break;  // the sides meet
    const bool a_done = at_speed(pa), c_done = at_speed(pc);
    if (a_done && c_done) {  // both at S'max: the rest at constant speed
      f.speed_active = true;
      f.constant_rad = (spec.height_m - pa.s - pc.s) / vmax;  // φ₀ = ΔS / S'max (5)
      break;
    }
    // The side with the lower S' advances, under the user limits and the caps.
    const bool advance_a = !a_done && (c_done || pa.s1 <= pc.s1);
    std::vector<Point>& side = advance_a ? f.a : f.c;
    std::vector<double>& ceil = advance_a ? ceil_a : ceil_c;
    const Point p = side.back();
    const size_t index = side.size();  // of the point being formed
    // The caps grow with the displacement from the base circle. Side C is formed backwards, so
    // its next point lies lower than the current one: evaluate there, bounded conservatively.
    const double a_user = advance_a ? aa : ac;
    const double s_abs = advance_a ? p.s : spec.height_m - (p.s + h * p.s1 + h * h * a_user);
    const Caps caps = GeometryCaps(spec, s_abs, p.s1, !advance_a, a_user);
    double a_cap = std::min(a_user, caps.amax);
    if (index < ceil.size()) a_cap = std::min(a_cap, ceil[index]);
    // The S'' this step may have: the caps, and the S' rule of Advance for a cap on S' that
    // fell since the step before (a pressure angle or face on side C).
    const double need = std::min(a_cap, caps.vmax < vmax ? SpeedRoot(p, j, caps.vmax, h) : 1e300);
    const double floor_s2 = std::max(need, 0.0);  // S'' does not change sign on a side
    if (j < 1e299 && floor_s2 < p.s2 - j * h * (1 + 1e-12) && index >= 2 &&
        f.backed_off < backoff_budget) {
      // Back off: the step m before this one must end within m·j·h of what this step may
      // have. Set those ceilings as far back as they bind, drop those steps and form them again.
      if (ceil.size() < index) ceil.resize(index, 1e300);
      size_t m = 1;
      for (; m < index; ++m) {
        const double reach = floor_s2 + static_cast<double>(m) * j * h;
        if (side[index - m].s2 <= reach) break;
        ceil[index - m] = std::min(ceil[index - m], reach);
      }
      side.resize(index - m + 1);  // keep the steps up to the first that needs no change
      f.backed_off += m - 1;
      continue;
    }
    f.v_bound = f.v_bound || caps.vmax < vmax;
    if (caps.amax < a_user) {
      f.a_bound = f.a_bound || caps.source == Caps::kCurvature;
      f.reserve_bound = f.reserve_bound || caps.source == Caps::kReserve;
      f.lube_bound = f.lube_bound || caps.source == Caps::kLubrication;
      f.stress_bound = f.stress_bound || caps.source == Caps::kStress;
    }
    side.push_back(Advance(p, a_cap, j, std::min(vmax, caps.vmax), h));
  }
  if (f.a.size() + f.c.size() >= budget) {
    f.total_rad = INFINITY;
    return f;
  }
  f.total_rad = h * static_cast<double>(f.a.size() - 1 + f.c.size() - 1) + f.constant_rad;
  return f;
}

// Form, with the jerk limit honoured where the two sides meet. Two sides that meet below S'max
// meet with S'' > 0 on A and S'' < 0 on C: a step in S'' of (a⁺ + a⁻)-size in one step, an
// unbounded S'''. Then the speed at which they meet is lowered to V*, the largest speed both
// sides still reach (S'' brought back to 0 under the jerk limit, the S'max rule of Advance)
// before their displacements add up to H: they join at V* with S'' = 0 on both sides, through
// a constant-speed stretch shorter than one step.
Formed FormSmooth(const SynthesisSpec& spec, double alpha, double vmax, double h,
                  double give_up_rad = INFINITY) {
  Formed f = Form(spec, alpha, vmax, h, give_up_rad);
  if (spec.jerk_limit >= 1e299 || f.speed_active || !std::isfinite(f.total_rad)) return f;
  double lo = 0.0, hi = std::max(f.a.back().s1, f.c.back().s1);
  for (int k = 0; k < 60 && hi - lo > 1e-14 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (Form(spec, alpha, mid, h, give_up_rad).speed_active ? lo : hi) = mid;
  }
  if (!(lo > 0.0)) return f;  // cannot happen for a positive height; keep the plain result
  Formed g = Form(spec, alpha, lo, h, give_up_rad);
  g.meet_speed = lo;
  return g;
}

// "; the caps that bound S' or S'': …" for a message, or "".
std::string BindingCaps(const Formed& f) {
  std::string names;
  auto add = [&](bool on, const char* name) {
    if (on) names += (names.empty() ? "" : ", ") + std::string(name);
  };
  add(f.v_bound, "pressure angle or face width");
  add(f.a_bound, "profile radius");
  add(f.reserve_bound, "spring reserve");
  add(f.lube_bound, "lubrication (entrainment)");
  add(f.stress_bound, "contact stress");
  return names.empty() ? "" : "; the caps that bound S' or S'': " + names;
}

}  // namespace

void SynthesisSpec::Validate() const {
  auto req = [](bool ok, const std::string& field, double v, const std::string& rule) {
    if (!ok)
      throw std::invalid_argument("SynthesisSpec." + field + " = " + std::to_string(v) + ": " +
                                  rule);
  };
  req(rise_rad > 0.0 && std::isfinite(rise_rad), "rise_rad", rise_rad, "must be positive");
  req(height_m > 0.0 && std::isfinite(height_m), "height_m", height_m, "must be positive");
  req(step_rad >= 0.0 && step_rad < rise_rad, "step_rad", step_rad, "must be in [0, rise)");
  req(speed_limit > 0.0, "speed_limit", speed_limit, "must be positive");
  req(accel_limit > 0.0 && std::isfinite(accel_limit), "accel_limit", accel_limit,
      "must be positive");
  req(decel_limit > 0.0 && std::isfinite(decel_limit), "decel_limit", decel_limit,
      "must be positive");
  req(jerk_limit > 0.0, "jerk_limit", jerk_limit, "must be positive");
  req(min_spring_reserve >= 0.0 && std::isfinite(min_spring_reserve), "min_spring_reserve",
      min_spring_reserve, "must not be negative");
  if (follower.base_radius_m > 0.0) {
    try {
      follower.Validate();
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("SynthesisSpec.follower: ") + e.what());
    }
    req(follower.offset_m == 0.0, "follower.offset_m", follower.offset_m,
        "must be 0: the steering caps assume a radial follower");
  }
  req(max_contact_stress_Pa >= 0.0 && std::isfinite(max_contact_stress_Pa), "max_contact_stress_Pa",
      max_contact_stress_Pa, "must not be negative");
  if (max_contact_stress_Pa > 0.0) {
    req(follower.base_radius_m > 0.0, "follower.base_radius_m", follower.base_radius_m,
        "must be positive with a contact-stress limit");
    req(contact_length_m > 0.0 && std::isfinite(contact_length_m), "contact_length_m",
        contact_length_m, "must be positive with a contact-stress limit");
    req(elastic_modulus_Pa > 0.0, "elastic_modulus_Pa", elastic_modulus_Pa, "must be positive");
    req(poisson >= 0.0 && poisson < 0.5, "poisson", poisson, "must be in [0, 0.5)");
  }
  if (min_spring_reserve > 0.0 || max_contact_stress_Pa > 0.0) {
    try {
      train.Validate();
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("SynthesisSpec.train: ") + e.what());
    }
    req(cam_omega > 0.0 && std::isfinite(cam_omega), "cam_omega", cam_omega,
        "must be positive with a spring reserve or a contact-stress limit");
  }
}

namespace {

// The step Δφ: as given, or Φ/4000.
double StepOf(const SynthesisSpec& spec) {
  return spec.step_rad > 0.0 ? spec.step_rad : spec.rise_rad / 4000.0;
}

// The least x ≥ start for which fits(x) holds, fits being false below some x and true above:
// doubling from start up to a millionfold (20 doublings, counted so that no overflow can make
// the loop endless; beyond: +∞), then bisection between the last two tries.
template <class Fits>
double LeastThatFits(double start, const Fits& fits) {
  double lo = start, hi = start;
  for (int doublings = 0; !fits(hi); ++doublings) {
    if (doublings >= 20) return INFINITY;
    lo = hi;
    hi *= 2.0;
  }
  for (int k = 0; k < 60 && hi - lo > 1e-12 * hi; ++k)
    (fits(0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
  return hi;
}

}  // namespace

double LeastSpeedLimit(const SynthesisSpec& spec) {
  const double h = StepOf(spec);
  const double least = spec.height_m / spec.rise_rad;  // S'max·Φ ≥ H at the very least
  if (!std::isfinite(least) || !(least > 0.0)) return INFINITY;
  return LeastThatFits(least, [&](double vmax) {
    return FormSmooth(spec, 1.0, vmax, h, 2 * spec.rise_rad).total_rad <= spec.rise_rad;
  });
}

double LeastBaseRadius(const SynthesisSpec& spec) {
  if (!(spec.follower.base_radius_m > 0.0)) return INFINITY;
  const double h = StepOf(spec);
  return LeastThatFits(spec.follower.base_radius_m, [&](double rb) {
    SynthesisSpec t = spec;
    t.follower.base_radius_m = rb;
    return FormSmooth(t, 1.0, spec.speed_limit, h, 2 * spec.rise_rad).total_rad <= spec.rise_rad;
  });
}

namespace {
// " (with the limits of the cam and its flat follower; the least base radius that fits is …)".
std::string FollowerNote(const SynthesisSpec& spec) {
  const double least = LeastBaseRadius(spec);
  return std::string(" (with the limits of the cam and its ") +
         FollowerKindName(spec.follower.kind) + " follower" +
         (std::isfinite(least)
              ? "; the least base radius that fits is " + std::to_string(least * 1e3) + " mm"
              : "; no base radius up to a millionfold fits") +
         ")";
}
}  // namespace

namespace {

// The smallest scale α ≤ 1 of the limits whose rise still fits in Φ (the rise angle falls as α
// grows): bracketed by quartering, then bisected.
double FittingScale(const SynthesisSpec& spec, double vmax, double h) {
  const double give_up = 2 * spec.rise_rad;
  double lo = 0.25, hi = 1.0;
  while (FormSmooth(spec, lo, vmax, h, give_up).total_rad <= spec.rise_rad) {
    hi = lo;
    lo *= 0.25;
    if (lo < 1e-12)
      throw std::invalid_argument("synthesis: the limits are far larger than the rise needs");
  }
  for (int k = 0; k < 100 && hi - lo > 1e-13 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (FormSmooth(spec, mid, vmax, h, give_up).total_rad > spec.rise_rad ? lo : hi) = mid;
  }

  return hi;
}

// The rise's samples: side A forward, the constant section at the speed v_const, side C
// reversed.
void Assemble(const Formed& f, double h, double v_const, SynthesizedLaw& law) {
  for (size_t i = 0; i < f.a.size(); ++i) {
    law.phi.push_back(h * i);
    law.s.push_back(f.a[i].s);
    law.s1.push_back(f.a[i].s1);
    law.s2.push_back(f.a[i].s2);
  }
  law.junction = law.phi.size() - 1;
  const double phi_a = h * (f.a.size() - 1);
  const double s_a = f.a.back().s;
  law.constant_start_rad = phi_a;
  law.constant_end_rad = phi_a + f.constant_rad;
  // The constant-speed section, at the same step (S is linear there).
  const int inner = static_cast<int>(std::floor(f.constant_rad / h - 1e-9));
  for (int m = 1; m <= inner; ++m) {
    law.phi.push_back(phi_a + h * m);
    law.s.push_back(s_a + v_const * h * m);
    law.s1.push_back(v_const);
    law.s2.push_back(0.0);
  }

  const double phi_c0 = phi_a + f.constant_rad;
  const double c_total = f.c.back().s;  // displacement of side C
  const double s_c0 = s_a + (f.speed_active ? f.constant_rad * v_const : 0.0);
  const double end_s = s_c0 + c_total;
  for (size_t k = 0; k < f.c.size(); ++k) {
    const size_t i = f.c.size() - 1 - k;  // from the junction back to the end at rest
    const double phi = phi_c0 + h * k;
    if (k == 0 && f.constant_rad == 0.0) continue;  // the junction point is side A's last
    law.phi.push_back(phi);
    law.s.push_back(end_s - f.c[i].s);
    law.s1.push_back(f.c[i].s1);
    law.s2.push_back(-f.c[i].s2);
  }
}

// Closes the angle and the height exactly (φ stretched by c ≥ 1, S scaled by H/S_end ≤ 1),
// and S3 as the first difference of S2.
void CloseAngleAndHeight(const SynthesisSpec& spec, SynthesizedLaw& law) {
  const double c = spec.rise_rad / law.phi.back();
  const double k = spec.height_m / law.s.back();
  for (size_t i = 0; i < law.phi.size(); ++i) {
    law.phi[i] *= c;
    law.s[i] *= k;
    law.s1[i] *= k / c;
    law.s2[i] *= k / (c * c);
  }
  law.constant_start_rad *= c;
  law.constant_end_rad *= c;
  law.s3.assign(law.phi.size(), 0.0);
  for (size_t i = 1; i < law.phi.size(); ++i) {
    law.s3[i] = (law.s2[i] - law.s2[i - 1]) / (law.phi[i] - law.phi[i - 1]);  // (1), k = 3
  }
}

}  // namespace

SynthesizedLaw SynthesizeRise(const SynthesisSpec& spec) {
  spec.Validate();
  const double h = StepOf(spec);
  // A flat face's cap on S' (its half-width) does not depend on S: it acts as S'max.
  const bool flat_face =
      spec.follower.base_radius_m > 0.0 && spec.follower.kind == FollowerKind::kFlat;
  const double vmax =
      flat_face ? std::min(spec.speed_limit, SpeedCap(spec.follower, spec.follower_limits, 0.0))
                : spec.speed_limit;
  if (vmax < 1e299 && vmax * spec.rise_rad <= spec.height_m) {
    throw std::invalid_argument(
        "infeasible: S'max × rise angle = " + std::to_string(vmax * spec.rise_rad * 1e3) +
        " mm is not more than the displacement " + std::to_string(spec.height_m * 1e3) +
        " mm; the least S'max that fits with these acceleration limits is " +
        std::to_string(LeastSpeedLimit(spec) * 1e3) + " mm/rad");
  }
  const Formed full = FormSmooth(spec, 1.0, vmax, h, 2 * spec.rise_rad);
  if (full.total_rad > spec.rise_rad) {
    const double least = LeastSpeedLimit(spec);
    throw std::invalid_argument(
        "infeasible: with the full limits the shortest rise of " +
        std::to_string(spec.height_m * 1e3) + " mm takes " +
        std::to_string(full.total_rad * 180.0 / kPi) + " deg, more than " +
        std::to_string(spec.rise_rad * 180.0 / kPi) + " deg" +
        (std::isfinite(least) && vmax < 1e299
             ? "; the least S'max that fits is " + std::to_string(least * 1e3) + " mm/rad"
             : "; raise the acceleration or jerk limits") +
        BindingCaps(full) + (spec.follower.base_radius_m > 0.0 ? FollowerNote(spec) : ""));
  }

  const double hi = FittingScale(spec, vmax, h);

  const Formed f = FormSmooth(spec, hi, vmax, h);
  // The speed of the constant section: S'max, or the speed the sides were made to meet at.
  const double v_const = f.meet_speed > 0.0 ? f.meet_speed : vmax;

  // Assemble: side A forward, the constant section, side C reversed.
  SynthesizedLaw law;
  law.scale = hi;
  law.speed_limit_active = f.speed_active && f.meet_speed == 0.0;
  law.meet_speed = f.meet_speed;
  law.pressure_angle_limited = f.v_bound;
  law.curvature_limited = f.a_bound;
  law.spring_reserve_limited = f.reserve_bound;
  law.lubrication_limited = f.lube_bound;
  law.stress_limited = f.stress_bound;
  law.face_width_limited = flat_face && vmax < spec.speed_limit && law.speed_limit_active;
  law.backed_off_steps = f.backed_off;

  Assemble(f, h, v_const, law);
  CloseAngleAndHeight(spec, law);
  return law;
}

}  // namespace needle
