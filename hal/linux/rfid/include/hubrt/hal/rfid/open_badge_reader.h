// RFID badge readers on Linux: HID keyboard-wedge readers through their input device (libevdev,
// grabbed so no keystroke reaches a console or a login prompt), serial ASCII readers through
// termios. Both are read without blocking: the cycle polls them.
#pragma once

#include <memory>

#include "hubrt/base/status.h"
#include "hubrt/hal/badge_reader.h"

namespace hubrt::hal::rfid {

// Opens the reader config.kind says. Errors, each naming the reader and its device:
// kNotFound (no such device), kPermissionDenied (not readable: udev rule or group missing),
// kBusy (evdev: another process grabbed it), kInvalidArgument (not an input device with an Enter
// key / not a terminal, or a baud rate termios has no constant for), kIo.
Expected<std::unique_ptr<BadgeReader>> open_badge_reader(const BadgeReaderConfig& config);

}  // namespace hubrt::hal::rfid
