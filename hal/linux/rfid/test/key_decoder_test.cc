// Key decoding on events recorded from keyboard-wedge readers (evemu-record shape: type, code,
// value; the MSC_SCAN and SYN_REPORT events such a reader sends between its keys included).
#include "key_decoder.h"

#include <vector>

#include <gtest/gtest.h>
#include <linux/input-event-codes.h>

namespace hubrt::hal::rfid {
namespace {

using std::chrono::milliseconds;

struct Event {
  std::uint16_t type;
  std::uint16_t code;
  std::int32_t value;
};

// One key as a USB HID keyboard reports it: scan code, press, sync, scan code, release, sync.
void key(std::vector<Event>& events, std::uint16_t code) {
  events.push_back({EV_MSC, MSC_SCAN, 0x70000 + code});
  events.push_back({EV_KEY, code, 1});
  events.push_back({EV_SYN, SYN_REPORT, 0});
  events.push_back({EV_MSC, MSC_SCAN, 0x70000 + code});
  events.push_back({EV_KEY, code, 0});
  events.push_back({EV_SYN, SYN_REPORT, 0});
}

class KeyDecoderTest : public ::testing::Test {
 protected:
  // Feeds `events` one per millisecond; the reads completed, in order.
  std::vector<BadgeRead> play(const std::vector<Event>& events) {
    std::vector<BadgeRead> reads;
    for (const Event& e : events) {
      clock_.advance(milliseconds(1));
      BadgeRead read;
      if (decoder_.feed(e.type, e.code, e.value, read, clock_.now().mono)) reads.push_back(read);
    }
    return reads;
  }

  ManualClock clock_;
  KeyDecoder decoder_{milliseconds(500)};
};

TEST_F(KeyDecoderTest, TenDigitBadgeEndedByEnterIsRead) {
  // An EM4100 reader typing "0004123456" + Enter.
  std::vector<Event> events;
  for (int code : {KEY_0, KEY_0, KEY_0, KEY_4, KEY_1, KEY_2, KEY_3, KEY_4, KEY_5, KEY_6})
    key(events, static_cast<std::uint16_t>(code));
  key(events, KEY_ENTER);
  const auto reads = play(events);
  ASSERT_EQ(reads.size(), 1u);
  EXPECT_FALSE(reads[0].malformed);
  EXPECT_EQ(reads[0].text(), "0004123456");
}

TEST_F(KeyDecoderTest, ShiftGivesUpperCaseHexAndKeypadDigitsCount) {
  std::vector<Event> events;
  events.push_back({EV_KEY, KEY_LEFTSHIFT, 1});
  key(events, KEY_A);
  key(events, KEY_F);
  events.push_back({EV_KEY, KEY_LEFTSHIFT, 0});
  key(events, KEY_KP7);
  key(events, KEY_B);
  key(events, KEY_KPENTER);
  const auto reads = play(events);
  ASSERT_EQ(reads.size(), 1u);
  EXPECT_EQ(reads[0].text(), "AF7b");
}

TEST_F(KeyDecoderTest, AutoRepeatIsNotASecondCharacter) {
  std::vector<Event> events{{EV_KEY, KEY_5, 1}, {EV_KEY, KEY_5, 2}, {EV_KEY, KEY_5, 2}, {EV_KEY, KEY_5, 0}};
  key(events, KEY_ENTER);
  const auto reads = play(events);
  ASSERT_EQ(reads.size(), 1u);
  EXPECT_EQ(reads[0].text(), "5");
}

TEST_F(KeyDecoderTest, AKeyThatIsNoBadgeCharacterMakesItMalformed) {
  std::vector<Event> events;
  key(events, KEY_1);
  key(events, KEY_F1);
  key(events, KEY_2);
  key(events, KEY_ENTER);
  key(events, KEY_3);  // the next badge is clean again
  key(events, KEY_ENTER);
  const auto reads = play(events);
  ASSERT_EQ(reads.size(), 2u);
  EXPECT_TRUE(reads[0].malformed);
  EXPECT_EQ(reads[0].text(), "");
  EXPECT_FALSE(reads[1].malformed);
  EXPECT_EQ(reads[1].text(), "3");
}

TEST_F(KeyDecoderTest, LostEventsMakeTheBadgeInProgressMalformed) {
  std::vector<Event> events;
  key(events, KEY_1);
  play(events);
  decoder_.events_lost(clock_.now().mono);
  events.clear();
  key(events, KEY_ENTER);
  const auto reads = play(events);
  ASSERT_EQ(reads.size(), 1u);
  EXPECT_TRUE(reads[0].malformed);
}

TEST_F(KeyDecoderTest, EnterAloneIsNoBadge) {
  std::vector<Event> events;
  key(events, KEY_ENTER);
  EXPECT_TRUE(play(events).empty());
}

}  // namespace
}  // namespace hubrt::hal::rfid
