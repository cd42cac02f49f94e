#include "apps/report/markdown_writer.h"

#include <set>
#include <sstream>
#include <vector>

namespace needle {
namespace {

// A cell: the value as JSON writes it (strings without their quotes), with '|' escaped and
// line ends turned into spaces so that a table row stays one line.
std::string Cell(const nlohmann::json& v) {
  std::string s = v.is_string() ? v.get<std::string>() : v.is_null() ? "—" : v.dump();
  std::string out;
  for (char ch : s) {
    if (ch == '|') {
      out += "\\|";
    } else if (ch == '\n' || ch == '\r') {
      out += ' ';
    } else {
      out += ch;
    }
  }
  return out;
}

bool IsScalar(const nlohmann::json& v) { return !v.is_object() && !v.is_array(); }

bool IsScalarArray(const nlohmann::json& v) {
  if (!v.is_array()) return false;
  for (const auto& e : v) {
    if (!IsScalar(e)) return false;
  }
  return true;
}

bool IsRecordArray(const nlohmann::json& v) {
  if (!v.is_array() || v.empty()) return false;
  for (const auto& e : v) {
    if (!e.is_object()) return false;
  }
  return true;
}

void Object(const nlohmann::json& o, int level, std::ostringstream& out);

// An array of records as one table: the columns are the records' scalar keys in first-seen
// order; a record's nested value is written as JSON in its cell.
void Records(const nlohmann::json& a, std::ostringstream& out) {
  std::vector<std::string> keys;
  std::set<std::string> seen;
  for (const auto& r : a) {
    for (const auto& [k, v] : r.items()) {
      if (seen.insert(k).second) keys.push_back(k);
    }
  }
  out << '|';
  for (const auto& k : keys) out << ' ' << Cell(k) << " |";
  out << "\n|";
  for (size_t i = 0; i < keys.size(); ++i) out << "---|";
  out << '\n';
  for (const auto& r : a) {
    out << '|';
    for (const auto& k : keys) out << ' ' << (r.contains(k) ? Cell(r.at(k)) : "") << " |";
    out << '\n';
  }
}

void Value(const std::string& key, const nlohmann::json& v, int level, std::ostringstream& out) {
  out << '\n' << std::string(static_cast<size_t>(level), '#') << ' ' << key << "\n\n";
  if (v.is_object()) {
    Object(v, level, out);
  } else if (IsRecordArray(v)) {
    Records(v, out);
  } else if (v.is_array()) {
    // Arrays of arrays (or of mixed values): one line per element, as JSON.
    for (const auto& e : v) out << "- " << Cell(e) << '\n';
  }
}

void Object(const nlohmann::json& o, int level, std::ostringstream& out) {
  bool table = false;
  for (const auto& [k, v] : o.items()) {
    if (!IsScalar(v) && !(IsScalarArray(v) && v.size() <= 16)) continue;
    if (!table) out << "| key | value |\n|---|---|\n";
    table = true;
    std::string cell;
    if (v.is_array()) {
      for (const auto& e : v) cell += (cell.empty() ? "" : ", ") + Cell(e);
    } else {
      cell = Cell(v);
    }
    out << "| " << Cell(k) << " | " << (cell.empty() ? "—" : cell) << " |\n";
  }
  for (const auto& [k, v] : o.items()) {
    if (IsScalar(v) || (IsScalarArray(v) && v.size() <= 16)) continue;
    if (IsScalarArray(v)) {
      out << '\n' << std::string(static_cast<size_t>(level + 1), '#') << ' ' << k << "\n\n";
      std::string line;
      for (const auto& e : v) line += (line.empty() ? "" : ", ") + Cell(e);
      out << line << '\n';
      continue;
    }
    Value(k, v, level + 1, out);
  }
}

}  // namespace

std::string MarkdownFromJson(const nlohmann::json& object) {
  std::ostringstream out;
  if (object.is_object()) {
    Object(object, 1, out);
  } else if (IsRecordArray(object)) {
    Records(object, out);
  } else {
    out << Cell(object) << '\n';
  }
  return out.str();
}

}  // namespace needle
