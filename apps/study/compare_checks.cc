#include "apps/study/compare_checks.h"

#include <algorithm>
#include <map>
#include <sstream>
#include <utility>

#include "lib/engine_cycle.h"
#include "lib/result_fields.h"

namespace needle {
namespace {

CheckValue Number(double v) { return {CheckValue::Kind::kNumber, v, false, {}}; }
CheckValue Count(long long v) {
  return {CheckValue::Kind::kCount, static_cast<double>(v), false, {}};
}
CheckValue Flag(bool v) { return {CheckValue::Kind::kFlag, 0.0, v, {}}; }
CheckValue Text(std::string v) { return {CheckValue::Kind::kText, 0.0, false, std::move(v)}; }

// A field as `check --json` writes it (PutFields), or none when compare leaves it out: a list,
// or a text that only explains (only a status, the spline and a row's verdict are items).
std::optional<CheckValue> ValueOf(const Field& f) {
  switch (f.kind) {
    case Field::Kind::kList:
      return std::nullopt;
    case Field::Kind::kText:
      if (f.Key() != "status" && f.Key() != "spline") return std::nullopt;
      return Text(f.text);
    case Field::Kind::kFlag:
      return Flag(f.flag);
    case Field::Kind::kNumber:
      break;
  }
  const std::optional<double> v = f.Shown();
  if (!v) return CheckValue{};
  return f.count ? Count(static_cast<long long>(*v)) : Number(*v);
}

// A yes/no or a text on either side: shown in the verdict table.
bool IsVerdict(const CheckValue& a, const CheckValue& b) {
  const auto kind = [](const CheckValue& v) {
    return v.kind == CheckValue::Kind::kFlag || v.kind == CheckValue::Kind::kText;
  };
  return kind(a) || kind(b);
}

// A pass/fail verdict: a yes/no, or "pass" / "fail" (the overall verdict, a limits row).
// "not judged", a status, a spline kind and none are not.
bool IsPassFail(const CheckValue& v) {
  return v.kind == CheckValue::Kind::kFlag ||
         (v.kind == CheckValue::Kind::kText && (v.text == "pass" || v.text == "fail"));
}

// Why two checked designs are not like for like: a different rated speed or engine cycle.
std::vector<std::string> Unlike(double a_rpm, EngineCycle a_cycle, double b_rpm,
                                EngineCycle b_cycle) {
  std::vector<std::string> why;
  if (a_rpm != b_rpm) {
    std::ostringstream s;
    s << "rated speed: A " << a_rpm << " rpm, B " << b_rpm << " rpm";
    why.push_back(s.str());
  }
  if (a_cycle != b_cycle)
    why.push_back(std::string("cycle: A ") + EngineCycleName(a_cycle) + ", B " +
                  EngineCycleName(b_cycle));
  return why;
}

}  // namespace

bool CheckValue::operator==(const CheckValue& o) const {
  if (is_number() && o.is_number()) return number == o.number;
  if (kind != o.kind) return false;
  switch (kind) {
    case Kind::kFlag:
      return flag == o.flag;
    case Kind::kText:
      return text == o.text;
    default:
      return true;  // none
  }
}

std::vector<CheckItem> CheckItems(const CheckResult& r, SplineKind spline) {
  // By top-level key, each entry's items in order; a std::map gives the keys' order, as a JSON
  // object's members are written.
  std::map<std::string, std::vector<CheckItem>> by_key;
  by_key["speed_rpm"] = {{"speed_rpm", Number(r.speed_rpm)}};
  by_key["overall"] = {{"overall", Text(r.pass ? "pass" : "fail")}};
  std::map<std::string, std::map<std::string, CheckValue>> groups;
  for (const FieldGroup& group : CheckFields(r)) {
    std::map<std::string, CheckValue>& members = groups[group.name];
    for (const Field& f : group.fields)
      if (auto v = ValueOf(f)) members[f.Key()] = *v;
  }
  groups["kinematics"]["spline"] = Text(SplineKindName(spline));
  if (r.harmonics) {
    groups["resonance"]["highest_significant_order"] =
        Count(r.harmonics->highest_significant_order);
  }
  for (const auto& [name, members] : groups)
    for (const auto& [key, value] : members) by_key[name].push_back({name + "." + key, value});
  std::vector<CheckItem>& limits = by_key["limits"];
  for (const LimitRow& row : r.limits) {
    const std::vector<Field> fields = LimitRowFields(row);
    for (const char* key : {"verdict", "value", "margin"}) {
      const Field& f = FieldAt(fields, key);
      limits.push_back({"limits." + row.key + "." + key, f.kind == Field::Kind::kText
                                                             ? Text(f.text)
                                                             : ValueOf(f).value_or(CheckValue{})});
    }
  }
  std::vector<CheckItem> items;
  for (auto& [key, list] : by_key) items.insert(items.end(), list.begin(), list.end());
  return items;
}

std::vector<ComparedItem> CompareChecks(const std::vector<CheckItem>& a,
                                        const std::vector<CheckItem>& b) {
  const auto find = [](const std::vector<CheckItem>& items, const std::string& key) {
    for (const CheckItem& i : items)
      if (i.key == key) return i.value;
    return CheckValue{};
  };
  std::vector<ComparedItem> items;
  for (const CheckItem& i : a) items.push_back({i.key, i.value, find(b, i.key)});
  for (const CheckItem& i : b) {
    if (std::none_of(a.begin(), a.end(), [&](const CheckItem& x) { return x.key == i.key; }))
      items.push_back({i.key, CheckValue{}, i.value});
  }
  for (ComparedItem& i : items) {
    i.verdict = IsVerdict(i.a, i.b);
    i.flips = i.verdict && IsPassFail(i.a) && IsPassFail(i.b) && i.a != i.b;
    i.differs = i.verdict && !i.flips && i.a != i.b;
  }
  return items;
}

Comparison CompareCases(BoundCase a_case, BoundCase b_case, std::optional<double> speed_rpm,
                        const std::function<void(int, int)>& progress) {
  Comparison cmp;
  cmp.a.c = std::move(a_case);
  cmp.b.c = std::move(b_case);
  int done_before = 0;  // the runs of A, when B is checked
  for (CheckedDesign* d : {&cmp.a, &cmp.b}) {
    d->law = d->c.lift.law;
    CheckOptions options;
    options.speed_rpm = speed_rpm;
    if (progress) {
      options.progress = [&](int done, int total) {
        progress(done_before + done, done_before + total);
      };
    }
    d->result = CheckScene(d->c, options);
    if (d->result.sweep) done_before += static_cast<int>(d->result.sweep->rows.size());
  }
  cmp.items = CompareChecks(CheckItems(cmp.a.result, cmp.a.law->kind()),
                            CheckItems(cmp.b.result, cmp.b.law->kind()));
  for (const ComparedItem& i : cmp.items) {
    if (i.flips) cmp.flipped.push_back(i.key);
    if (i.differs) cmp.differing.push_back(i.key);
  }
  cmp.unlike = Unlike(cmp.a.result.speed_rpm, cmp.a.c.engine.cycle, cmp.b.result.speed_rpm,
                      cmp.b.c.engine.cycle);
  return cmp;
}

}  // namespace needle
