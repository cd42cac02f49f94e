#pragma once
/// @file
/// The one error type of bad input: what() is one line naming the file (or the option), the
/// key and what was expected. Commands turn it into exit status 2.

#include <cstdio>
#include <stdexcept>
#include <string>

namespace needle {

/// A case-file or option problem; what() is one line naming the file, the key and what was
/// expected. Control characters in the text (a value echoed from the file may hold a newline
/// written as "\n" in TOML) are shown escaped, so that the message stays one line.
class CaseError : public std::runtime_error {
 public:
  explicit CaseError(const std::string& what) : std::runtime_error(OneLine(what)) {}
  explicit CaseError(const char* what) : CaseError(std::string(what)) {}

 private:
  static std::string OneLine(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (const char ch : text) {
      const auto c = static_cast<unsigned char>(ch);
      if (c == '\n') {
        out += "\\n";
      } else if (c == '\r') {
        out += "\\r";
      } else if (c == '\t') {
        out += "\\t";
      } else if (c < 0x20 || c == 0x7f) {
        char hex[8];
        std::snprintf(hex, sizeof hex, "\\x%02X", c);
        out += hex;
      } else {
        out += ch;
      }
    }
    return out;
  }
};

}  // namespace needle
