#include "hubrt/runtime/error_list.h"

#include <cstdint>
#include <string>

#include <gtest/gtest.h>

#include "hubrt/base/utf8.h"
#include "hubrt/runtime/text_buffer.h"

#include "valve_test_typed.h"

namespace hubrt::runtime {
namespace {

TEST(TextBuffer, FormatsAndCutsLongTextVisibly) {
  TextBuffer<8> text;
  text.format("{}-{}", 12, "ab");
  EXPECT_EQ(text.view(), "12-ab");
  text.assign("0123456789");
  EXPECT_EQ(text.view(), "01234...");
  text.format("{}", "abcdefghijk");
  EXPECT_EQ(text.view(), "abcde...");
  EXPECT_EQ(std::string(text.c_str()), "abcde...");
}

TEST(TextBuffer, CuttingNeverSplitsAUtf8Character) {
  TextBuffer<8> text;
  // "abcd" + U+1F527 (4 bytes): the cut at byte 5 would fall inside the character.
  text.assign("abcd\xf0\x9f\x94\xa7xyz");
  EXPECT_EQ(text.view(), "abcd...");
  EXPECT_TRUE(is_valid_utf8(text.view()));
  text.format("{}", "ab\xc3\xbc\xc3\xbc\xc3\xbc\xc3\xbc");  // "ab" and four "ü": the cut falls inside one
  EXPECT_TRUE(is_valid_utf8(text.view())) << text.view();
  EXPECT_EQ(text.view(), "ab\xc3\xbc...");
}

TEST(ErrorList, AMessageQuotingBadBytesIsStoredEscaped) {
  ErrorList errors;
  // What issue 11 saw: raw peer bytes formatted into an error (here on purpose, unescaped).
  errors.add("unknown action '{}'", "a\xed\xa0\x80");
  errors.add("device says '{}'", std::string(300, '\xff'));
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_EQ(errors.at(0), "unknown action 'a\\xED\\xA0\\x80'");
  EXPECT_TRUE(is_valid_utf8(errors.at(1)));
  EXPECT_LE(errors.at(1).size(), ErrorList::kMaxLength);
  EXPECT_EQ(errors.at(1).substr(errors.at(1).size() - 3), "...");
  errors.add("plain \xc3\xbc stays");
  EXPECT_EQ(errors.at(2), "plain \xc3\xbc stays");
}

// Into a State's error_list (the generated sequence<string<191>, 16>), whose bounds are the list's:
// every entry fits whole, the full list included.
TEST(ErrorList, CopiesIntoTheStatesBoundedErrorList) {
  ErrorList errors;
  errors.add("slot {}: sensor read failed", "smart_tool");
  errors.add("pressure low");
  hubrt_test::ValveState state;
  errors.copy_to(state.error_list());
  ASSERT_EQ(state.view().error_list().size(), 2u);
  EXPECT_EQ(state.view().error_list()[0], "slot smart_tool: sensor read failed");
  EXPECT_EQ(state.view().error_list()[1], "pressure low");
  EXPECT_TRUE(errors.contains("pressure"));
  errors.clear();
  errors.copy_to(state.error_list());
  EXPECT_TRUE(state.view().error_list().empty());

  for (std::size_t i = 0; i < ErrorList::kMaxEntries + 2; ++i) errors.add("{:=>190}", i);
  errors.copy_to(state.error_list());
  ASSERT_EQ(state.view().error_list().size(), ErrorList::kMaxEntries);
  EXPECT_EQ(state.view().error_list()[0].size(), 190u);
  EXPECT_EQ(state.view().error_list()[ErrorList::kMaxEntries - 1], "... and 3 more errors");
}

TEST(ErrorList, OverflowIsCountedInTheLastEntry) {
  ErrorList errors;
  for (std::size_t i = 0; i < ErrorList::kMaxEntries + 3; ++i) errors.add("error {}", i);
  ASSERT_EQ(errors.size(), ErrorList::kMaxEntries);
  EXPECT_EQ(errors.at(ErrorList::kMaxEntries - 1), "... and 4 more errors");
  EXPECT_EQ(errors.at(0), "error 0");
}

TEST(ErrorList, LongMessagesAreCutNotDropped) {
  ErrorList errors;
  errors.add("{}", std::string(500, 'x'));
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors.at(0).size(), ErrorList::kMaxLength);
  EXPECT_EQ(errors.at(0).substr(ErrorList::kMaxLength - 3), "...");
}

// Rebuilt every cycle, an entry is formatted again only when its format string or an argument
// changed (issue 16: nothing formatted per cycle that did not change); what it says is always what
// formatting it now would say.
TEST(ErrorList, AMessageIsFormattedAgainOnlyWhenWhatItIsMadeOfChanged) {
  ErrorList errors;
  std::string device_error = "chip gpiochip0 not found";
  const auto cycle = [&](int failures, double seconds) {
    errors.clear();
    errors.add("sensor {} not available: {}", "dock.slot.smart_tool", device_error);
    errors.add("sensor failed {} time(s), silent for {:.1f} s", failures, seconds);
  };
  cycle(1, 0.5);
  EXPECT_EQ(errors.formatted(), 2u);
  cycle(1, 0.5);
  cycle(1, 0.5);
  EXPECT_EQ(errors.formatted(), 2u);
  EXPECT_EQ(errors.at(0), "sensor dock.slot.smart_tool not available: chip gpiochip0 not found");
  EXPECT_EQ(errors.at(1), "sensor failed 1 time(s), silent for 0.5 s");

  // A string argument changed in place (same buffer, same length): seen.
  device_error[5] = 'X';
  cycle(1, 0.5);
  EXPECT_EQ(errors.formatted(), 3u);
  EXPECT_EQ(errors.at(0), "sensor dock.slot.smart_tool not available: chip Xpiochip0 not found");
  // A number changed: only that entry.
  cycle(2, 0.5);
  EXPECT_EQ(errors.formatted(), 4u);
  EXPECT_EQ(errors.at(1), "sensor failed 2 time(s), silent for 0.5 s");
  cycle(2, 0.6);
  EXPECT_EQ(errors.formatted(), 5u);
  EXPECT_EQ(errors.at(1), "sensor failed 2 time(s), silent for 0.6 s");

  // Another message in the same place: formatted, even with the same arguments.
  errors.clear();
  errors.add("sensor {} failed: {}", "dock.slot.smart_tool", device_error);
  EXPECT_EQ(errors.formatted(), 6u);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors.at(0), "sensor dock.slot.smart_tool failed: chip Xpiochip0 not found");
}

