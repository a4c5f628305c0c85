// A simulated RFID badge reader: a test, the sim bridge (/sim/input with a text) or the demo
// "shows it a badge"; the reader then sends that text and its end mark, as a real one would,
// through the same BadgeLineAssembler, so a text with control bytes or one too long is
// malformed exactly as from a real reader. It can be unplugged and plugged in again.
// Thread-safety: none; the cycle thread's (as the fake GPIO).
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <string_view>

#include "hubrt/base/status.h"
#include "hubrt/hal/badge_reader.h"

namespace hubrt::hal::fake {

class SimulatedBadgeReader {
 public:
  explicit SimulatedBadgeReader(BadgeReaderConfig config) : config_(std::move(config)) {}

  // The reader reads `text` (any bytes) next. At most kMaxQueued wait; older ones are dropped
  // first (a real reader has no queue at all beyond the kernel's).
  void present(std::string_view text);
  void unplug() noexcept;
  void plug_in() noexcept { plugged_ = true; }
  [[nodiscard]] bool plugged() const noexcept { return plugged_; }
  [[nodiscard]] const BadgeReaderConfig& config() const noexcept { return config_; }

  // The device the backend hands out. Errors: kNotFound while unplugged.
  Expected<std::unique_ptr<BadgeReader>> open();

  static constexpr std::size_t kMaxQueued = 8;

 private:
  class Device;
  BadgeReaderConfig config_;
  std::deque<std::string> queued_;
  bool plugged_ = true;
  std::uint32_t generation_ = 0;  // bumped by unplug(): devices opened before are gone
};

}  // namespace hubrt::hal::fake
