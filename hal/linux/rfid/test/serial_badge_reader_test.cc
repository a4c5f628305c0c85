// The serial reader against a pty pair: the test writes to the master side what a reader would
// send; the hub's reader has the slave side (a real termios device).
#include <fcntl.h>
#include <stdlib.h>
#include <unistd.h>

#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "hubrt/hal/rfid/open_badge_reader.h"

namespace hubrt::hal::rfid {
namespace {

using std::chrono::milliseconds;

class SerialBadgeReaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    master_ = ::posix_openpt(O_RDWR | O_NOCTTY);
    ASSERT_GE(master_, 0);
    ASSERT_EQ(::grantpt(master_), 0);
    ASSERT_EQ(::unlockpt(master_), 0);
    config_.reader = "operator.rfid";
    config_.kind = BadgeReaderKind::kSerial;
    config_.device = ::ptsname(master_);
    config_.baud = 9600;
    config_.terminator = '\r';
    config_.timeout = milliseconds(300);
    auto opened = open_badge_reader(config_);
    ASSERT_TRUE(opened) << opened.error().message;
    reader_ = std::move(*opened);
  }
  void TearDown() override {
    reader_.reset();
    if (master_ >= 0) ::close(master_);
  }

  void send(std::string_view bytes) {
    ASSERT_EQ(::write(master_, bytes.data(), bytes.size()), static_cast<ssize_t>(bytes.size()));
  }
  // Polls until a badge comes or the (generous: the machine is shared) deadline of polls passes;
  // the bytes cross the pty in the kernel, so they are there after the write returned, but a
  // loaded machine may schedule the line discipline's work later.
  bool next(BadgeRead& read) {
    for (int i = 0; i < 2000; ++i) {
      const Result<bool> got = reader_->poll(read, clock_.now().mono);
      EXPECT_TRUE(got.is_ok());
      if (!got.is_ok()) return false;
      if (got.value()) return true;
      ::usleep(1000);
    }
    return false;
  }

  ManualClock clock_;
  int master_ = -1;
  BadgeReaderConfig config_;
  std::unique_ptr<BadgeReader> reader_;
};

TEST_F(SerialBadgeReaderTest, LineEndedByTheTerminatorIsABadge) {
  send("0004123456\r\n");
  BadgeRead read;
  ASSERT_TRUE(next(read));
  EXPECT_FALSE(read.malformed);
  EXPECT_EQ(read.text(), "0004123456");
}

TEST_F(SerialBadgeReaderTest, TwoBadgesInOneWriteAreReadOneAfterTheOther) {
  send("111\r222\r");
  BadgeRead read;
  ASSERT_TRUE(next(read));
  EXPECT_EQ(read.text(), "111");
  ASSERT_TRUE(next(read));
  EXPECT_EQ(read.text(), "222");
}

TEST_F(SerialBadgeReaderTest, GarbageBytesGiveOneMalformedReadAndNoCrash) {
  send(std::string("\x00\x01\xff\xfe garbage\x1b[2J", 16) + "\r");
  BadgeRead read;
  ASSERT_TRUE(next(read));
  EXPECT_TRUE(read.malformed);
  EXPECT_EQ(read.problem, "not printable ASCII");
  send("42\r");
  ASSERT_TRUE(next(read));
  EXPECT_FALSE(read.malformed);
  EXPECT_EQ(read.text(), "42");
}

TEST_F(SerialBadgeReaderTest, AnEndlessLineIsMalformedNotUnbounded) {
  send(std::string(4096, '9') + "\r");
  BadgeRead read;
  ASSERT_TRUE(next(read));
  EXPECT_TRUE(read.malformed);
  EXPECT_EQ(read.problem, "too long");
}

TEST_F(SerialBadgeReaderTest, APartialLineIsDroppedAfterTheTimeout) {
  send("1234");
  BadgeRead read;
  for (int i = 0; i < 200; ++i) {  // let the bytes arrive: nothing complete yet
    ASSERT_TRUE(reader_->poll(read, clock_.now().mono).is_ok());
    ::usleep(1000);
  }
  clock_.advance(milliseconds(301));
  ASSERT_TRUE(next(read));
  EXPECT_TRUE(read.malformed);
  EXPECT_NE(read.problem.find("cut off"), std::string_view::npos);
}

TEST_F(SerialBadgeReaderTest, TheOtherSideClosingIsUnavailable) {
  ::close(master_);
  master_ = -1;
  BadgeRead read;
  const Result<bool> got = reader_->poll(read, clock_.now().mono);
  ASSERT_FALSE(got.is_ok());
  EXPECT_EQ(got.status().code(), ErrorCode::kUnavailable);
}

}  // namespace
}  // namespace hubrt::hal::rfid
