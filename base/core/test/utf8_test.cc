#include "hubrt/base/utf8.h"

#include <array>
#include <string>

#include <gtest/gtest.h>

namespace hubrt {
namespace {

struct Case {
  std::string_view bytes;
  const char* why;
};

// Every class of ill-formed sequence RFC 3629 §4 excludes, at the start, middle and end.
constexpr std::array kInvalid{
    Case{"\x80", "stray continuation byte"},
    Case{"a\xbf", "stray continuation byte at the end"},
    Case{"\xc0\xaf", "overlong '/' (C0)"},
    Case{"\xc1\xbf", "overlong (C1)"},
    Case{"\xe0\x80\xaf", "overlong 3-byte '/'"},
    Case{"\xe0\x9f\xbf", "overlong 3-byte, highest"},
    Case{"\xf0\x80\x80\xaf", "overlong 4-byte '/'"},
    Case{"\xf0\x8f\xbf\xbf", "overlong 4-byte, highest"},
    Case{"\xed\xa0\x80", "encoded high surrogate U+D800"},
    Case{"\xed\xbf\xbf", "encoded low surrogate U+DFFF"},
    Case{"\xed\xa0\xbd\xed\xb8\x80", "CESU-8 surrogate pair"},
    Case{"\xf4\x90\x80\x80", "U+110000, above the Unicode range"},
    Case{"\xf5\x80\x80\x80", "lead byte F5"},
    Case{"\xff", "byte FF"},
    Case{"\xfe\xfe\xff\xff", "UTF-16 BOMs as bytes"},
    Case{"\xe2\x82", "truncated 3-byte sequence"},
    Case{"\xf0\x9f\x98", "truncated 4-byte sequence"},
    Case{"\xc3(", "continuation byte replaced by ASCII"},
    Case{"ok\xe2\x28\xa1", "bad second byte in the middle"},
};

constexpr std::array kValid{
    Case{"", "empty"},
    Case{"plain ascii", "ASCII"},
    Case{"\xc2\x80", "U+0080, lowest 2-byte"},
    Case{"\xdf\xbf", "U+07FF, highest 2-byte"},
    Case{"\xe0\xa0\x80", "U+0800, lowest 3-byte"},
    Case{"\xed\x9f\xbf", "U+D7FF, just below the surrogates"},
    Case{"\xee\x80\x80", "U+E000, just above the surrogates"},
    Case{"\xef\xbf\xbd", "U+FFFD"},
    Case{"\xf0\x90\x80\x80", "U+10000, lowest 4-byte"},
    Case{"\xf4\x8f\xbf\xbf", "U+10FFFF, the highest code point"},
    Case{"Dr\xc3\xbc"
         "cken \xe2\x86\x92 \xf0\x9f\x94\xa7",
         "mixed"},
    Case{"tab\there", "control characters are valid UTF-8"},
};

TEST(Utf8, RejectsEveryIllFormedSequenceOfRfc3629) {
  for (const Case& c : kInvalid) EXPECT_FALSE(is_valid_utf8(c.bytes)) << c.why;
}

TEST(Utf8, AcceptsTheBoundariesOfEveryWellFormedRange) {
  for (const Case& c : kValid) EXPECT_TRUE(is_valid_utf8(c.bytes)) << c.why;
}

TEST(Utf8, SequenceLengthIsZeroForABadStartAndTheLengthOtherwise) {
  EXPECT_EQ(utf8_sequence_length(""), 0U);
  EXPECT_EQ(utf8_sequence_length("a"), 1U);
  EXPECT_EQ(utf8_sequence_length("\xc3\xbcx"), 2U);
  EXPECT_EQ(utf8_sequence_length("\xed\xa0\x80"), 0U) << "surrogate";
  EXPECT_EQ(utf8_sequence_length("\xf4\x8f\xbf\xbf"), 4U);
}

std::string escaped(std::string_view text, std::size_t capacity = 256, bool* complete = nullptr) {
  std::array<char, 256> out{};
  const EscapedUtf8 r = append_escaped_utf8(text, std::span<char>(out.data(), capacity));
  if (complete != nullptr) *complete = r.complete;
  return std::string(out.data(), r.written);
}

TEST(Utf8, EscapesBadBytesControlCharactersAndBackslashesAndKeepsTheRest) {
  EXPECT_EQ(escaped("id\xed\xa0\x80le"), "id\\xED\\xA0\\x80le");
  EXPECT_EQ(escaped("\xc0\xaf"), "\\xC0\\xAF");
  EXPECT_EQ(escaped("a\tb\x7f"), "a\\x09b\\x7F");
  EXPECT_EQ(escaped("back\\slash"), "back\\\\slash");
  EXPECT_EQ(escaped("Dr\xc3\xbc"
                    "cken \xf0\x9f\x94\xa7"),
            "Dr\xc3\xbc"
            "cken \xf0\x9f\x94\xa7");
  EXPECT_EQ(escaped(std::string_view("nul\0here", 8)), "nul\\x00here");
}

TEST(Utf8, EscapedTextIsAlwaysValidUtf8WhateverTheInput) {
  for (const Case& c : kInvalid) {
    const std::string out = escaped(c.bytes);
    EXPECT_TRUE(is_valid_utf8(out)) << c.why << ": " << out;
  }
  // Every single byte, and every pair: no input leaves a raw bad byte behind.
  for (int a = 0; a < 256; ++a) {
    for (int b = 0; b < 256; ++b) {
      const char pair[2] = {static_cast<char>(a), static_cast<char>(b)};
      ASSERT_TRUE(is_valid_utf8(escaped(std::string_view(pair, 2)))) << a << " " << b;
    }
  }
}

TEST(Utf8, StopsBeforeACharacterOrEscapeThatDoesNotFitWhole) {
  bool complete = true;
  EXPECT_EQ(escaped("ab\xed", 4, &complete), "ab") << "a 4-byte escape does not fit in 2 bytes";
  EXPECT_FALSE(complete);
  EXPECT_EQ(escaped("a\xf0\x9f\x94\xa7", 3, &complete), "a") << "a 4-byte character is never split";
  EXPECT_FALSE(complete);
  EXPECT_EQ(escaped("abc", 3, &complete), "abc");
  EXPECT_TRUE(complete);
}

}  // namespace
}  // namespace hubrt
