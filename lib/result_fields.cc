#include "lib/result_fields.h"

#include <sstream>
#include <stdexcept>

#include "lib/units.h"

namespace needle {
namespace display {
const DisplayUnit kNone{"", "", 1.0};
const DisplayUnit kMm{"mm", "mm", 1e3};
const DisplayUnit kDegree{"deg", "deg", ::needle::kDeg, true};
const DisplayUnit kN{"N", "N", 1.0};
const DisplayUnit kRpm{"rpm", "rpm", 1.0};
const DisplayUnit kMPerS{"m_s", "m/s", 1.0};
const DisplayUnit kS{"s", "s", 1.0};
const DisplayUnit kMPa{"MPa", "MPa", 1e-6};
const DisplayUnit kMmPerRad{"mm_rad", "mm/rad", 1e3};
const DisplayUnit kMmPerRad2{"mm_rad2", "mm/rad2", 1e3};
const DisplayUnit kMmPerRad3{"mm_rad3", "mm/rad3", 1e3};
}  // namespace display

namespace {
std::string KeyOf(const std::string& name, const DisplayUnit& unit) {
  return unit.key[0] == '\0' ? name : name + "_" + unit.key;
}
}  // namespace

std::string Field::Key() const { return key.empty() ? KeyOf(name, unit) : key; }

std::optional<double> Field::Shown() const {
  if (!si) return std::nullopt;
  return unit.FromSi(*si);
}

std::string Column::Key() const { return KeyOf(name, unit); }

std::string CsvTable(const std::vector<Column>& columns,
                     const std::vector<std::vector<double>>& rows_si, int precision) {
  std::ostringstream csv;
  csv.precision(precision);
  for (size_t i = 0; i < columns.size(); ++i) csv << (i ? "," : "") << columns[i].Key();
  csv << '\n';
  for (const auto& row : rows_si) {
    if (row.size() != columns.size())
      throw std::logic_error("CsvTable: a row has " + std::to_string(row.size()) + " values for " +
                             std::to_string(columns.size()) + " columns");
    for (size_t i = 0; i < row.size(); ++i) csv << (i ? "," : "") << columns[i].unit.FromSi(row[i]);
    csv << '\n';
  }
  return csv.str();
}

}  // namespace needle
