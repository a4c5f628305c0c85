#include "hubrt/hal/common/device_supervision.h"

#include <algorithm>

namespace hubrt::hal {

std::string_view to_string(DeviceHealth health) noexcept {
  switch (health) {
    case DeviceHealth::kOpen:
      return "open";
    case DeviceHealth::kRetrying:
      return "retrying";
    case DeviceHealth::kNeverOpened:
      break;
  }
  return "never opened";
}

DeviceSupervision::DeviceSupervision(BackOff back_off) noexcept : back_off_(back_off), wait_(back_off.first) {
  set_error("not opened yet");
}

void DeviceSupervision::opened() noexcept {
  if (attempted_) {
    ++reopen_attempts_;
    ++reopens_;
  }
  attempted_ = true;
  health_ = DeviceHealth::kOpen;
  wait_ = back_off_.first;
  error_length_ = 0;
}

void DeviceSupervision::open_failed(std::string_view why, Time now) noexcept {
  if (attempted_) ++reopen_attempts_;
  attempted_ = true;
  // A device that was open once stays "retrying"; one never opened stays so until it opens.
  set_error(why);
  next_attempt_ = now + wait_;
  wait_ = std::min(wait_ * 2, back_off_.cap);
}

void DeviceSupervision::dropped(Time now) noexcept {
  ++drops_;
  health_ = DeviceHealth::kRetrying;
  set_error("device went away");
  wait_ = back_off_.first;
  next_attempt_ = now + wait_;
  wait_ = std::min(wait_ * 2, back_off_.cap);
}

void DeviceSupervision::dropped_without_time() noexcept {
  ++drops_;
  health_ = DeviceHealth::kRetrying;
  set_error("device went away");
  wait_ = back_off_.first;
  next_attempt_ = Time{};
}

void DeviceSupervision::set_error(std::string_view text) noexcept {
  std::size_t n = std::min(text.size(), error_.size());
  std::copy_n(text.data(), n, error_.data());
  if (text.size() > error_.size()) {
    // Cut before the character "..." would overwrite, so no lead byte loses its continuation.
    std::size_t cut = error_.size() - 3;
    while (cut > 0 && (static_cast<unsigned char>(error_[cut]) & 0xc0U) == 0x80U) --cut;
    std::fill_n(error_.data() + cut, 3, '.');
    n = cut + 3;
  }
  error_length_ = n;
}

}  // namespace hubrt::hal
