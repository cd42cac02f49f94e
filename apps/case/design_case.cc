#include "apps/case/design_case.h"

#include <cmath>
#include <sstream>

#include "lib/units.h"

namespace needle {

std::string DesignCaseText(const DesignInputs& in, const DesignResult& r) {
  std::ostringstream c;
  c.precision(10);
  c << "# Written by `needle design " << in.path << " --case`: Basu's design chain (NACA TM 477).\n"
    << "# Values marked ASSUMED are not computed by the chain; replace them with your own.\n"
    << "title = \"" << (in.title.empty() ? std::string("designed valve") : in.title)
    << " (designed)\"\n\n[engine]\nspeed_rpm = " << in.speed_rpm << "\ncycle = \""
    << EngineCycleName(in.cycle) << "\"\n\n# The normal curve scaled to the maximum lift "
    << r.max_lift_m * 1e3 << " mm.\n[lift]\ncrank_deg = [";
  for (size_t i = 0; i < r.lift_table.crank_rad.size(); ++i)
    c << (i ? ", " : "") << r.lift_table.crank_rad[i] / kDeg;
  c << "]\nlift_mm = [";
  for (size_t i = 0; i < r.lift_table.lift_m.size(); ++i)
    c << (i ? ", " : "") << r.lift_table.lift_m[i] * 1e3;
  c << "]\n\n[needle]\n";
  if (in.moving_mass_kg) {
    c << "mass_kg = " << *in.moving_mass_kg << "  # [design] moving_mass_kg\n";
  } else {
    // Basu's Example 1: 11.5 kg of needle and disks with a 31 mm needle.
    const double m = 11.5 * std::pow(r.needle_diameter_m / 31e-3, 3);
    c << "mass_kg = " << m
      << "  # ASSUMED: Basu's Example 1 (11.5 kg at a 31 mm needle) scaled by the needle "
         "diameter cubed; weigh yours or give [design] moving_mass_kg\n";
  }
  c << "diameter_mm = " << r.needle_diameter_m * 1e3
    << "  # the gas load defaults to Basu's 35 kg/cm2 on it\n\n[spring]\npreload_N = "
    << r.spring_preload_N
    << "  # Basu's formula\nrate_N_mm = " << 0.1 * r.spring_preload_N / r.max_lift_m * 1e-3
    << "  # ASSUMED: 10 % more force at full lift\n\n"
    << "# ASSUMED: a stiff steel roller-on-cam contact and seat, no roller play.\n"
    << "[train]\ncontact_stiffness_N_m = 1e9\ncontact_damping_ratio = 0.05\n"
       "seat_stiffness_N_m = 1e9\nseat_damping_ratio = 0.05\nplay_mm = 0\n\n"
    << "# The cam disk and roller of the chain; a radial roller "
       "follower.\n[profile]\nbase_radius_mm = "
    << r.cam_disk_m * 1e3 / 2 << "\nroller_radius_mm = " << r.roller_m * 1e3 / 2
    << "\noffset_mm = 0\n";
  return c.str();
}

}  // namespace needle
