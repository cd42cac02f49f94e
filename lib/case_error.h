#pragma once
/// @file
/// The one error type of bad input: what() is one line naming the file (or the option), the
/// key and what was expected. Commands turn it into exit status 2.

#include <cstdio>
#include <stdexcept>
#include <string>

namespace needle {

/// `text` with its control characters shown escaped: "\n", "\r", "\t", and "\x1B" for the
/// other C0 controls, DEL and the C1 controls (UTF-8 "\xC2\x9B"); line ends kept when
/// `keep_line_ends`. For messages (one line) and for text written to a terminal, where a title
/// typed as "\u001b[31m" in a case file would otherwise drive it.
inline std::string EscapeControls(const std::string& text, bool keep_line_ends) {
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    const bool c1 = c == 0xC2 && i + 1 < text.size() &&
                    (static_cast<unsigned char>(text[i + 1]) & 0xE0) == 0x80;  // U+0080…U+009F
    if (c == '\n' && keep_line_ends) {
      out += '\n';
    } else if (c == '\n' || c == '\r' || c == '\t') {
      out += c == '\n' ? "\\n" : c == '\r' ? "\\r" : "\\t";
    } else if (c < 0x20 || c == 0x7f || c1) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", c);
      out += hex;
      if (c1) {
        std::snprintf(hex, sizeof hex, "\\x%02X", static_cast<unsigned char>(text[++i]));
        out += hex;
      }
    } else {
      out += text[i];
    }
  }
  return out;
}

/// A case-file or option problem; what() is one line naming the file, the key and what was
/// expected. Control characters in the text (a value echoed from the file may hold a newline
/// written as "\n" in TOML) are shown escaped, so that the message stays one line.
class CaseError : public std::runtime_error {
 public:
  explicit CaseError(const std::string& what) : std::runtime_error(EscapeControls(what, false)) {}
  explicit CaseError(const char* what) : CaseError(std::string(what)) {}
};

}  // namespace needle
