#pragma once
/// @file
/// Ranges of the command-line options, in one place: a value outside gets one line naming the
/// option, the range and the value (CLI11 prefixes the option), exit 2. NaN and ±∞ never pass.

#include <CLI/CLI.hpp>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>

#include "apps/scene/case_file.h"

namespace needle {

/// "expected WHAT in [lo, hi], got V": the rule both checks below state.
inline std::string RangeRule(double lo, double hi, const std::string& what, const std::string& v) {
  std::ostringstream m;
  m << "expected " << what << " in [" << lo << ", " << hi << "], got " << v;
  return m.str();
}

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
        return RangeRule(lo, hi, what, s);
      },
      what, "");
}

/// Crank speeds: (0, 1e6] rpm (the lower end 1e-3).
inline CLI::Validator SpeedRpm() { return NumberIn(1e-3, 1e6, "a speed in rpm"); }

/// The same rule where no parser stood in front (the Compute functions, called from Python):
/// throws CaseError "OPTION: expected WHAT in [lo, hi], got V".
inline void RequireIn(const std::string& option, const std::optional<double>& v, double lo,
                      double hi, const std::string& what) {
  if (!v || (std::isfinite(*v) && *v >= lo && *v <= hi)) return;
  std::ostringstream text;
  text << *v;
  throw CaseError(option + ": " + RangeRule(lo, hi, what, text.str()));
}
inline void RequireSpeed(const std::optional<double>& rpm) {
  RequireIn("--rpm", rpm, 1e-3, 1e6, "a speed in rpm");
}

}  // namespace needle
