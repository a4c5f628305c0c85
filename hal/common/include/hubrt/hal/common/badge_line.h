// Assembles badge reads from characters as they arrive, for every badge reader backend (evdev
// keys, serial bytes, the simulator): bounded, printable ASCII only, ended by the reader's end
// mark, and dropped as malformed when it is too long, holds anything else, or stops half way.
// Never allocates; time is passed in. Not thread-safe (one owner).
#pragma once

#include <cstddef>

#include "hubrt/base/time.h"
#include "hubrt/hal/badge_reader.h"

namespace hubrt::hal {

class BadgeLineAssembler {
 public:
  // `timeout`: a badge whose next character does not come within this is dropped as cut off.
  explicit BadgeLineAssembler(Duration timeout) noexcept : timeout_(timeout) {}

  // One character of a badge. Printable ASCII (0x20..0x7E) is kept; anything else marks the badge
  // malformed (it is still read to its end, then reported once).
  void add(char c, Time now) noexcept;
  // Something that is no character (a key we cannot decode): marks the badge malformed.
  void add_garbage(std::string_view problem, Time now) noexcept;
  // The end mark (Enter, the terminator). True and `out` filled when a badge (good or malformed)
  // was in progress; an end mark with nothing before it is ignored.
  bool end(BadgeRead& out, Time now) noexcept;
  // True and `out` filled (malformed, "cut off") when a badge in progress has waited longer than
  // the timeout for its next character. Call before adding what arrived at `now`.
  bool expire(BadgeRead& out, Time now) noexcept;
  // Forgets a badge in progress (the device went away).
  void clear() noexcept;

  [[nodiscard]] bool in_progress() const noexcept { return started_; }

 private:
  void start(Time now) noexcept;
  void finish(BadgeRead& out) noexcept;

  Duration timeout_;
  BadgeRead current_;
  bool started_ = false;
};

}  // namespace hubrt::hal
