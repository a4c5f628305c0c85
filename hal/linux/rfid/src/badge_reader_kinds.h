// The two kinds of Linux badge reader. Errors: as open_badge_reader.
#pragma once

#include <memory>

#include "hubrt/base/status.h"
#include "hubrt/hal/badge_reader.h"

namespace hubrt::hal::rfid {
Expected<std::unique_ptr<BadgeReader>> open_evdev_badge_reader(const BadgeReaderConfig& config);
Expected<std::unique_ptr<BadgeReader>> open_serial_badge_reader(const BadgeReaderConfig& config);
}  // namespace hubrt::hal::rfid
