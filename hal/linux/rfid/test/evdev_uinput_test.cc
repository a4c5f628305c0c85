// The keyboard-wedge reader against a real input device: a uinput virtual keyboard (libevdev's
// uinput API, https://www.freedesktop.org/software/libevdev/doc/latest/group__uinput.html) types
// a badge and Enter; the reader, holding the device grabbed, reads it; nobody else can grab it
// meanwhile; unplugged, it says so. Needs /dev/uinput and evdev: the kernel tier's guest loads
// both (tests/kernel, label "kernel"); elsewhere it skips.
#include <fcntl.h>
#include <unistd.h>

#include <cstring>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <libevdev/libevdev-uinput.h>
#include <libevdev/libevdev.h>
#include <linux/input.h>

#include "hubrt/hal/rfid/open_badge_reader.h"

namespace hubrt::hal::rfid {
namespace {

using std::chrono::milliseconds;

class EvdevUinputTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const int probe = ::open("/dev/uinput", O_RDWR | O_CLOEXEC);
    if (probe < 0) GTEST_SKIP() << "no /dev/uinput here (the kernel tier has it)";
    ::close(probe);
    libevdev* dev = libevdev_new();
    libevdev_set_name(dev, "hubrt test RFID reader");
    libevdev_enable_event_type(dev, EV_KEY);
    for (unsigned code : {KEY_0, KEY_1, KEY_2, KEY_3, KEY_4, KEY_5, KEY_6, KEY_7, KEY_8, KEY_9, KEY_ENTER,
                          KEY_LEFTSHIFT, KEY_A}) {
      libevdev_enable_event_code(dev, EV_KEY, code, nullptr);
    }
    const int rc = libevdev_uinput_create_from_device(dev, LIBEVDEV_UINPUT_OPEN_MANAGED, &uinput_);
    libevdev_free(dev);
    ASSERT_EQ(rc, 0) << "uinput: " << std::strerror(-rc);
    devnode_ = libevdev_uinput_get_devnode(uinput_);
    // udev-less guest: the node appears through devtmpfs shortly after the device is made.
    for (int i = 0; i < 200 && ::access(devnode_.c_str(), R_OK) != 0; ++i)
      std::this_thread::sleep_for(milliseconds(10));
    config_.reader = "operator_rfid";
    config_.kind = BadgeReaderKind::kEvdev;
    config_.device = devnode_;
    config_.grab = true;
  }
  void TearDown() override {
    if (uinput_ != nullptr) libevdev_uinput_destroy(uinput_);
  }

  void key(unsigned code) {
    libevdev_uinput_write_event(uinput_, EV_KEY, code, 1);
    libevdev_uinput_write_event(uinput_, EV_SYN, SYN_REPORT, 0);
    libevdev_uinput_write_event(uinput_, EV_KEY, code, 0);
    libevdev_uinput_write_event(uinput_, EV_SYN, SYN_REPORT, 0);
  }
  bool next(BadgeReader& reader, BadgeRead& read) {
    for (int i = 0; i < 2000; ++i) {  // up to 2 s: a loaded emulated guest
      const Result<bool> got = reader.poll(read, clock_.now().mono);
      EXPECT_TRUE(got.is_ok());
      if (!got.is_ok()) return false;
      if (got.value()) return true;
      std::this_thread::sleep_for(milliseconds(1));
    }
    return false;
  }

  ManualClock clock_;
  libevdev_uinput* uinput_ = nullptr;
  std::string devnode_;
  BadgeReaderConfig config_;
};

TEST_F(EvdevUinputTest, AVirtualKeyboardTypesABadgeAndTheGrabbedReaderReadsIt) {
  auto opened = open_badge_reader(config_);
  ASSERT_TRUE(opened) << opened.error().message;
  for (unsigned code : {KEY_0, KEY_0, KEY_0, KEY_4, KEY_1, KEY_2, KEY_3, KEY_4, KEY_5, KEY_6}) key(code);
  key(KEY_ENTER);
  BadgeRead read;
  ASSERT_TRUE(next(**opened, read));
  EXPECT_FALSE(read.malformed) << read.problem;
  EXPECT_EQ(read.text(), "0004123456");

  // Grabbed: a second reader of the same device cannot have it.
  auto second = open_badge_reader(config_);
  ASSERT_FALSE(second);
  EXPECT_EQ(second.error().code, ErrorCode::kBusy) << second.error().message;
}

TEST_F(EvdevUinputTest, AnUnpluggedReaderIsUnavailable) {
  auto opened = open_badge_reader(config_);
  ASSERT_TRUE(opened) << opened.error().message;
  libevdev_uinput_destroy(uinput_);
  uinput_ = nullptr;
  BadgeRead read;
  Result<bool> got = (*opened)->poll(read, clock_.now().mono);
  for (int i = 0; i < 200 && got.is_ok(); ++i) {
    std::this_thread::sleep_for(milliseconds(10));
    got = (*opened)->poll(read, clock_.now().mono);
  }
  ASSERT_FALSE(got.is_ok());
  EXPECT_EQ(got.status().code(), ErrorCode::kUnavailable);
}

}  // namespace
}  // namespace hubrt::hal::rfid
