#include "hubrt/hal/rfid/open_badge_reader.h"

#include "badge_reader_kinds.h"

namespace hubrt::hal::rfid {

Expected<std::unique_ptr<BadgeReader>> open_badge_reader(const BadgeReaderConfig& config) {
  if (config.kind == BadgeReaderKind::kSerial) return open_serial_badge_reader(config);
  return open_evdev_badge_reader(config);
}

}  // namespace hubrt::hal::rfid
