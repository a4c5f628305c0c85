#include "hubrt/runtime/reflected_message_ops.h"

#include <gtest/gtest.h>

#include "node_test_support.h"
#include "valve_test_reflect.h"

namespace hubrt::runtime::testing {
namespace {

class ReflectedOpsTest : public ::testing::Test {
 protected:
  ReflectedMessageOps ops_{msgs::type_info_of<ValveCommand>()};
  Arena arena_{4096};
};

TEST_F(ReflectedOpsTest, EqualComparesContentNotPointers) {
  OwnedValveCommand a;
  a.tags = {"x", "y"};
  OwnedValveCommand b = a;
  ValveCommand wa = a.wire();
  ValveCommand wb = b.wire();
  ASSERT_NE(wa.action, wb.action);
  EXPECT_TRUE(ops_.equal(&wa, &wb));
  b.tags[1] = "z";
  wb = b.wire();
  EXPECT_FALSE(ops_.equal(&wa, &wb));
  b.tags.pop_back();
  wb = b.wire();
  EXPECT_FALSE(ops_.equal(&wa, &wb)) << "sequence lengths differ";
  OwnedValveCommand c = a;
  c.pressure_bar = 2.6f;
  ValveCommand wc = c.wire();
  EXPECT_FALSE(ops_.equal(&wa, &wc));
}

TEST_F(ReflectedOpsTest, CopyIsDeepAndLivesInTheArena) {
  OwnedValveCommand a;
  a.tags = {"first", "second"};
  ValveCommand src = a.wire();
  ValveCommand dst{};
  ASSERT_TRUE(ops_.copy_into(&src, &dst, arena_));
  EXPECT_TRUE(ops_.equal(&src, &dst));
  EXPECT_NE(dst.action, src.action);
  EXPECT_NE(dst.tags._buffer, src.tags._buffer);
  EXPECT_FALSE(dst.tags._release);
  src.action[0] = 'X';  // mutate the source: the copy must not see it
  EXPECT_STREQ(dst.action, "open");
  EXPECT_GT(arena_.used(), 0u);
}

TEST_F(ReflectedOpsTest, CopyFailsCleanlyWhenTheArenaIsTooSmall) {
  Arena tiny(16);
  OwnedValveCommand a;
  a.tags = {std::string(40, 'x')};
  ValveCommand src = a.wire();
  ValveCommand dst{};
  EXPECT_FALSE(ops_.copy_into(&src, &dst, tiny));
  EXPECT_STREQ(dst.action, "") << "left zeroed, never half-copied";
  EXPECT_EQ(dst.tags._buffer, nullptr);
}

TEST(StringProblem, AcceptsPlainAndMultibyteText) {
  EXPECT_EQ(string_problem("open", 64), nullptr);
  EXPECT_EQ(string_problem("", 64), nullptr);
  EXPECT_EQ(string_problem("Drehmoment 12 N·m — ok ✓ 🔧", 64), nullptr);
  EXPECT_EQ(string_problem("abcd", 4), nullptr) << "exactly at the limit";
}

TEST(StringProblem, RejectsWhatAPlannerShouldNeverSend) {
  EXPECT_STREQ(string_problem(nullptr, 64), "is missing");
  EXPECT_STREQ(string_problem("abcde", 4), "is too long");
  EXPECT_STREQ(string_problem("ab\u00e9", 3), "is too long") << "the limit counts bytes";
  EXPECT_STREQ(string_problem("tab\there", 64), "contains a control character");
  EXPECT_STREQ(string_problem("del\x7f", 64), "contains a control character");
  EXPECT_STREQ(string_problem("\xc0\xaf", 64), "is not valid UTF-8") << "overlong encoding";
  EXPECT_STREQ(string_problem("\xe2\x82", 64), "is not valid UTF-8") << "truncated sequence";
  EXPECT_STREQ(string_problem("\xf5\x80\x80\x80", 64), "is not valid UTF-8") << "beyond U+10FFFF";
  EXPECT_STREQ(string_problem("\x80", 64), "is not valid UTF-8") << "stray continuation byte";
  EXPECT_STREQ(string_problem("\xed\xa0\x80", 64), "is not valid UTF-8") << "encoded surrogate U+D800";
  EXPECT_STREQ(string_problem("\xe0\x80\xaf", 64), "is not valid UTF-8") << "overlong 3-byte form";
  EXPECT_STREQ(string_problem("\xf0\x80\x80\xaf", 64), "is not valid UTF-8") << "overlong 4-byte form";
  EXPECT_STREQ(string_problem("\xf4\x90\x80\x80", 64), "is not valid UTF-8") << "U+110000";
}

}  // namespace
}  // namespace hubrt::runtime::testing
