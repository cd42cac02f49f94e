#pragma once
/// @file
/// Every key of a case file's sections (and of the synthesis file's [checks] and the engine
/// file's [engine]), declared once:
/// its section, its name without the unit suffix, its dimension (the suffixes lib/units.h
/// allows; Dimension::kNone: a plain key, written without one), a one-line doc and its
/// plausible range (plausible_ranges.h; none for a name, a flag, a count or a rule's number).
///
/// Walked by:
/// - the section readers: SectionReader asks the list for every key it reads and refuses one
///   that is not declared, or declared with another dimension (std::logic_error: a bug, exit 3);
/// - the range check: SectionReader::Finish holds each value read to its key's range;
/// - docs/case-file.md's key reference (CaseKeysMarkdown) and docs/ranges.md
///   (PlausibleRangesMarkdown), written from it by `NEEDLE_REGENERATE=1 ctest -R
///   "TheDocsKeyReferenceIsTheList|TheDocsRangesTableIsTheCodes"`;
/// - the tests: every case-file key is read by its section's reader
///   (CaseFileTest.EveryDeclaredKeyIsReadByItsSectionsReader).
/// A key is declared with the same (section, name) twice only for two dimensions (`ramp` and
/// `ramp_deg`, `end_slope` and `end_slope_mm_deg`).

#include <cstddef>
#include <string>

#include "apps/case/plausible_ranges.h"
#include "lib/units.h"

namespace needle {

struct CaseKey {
  const char* section;  ///< "train"
  const char* name;     ///< without the unit suffix ("contact_stiffness")
  Dimension dimension;  ///< kNone: a plain key (number, string, flag or array of them)
  const char* doc;      ///< one line, for docs/case-file.md
  const PlausibleRange* range = nullptr;  ///< checked by SectionReader::Finish; nullptr: none
  bool upper_only = false;                ///< a table's entries: the upper end only
};

/// The keys of one file's sections: a case file's or the synthesis file's [checks].
struct CaseKeyList {
  const CaseKey* first = nullptr;  ///< nullptr: no list
  std::size_t size = 0;
  template <std::size_t N>
  static constexpr CaseKeyList Of(const CaseKey (&keys)[N]) {
    return {keys, N};
  }
  const CaseKey* begin() const { return first; }
  const CaseKey* end() const { return first + size; }
};

/// The case file's keys, in the order docs/case-file.md lists them.
CaseKeyList CaseFileKeys();
/// The synthesis file's [checks] keys (the follower and the synthesized cam's checks).
CaseKeyList SynthesisCheckKeys();
/// The engine file's [engine] keys (`needle design`).
CaseKeyList EngineFileKeys();

/// The declaration of `name` (without its suffix) of `dimension` in `section` of `keys`, or
/// nullptr.
const CaseKey* FindCaseKey(CaseKeyList keys, const std::string& section, const std::string& name,
                           Dimension dimension);

/// Key `name` of case-file section `section` as a writer writes it, with unit suffix `unit`
/// ("" for a plain key): CaseKeyText("train", "contact_stiffness", "N_m") is
/// "contact_stiffness_N_m". Throws std::logic_error (a writer's bug) unless the list declares the
/// key with a dimension that has that suffix (or, for "", a plain key).
std::string CaseKeyText(const std::string& section, const std::string& name,
                        const std::string& unit = "");

/// docs/case-file.md's key reference: one row per key, with its unit suffixes, range and doc.
std::string CaseKeysMarkdown();

}  // namespace needle
