#pragma once
/// @file
/// Ranges of the command-line options, in one place: a value outside gets one line naming the
/// option, the range and the value (CLI11 prefixes the option), exit 2. NaN and ±∞ never pass.

#include <CLI/CLI.hpp>
#include <cmath>
#include <string>

namespace needle {

/// A number in [lo, hi] (`what` names the quantity and unit, e.g. "a speed in rpm").
inline CLI::Validator NumberIn(double lo, double hi, const std::string& what) {
  return CLI::Validator(
      [lo, hi, what](std::string& s) -> std::string {
        double v = NAN;
        try {
          size_t used = 0;
          v = std::stod(s, &used);
          if (used != s.size()) v = NAN;
        } catch (const std::exception&) {
        }
        if (std::isfinite(v) && v >= lo && v <= hi) return {};
        std::ostringstream m;
        m << "expected " << what << " in [" << lo << ", " << hi << "], got " << s;
        return m.str();
      },
      what, "");
}

/// Crank speeds: (0, 1e6] rpm (the lower end 1e-3).
inline CLI::Validator SpeedRpm() { return NumberIn(1e-3, 1e6, "a speed in rpm"); }

}  // namespace needle
