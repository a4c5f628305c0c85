// The board's rfid: section: keyboard-wedge and serial readers, their defaults and their errors.
#include <gtest/gtest.h>

#include "hubrt/hal/board/board_loader.h"
#include "hubrt/hal/board/board_requirements.h"

namespace hubrt::hal {
namespace {

using std::chrono::milliseconds;

Expected<BoardConfig> with_rfid(const std::string& rfid) {
  return load_board_string("board: b\narch: arm64\nhub: operator_hub\nrfid:\n" + rfid, "b.yaml");
}

TEST(RfidSection, ReadsBothKindsWithTheirDefaults) {
  auto board = with_rfid(
      "  front: {evdev: {device: /dev/input/by-id/usb-x-event-kbd}}\n"
      "  back: {serial: {device: /dev/ttyUSB0, baud: 19200, terminator: lf}, timeout_ms: 200}\n");
  ASSERT_TRUE(board) << board.error().message;
  const BoardBadgeReader* front = board->find_badge_reader("front");
  ASSERT_NE(front, nullptr);
  EXPECT_EQ(front->config.kind, BadgeReaderKind::kEvdev);
  EXPECT_TRUE(front->config.grab);
  EXPECT_EQ(front->config.timeout, milliseconds(500));
  EXPECT_EQ(front->where.line, 5);
  const BoardBadgeReader* back = board->find_badge_reader("back");
  ASSERT_NE(back, nullptr);
  EXPECT_EQ(back->config.kind, BadgeReaderKind::kSerial);
  EXPECT_EQ(back->config.baud, 19200U);
  EXPECT_EQ(back->config.terminator, '\n');
  EXPECT_EQ(back->config.timeout, milliseconds(200));
}

TEST(RfidSection, AReaderIsRequiredAsOne) {
  auto board = with_rfid("  front: {evdev: {device: /dev/input/event3}}\n");
  ASSERT_TRUE(board);
  BoardRequirements needs{"operator_hub", {}, {}, {}, {}};
  needs.badge_readers = {"front"};
  EXPECT_TRUE(check_requirements(*board, needs));
  needs.badge_readers = {"back"};
  const auto missing = check_requirements(*board, needs);
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().message,
            "hub operator_hub needs RFID reader 'back' but b.yaml does not declare it");
}

struct BrokenRfid {
  const char* name;
  const char* rfid;
  const char* expected;
};

class BrokenRfidSection : public ::testing::TestWithParam<BrokenRfid> {};

TEST_P(BrokenRfidSection, IsRefusedWithItsLine) {
  auto board = with_rfid(GetParam().rfid);
  ASSERT_FALSE(board);
  EXPECT_NE(board.error().message.find(GetParam().expected), std::string::npos) << board.error().message;
}

INSTANTIATE_TEST_SUITE_P(
    Readers, BrokenRfidSection,
    ::testing::Values(
        BrokenRfid{"Both", "  r: {evdev: {device: /dev/input/event1}, serial: {device: /dev/ttyS0}}\n",
                   "b.yaml:5:6: rfid.r: give exactly one of evdev or serial"},
        BrokenRfid{"NotAnInputDevice", "  r: {evdev: {device: /dev/ttyS0}}\n",
                   "'/dev/ttyS0' is not an input device path (/dev/input/...)"},
        BrokenRfid{"DotDot", "  r: {evdev: {device: /dev/input/../sda}}\n", "is not an input device path"},
        BrokenRfid{"OddBaud", "  r: {serial: {device: /dev/ttyUSB0, baud: 10000}}\n",
                   "10000 is not a standard baud rate"},
        BrokenRfid{"Terminator", "  r: {serial: {device: /dev/ttyUSB0, terminator: tab}}\n", "terminator"},
        BrokenRfid{"Timeout", "  r: {evdev: {device: /dev/input/event1}, timeout_ms: 0}\n", "timeout_ms"},
        BrokenRfid{"UnknownKey", "  r: {evdev: {device: /dev/input/event1, grab: true, led: on}}\n", "led"}),
    [](const auto& rfid_info) { return std::string(rfid_info.param.name); });

}  // namespace
}  // namespace hubrt::hal
