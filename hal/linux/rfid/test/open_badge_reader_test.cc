// What opening a reader says when it cannot: each error names the reader and its device.
#include "hubrt/hal/rfid/open_badge_reader.h"

#include <gtest/gtest.h>

namespace hubrt::hal::rfid {
namespace {

BadgeReaderConfig reader(BadgeReaderKind kind, std::string device) {
  BadgeReaderConfig config;
  config.reader = "operator.rfid";
  config.kind = kind;
  config.device = std::move(device);
  return config;
}

TEST(OpenBadgeReaderTest, MissingInputDeviceIsNotFound) {
  auto opened = open_badge_reader(reader(BadgeReaderKind::kEvdev, "/dev/input/by-id/no-such-reader"));
  ASSERT_FALSE(opened);
  EXPECT_EQ(opened.error().code, ErrorCode::kNotFound);
  EXPECT_NE(opened.error().message.find("operator.rfid: input device /dev/input/by-id/no-such-reader"),
            std::string::npos)
      << opened.error().message;
}

TEST(OpenBadgeReaderTest, AFileThatIsNoInputDeviceIsRefused) {
  auto opened = open_badge_reader(reader(BadgeReaderKind::kEvdev, "/dev/null"));
  ASSERT_FALSE(opened);
  EXPECT_EQ(opened.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(opened.error().message.find("not an input event device"), std::string::npos)
      << opened.error().message;
}

TEST(OpenBadgeReaderTest, MissingSerialPortIsNotFound) {
  auto opened = open_badge_reader(reader(BadgeReaderKind::kSerial, "/dev/ttyNoSuchPort"));
  ASSERT_FALSE(opened);
  EXPECT_EQ(opened.error().code, ErrorCode::kNotFound);
}

TEST(OpenBadgeReaderTest, AFileThatIsNoTerminalIsRefused) {
  auto opened = open_badge_reader(reader(BadgeReaderKind::kSerial, "/dev/null"));
  ASSERT_FALSE(opened);
  EXPECT_EQ(opened.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(opened.error().message.find("not a terminal"), std::string::npos) << opened.error().message;
}

TEST(OpenBadgeReaderTest, NonStandardBaudIsRefused) {
  BadgeReaderConfig config = reader(BadgeReaderKind::kSerial, "/dev/null");
  config.baud = 12345;
  auto opened = open_badge_reader(config);
  ASSERT_FALSE(opened);
  EXPECT_EQ(opened.error().code, ErrorCode::kInvalidArgument);
}

}  // namespace
}  // namespace hubrt::hal::rfid
