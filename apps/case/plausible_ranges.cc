#include "apps/case/plausible_ranges.h"

#include <cmath>
#include <sstream>

#include "apps/case/case_file.h"

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

const RangedKey* FindRangedKey(const std::string& section, const std::string& name) {
  for (const RangedKey& k : kRangedKeys) {
    if (section == k.section && name == k.name) return &k;
  }
  return nullptr;
}

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
  std::string out =
      "| quantity | plausible range | case-file keys and options | why |\n"
      "| --- | --- | --- | --- |\n";
  const PlausibleRange* done[sizeof kRangedKeys / sizeof kRangedKeys[0]] = {};
  size_t n_done = 0;
  for (const RangedKey& k : kRangedKeys) {
    bool seen = false;
    for (size_t i = 0; i < n_done; ++i) seen = seen || done[i] == k.range;
    if (seen) continue;
    done[n_done++] = k.range;
    std::string where;
    for (const RangedKey& other : kRangedKeys) {
      if (other.range != k.range) continue;
      const std::string section(other.section);
      where += where.empty() ? "" : ", ";
      where += section.empty() ? std::string("`") + other.name + "`"
                               : "`[" + section + "] " + other.name + "`" +
                                     (other.upper_only ? " (entries: upper end)" : "");
    }
    out += std::string("| ") + k.range->quantity + " | " + RangeText(*k.range) + " | " + where +
           " | " + k.range->reason + " |\n";
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
