#pragma once
/// @file
/// The writers that consume a result's field table (lib/result_fields.h): JSON members and
/// text values. A command formats; it does not convert units itself.

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lib/lift_data.h"
#include "lib/output.h"
#include "lib/result_fields.h"

namespace needle {

/// Sets j[field.Key()] to each field's shown value, or null when it has none.
/// A number for JSON: the value when finite, else null (JSON has no NaN or infinity).
inline nlohmann::json Finite(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

inline void PutFields(nlohmann::json& j, const std::vector<Field>& fields) {
  for (const Field& f : fields) {
    const auto v = f.Shown();
    if (f.kind == Field::Kind::kText) {
      j[f.Key()] = f.text;
    } else if (f.kind == Field::Kind::kFlag) {
      j[f.Key()] = f.flag;
    } else if (f.kind == Field::Kind::kList) {
      nlohmann::json list = nlohmann::json::array();
      for (double si : f.list_si) list.push_back(f.unit.FromSi(si));
      j[f.Key()] = list;
    } else if (!v) {
      j[f.Key()] = nullptr;
    } else if (f.count) {
      j[f.Key()] = static_cast<long long>(*v);
    } else {
      j[f.Key()] = *v;
    }
  }
}

/// Whether a number field shows at its decimals: a warning about a value that prints as
/// "0.0000" would say nothing (a spline's dip of 1e-16 mm at a table's last point).
inline bool Shows(const Field& f) {
  const auto v = f.Shown();
  return v && Fixed(std::abs(*v), f.decimals) != Fixed(0.0, f.decimals);
}

/// One row of a table as a JSON object: each column's Key() to its SI value shown in its
/// unit, or null for a NaN (a missing value).
inline nlohmann::json RowObject(const std::vector<Column>& columns,
                                const std::vector<double>& row_si) {
  nlohmann::json row = nlohmann::json::object();
  for (size_t k = 0; k < columns.size(); ++k)
    row[columns[k].Key()] = std::isnan(row_si[k])
                                ? nlohmann::json(nullptr)
                                : nlohmann::json(columns[k].unit.FromSi(row_si[k]));
  return row;
}

/// "value" with the field's decimals (no unit; a count as an integer; a list space separated),
/// or "none".
inline std::string ValueText(const Field& f) {
  if (f.kind == Field::Kind::kText) return f.text;
  if (f.kind == Field::Kind::kFlag) return f.flag ? "yes" : "no";
  if (f.kind == Field::Kind::kList) {
    std::string s;
    for (double si : f.list_si) s += (s.empty() ? "" : " ") + Fixed(f.unit.FromSi(si), f.decimals);
    return s;
  }
  const auto v = f.Shown();
  if (!v) return "none";
  return f.count ? std::to_string(static_cast<long long>(*v)) : Fixed(*v, f.decimals);
}

/// "value unit" in the field's display unit, or "none".
inline std::string FieldText(const Field& f) {
  if (f.kind != Field::Kind::kNumber) return ValueText(f);
  const auto v = f.Shown();
  if (!v) return "none";
  return f.unit.text[0] == '\0' ? Fixed(*v, f.decimals) : Fixed(*v, f.decimals) + " " + f.unit.text;
}

/// A JSON array of records, one object per item, each from its field table `fields_of(item)`.
template <class Items, class FieldsOf>
nlohmann::json RecordList(const Items& items, const FieldsOf& fields_of) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& item : items) {
    list.push_back(nlohmann::json::object());
    PutFields(list.back(), fields_of(item));
  }
  return list;
}

/// FieldText of the field named `key` in `fields`.
inline std::string TextAt(const std::vector<Field>& fields, const std::string& key) {
  return FieldText(FieldAt(fields, key));
}

/// The lift table's warnings, one "WARNING: …" line each: a rise or return it does not resolve
/// (lib/lift_data.h UnresolvedSides; `runs`, e.g. "the run reads", who reads the law fitted
/// there, or none) and an end above the seat (OffSeatEnds).
inline std::string LiftTableWarnings(const LiftLawChoice& choice, const LiftLaw& law,
                                     const char* runs = nullptr) {
  std::string out;
  if (const std::string w = UnresolvedSides(choice.table); !w.empty()) {
    out += std::string("WARNING: ") +
           (runs ? std::string(runs) + " the lift law fitted where " : "") + w + "\n";
  }
  if (const std::string w = OffSeatEnds(law); !w.empty()) out += "WARNING: " + w + "\n";
  return out;
}
/// The same as JSON members: "unresolved" and "off_seat".
inline void PutLiftTableWarnings(nlohmann::json& j, const LiftLawChoice& choice,
                                 const LiftLaw& law) {
  if (const std::string w = UnresolvedSides(choice.table); !w.empty()) j["unresolved"] = w;
  if (const std::string w = OffSeatEnds(law); !w.empty()) j["off_seat"] = w;
}

}  // namespace needle
