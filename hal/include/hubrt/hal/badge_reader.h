// An RFID badge reader: badges read as bounded text with the time they were read. Two kinds of
// reader are common and both present a badge as a line of text: HID "keyboard wedge" readers type
// the badge's ID as key presses ended by Enter (Linux input events), serial readers send it as an
// ASCII line. Which one a reader is, and where, is the board file's business (boards/README.md).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"

namespace hubrt::hal {

enum class BadgeReaderKind : std::uint8_t {
  kEvdev,   // Linux input device (/dev/input/event*), keys decoded, Enter ends a badge
  kSerial,  // serial line (/dev/tty*), ASCII, a terminator byte ends a badge
};

struct BadgeReaderConfig {
  std::string reader;  // logical name used in error messages, e.g. "operator.rfid"
  BadgeReaderKind kind = BadgeReaderKind::kEvdev;
  std::string device;  // e.g. "/dev/input/by-id/usb-...-event-kbd", "/dev/ttyUSB0"
  bool grab = true;    // evdev: take the device for ourselves (EVIOCGRAB): no keystrokes reach a console
  std::uint32_t baud = 9600;  // serial only
  char terminator = '\r';     // serial only: the byte that ends a badge ('\r' or '\n'; the other is ignored)
  // A badge whose characters stop arriving for this long without its end is dropped as malformed
  // (a reader unplugged mid-badge, line noise).
  Duration timeout{std::chrono::milliseconds(500)};
};

// One badge as the reader gave it. Never allocates: the text lives in the object.
struct BadgeRead {
  static constexpr std::size_t kMaxLength = 32;  // longer is malformed (no real badge ID is)

  bool malformed = false;    // garbage bytes, too long, or cut off; `problem` says which
  std::string_view problem;  // static text, e.g. "not printable ASCII"; empty for a good read
  std::array<char, kMaxLength> chars{};
  std::uint8_t length = 0;  // bytes in chars (the text read so far, for a malformed read: for no one to see)
  Time at{};                // when its last character arrived

  [[nodiscard]] std::string_view text() const noexcept { return {chars.data(), length}; }
};

// Not thread-safe: one owner (the node, on the cycle thread).
class BadgeReader {
 public:
  virtual ~BadgeReader() = default;
  BadgeReader(const BadgeReader&) = delete;
  BadgeReader& operator=(const BadgeReader&) = delete;

  // Takes what the device has without waiting; `out` gets the next complete badge (good or
  // malformed), and true is returned; false when there is none yet. Never blocks.
  // Errors: kUnavailable (the device went away: unplugged), kIo (a read failed otherwise).
  Result<bool> poll(BadgeRead& out, Time now) noexcept { return do_poll(out, now); }

 protected:
  BadgeReader() = default;

 private:
  virtual Result<bool> do_poll(BadgeRead& out, Time now) noexcept = 0;
};

}  // namespace hubrt::hal
