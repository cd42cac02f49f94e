// What `check` prints without --json (check_writers.h).
#include <sstream>

#include "apps/report/check_writers.h"
#include "lib/output.h"

namespace needle {

std::string CheckText(const BoundCase& c, const CheckResult& result, const std::string& path,
                      int figures) {
  std::ostringstream out;
  out << (c.title.empty() ? c.path : c.title) << '\n';
  for (const auto& k : result.skipped) out << "skipped: " << k << '\n';
  if (result.spring) out << "spring check: " << (result.spring->pass ? "pass" : "FAIL") << '\n';
  if (result.profile)
    out << "cam profile: " << (result.profile->undercut ? "UNDERCUT" : "no undercut") << '\n';
  if (result.run)
    out << "lift-off at " << Fixed(result.speed_rpm, 0) << " rpm: "
        << (result.run->liftoff() ? "YES" + ShortJumpNote(*result.run)
                                  : "no" + BounceNote(*result.run))
        << '\n';
  if (result.sweep) {
    out << "n_qs " << FixedOrNone(result.n_qs_rpm, 1) << " rpm, n_dyn "
        << OverspeedOutcome(*result.sweep) << '\n';
  }
  if (!result.limits.empty()) {
    out << "limits (value, limit, margin, verdict):\n";
    for (const LimitRow& x : result.limits) {
      const std::string u = x.UnitSuffix();
      const int d = DecimalsApart(x.value, x.limit, 2);
      out << "  " << x.name << ": "
          << (x.verdict == "not judged"
                  ? "not judged (" + x.note + ")"
                  : FixedOrNone(x.value, d) + u + (x.at_most ? " <= " : " >= ") +
                        FixedOrNone(x.limit, d) + u + ", margin " + FixedOrNone(x.margin, d) + u +
                        ", " + x.verdict)
          << '\n';
    }
  }
  for (const auto& w : result.warnings) out << "warns: " << w << '\n';
  for (const auto& f : result.failing) out << "fails: " << f << '\n';
  out << "report: " << path << " (" << figures << " figures)\n"
      << "overall: " << (result.pass ? "pass" : "FAIL")
      << (result.not_judged.empty() ? "" : "; not judged: " + result.not_judged) << '\n';
  return out.str();
}

}  // namespace needle
