// A badge reader kept as a supervised device (supervised_device.h): opened again with back-off
// when it is unplugged (kUnavailable from poll), like a GPIO chip that went away.
#pragma once

#include "hubrt/hal/badge_reader.h"
#include "hubrt/hal/common/supervised_device.h"

namespace hubrt::hal {

template <>
struct DeviceOpener<BadgeReader> {
  using Config = BadgeReaderConfig;
  static Expected<std::unique_ptr<BadgeReader>> open(Backend& backend, const Config& config) {
    return backend.open_badge_reader(config);
  }
  static std::string_view name(const Config& config) noexcept { return config.reader; }
  static constexpr bool gone(ErrorCode code) noexcept { return code == ErrorCode::kUnavailable; }
};

using SupervisedBadgeReader = SupervisedDevice<BadgeReader>;

// The next badge, opening the reader first when a retry is due. True and `out` filled when one
// was read. Errors: kUnavailable while not open (or it just went away: dropped); the reader's own.
inline Result<bool> poll_badge(SupervisedBadgeReader& reader, BadgeRead& out, Time now) noexcept {
  BadgeReader* device = reader.device(now);
  if (device == nullptr) return Status(ErrorCode::kUnavailable);
  const Result<bool> polled = device->poll(out, now);
  if (!polled.is_ok()) reader.observe(polled.status().code(), now);
  return polled;
}

}  // namespace hubrt::hal
