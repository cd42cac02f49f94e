#pragma once
/// @file
/// One verdict row, the one type of `needle check`'s limits table (apps/study/limits_table.h,
/// LimitRow) and `needle size`'s rules (spring/spring_sizing.h, SizingRule): a value judged
/// against a limit,
///
///     margin = limit − value  (at most)   or   value − limit  (at least);   pass ⇔ margin ≥ 0
///
/// in the row's display unit (a value that is NaN fails). A check's row may be left "not
/// judged" (what it needs is missing) or made a "warning" by its own rule.

#include <cmath>
#include <string>

namespace needle {

struct VerdictRow {
  std::string key;      ///< JSON name, e.g. "seating_velocity", "coil_gap"
  std::string name;     ///< "seating velocity"
  std::string unit;     ///< display unit, e.g. "m/s", "mm"; empty for a pure number
  double value = NAN;   ///< NaN when not judged
  double limit = NAN;   ///< in `unit`
  bool at_most = true;  ///< passes when value ≤ limit (else value ≥ limit)
  double margin = NAN;  ///< limit − value (at most) or value − limit (at least), in `unit`
  /// "pass", "fail", "warning" (outside a screen, no harm shown) or "not judged".
  std::string verdict = "not judged";
  std::string note;    ///< where or why (not judged: what is missing)
  std::string source;  ///< the limit's source, or "[limits] KEY" when the case sets it

  /// A row not yet judged: its limit, direction and source.
  static VerdictRow Unjudged(std::string key, std::string name, std::string unit, bool at_most,
                             double limit, std::string source = {});
  /// Judges `value` against the limit: the margin and "pass" or "fail"; `note` says where.
  void Judge(double value, std::string note = {});
  bool passes() const { return verdict == "pass"; }
  /// The verdict as a text table shows it: "pass", or "FAIL" when it does not pass.
  std::string Shouted() const { return passes() ? "pass" : "FAIL"; }
  /// How far it fails, as a fraction of the limit (0 when it passes).
  double Violation() const;
  /// " unit" after a number, or nothing for a pure number.
  std::string UnitSuffix() const { return unit.empty() ? "" : " " + unit; }
};

}  // namespace needle
