#pragma once
/// @file
/// Ranges of the command-line options, in one place: a value outside gets one line naming the
/// option, the range and the value (CLI11 prefixes the option), exit 2. NaN and ±∞ never pass.

#include <CLI/CLI.hpp>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>

#include "apps/case/case_file.h"
#include "apps/case/plausible_ranges.h"

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
        return RangeRule(lo, hi, what, s);
      },
      what, "");
}

/// A number in a plausible range of apps/case/plausible_ranges.h, in its shown unit.
inline CLI::Validator InRange(const PlausibleRange& r, const std::string& what) {
  return NumberIn(r.lo / r.unit_si, r.hi / r.unit_si, what);
}

/// Crank speeds (--rpm, --from, --to): the plausible range of [engine] speed_rpm, 1…50000 rpm.
inline CLI::Validator SpeedRpm() { return InRange(kCrankSpeedRange, "a speed in rpm"); }

/// The commands' `--rpm` option: a crank speed checked against kCrankSpeedRange.
inline void AddSpeedOption(CLI::App* cmd, std::optional<double>& speed_rpm,
                           const std::string& help =
                               "crank speed in rpm (default: [engine] "
                               "speed_rpm)") {
  cmd->add_option("--rpm", speed_rpm, help)->check(SpeedRpm());
}

/// A 64-bit seed: digits only, at most 18446744073709551615 (CLI11 alone took a longer number
/// without a word).
inline CLI::Validator Seed() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        const bool digits =
            !s.empty() && s.size() <= 20 && s.find_first_not_of("0123456789") == std::string::npos;
        if (digits && (s.size() < 20 || s <= "18446744073709551615")) return {};
        return "expected a whole number in " + RangeText(kSeedRange) + ", got " + s;
      },
      "SEED", "");
}

}  // namespace needle
