#include "apps/case/plausible_ranges.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "apps/case/case_file.h"
#include "apps/case/case_keys.h"

namespace needle {
namespace {

std::string Shown(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string WithUnit(const PlausibleRange& r, const std::string& number) {
  return std::string(r.unit).empty() ? number : number + " " + r.unit;
}

}  // namespace

std::string RangeText(const PlausibleRange& r) {
  // The seed's end is a whole number a double cannot show.
  if (&r == &kSeedRange) return "[0, 18446744073709551615]";
  return WithUnit(r, "[" + Shown(r.lo / r.unit_si) + ", " + Shown(r.hi / r.unit_si) + "]");
}

std::string ShownValue(const PlausibleRange& r, double si) {
  return WithUnit(r, Shown(si / r.unit_si));
}

std::string AboveRangeEnd(const PlausibleRange& r, double si) {
  return ShownValue(r, si) + " is above the plausible range's end " + ShownValue(r, r.hi) +
         " (docs/ranges.md)";
}

std::string PlausibleRangesMarkdown() {
  // Where each range applies: the case file's keys, the synthesis file's [checks], the options.
  struct Use {
    const PlausibleRange* range;
    std::string where;
  };
  std::vector<Use> uses;
  const auto add = [&uses](const PlausibleRange* range, const std::string& where) {
    auto it =
        std::find_if(uses.begin(), uses.end(), [&](const Use& u) { return u.range == range; });
    if (it == uses.end()) {
      uses.push_back({range, where});
    } else {
      it->where += ", " + where;
    }
  };
  for (CaseKeyList keys : {CaseFileKeys(), SynthesisCheckKeys()}) {
    for (const CaseKey& k : keys) {
      if (k.range)
        add(k.range, std::string("`[") + k.section + "] " + k.name + "`" +
                         (k.upper_only ? " (entries: upper end)" : ""));
    }
  }
  for (const RangedOption& o : kRangedOptions) add(o.range, std::string("`") + o.name + "`");
  std::string out =
      "| quantity | plausible range | case-file keys and options | why |\n"
      "| --- | --- | --- | --- |\n";
  for (const Use& u : uses) {
    out += std::string("| ") + u.range->quantity + " | " + RangeText(*u.range) + " | " + u.where +
           " | " + u.range->reason + " |\n";
  }
  for (const DerivedRange& d : kDerivedRanges) {
    out += std::string("| ") + d.range->quantity + " | " + RangeText(*d.range) + " | " + d.keys +
           " | " + d.range->reason + " |\n";
  }
  return out;
}

std::string RangeRule(double lo, double hi, const std::string& what, const std::string& v) {
  std::ostringstream m;
  m << "expected " << what << " in [" << lo << ", " << hi << "], got " << v;
  return m.str();
}

void RequireIn(const std::string& option, const std::optional<double>& v, double lo, double hi,
               const std::string& what) {
  if (!v || (std::isfinite(*v) && *v >= lo && *v <= hi)) return;
  std::ostringstream text;
  text << *v;
  throw CaseError(option + ": " + RangeRule(lo, hi, what, text.str()));
}

void RequireSpeed(const std::optional<double>& rpm, const std::string& option) {
  RequireIn(option, rpm, kCrankSpeedRange.lo, kCrankSpeedRange.hi, "a speed in rpm");
}

}  // namespace needle
