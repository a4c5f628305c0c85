#include "arm_position.h"

#include <gtest/gtest.h>

namespace hubrt::tool_ecu {
namespace {

TEST(ArmPosition, NoneActiveIsOperatingOneIsItsPositionMoreIsUnclear) {
  EXPECT_EQ(decode_arm_position(false, false, false), ArmPosition::kOperating);
  EXPECT_EQ(decode_arm_position(true, false, false), ArmPosition::kHome);
  EXPECT_EQ(decode_arm_position(false, true, false), ArmPosition::kPreHome);
  EXPECT_EQ(decode_arm_position(false, false, true), ArmPosition::kOutOfRange);
  EXPECT_EQ(decode_arm_position(true, true, false), ArmPosition::kUnclear);
  EXPECT_EQ(decode_arm_position(true, false, true), ArmPosition::kUnclear);
  EXPECT_EQ(decode_arm_position(false, true, true), ArmPosition::kUnclear);
  EXPECT_EQ(decode_arm_position(true, true, true), ArmPosition::kUnclear);
}

TEST(ArmPosition, NamesAreTheStateStrings) {
  EXPECT_EQ(to_string(ArmPosition::kOperating), "operating");
  EXPECT_EQ(to_string(ArmPosition::kHome), "home");
  EXPECT_EQ(to_string(ArmPosition::kPreHome), "pre_home");
  EXPECT_EQ(to_string(ArmPosition::kOutOfRange), "out_of_range");
  EXPECT_EQ(to_string(ArmPosition::kUnclear), "unclear");
  EXPECT_EQ(to_string(ArmPosition::kUnknown), "unknown");
}

}  // namespace
}  // namespace hubrt::tool_ecu
