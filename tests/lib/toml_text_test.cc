// The ASCII transcoding in front of the TOML parser (lib/toml_text.h): ASCII passes unchanged,
// and whatever the input, the output is ASCII or the input is refused with one line.
#include "lib/toml_text.h"

#include <gtest/gtest.h>

#include <random>

#include "lib/case_error.h"

namespace needle {
namespace {

TEST(TomlTextTest, AsciiIsUnchanged) {
  const std::string t = "a = \"x\\\"y\" # c\nb = 'q\\' \nc = \"\"\"\nm\"\"\"\n";
  EXPECT_EQ(AsciiTomlText(t, "t"), t);
}

TEST(TomlTextTest, EscapesAndRewrites) {
  EXPECT_EQ(AsciiTomlText("a = \"\xc3\xa9\xf0\x9f\x94\xa7\"\n", "t"),
            "a = \"\\u00E9\\U0001F527\"\n");
  EXPECT_EQ(AsciiTomlText("a = 'x\\ \"\xc3\xa9'\n", "t"), "a = \"x\\\\ \\\"\\u00E9\"\n");
  EXPECT_EQ(AsciiTomlText("# \xcf\x80\n", "t"), "# ?\n");
}

// 200 000 random documents made of TOML's delimiters and UTF-8 pieces, valid and not: never
// a non-ASCII byte out, never anything but a CaseError.
TEST(TomlTextTest, OutputIsAsciiWhateverTheInput) {
  const std::vector<std::string> pieces = {"\"",
                                           "'",
                                           "\"\"\"",
                                           "'''",
                                           "\\",
                                           "#",
                                           "\n",
                                           "=",
                                           "[",
                                           "]",
                                           " ",
                                           "a",
                                           "6",
                                           "\xc3\x89",
                                           "\xf0\x9f\x94\xa7",
                                           "\xc3",
                                           "\x89",
                                           "\xed\xa0\x80",
                                           "\xef\xbb\xbf",
                                           "\xff",
                                           "{",
                                           ",",
                                           "."};
  std::mt19937_64 rng(12);
  int refused = 0;
  for (int n = 0; n < 200000; ++n) {
    std::string text;
    const int len = 1 + static_cast<int>(rng() % 24);
    for (int k = 0; k < len; ++k) text += pieces[rng() % pieces.size()];
    try {
      const std::string out = AsciiTomlText(text, "t");
      for (char c : out) ASSERT_LT(static_cast<unsigned char>(c), 0x80) << text;
    } catch (const CaseError& e) {
      ++refused;
      ASSERT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  }
  EXPECT_GT(refused, 1000);
}

}  // namespace
}  // namespace needle
