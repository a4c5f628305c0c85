// A digital output that may not be open: a missing chip must not stop the hub. The hub comes up,
// the State says what is missing, and the line is opened again every retry interval. While it is
// not open nothing drives it, so the valve sits de-energised (for the lock valve: locked).
#pragma once

#include <memory>
#include <string_view>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/hal/backend.h"
#include "hubrt/runtime/text_buffer.h"

namespace hubrt::rsp_ecu {

// Not thread-safe: owned by one node on the cycle thread. Opening (the first time and on retry)
// allocates; writing an open line does not.
class ReopeningOutput {
 public:
  static constexpr Duration kDefaultRetryInterval = std::chrono::seconds(2);

  ReopeningOutput(hal::Backend& backend, hal::DigitalOutputConfig config,
                  Duration retry_interval = kDefaultRetryInterval);

  // Tries to open now (the line then drives config.initial); a failure is kept and retried later.
  void open_now(Time now);
  // Drives `active`, opening the line first if it is closed and the retry interval has passed.
  // Errors: kUnavailable while not open; the device's own errors when the write fails (a chip
  // that went away is dropped and opened again later).
  Status write(bool active, Time now) noexcept;
  // Drives `active` if the line is open; never opens it (for shutdown and faults, where no time
  // is at hand). Errors: kUnavailable while not open; the device's own.
  Status write_if_open(bool active) noexcept;

  [[nodiscard]] bool is_open() const noexcept { return output_ != nullptr; }
  // Why the line is not open (empty when it is).
  [[nodiscard]] std::string_view open_error() const noexcept { return open_error_.view(); }
  [[nodiscard]] const hal::DigitalOutputConfig& config() const noexcept { return config_; }

 private:
  hal::Backend* backend_;
  hal::DigitalOutputConfig config_;
  Duration retry_interval_;
  std::unique_ptr<hal::DigitalOutput> output_;
  runtime::TextBuffer<191> open_error_;
  Time next_attempt_{};
};

}  // namespace hubrt::rsp_ecu
