#include "hubrt/base/status.h"

#include <gtest/gtest.h>

namespace hubrt {
namespace {

TEST(Status, DefaultIsOk) {
  EXPECT_TRUE(Status().is_ok());
  EXPECT_FALSE(Status(ErrorCode::kTimeout).is_ok());
  EXPECT_EQ(to_string(ErrorCode::kTimeout), "timeout");
}

TEST(Result, CarriesValueOrStatus) {
  Result<int> good = 7;
  ASSERT_TRUE(good.is_ok());
  EXPECT_EQ(good.value(), 7);
  Result<int> bad = Status(ErrorCode::kIo);
  EXPECT_FALSE(bad.is_ok());
  EXPECT_EQ(bad.status().code(), ErrorCode::kIo);
  EXPECT_EQ(bad.value_or(3), 3);
}

TEST(Expected, CarriesValueOrMessage) {
  Expected<std::string> good = std::string("x");
  ASSERT_TRUE(good);
  EXPECT_EQ(*good, "x");
  Expected<std::string> bad = make_error(ErrorCode::kNotFound, "chip gone");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().code, ErrorCode::kNotFound);
  EXPECT_EQ(bad.error().message, "chip gone");
  Expected<void> fine;
  EXPECT_TRUE(fine);
  Expected<void> failed = make_error(ErrorCode::kIo, "nope");
  EXPECT_FALSE(failed);
}

}  // namespace
}  // namespace hubrt
