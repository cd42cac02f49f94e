#include "lib/toml_text.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "lib/case_error.h"

namespace needle {
namespace {

enum class State { kNormal, kComment, kBasic, kLiteral, kMultiBasic, kMultiLiteral };

class Transcoder {
 public:
  Transcoder(const std::string& text, const std::string& path) : text_(text), path_(path) {}

  std::string Run() {
    if (text_.compare(0, 3, "\xEF\xBB\xBF") == 0) i_ = 3;
    out_.reserve(text_.size());
    while (i_ < text_.size()) Step();
    Flush();
    return out_;
  }

 private:
  [[noreturn]] void Fail(const std::string& what) const {
    throw CaseError(path_ + ":" + std::to_string(line_) + ":" + std::to_string(column_) + ": " +
                    what);
  }

  bool Starts(const char* s) const { return text_.compare(i_, std::strlen(s), s) == 0; }

  // Decodes the UTF-8 character at i_ (strictly) and moves past it; returns the code point.
  unsigned long Decode() {
    const auto byte = [&](size_t k) { return static_cast<unsigned char>(text_[k]); };
    const unsigned char b0 = byte(i_);
    int n;
    unsigned long cp, min;
    if (b0 >= 0xC2 && b0 <= 0xDF) {
      n = 1, cp = b0 & 0x1F, min = 0x80;
    } else if (b0 >= 0xE0 && b0 <= 0xEF) {
      n = 2, cp = b0 & 0x0F, min = 0x800;
    } else if (b0 >= 0xF0 && b0 <= 0xF4) {
      n = 3, cp = b0 & 0x07, min = 0x10000;
    } else {
      Fail("malformed UTF-8 (byte 0x" + Hex(b0, 2) + ")");
    }
    for (int k = 1; k <= n; ++k) {
      if (i_ + k >= text_.size() || (byte(i_ + k) & 0xC0) != 0x80)
        Fail("malformed UTF-8 (a character cut short)");
      cp = (cp << 6) | (byte(i_ + k) & 0x3F);
    }
    if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF))
      Fail("malformed UTF-8 (overlong, surrogate or beyond U+10FFFF)");
    i_ += n + 1;
    return cp;
  }

  static std::string Hex(unsigned long v, int digits) {
    char buf[24];  // 16 hexadecimal digits of an unsigned long at most, and the terminator
    std::snprintf(buf, sizeof buf, "%0*lX", digits, v);
    return buf;
  }

  static std::string Escape(unsigned long cp) {
    return cp <= 0xFFFF ? "\\u" + Hex(cp, 4) : "\\U" + Hex(cp, 8);
  }

  // Appends to the output, or to the literal string being held back.
  void Emit(const std::string& s) { (held_ ? literal_ : out_) += s; }
  void Emit(char c) { (held_ ? literal_ : out_) += c; }

  // A literal string is held back until its end: as it was when all ASCII, else rewritten as a
  // basic string (the escaped form is built alongside).
  void OpenLiteral(bool multi) {
    held_ = true;
    literal_.clear();
    escaped_.clear();
    literal_non_ascii_ = false;
    literal_multi_ = multi;
  }
  void CloseLiteral() {
    const char* quote = literal_multi_ ? "\"\"\"" : "\"";
    if (literal_non_ascii_) {
      out_ += quote + escaped_ + quote;
    } else {
      const char* lq = literal_multi_ ? "'''" : "'";
      out_ += lq + literal_ + lq;
    }
    held_ = false;
  }
  void Flush() {
    if (held_) {  // never closed: the parser reports it; keep it ASCII
      out_ += literal_multi_ ? "'''" : "'";
      out_ += literal_non_ascii_ ? escaped_ : literal_;
      held_ = false;
    }
  }

  void Step() {
    const unsigned char ch = static_cast<unsigned char>(text_[i_]);
    if (ch == '\n') {
      if (state_ == State::kComment) state_ = State::kNormal;
      if (held_) {
        literal_ += '\n';
        escaped_ += '\n';
      } else {
        out_ += '\n';
      }
      ++i_;
      ++line_;
      column_ = 0;
      return;
    }
    ++column_;
    switch (state_) {
      case State::kNormal:
        return StepNormal(ch);
      case State::kComment:
        return StepComment(ch);
      case State::kBasic:
      case State::kMultiBasic:
        return StepBasic(ch);
      case State::kLiteral:
      case State::kMultiLiteral:
        return StepLiteral(ch);
    }
  }

