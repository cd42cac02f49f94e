#pragma once
/// @file
/// Ranges of the command-line options, in one place: a value outside gets one line naming the
/// option, the range and the value (CLI11 prefixes the option), exit 2. NaN and ±∞ never pass,
/// and a number is decimal as typed: CLI11 and std::stod alone read "0x10" as 16 and a whole
/// "010" as octal 8.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <system_error>

#include "apps/case/case_file.h"
#include "apps/case/plausible_ranges.h"
#include "dynamics/solver/integrator.h"

namespace needle {

/// The value of a decimal number as typed, digits with a sign, a point and an exponent, each
/// optional; nullopt for anything else ("0x10", "inf", "nan", "1e", " 5") and beyond a double.
/// std::from_chars in its general format reads no hexadecimal and no '+' (taken off first); a
/// regular expression took a sixth of a short command's instructions to compile.
inline std::optional<double> DecimalValue(const std::string& s) {
  const char* first = s.data();
  const char* const last = first + s.size();
  if (last - first > 1 && *first == '+' &&
      (std::isdigit(static_cast<unsigned char>(first[1])) || first[1] == '.'))
    ++first;
  double v = NAN;
  const auto [end, error] = std::from_chars(first, last, v, std::chars_format::general);
  if (error != std::errc() || end != last || !std::isfinite(v)) return std::nullopt;
  return v;
}

/// A number in [lo, hi] (`what` names the quantity and unit, e.g. "a speed in rpm").
inline CLI::Validator NumberIn(double lo, double hi, const std::string& what) {
  return CLI::Validator(
      [lo, hi, what](std::string& s) -> std::string {
        const std::optional<double> v = DecimalValue(s);
        if (v && *v >= lo && *v <= hi) return {};
        return RangeRule(lo, hi, what, s);
      },
      what, "");
}

/// Whether `s` is decimal digits only; if so, without its leading zeros ("007" → "7").
inline bool DropLeadingZeros(std::string& s) {
  if (s.empty() || s.find_first_not_of("0123456789") != std::string::npos) return false;
  s.erase(0, std::min(s.find_first_not_of('0'), s.size() - 1));
  return true;
}

/// A whole number in `r` in decimal digits, its leading zeros dropped (a transform: CLI11 reads
/// the value after it, and would take "010" as octal).
inline CLI::Validator WholeIn(const PlausibleRange& r, const std::string& what) {
  return CLI::Validator(
      [r, what](std::string& s) -> std::string {
        const std::string given = s;
        if (DropLeadingZeros(s) && s.size() <= 15 && std::stod(s) >= r.lo && std::stod(s) <= r.hi)
          return {};
        return "expected " + what + " in [" + std::to_string(std::llround(r.lo)) + ", " +
               std::to_string(std::llround(r.hi)) + "], got " + given;
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

/// A method of the method table or "auto", checked when the option is read: before the case is
/// loaded, so a wrong name is reported as the option's fault whatever the case holds.
inline CLI::Validator KnownMethod() {
  return CLI::Validator([](std::string& s) { return MethodNameFault(s); }, "METHOD", "");
}

/// The dynamic commands' `--method` and `--rtol` (simulate, overspeed): each defaults to the
/// case's [solver] (then auto and 1e-8); the tolerance is held to kRtolRange.
inline void AddMethodOptions(CLI::App* cmd, std::optional<std::string>& method,
                             std::optional<double>& rtol) {
  cmd->add_option("--method", method, MethodList() + " (default: [solver] method or auto)")
      ->check(KnownMethod());
  cmd->add_option("--rtol", rtol, "relative tolerance (default: [solver] rtol or 1e-8)")
      ->check(InRange(kRtolRange, "a relative tolerance"));
}

/// A 64-bit seed: digits only, at most 18446744073709551615 (CLI11 alone took a longer number
/// without a word), its leading zeros dropped (a transform, as WholeIn).
inline CLI::Validator Seed() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        const std::string given = s;
        if (DropLeadingZeros(s) &&
            (s.size() < 20 || (s.size() == 20 && s <= "18446744073709551615")))
          return {};
        return "expected a whole number in " + RangeText(kSeedRange) + ", got " + given;
      },
      "SEED", "");
}

}  // namespace needle
