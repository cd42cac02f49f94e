// Lift tables from CSV files (lib/lift_data.h).
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>
#include <sstream>
#include <string_view>

#include "lib/case_error.h"
#include "lib/input_file.h"
#include "lib/lift_data.h"
#include "lib/output.h"
#include "lib/units.h"

namespace needle {
namespace {

std::string_view Trim(std::string_view s) {
  const size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string_view::npos) return {};
  const size_t b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

// A field as a spreadsheet writes it: trimmed, and one pair of enclosing double quotes (Calc
// quotes its text cells, the header) removed.
std::string_view Unquote(std::string_view s) {
  const std::string_view t = Trim(s);
  if (t.size() >= 2 && t.front() == '"' && t.back() == '"') return Trim(t.substr(1, t.size() - 2));
  return t;
}

// The fields between separators (an empty one after a trailing separator); none of "". Views
// into `line`, into `out` (reused from row to row: a table of a million rows allocates once).
void Fields(std::string_view line, char separator, std::vector<std::string_view>* out) {
  out->clear();
  if (line.empty()) return;
  for (size_t start = 0;;) {
    const size_t end = line.find(separator, start);
    out->push_back(Unquote(line.substr(start, end == std::string_view::npos ? end : end - start)));
    if (end == std::string_view::npos) return;
    start = end + 1;
  }
}

std::string Quoted(char c) { return std::string("'") + c + "'"; }

// std::from_chars reads a plain decimal number (correctly rounded, as strtod does) at a fraction
// of strtod's cost; anything else (hex, inf, out of range, a subnormal, a zero that may be an
// underflow) is left to strtod and its messages: nullopt.
std::optional<double> PlainDecimal(std::string_view number) {
  const char* first = number.data() + (number.size() > 1 && number[0] == '+' ? 1 : 0);
  const char* last = number.data() + number.size();
  double x = 0.0;
  const auto [ptr, ec] = std::from_chars(first, last, x);
  if (ec == std::errc() && ptr == last && std::isfinite(x) &&
      std::abs(x) >= std::numeric_limits<double>::min() &&
      (first == number.data() || *first != '-')) {
    return x;
  }
  return std::nullopt;
}

// The number in `field` of column `name` (decimal mark ',' when the separator is ';'); `why` set
// to what is wrong with it otherwise.
double FieldValue(std::string_view field_view, char separator, const std::string& name,
                  std::string& why) {
  if (separator != ';') {  // decimal mark '.': a plain number is read where it lies
    if (const std::optional<double> x = PlainDecimal(field_view)) return *x;
  }
  const std::string field(field_view);
  std::string number = field;
  if (separator == ';') {  // the decimal mark is ','
    if (field.find('.') != std::string::npos) {
      why = "'" + field + "' has a '.' in a table separated by " + Quoted(separator) +
            ", whose decimal mark is ',' ('.' may be a thousands separator); write it "
            "without thousands separators and with a decimal comma, or save the table "
            "with ',' between columns and '.' as the decimal mark";
      return NAN;
    }
    for (char& ch : number) {
      if (ch == ',') ch = '.';
    }
  } else if (separator == '\t' && field.find(',') != std::string::npos) {
    why = "'" + field +
          "' has a ',' in a tab-separated table, whose decimal mark is '.'; save "
          "it with '.' as the decimal mark, or separated by ';' with decimal commas";
    return NAN;
  }
  if (separator == ';') {
    if (const std::optional<double> x = PlainDecimal(number)) return *x;
  }
  char* end = nullptr;
  errno = 0;
  const double x = number.empty() ? NAN : std::strtod(number.c_str(), &end);
  if (number.empty() || end != number.c_str() + number.size()) {
    why = "'" + field + "' is not a number (column " + name + ")";
  } else if (!std::isfinite(x) || errno == ERANGE) {
    why = "'" + field + "' is not a finite number (column " + name + ")";
  }
  return x;
}

}  // namespace

namespace {

[[noreturn]] void CsvFail(const std::string& path, int line, int column, const std::string& what) {
  std::string where = path + ":" + std::to_string(line);
  if (column > 0) where += ":" + std::to_string(column);
  throw CaseError(where + ": " + what);
}

// The column separator, from the header: ',' (decimal mark '.'), or ';' when the header has
// ';' and no ',' (a spreadsheet in a locale whose decimal mark is ',': 12,5), or a tab when it
// has tabs and neither (a spreadsheet's "tab-separated" export; decimal mark '.').
char Separator(const std::string& header, const std::string& path, int line) {
  const bool semicolon = header.find(';') != std::string::npos;
  const bool comma = header.find(',') != std::string::npos;
  if (semicolon && comma) {
    CsvFail(path, line, 0,
            "the header has both ';' and ',', so the separator is ambiguous; separate the "
            "columns with ',' (decimal mark '.') or with ';' (decimal mark ',')");
  }
  return semicolon ? ';' : comma || header.find('\t') == std::string::npos ? ',' : '\t';
}

// The header's columns: which field is the angle, the lift and (a trace's) time, and the scale
// from each column's unit to SI.
struct CsvColumns {
  int angle = -1, lift = -1, time = -1, count = 0;
  bool empty_last = false;  // a trailing separator's empty last column
  double angle_scale = 0.0, lift_scale = 0.0, time_scale = 0.0;
  std::string angle_name, lift_name, time_name;
};

CsvColumns ReadHeader(const std::vector<std::string>& f, const std::string& path, int line,
                      EngineCycle cycle, bool with_time) {
  CsvColumns c;
  c.count = static_cast<int>(f.size());
  for (int k = 0; k < c.count; ++k) {
    // Names as a spreadsheet may case them (Crank_Deg); an empty last one is a trailing
    // separator's, its column read by none (every row ends with the same empty field).
    std::string name = f[k];
    std::transform(name.begin(), name.end(), name.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    if (name.empty() && k + 1 == c.count && k > 0) {
      c.empty_last = true;
      continue;
    }
    if (name == "crank_deg" || name == "cam_deg") {
      if (c.angle >= 0) CsvFail(path, line, k + 1, "two angle columns; keep one");
      c.angle = k;
      c.angle_name = name;
      c.angle_scale = kDeg * (name == "cam_deg" ? CrankTurnsPerCycle(cycle) : 1.0);
    } else if (name == "lift_mm" || name == "lift_um" || name == "lift_in" || name == "lift_m") {
      if (c.lift >= 0) CsvFail(path, line, k + 1, "two lift columns; keep one");
      c.lift = k;
      c.lift_name = name;
      c.lift_scale =
          name == "lift_in" ? kInchMm * 1e-3 : ToSi(Dimension::kLength, name.substr(5), 1.0);
    } else if (with_time && (name == "time_s" || name == "time_ms")) {
      if (c.time >= 0) CsvFail(path, line, k + 1, "two time columns; keep one");
      c.time = k;
      c.time_name = name;
      c.time_scale = name == "time_ms" ? 1e-3 : 1.0;
    } else if (name == "crank" || name == "cam" || name == "lift" || name == "angle") {
      CsvFail(
          path, line, k + 1,
          "column '" + f[k] + "' needs a unit: " +
              (name == "lift" ? "lift_mm, lift_um, lift_in or lift_m" : "crank_deg or cam_deg"));
    } else {
      CsvFail(path, line, k + 1,
              "unknown column '" + f[k] +
                  "'; expected a header of crank_deg (or cam_deg) and lift_mm (or lift_um, "
                  "lift_in, lift_m)" +
                  (with_time ? std::string(", and optionally time_s (or time_ms)") : ""));
    }
  }
  if (c.angle < 0)
    CsvFail(path, line, 0, "the header has no angle column; expected crank_deg or cam_deg");
  if (c.lift < 0)
    CsvFail(path, line, 0,
            "the header has no lift column; expected lift_mm, lift_um, lift_in or lift_m");
  return c;
}

// Plausible readings (lib/lift_data.h), shown in the column's own unit: `v` as written, `si`
// in rad and m.
void CheckPlausible(const std::string& path, int line, const CsvColumns& c, const double v[2],
                    const double si[2]) {
  const double limits[2] = {kMaxCrankRad / c.angle_scale, kMaxLiftM / c.lift_scale};
  const int cols[2] = {c.angle, c.lift};
  const std::string* names[2] = {&c.angle_name, &c.lift_name};
  const char* ranges[2] = {
      "a crank angle within ±720°, a four-stroke cycle either side of dead centre",
      "a lift within ±1 m"};
  for (int k = 0; k < 2; ++k) {
    if (!(std::abs(si[k]) <= (k == 0 ? kMaxCrankRad : kMaxLiftM))) {
      std::ostringstream m;
      m << *names[k] << " " << v[k] << " is outside the plausible range ±" << limits[k] << " "
        << names[k]->substr(names[k]->find('_') + 1) << " (" << ranges[k]
        << "); a typo or a unit mix-up?";
      CsvFail(path, line, cols[k] + 1, m.str());
    }
  }
}

}  // namespace

LiftTable ParseLiftCsv(const std::string& text, const std::string& path, EngineCycle cycle,
                       std::vector<int>* lines, std::vector<double>* time_s) {
  if (lines) lines->clear();
  if (time_s) time_s->clear();
  // A UTF-8 byte-order mark (Excel's "CSV UTF-8", Calc with the option) is no part of the header.
  constexpr char kUtf8Bom[] = "\xEF\xBB\xBF";
  const bool bom = text.compare(0, 3, kUtf8Bom) == 0;
  if (text.compare(0, 2, "\xFF\xFE") == 0 || text.compare(0, 2, "\xFE\xFF") == 0) {
    CsvFail(path, 1, 0,
            "the file is UTF-16 (it starts with a UTF-16 byte-order mark); save it as UTF-8");
  }
  const std::string_view text_all = std::string_view(text).substr(bom ? 3 : 0);
  int line = 0, last_line = 0;
  double last_angle = 0.0;  // as written, for a refusal's message
  char separator = ',';
  CsvColumns c;
  LiftTable t;
  std::vector<std::string_view> f;
  // The lines, as std::getline splits them; a line ends at LF, CRLF or a CR alone (classic Mac
  // OS, some loggers; a file of such lines with one LF at its end too).
  std::string unified;
  std::string_view all = text_all;
  if (all.find('\r') != std::string_view::npos) {
    unified.reserve(all.size());
    for (size_t k = 0; k < all.size(); ++k) {
      if (all[k] != '\r')
        unified.push_back(all[k]);
      else if (k + 1 == all.size() || all[k + 1] != '\n')
        unified.push_back('\n');
    }
    all = unified;
  }
  for (size_t at = 0; at < all.size();) {
    const size_t end = std::min(all.find('\n', at), all.size());
    const std::string_view raw = all.substr(at, end - at);
    at = end + 1;
    ++line;
    const std::string_view s = Trim(raw);
    if (s.empty() || s[0] == '#') continue;
    const bool header = c.count == 0;
    if (header) separator = Separator(std::string(s), path, line);
    Fields(s, separator, &f);
    if (header) {
      c = ReadHeader(std::vector<std::string>(f.begin(), f.end()), path, line, cycle,
                     time_s != nullptr);
      continue;
    }
    if (static_cast<int>(f.size()) != c.count) {
      CsvFail(path, line, 0,
              "expected " + std::to_string(c.count) + " fields, got " + std::to_string(f.size()));
    }
    if (c.empty_last && !Trim(f.back()).empty()) {
      CsvFail(path, line, c.count,
              "'" + std::string(f.back()) +
                  "' under the header's empty last column (a trailing separator); name the "
                  "column or leave the field empty");
    }
    double v[3] = {0.0, 0.0, 0.0};
    const int cols[3] = {c.angle, c.lift, c.time};
    const std::string* names[3] = {&c.angle_name, &c.lift_name, &c.time_name};
    for (int k = 0; k < (c.time >= 0 ? 3 : 2); ++k) {
      std::string why;
      v[k] = FieldValue(f[cols[k]], separator, *names[k], why);
      if (!why.empty()) CsvFail(path, line, cols[k] + 1, why);
    }
    const double si[2] = {v[0] * c.angle_scale, v[1] * c.lift_scale};
    CheckPlausible(path, line, c, v, si);
    if (!t.crank_rad.empty() && !(si[0] > t.crank_rad.back())) {
      const auto [a, b] = SignificantApart(v[0], last_angle);
      CsvFail(path, line, c.angle + 1,
              c.angle_name + " " + a + " does not increase after " + b + " (line " +
                  std::to_string(last_line) + "); angles must increase strictly");
    }
    t.crank_rad.push_back(si[0]);
    t.lift_m.push_back(si[1]);
    if (c.time >= 0) time_s->push_back(v[2] * c.time_scale);
    if (lines) lines->push_back(line);
    last_line = line;
    last_angle = v[0];
  }
  if (c.count == 0) {
    const std::string expected =
        "expected a header of crank_deg (or cam_deg) and lift_mm (or lift_um, lift_in, lift_m)";
    if (line == 0) throw CaseError(path + ": the file is empty; " + expected);  // no line 0
    CsvFail(path, line, 0, "no header; " + expected);
  }
  if (t.crank_rad.size() < 2) {
    CsvFail(path, line, 0,
            "has " + std::to_string(t.crank_rad.size()) +
                " row(s) of data; a lift table needs at least 2");
  }
  return t;
}

LiftTable ReadLiftCsv(const std::string& path, EngineCycle cycle, std::vector<int>* lines,
                      std::vector<double>* time_s) {
  return ParseLiftCsv(ReadInputFile(path, "lift table"), path, cycle, lines, time_s);
}

}  // namespace needle
