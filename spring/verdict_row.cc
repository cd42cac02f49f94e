#include "spring/verdict_row.h"

#include <algorithm>
#include <utility>

namespace needle {

VerdictRow VerdictRow::Unjudged(std::string key, std::string name, std::string unit, bool at_most,
                                double limit, std::string source) {
  VerdictRow x;
  x.key = std::move(key);
  x.name = std::move(name);
  x.unit = std::move(unit);
  x.at_most = at_most;
  x.limit = limit;
  x.source = std::move(source);
  return x;
}

void VerdictRow::Judge(double v, std::string where) {
  value = v;
  margin = at_most ? limit - v : v - limit;
  verdict = margin >= 0.0 ? "pass" : "fail";
  note = std::move(where);
}

double VerdictRow::Violation() const {
  if (passes()) return 0.0;
  return -margin / std::max(std::abs(limit), 1e-300);
}

}  // namespace needle
