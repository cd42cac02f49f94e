#pragma once
/// @file
/// The text handed to the TOML parser is pure ASCII, by construction.
///
/// toml++ 3.3.0 (Debian 12) reaches TOML_UNREACHABLE, undefined behaviour, on some non-ASCII
/// input (marzer/tomlplusplus#295, fixed upstream after 3.3.0). Two pre-scans that refused
/// non-ASCII "outside strings" were bypassed by the fuzzer (issue 12: `x = 6="É"`), because
/// they had to guess, as toml++ does, where a string starts in text that is not TOML. This
/// transcoder does not guess: whatever it decides, its output has no byte ≥ 0x80, so toml++
/// never meets the code paths at fault. For valid TOML it changes nothing the parser reports:
///
///   - in a basic string ("…", """…""") each UTF-8 character becomes \uXXXX or \UXXXXXXXX,
///     which toml++ decodes to the same UTF-8;
///   - a literal string ('…', '''…''') holding non-ASCII becomes the equivalent basic string
///     (backslashes and quotes escaped, non-ASCII as above);
///   - in a comment each non-ASCII character becomes '?' (comments carry no value);
///   - non-ASCII anywhere else is refused (TOML allows it only in strings and comments), and so
///     is malformed UTF-8 anywhere (overlong forms, surrogates, past U+10FFFF, cut short), and
///     a backslash before a non-ASCII character (no such escape).
///
/// Lines are kept, so the parser's line numbers stay right; columns on a line with
/// transcoded characters count the escapes.

#include <string>

namespace needle {

/// The ASCII transcoding of `text`; throws CaseError "PATH:LINE:COLUMN: what" for the input
/// refused above. A leading UTF-8 byte-order mark is dropped.
std::string AsciiTomlText(const std::string& text, const std::string& path);

}  // namespace needle
