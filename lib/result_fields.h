#pragma once
/// @file
/// How a result describes its fields once, for every writer: a name, the SI value and the
/// unit it is shown in. The JSON key and the CSV header are `name_unit` (`max_lift_mm`,
/// `jump_deg`), the text shows `value unit`; the conversion from SI happens here and nowhere
/// else:
///
///     shown = SI · factor   (mm, MPa, …)   or   SI / factor   (deg: rad / (π/180)).
///
/// Writers that consume these tables: apps/report/result_writers.h (JSON, CSV, text).

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace needle {

/// A display unit: its key suffix (`mm_rad`), its text (`mm/rad`), its factor from SI and the
/// key suffix of the SI unit it converts from (`m_rad`).
struct DisplayUnit {
  const char* key;          ///< suffix of JSON keys and CSV headers; "" for plain numbers
  const char* text;         ///< as printed after a value; "" for plain numbers
  double factor;            ///< > 0
  bool divide = false;      ///< shown = SI / factor (angles); otherwise SI · factor
  const char* si_key = "";  ///< suffix of the SI value's key (`rad`, `m`); "" for plain numbers

  /// The SI value in this unit.
  double FromSi(double si) const { return divide ? si / factor : si * factor; }
};

/// The display units results use (one table).
namespace display {
extern const DisplayUnit kNone;             ///< a plain number (a ratio, a count)
extern const DisplayUnit kMm;               ///< m → mm
extern const DisplayUnit kDegree;           ///< rad → deg
extern const DisplayUnit kN;                ///< N
extern const DisplayUnit kRpm;              ///< rpm (speeds are kept in rpm at the edges)
extern const DisplayUnit kMPerS;            ///< m/s
extern const DisplayUnit kMPerS2;           ///< m/s² (text m/s^2)
extern const DisplayUnit kMPerS3;           ///< m/s³ (text m/s^3)
extern const DisplayUnit kMs;               ///< s → ms
extern const DisplayUnit kS;                ///< s
extern const DisplayUnit kMPa;              ///< Pa → MPa
extern const DisplayUnit kMmPerRad;         ///< m/rad → mm/rad (a cam law's S')
extern const DisplayUnit kMmPerRad2;        ///< m/rad² → mm/rad² (S'')
extern const DisplayUnit kMmPerRad3;        ///< m/rad³ → mm/rad³ (S''')
extern const DisplayUnit kKgForce;          ///< N → kgf (÷ g₀)
extern const DisplayUnit kNPerMm;           ///< N/m → N/mm
extern const DisplayUnit kHz;               ///< Hz
extern const DisplayUnit kMm2;              ///< m² → mm²
extern const DisplayUnit kCm3;              ///< cm³ (the design chain's volumes, kept in cm³)
extern const DisplayUnit kGram;             ///< g (the design chain's fuel, kept in g)
extern const DisplayUnit kHp;               ///< W → HP (metric, ÷ 735.49875)
extern const DisplayUnit kPercent;          ///< a percentage
extern const DisplayUnit kFractionPercent;  ///< a fraction (0.05) shown in % (5)
extern const DisplayUnit kJoule;            ///< J
extern const DisplayUnit kKg;               ///< kg
}  // namespace display

/// One value of a result: a number (`si`; a count when `count`), or with `kind` a string, a
/// yes/no or a list of numbers. An empty number is shown as null (JSON) or "none" (text).
struct Field {
  /// What the value is; a number unless a helper below says otherwise.
  enum class Kind { kNumber, kText, kFlag, kList };

  std::string name;          ///< key stem, e.g. "max_lift"; the key is name_unit
  DisplayUnit unit;          ///< how it is shown
  std::optional<double> si;  ///< the value in SI (or rpm for speeds)
  int decimals = 3;          ///< digits after the point in text
  /// The JSON key when it is not name_unit (a published key kept as it was, e.g.
  /// `liftoff_rpm_quasi_static`); empty: name_unit.
  std::string key = {};
  /// A count (steps, impacts): written as an integer.
  bool count = false;
  Kind kind = Kind::kNumber;         ///< kText: `text`; kFlag: `flag`; kList: `list_si`
  std::string text = {};             ///< a string value (kText)
  bool flag = false;                 ///< a yes/no value (kFlag)
  std::vector<double> list_si = {};  ///< a list of numbers in SI (kList), shown in `unit`

  /// `key` if set, else name + "_" + unit key (or the name alone for plain numbers).
  std::string Key() const;
  /// The value in its display unit; empty when `si` is.
  std::optional<double> Shown() const;
};

/// `v` when finite, else none (unbounded or undefined: shown as null or "none").
std::optional<double> FiniteOrNone(double v);
/// The field named `key` (its Key()) from a table; throws std::logic_error when absent.
const Field& FieldAt(const std::vector<Field>& fields, const std::string& key);

/// A count (steps, impacts, an index); its key is `name`, written as an integer.
Field CountField(std::string name, long long n);
/// A string-valued field (a name, a reason); its key is `name`.
Field TextField(std::string name, std::string text);
/// A yes/no field; its key is `name`.
Field FlagField(std::string name, bool flag);
/// A list of numbers in SI, shown in `unit` (key name_unit).
Field ListField(std::string name, DisplayUnit unit, std::vector<double> list_si);

/// A named group of fields (a JSON object inside the result's).
struct FieldGroup {
  std::string name;  ///< the member's key
  std::vector<Field> fields;
};

/// One column of a table (a CSV file, a JSON array of rows).
struct Column {
  std::string name;  ///< header stem; the header is name_unit
  DisplayUnit unit;
  std::string Key() const;
  /// name_siunit (`crank_rad`, `S1_m_rad`): the key of the column's SI values.
  std::string SiKey() const;
};

/// A CSV table's header line (with its newline): each column's Key(), comma separated.
std::string CsvHeader(const std::vector<Column>& columns);
/// One CSV row (with its newline): `row_si`'s values (columns.size() of them) converted by
/// their columns' units, with `precision` significant digits; a NaN (a missing value) is
/// left empty. Appended to `out`.
void AppendCsvRow(const std::vector<Column>& columns, const double* row_si, int precision,
                  std::string& out);

/// A CSV table: header from `columns`, each row's SI values converted by its column's unit,
/// printed with `precision` significant digits. Every row has columns.size() values.
std::string CsvTable(const std::vector<Column>& columns,
                     const std::vector<std::vector<double>>& rows_si, int precision);

/// The same table as SI columns, each under its SiKey() (the Python module's arrays).
std::map<std::string, std::vector<double>> SiColumns(
    const std::vector<Column>& columns, const std::vector<std::vector<double>>& rows_si);

}  // namespace needle
