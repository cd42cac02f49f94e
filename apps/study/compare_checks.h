#pragma once
/// @file
/// The compare job: two designs checked as `needle check` checks them (CheckScene) and set side
/// by side item by item: every number, yes/no, verdict and status of each check, matched by its
/// path, and the verdicts that flip (pass against fail) apart from those that only differ.
/// `needle compare` and the Python module call it; the writers are in
/// apps/report/compare_writer.h.

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apps/case/bound_case.h"
#include "apps/study/check_scene.h"
#include "lib/lift_law.h"
#include "lib/spline.h"

namespace needle {

/// One value of a check as compare reads it: a number in its display unit, a whole number, a
/// yes/no, a text, or none (a number the check does not have).
struct CheckValue {
  enum class Kind { kNone, kNumber, kCount, kFlag, kText };
  Kind kind = Kind::kNone;
  double number = 0.0;  ///< kNumber, kCount
  bool flag = false;    ///< kFlag
  std::string text;     ///< kText

  bool is_number() const { return kind == Kind::kNumber || kind == Kind::kCount; }
  /// Equal kinds and values; a number and a whole number compare by value.
  bool operator==(const CheckValue& o) const;
  bool operator!=(const CheckValue& o) const { return !(*this == o); }
};

/// A reported item of a check: its path in `check --json` ("spring.preload_N",
/// "limits.KEY.verdict") and its value.
struct CheckItem {
  std::string key;
  CheckValue value;
};

/// Every item of a check compare sets side by side, in the order `check --json` lists them
/// (members by key at each level; the limits rows in their order, each row's verdict, value and
/// margin): its numbers, yes/no values and counts, the overall verdict, the statuses and the
/// spline kind. Lists (failing, warnings) and the texts that only explain are left out.
std::vector<CheckItem> CheckItems(const CheckResult& result, SplineKind spline);

/// One item of both designs.
struct ComparedItem {
  std::string key;
  CheckValue a, b;       ///< none where a design does not report the item (or does not judge it)
  bool verdict = false;  ///< not a number: a verdict or a text, shown in the verdict table
  /// Both sides are pass/fail (a yes/no, "pass" or "fail") and they differ: counts for exit 1.
  bool flips = false;
  /// A verdict or text that differs without flipping (a spline kind, a status, "pass" against
  /// "not judged" or absent): listed, not counted.
  bool differs = false;
};

/// The items of two checks matched by key, in A's order then B's extras.
std::vector<ComparedItem> CompareChecks(const std::vector<CheckItem>& a,
                                        const std::vector<CheckItem>& b);

/// One design checked: the case, its lift law and the check.
struct CheckedDesign {
  BoundCase c;
  std::shared_ptr<const LiftLaw> law;
  CheckResult result;
};

/// Two designs checked and set side by side.
struct Comparison {
  CheckedDesign a, b;
  std::vector<ComparedItem> items;     ///< every item of both
  std::vector<std::string> flipped;    ///< the keys of the verdicts that flip
  std::vector<std::string> differing;  ///< the keys of the verdicts and texts that only differ
  std::vector<std::string> unlike;     ///< why the two are not like for like (empty: they are)
  int status() const { return flipped.empty() ? 0 : 1; }  ///< exit 1 when a verdict flips
};

/// Checks both cases as `check` does (at `speed_rpm` when given, else each case's own) and
/// compares them. `progress` gets the runs done of both sweeps.
Comparison CompareCases(BoundCase a, BoundCase b, std::optional<double> speed_rpm,
                        const std::function<void(int, int)>& progress = {});

}  // namespace needle
