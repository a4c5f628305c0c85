#include "hubrt/runtime/error_list.h"

#include <string>

#include <gtest/gtest.h>

#include "hubrt/runtime/text_buffer.h"

namespace hubrt::runtime {
namespace {

// The shape idlc generates for sequence<string>.
struct StringSequence {
  std::uint32_t _maximum;
  std::uint32_t _length;
  char** _buffer;
  bool _release;
};

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

TEST(ErrorList, BindsIntoTheWireSequenceWithoutCopying) {
  ErrorList errors;
  errors.add("slot {}: sensor read failed", "smart_tool");
  errors.add("pressure low");
  StringSequence seq{};
  errors.bind(seq);
  ASSERT_EQ(seq._length, 2u);
  EXPECT_FALSE(seq._release) << "the sample must not free our storage";
  EXPECT_STREQ(seq._buffer[0], "slot smart_tool: sensor read failed");
  EXPECT_STREQ(seq._buffer[1], "pressure low");
  EXPECT_TRUE(errors.contains("pressure"));
  errors.clear();
  errors.bind(seq);
  EXPECT_EQ(seq._length, 0u);
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
