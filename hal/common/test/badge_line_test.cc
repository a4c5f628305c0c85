#include "hubrt/hal/common/badge_line.h"

#include <string>

#include <gtest/gtest.h>

namespace hubrt::hal {
namespace {

using std::chrono::milliseconds;

class BadgeLineTest : public ::testing::Test {
 protected:
  void type(std::string_view text) {
    for (char c : text) line_.add(c, now());
  }
  Time now() const { return clock_.now().mono; }

  ManualClock clock_;
  BadgeLineAssembler line_{milliseconds(500)};
  BadgeRead read_;
};

TEST_F(BadgeLineTest, PrintableTextEndedIsOneGoodBadge) {
  type("0004123456");
  ASSERT_TRUE(line_.end(read_, now()));
  EXPECT_FALSE(read_.malformed);
  EXPECT_EQ(read_.text(), "0004123456");
  EXPECT_FALSE(line_.in_progress());
}

TEST_F(BadgeLineTest, EndWithNothingBeforeIsIgnored) {
  EXPECT_FALSE(line_.end(read_, now()));
}

TEST_F(BadgeLineTest, ControlBytesMakeItMalformedAndKeepNoText) {
  type(
      "12\x01"
      "34");
  ASSERT_TRUE(line_.end(read_, now()));
  EXPECT_TRUE(read_.malformed);
  EXPECT_EQ(read_.problem, "not printable ASCII");
  EXPECT_EQ(read_.text(), "");
  type("5678");  // the next badge starts clean
  ASSERT_TRUE(line_.end(read_, now()));
  EXPECT_FALSE(read_.malformed);
  EXPECT_EQ(read_.text(), "5678");
}

TEST_F(BadgeLineTest, NonAsciiBytesAreMalformed) {
  type("\xc3\xa9");
  ASSERT_TRUE(line_.end(read_, now()));
  EXPECT_TRUE(read_.malformed);
}

TEST_F(BadgeLineTest, LongerThanTheBoundIsMalformed) {
  type(std::string(BadgeRead::kMaxLength, '7'));
  type("8");
  ASSERT_TRUE(line_.end(read_, now()));
  EXPECT_TRUE(read_.malformed);
  EXPECT_EQ(read_.problem, "too long");
}

TEST_F(BadgeLineTest, ExactlyTheBoundIsGood) {
  type(std::string(BadgeRead::kMaxLength, '7'));
  ASSERT_TRUE(line_.end(read_, now()));
  EXPECT_FALSE(read_.malformed);
  EXPECT_EQ(read_.length, BadgeRead::kMaxLength);
}

TEST_F(BadgeLineTest, ABadgeThatStopsHalfWayExpiresAfterTheTimeoutOnly) {
  type("1234");
  clock_.advance(milliseconds(500));
  EXPECT_FALSE(line_.expire(read_, now()));
  clock_.advance(milliseconds(1));
  ASSERT_TRUE(line_.expire(read_, now()));
  EXPECT_TRUE(read_.malformed);
  EXPECT_NE(read_.problem.find("cut off"), std::string_view::npos);
  EXPECT_FALSE(line_.in_progress());
}

TEST_F(BadgeLineTest, GarbageMarksMalformedWithItsReason) {
  type("12");
  line_.add_garbage("key 'F1' is no badge character", now());
  type("3");
  ASSERT_TRUE(line_.end(read_, now()));
  EXPECT_TRUE(read_.malformed);
  EXPECT_EQ(read_.problem, "key 'F1' is no badge character");
}

}  // namespace
}  // namespace hubrt::hal
