#include "hubrt/runtime/error_list.h"

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

}  // namespace
}  // namespace hubrt::runtime
