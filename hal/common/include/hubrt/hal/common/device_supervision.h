// The bookkeeping of a supervised device (hubrt/hal/common/supervised_device.h) that does not
// depend on the kind of device: health, why it is not open, when to try again, counters.
#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "hubrt/base/time.h"

namespace hubrt::hal {

enum class DeviceHealth : std::uint8_t {
  kNeverOpened,  // not opened since start; retried with back-off
  kOpen,
  kRetrying,  // was open, went away (or failed to open again); retried with back-off
};
// "never opened", "open", "retrying".
std::string_view to_string(DeviceHealth health) noexcept;

// The wait before the first retry after a failure, doubled after each failed retry up to `cap`.
struct BackOff {
  Duration first{std::chrono::milliseconds(100)};
  Duration cap{std::chrono::seconds(2)};
};
inline constexpr BackOff kDefaultBackOff{};

// Not thread-safe (one owner). Never allocates.
class DeviceSupervision {
 public:
  // Room for the reason a device is not open; longer texts are cut at a UTF-8 character and end
  // in "...".
  static constexpr std::size_t kErrorCapacity = 191;

  // Precondition: 0 < back_off.first <= back_off.cap.
  explicit DeviceSupervision(BackOff back_off) noexcept;

  [[nodiscard]] DeviceHealth health() const noexcept { return health_; }
  // Why the device is not open; empty while it is.
  [[nodiscard]] std::string_view error() const noexcept { return {error_.data(), error_length_}; }
  // Retries so far (opening again after a failure or after the device went away), and how many
  // of them worked; times the device went away.
  [[nodiscard]] std::uint32_t reopen_attempts() const noexcept { return reopen_attempts_; }
  [[nodiscard]] std::uint32_t reopens() const noexcept { return reopens_; }
  [[nodiscard]] std::uint32_t drops() const noexcept { return drops_; }
  // When the next retry is due (meaningful while not open).
  [[nodiscard]] Time next_attempt() const noexcept { return next_attempt_; }
  [[nodiscard]] bool retry_due(Time now) const noexcept {
    return health_ != DeviceHealth::kOpen && now >= next_attempt_;
  }

  // --- For SupervisedDevice ---------------------------------------------------------------------
  void opened() noexcept;
  void open_failed(std::string_view why, Time now) noexcept;
  // The device went away at `now`: the first retry is due `back_off.first` later.
  void dropped(Time now) noexcept;
  // The device went away where no time was at hand: the next call with a time retries.
  void dropped_without_time() noexcept;

 private:
  void set_error(std::string_view text) noexcept;

  BackOff back_off_;
  Duration wait_;  // before the next retry after a failed one
  Time next_attempt_{};
  DeviceHealth health_ = DeviceHealth::kNeverOpened;
  bool attempted_ = false;  // the first open was tried: later ones are retries
  std::uint32_t reopen_attempts_ = 0;
  std::uint32_t reopens_ = 0;
  std::uint32_t drops_ = 0;
  std::array<char, kErrorCapacity> error_{};
  std::size_t error_length_ = 0;
};

}  // namespace hubrt::hal
