// The strict UTF-8 corpus: what RFC 3629 allows and, one by one, the ill-formed sequences it
// forbids (the classes of Markus Kuhn's UTF-8 decoder stress test).
#include <cctype>
#include <string>

#include <gtest/gtest.h>

#include "hubrt/base/utf8.h"

namespace hubrt {
namespace {

std::string bytes(std::initializer_list<unsigned char> list) {
  return {list.begin(), list.end()};
}

TEST(Utf8Prefix, AcceptsWellFormedText) {
  EXPECT_TRUE(is_valid_utf8(""));
  EXPECT_TRUE(is_valid_utf8("dock_ecu: plain ASCII\n"));
  EXPECT_TRUE(
      is_valid_utf8("Greifer \xC3\xB6"
                    "ffnen"));                                  // U+00F6, 2 bytes
  EXPECT_TRUE(is_valid_utf8("\xE2\x82\xAC"));                   // U+20AC, 3 bytes
  EXPECT_TRUE(is_valid_utf8("\xF0\x9F\xA4\x96"));               // U+1F916, 4 bytes
  EXPECT_TRUE(is_valid_utf8(bytes({0xF4, 0x8F, 0xBF, 0xBF})));  // U+10FFFF, the last
  EXPECT_TRUE(is_valid_utf8(bytes({0xED, 0x9F, 0xBF})));        // U+D7FF, below surrogates
  EXPECT_TRUE(is_valid_utf8(bytes({0xEE, 0x80, 0x80})));        // U+E000, above surrogates
  EXPECT_TRUE(is_valid_utf8(bytes({0xEF, 0xBB, 0xBF})));        // U+FEFF, a byte order mark
  EXPECT_TRUE(is_valid_utf8(std::string("a\0b", 3)));           // U+0000 is a character
}

struct IllFormed {
  const char* what;
  std::string text;
  std::size_t valid_prefix;
};

// gtest prints the parameter when a case fails, and names the case after it.
void PrintTo(const IllFormed& c, std::ostream* out) {
  *out << c.what;
}

std::string corpus_name(const ::testing::TestParamInfo<IllFormed>& param) {
  std::string name;
  for (const char* c = param.param.what; *c != '\0'; ++c) name += std::isalnum(*c) != 0 ? *c : '_';
  return name;
}

class Utf8PrefixIllFormed : public ::testing::TestWithParam<IllFormed> {};

TEST_P(Utf8PrefixIllFormed, IsRejectedAtItsFirstByte) {
  const IllFormed& c = GetParam();
  EXPECT_FALSE(is_valid_utf8(c.text)) << c.what;
  EXPECT_EQ(valid_utf8_prefix(c.text), c.valid_prefix) << c.what;
}

INSTANTIATE_TEST_SUITE_P(
    Corpus, Utf8PrefixIllFormed,
    ::testing::Values(IllFormed{"surrogate U+D800", bytes({0xED, 0xA0, 0x80}), 0},
                      IllFormed{"surrogate U+DFFF after text", "ok" + bytes({0xED, 0xBF, 0xBF}), 2},
                      IllFormed{"surrogate pair as CESU-8", bytes({0xED, 0xA0, 0xBD, 0xED, 0xB2, 0xA9}), 0},
                      IllFormed{"overlong '/' in 2 bytes", bytes({0xC0, 0xAF}), 0},
                      IllFormed{"overlong U+007F in 2 bytes", bytes({0xC1, 0xBF}), 0},
                      IllFormed{"overlong '/' in 3 bytes", bytes({0xE0, 0x80, 0xAF}), 0},
                      IllFormed{"overlong U+07FF in 3 bytes", bytes({0xE0, 0x9F, 0xBF}), 0},
                      IllFormed{"overlong '/' in 4 bytes", bytes({0xF0, 0x80, 0x80, 0xAF}), 0},
                      IllFormed{"overlong U+FFFF in 4 bytes", bytes({0xF0, 0x8F, 0xBF, 0xBF}), 0},
                      IllFormed{"U+110000, above the last code point", bytes({0xF4, 0x90, 0x80, 0x80}), 0},
                      IllFormed{"lead F5 (old 4-byte range)", bytes({0xF5, 0x80, 0x80, 0x80}), 0},
                      IllFormed{"5-byte form", bytes({0xF8, 0x88, 0x80, 0x80, 0x80}), 0},
                      IllFormed{"byte FF", "a" + bytes({0xFF}), 1},
                      IllFormed{"lone continuation byte", "x" + bytes({0x80}) + "y", 1},
                      IllFormed{"continuation byte BF at the start", bytes({0xBF}), 0},
                      IllFormed{"2-byte sequence cut at the end", "ab" + bytes({0xC3}), 2},
                      IllFormed{"3-byte sequence cut at the end", bytes({0xE2, 0x82}), 0},
                      IllFormed{"4-byte sequence cut at the end", bytes({0xF0, 0x9F, 0xA4}), 0},
                      IllFormed{"3-byte sequence cut by ASCII", bytes({0xE2, 0x82}) + "A", 0},
                      IllFormed{"4-byte sequence cut by a new lead", bytes({0xF0, 0x9F, 0xC3, 0xB6}), 0},
                      IllFormed{"Latin-1 text", "Gr" + bytes({0xFC}) + "n", 2}),
    corpus_name);

}  // namespace
}  // namespace hubrt
