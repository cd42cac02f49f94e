// The case file's keys, declared once (apps/case/case_keys.h): the reader may ask only for a
// declared key, and docs/case-file.md's key reference is the list. That every declared key is
// read by its section's reader is CaseFileTest.EveryDeclaredKeyIsReadByItsSectionsReader.
#include "apps/case/case_keys.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "apps/case/case_file.h"
#include "apps/case/section_reader.h"
#include "apps/case/synthesis_file.h"

namespace needle {
namespace {

using case_internal::SectionReader;

// A reader that asks for a key its file does not declare, or asks with another dimension, is
// a bug of the reader (std::logic_error: exit 3), not the user's: it fails on any case, with or
// without the key in the file.
TEST(CaseKeysTest, AReaderAskingForAnUndeclaredKeyIsABug) {
  toml::table train = toml::parse("play_mm = 0.1\n");
  SectionReader r(&train, "t.toml", "train", CaseFileKeys());
  EXPECT_EQ(r.OptionalQuantity("play", Dimension::kLength), 1e-4);
  try {
    r.OptionalNumber("cam_friction");
    FAIL() << "an undeclared key was read";
  } catch (const std::logic_error& e) {
    EXPECT_STREQ(e.what(),
                 "[train] cam_friction (a dimensionless number) is read but not declared in "
                 "apps/case/case_keys.cc");
  }
  EXPECT_THROW(r.OptionalQuantity("play", Dimension::kAngle), std::logic_error);
  SectionReader absent(nullptr, "t.toml", "train", CaseFileKeys());  // asked, though absent
  EXPECT_THROW(absent.OptionalBool("clash"), std::logic_error);
  // A reader without a list (the engine file's [design]) asks for what it likes.
  SectionReader design(&train, "e.toml", "design");
  EXPECT_FALSE(design.OptionalNumber("mixing_ratio"));
}

// The message of the CaseError `run` throws, or "(no error)".
template <typename Run>
std::string CaseErrorOf(const Run& run) {
  try {
    run();
  } catch (const CaseError& e) {
    return e.what();
  }
  return "(no error)";
}

std::string Bundled(const std::string& file) {
  std::stringstream s;
  s << std::ifstream(std::string(NEEDLE_SOURCE_DIR) + "/cases/" + file).rdbuf();
  return s.str();
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

// The engine file's [engine] and the synthesis file's [checks] hold their keys to the ranges
// their own lists declare (EngineFileKeys, SynthesisCheckKeys), as a case file's sections do.
TEST(CaseKeysTest, TheEngineAndSynthesisFilesHoldTheirDeclaredRanges) {
  const std::string engine = Bundled("basu-example1-engine.toml");
  EXPECT_NO_THROW(ParseDesignInputs(engine, "e.toml"));
  EXPECT_EQ(CaseErrorOf([&] {
              ParseDesignInputs(Replace(engine, "speed_rpm = 125", "speed_rpm = 1e6"), "e.toml");
            }),
            "e.toml: [engine] speed_rpm: 1e+06 rpm is outside the plausible range [1, 50000] rpm "
            "(docs/ranges.md)");
  const std::string synth = Bundled("matec-2018-synth.toml");
  EXPECT_NO_THROW(ParseSynthesisFile(synth, "s.toml"));
  EXPECT_EQ(CaseErrorOf([&] {
              ParseSynthesisFile(Replace(synth, "base_radius_mm = 10", "base_radius_mm = 2e7"),
                                 "s.toml");
            }),
            "s.toml: [checks] base_radius_mm: 2e+07 mm is outside the plausible range [0, 2000] "
            "mm (docs/ranges.md)");
}

// A case writer names each key through the list: a key it does not declare, or a unit that is
// not one of the key's, is the writer's bug.
TEST(CaseKeysTest, AWriterWritesOnlyDeclaredKeys) {
  EXPECT_EQ(CaseKeyText("train", "contact_stiffness", "N_m"), "contact_stiffness_N_m");
  EXPECT_EQ(CaseKeyText("spring", "active_coils"), "active_coils");
  EXPECT_EQ(CaseKeyText("train", "ramp", "deg"), "ramp_deg");  // and the plain `ramp`
  EXPECT_EQ(CaseKeyText("train", "ramp"), "ramp");
  EXPECT_THROW(CaseKeyText("train", "contact_stiffness", "kg"), std::logic_error);
  EXPECT_THROW(CaseKeyText("train", "contact_stiffness"), std::logic_error);
  try {
    CaseKeyText("train", "cam_friction");
    FAIL() << "an undeclared key was written";
  } catch (const std::logic_error& e) {
    EXPECT_STREQ(e.what(),
                 "a case writer writes [train] cam_friction, which apps/case/case_keys.cc does "
                 "not declare");
  }
}

// The declared range is the one Finish holds the value to.
TEST(CaseKeysTest, FinishHoldsAValueToItsDeclaredRange) {
  toml::table train = toml::parse("play_mm = 20\n");
  SectionReader r(&train, "t.toml", "train", CaseFileKeys());
  r.OptionalQuantity("play", Dimension::kLength);
  EXPECT_EQ(CaseErrorOf([&] { r.Finish(); }),
            "t.toml: [train] play_mm: 20 mm is outside the plausible range [0, 10] mm "
            "(docs/ranges.md)");
}

// The block of generated document `page` (docs/…) between `begin` and `end` is `table`; with
// NEEDLE_REGENERATE set, the test writes the table into the page first (as
// MeasuredTableTest.BundledCsvTablesAreTheGenerators writes the bundled CSVs).
void ExpectGeneratedBlock(const std::string& page, const std::string& begin, const std::string& end,
                          const std::string& table, const std::string& test) {
  const std::string path = std::string(NEEDLE_SOURCE_DIR) + "/docs/" + page;
  std::stringstream doc;
  doc << std::ifstream(path).rdbuf();
  std::string text = doc.str();
  const size_t at = text.find(begin), e = text.find(end);
  ASSERT_TRUE(at != std::string::npos && e != std::string::npos) << page;
  const size_t b = at + begin.size();
  if (std::getenv("NEEDLE_REGENERATE")) {
    text.replace(b, e - b, table);
    std::ofstream(path, std::ios::binary) << text;
  }
  EXPECT_EQ(text.substr(b, text.find(end) - b), table)
      << "regenerate docs/" << page << ": NEEDLE_REGENERATE=1 ctest -R " << test;
}

// docs/case-file.md's key reference is CaseKeysMarkdown's, so it cannot drift from the list;
// every key is declared once (section, name and dimension) and found as declared.
TEST(CaseKeysTest, TheDocsKeyReferenceIsTheList) {
  ExpectGeneratedBlock("case-file.md", "<!-- case-keys: begin -->\n", "<!-- case-keys: end -->",
                       CaseKeysMarkdown(), "TheDocsKeyReferenceIsTheList");
  for (const CaseKey& k : CaseFileKeys())
    EXPECT_EQ(FindCaseKey(CaseFileKeys(), k.section, k.name, k.dimension), &k) << k.name;
  EXPECT_EQ(FindCaseKey(CaseFileKeys(), "limits", "mass", Dimension::kMass), nullptr);
}

// docs/ranges.md carries the code's table, generated by PlausibleRangesMarkdown from the
// ranges and the keys that declare them.
TEST(CaseFileTest, TheDocsRangesTableIsTheCodes) {
  ExpectGeneratedBlock("ranges.md", "<!-- ranges: begin -->\n", "<!-- ranges: end -->",
                       PlausibleRangesMarkdown(), "TheDocsRangesTableIsTheCodes");
}

}  // namespace
}  // namespace needle
