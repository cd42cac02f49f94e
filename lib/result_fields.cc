#include "lib/result_fields.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "lib/units.h"

namespace needle {
namespace display {
const DisplayUnit kNone{"", "", 1.0};
const DisplayUnit kMm{"mm", "mm", 1e3, false, "m"};
const DisplayUnit kDegree{"deg", "deg", ::needle::kDeg, true, "rad"};
const DisplayUnit kN{"N", "N", 1.0, false, "N"};
const DisplayUnit kRpm{"rpm", "rpm", 1.0, false, "rpm"};
const DisplayUnit kMPerS{"m_s", "m/s", 1.0, false, "m_s"};
const DisplayUnit kMPerS2{"m_s2", "m/s^2", 1.0, false, "m_s2"};
const DisplayUnit kMPerS3{"m_s3", "m/s^3", 1.0, false, "m_s3"};
const DisplayUnit kMs{"ms", "ms", 1e3, false, "s"};
const DisplayUnit kS{"s", "s", 1.0, false, "s"};
const DisplayUnit kMPa{"MPa", "MPa", 1e-6, false, "Pa"};
const DisplayUnit kMmPerRad{"mm_rad", "mm/rad", 1e3, false, "m_rad"};
const DisplayUnit kMmPerRad2{"mm_rad2", "mm/rad2", 1e3, false, "m_rad2"};
const DisplayUnit kMmPerRad3{"mm_rad3", "mm/rad3", 1e3, false, "m_rad3"};
const DisplayUnit kKgForce{"kgf", "kgf", ::needle::kKgf, true, "N"};
const DisplayUnit kNPerMm{"N_mm", "N/mm", 1e-3, false, "N_m"};
const DisplayUnit kHz{"hz", "Hz", 1.0, false, "hz"};
const DisplayUnit kMm2{"mm2", "mm2", 1e6, false, "m2"};
const DisplayUnit kCm3{"cm3", "cm3", 1.0, false, "cm3"};
const DisplayUnit kGram{"g", "g", 1.0, false, "g"};
const DisplayUnit kHp{"hp", "HP", 735.49875, true, "W"};
const DisplayUnit kPercent{"percent", "%", 1.0, false, "percent"};
const DisplayUnit kFractionPercent{"percent", "%", 100.0, false, "fraction"};
const DisplayUnit kJoule{"J", "J", 1.0, false, "J"};
const DisplayUnit kKg{"kg", "kg", 1.0, false, "kg"};
}  // namespace display

namespace {
std::string KeyOf(const std::string& name, const char* suffix) {
  return suffix[0] == '\0' ? name : name + "_" + suffix;
}
}  // namespace

std::string Field::Key() const { return key.empty() ? KeyOf(name, unit.key) : key; }

std::optional<double> Field::Shown() const {
  if (!si) return std::nullopt;
  return unit.FromSi(*si);
}

std::optional<double> FiniteOrNone(double v) {
  return std::isfinite(v) ? std::optional<double>(v) : std::nullopt;
}

const Field& FieldAt(const std::vector<Field>& fields, const std::string& key) {
  for (const Field& f : fields)
    if (f.Key() == key) return f;
  throw std::logic_error("no result field " + key);
}

Field CountField(std::string name, long long n) {
  return Field{std::move(name), display::kNone, static_cast<double>(n), 0, "", true};
}

Field TextField(std::string name, std::string text) {
  Field f{std::move(name), display::kNone, std::nullopt};
  f.kind = Field::Kind::kText;
  f.text = std::move(text);
  return f;
}

Field FlagField(std::string name, bool flag) {
  Field f{std::move(name), display::kNone, std::nullopt};
  f.kind = Field::Kind::kFlag;
  f.flag = flag;
  return f;
}

Field ListField(std::string name, DisplayUnit unit, std::vector<double> list_si) {
  Field f{std::move(name), unit, std::nullopt};
  f.kind = Field::Kind::kList;
  f.list_si = std::move(list_si);
  return f;
}

std::string Column::Key() const { return KeyOf(name, unit.key); }
std::string Column::SiKey() const { return KeyOf(name, unit.si_key); }

std::string CsvHeader(const std::vector<Column>& columns) {
  std::string line;
  for (size_t i = 0; i < columns.size(); ++i) line += (i ? "," : "") + columns[i].Key();
  return line + '\n';
}

void AppendCsvRow(const std::vector<Column>& columns, const double* row_si, int precision,
                  std::string& out) {
  thread_local std::ostringstream csv;  // one stream for every row: no locale set-up per row
  csv.str(std::string());
  csv.precision(precision);
  for (size_t i = 0; i < columns.size(); ++i) {
    if (i) csv << ',';
    if (!std::isnan(row_si[i])) csv << columns[i].unit.FromSi(row_si[i]);  // NaN: left empty
  }
  csv << '\n';
  out += csv.str();
}

std::string CsvTable(const std::vector<Column>& columns,
                     const std::vector<std::vector<double>>& rows_si, int precision) {
  std::string csv = CsvHeader(columns);
  for (const auto& row : rows_si) {
    if (row.size() != columns.size())
      throw std::logic_error("CsvTable: a row has " + std::to_string(row.size()) + " values for " +
                             std::to_string(columns.size()) + " columns");
    AppendCsvRow(columns, row.data(), precision, csv);
  }
  return csv;
}

std::map<std::string, std::vector<double>> SiColumns(
    const std::vector<Column>& columns, const std::vector<std::vector<double>>& rows_si) {
  std::map<std::string, std::vector<double>> out;
  for (size_t i = 0; i < columns.size(); ++i) {
    std::vector<double>& column = out[columns[i].SiKey()];
    for (const auto& row : rows_si) column.push_back(row.at(i));
  }
  return out;
}

}  // namespace needle
