// Keyboard-wedge decoding: the key events a HID RFID reader "types" (linux/input-event-codes.h)
// into badge characters, US layout, as such readers send them: digits (and letters for hex IDs)
// as key presses, Shift for upper case, Enter at the end. Pure (no device): the evdev reader feeds
// it, and tests feed it recorded events.
#pragma once

#include <cstdint>

#include "hubrt/hal/common/badge_line.h"

namespace hubrt::hal::rfid {

class KeyDecoder {
 public:
  explicit KeyDecoder(Duration timeout) noexcept : line_(timeout) {}

  // One input event (struct input_event's type, code, value). True and `out` filled when it
  // completed a badge. Key releases, auto-repeat, sync and scan-code events carry nothing; a
  // key that is neither a badge character, Enter nor a modifier makes the badge malformed.
  bool feed(std::uint16_t type, std::uint16_t code, std::int32_t value, BadgeRead& out, Time now) noexcept;
  // A badge in progress for longer than the timeout: see BadgeLineAssembler::expire.
  bool expire(BadgeRead& out, Time now) noexcept { return line_.expire(out, now); }
  // The kernel dropped events (SYN_DROPPED): a badge in progress cannot be trusted.
  void events_lost(Time now) noexcept;
  void clear() noexcept {
    line_.clear();
    shift_ = 0;
  }

 private:
  BadgeLineAssembler line_;
  unsigned shift_ = 0;  // Shift keys held (left and right count separately)
};

}  // namespace hubrt::hal::rfid