  // Step() on the character ch at i_ (not a newline) outside strings and comments.
  void StepNormal(unsigned char ch) {
    if (ch >= 0x80)
      Fail("non-ASCII character outside a string or comment (TOML allows it only there)");
    if (ch == '#') {
      state_ = State::kComment;
    } else if (ch == '"' && Starts("\"\"\"")) {
      state_ = State::kMultiBasic;
      out_ += "\"\"\"";
      i_ += 3;
      column_ += 2;
      return;
    } else if (ch == '\'' && Starts("'''")) {
      state_ = State::kMultiLiteral;
      OpenLiteral(true);
      i_ += 3;
      column_ += 2;
      return;
    } else if (ch == '"') {
      state_ = State::kBasic;
    } else if (ch == '\'') {
      state_ = State::kLiteral;
      OpenLiteral(false);
      ++i_;
      return;
    }
    out_ += static_cast<char>(ch);
    ++i_;
  }

  // … inside a comment: passed on, a non-ASCII character as '?'.
  void StepComment(unsigned char ch) {
    if (ch >= 0x80) {
      Decode();
      out_ += '?';
      return;
    }
    out_ += static_cast<char>(ch);
    ++i_;
  }

  // … inside a basic string: passed on, a non-ASCII character as its escape.
  void StepBasic(unsigned char ch) {
    if (ch >= 0x80) {
      out_ += Escape(Decode());
      return;
    }
    if (ch == '\\') {
      out_ += '\\';
      ++i_;
      if (i_ < text_.size()) {
        const unsigned char next = static_cast<unsigned char>(text_[i_]);
        if (next >= 0x80) Fail("a backslash before a non-ASCII character (no such escape)");
        if (next != '\n') {  // a line-ending backslash is handled as a newline
          out_ += static_cast<char>(next);
          ++i_;
          ++column_;
        }
      }
      return;
    }
    if (state_ == State::kBasic && ch == '"') {
      state_ = State::kNormal;
    } else if (state_ == State::kMultiBasic && ch == '"' && Starts("\"\"\"")) {
      // Up to two more quotes may end the content ("""a""""" is a"").
      size_t run = 0;
      while (i_ + run < text_.size() && text_[i_ + run] == '"' && run < 5) ++run;
      out_.append(run, '"');
      i_ += run;
      column_ += static_cast<int>(run) - 1;
      state_ = State::kNormal;
      return;
    }
    out_ += static_cast<char>(ch);
    ++i_;
  }

  // … inside a literal string: held back (OpenLiteral), and its escaped form built alongside.
  void StepLiteral(unsigned char ch) {
    if (state_ == State::kLiteral && ch == '\'') {
      ++i_;
      state_ = State::kNormal;
      CloseLiteral();
      return;
    }
    if (state_ == State::kMultiLiteral && ch == '\'' && Starts("'''")) {
      size_t run = 0;
      while (i_ + run < text_.size() && text_[i_ + run] == '\'' && run < 5) ++run;
      // The last three close it; up to two before them belong to the content.
      for (size_t k = 0; k + 3 < run; ++k) {
        literal_ += '\'';
        escaped_ += '\'';
      }
      i_ += run;
      column_ += static_cast<int>(run) - 1;
      state_ = State::kNormal;
      CloseLiteral();
      return;
    }
    if (ch >= 0x80) {
      const size_t from = i_;
      const unsigned long cp = Decode();
      literal_ += text_.substr(from, i_ - from);
      escaped_ += Escape(cp);
      literal_non_ascii_ = true;
      return;
    }
    literal_ += static_cast<char>(ch);
    if (ch == '\\' || ch == '"') escaped_ += '\\';
    escaped_ += static_cast<char>(ch);
    ++i_;
  }

  const std::string& text_;
  const std::string& path_;
  std::string out_;
  size_t i_ = 0;
  int line_ = 1, column_ = 0;
  State state_ = State::kNormal;
  bool held_ = false, literal_non_ascii_ = false, literal_multi_ = false;
  std::string literal_, escaped_;
};

}  // namespace

std::string AsciiTomlText(const std::string& text, const std::string& path) {
  // ASCII already (no byte-order mark either): every state passes each byte on as it is, so
  // the transcoding is the text itself (a case of 1e6-element arrays is 20 MB).
  if (std::none_of(text.begin(), text.end(), [](char c) { return c & 0x80; })) return text;
  const std::string out = Transcoder(text, path).Run();
  for (char c : out) {
    // The invariant the parser's safety rests on, checked, not assumed.
    if (static_cast<unsigned char>(c) >= 0x80)
      throw std::logic_error("AsciiTomlText: non-ASCII left after transcoding " + path);
  }
  return out;
}

}  // namespace needle