TEST(ErrorList, AnArgumentOfAnotherTypeWithTheSameBytesIsFormattedAgain) {
  ErrorList errors;
  const auto one = [&](auto value) {
    errors.clear();
    errors.add("value {}", value);
  };
  one(1);
  one(1u);
  one(std::int64_t{1});
  one(true);
  EXPECT_EQ(errors.formatted(), 4u);
  EXPECT_EQ(errors.at(0), "value true");
  one('a');
  one("a");
  EXPECT_EQ(errors.formatted(), 6u);
  EXPECT_EQ(errors.at(0), "value a");
  one(-1);
  one(0xffffffffu);
  EXPECT_EQ(errors.formatted(), 8u);
  EXPECT_EQ(errors.at(0), "value 4294967295");
  one(1.0F);
  one(0x3f800000);  // 1.0F's bytes
  EXPECT_EQ(errors.formatted(), 10u);
  EXPECT_EQ(errors.at(0), "value 1065353216");
}

struct Custom {
  int value = 0;
};

}  // namespace
}  // namespace hubrt::runtime

template <>
struct fmt::formatter<hubrt::runtime::Custom> : fmt::formatter<int> {
  auto format(const hubrt::runtime::Custom& custom, format_context& context) const {
    return fmt::formatter<int>::format(custom.value, context);
  }
};

namespace hubrt::runtime {
namespace {

// What FormatKey cannot copy — a type with a formatter of its own, arguments larger than its
// room — is formatted every cycle, as without a key; the text is right either way.
TEST(ErrorList, WhatHasNoKeyIsFormattedEveryTime) {
  ErrorList errors;
  Custom custom{7};
  const std::string long_text(ErrorList::kMaxKeyBytes, 'x');
  for (int i = 0; i < 3; ++i) {
    errors.clear();
    errors.add("custom {}", custom);
    errors.add("long {}", long_text);
  }
  EXPECT_EQ(errors.formatted(), 6u);
  EXPECT_EQ(errors.at(0), "custom 7");
  custom.value = 8;
  errors.clear();
  errors.add("custom {}", custom);
  EXPECT_EQ(errors.at(0), "custom 8");
}

// The overflow entry replaces the last message: the next cycle formats that message again.
TEST(ErrorList, AfterAnOverflowTheLastEntryIsRightAgain) {
  ErrorList errors;
  const auto cycle = [&](std::size_t n) {
    errors.clear();
    for (std::size_t i = 0; i < n; ++i) errors.add("error {}", i);
  };
  cycle(ErrorList::kMaxEntries + 2);
  EXPECT_EQ(errors.at(ErrorList::kMaxEntries - 1), "... and 3 more errors");
  cycle(ErrorList::kMaxEntries);
  EXPECT_EQ(errors.at(ErrorList::kMaxEntries - 1), "error 15");
  cycle(ErrorList::kMaxEntries + 1);
  EXPECT_EQ(errors.at(ErrorList::kMaxEntries - 1), "... and 2 more errors");
  EXPECT_EQ(errors.at(0), "error 0");
}

// A message quoting bad bytes is escaped when it is formatted, and stays so while unchanged.
TEST(ErrorList, AnUnchangedMessageKeepsItsEscapes) {
  ErrorList errors;
  for (int i = 0; i < 3; ++i) {
    errors.clear();
    errors.add("device says '{}'", "a\xff");
  }
  EXPECT_EQ(errors.formatted(), 1u);
  EXPECT_EQ(errors.at(0), "device says 'a\\xFF'");
}

}  // namespace
}  // namespace hubrt::runtime
