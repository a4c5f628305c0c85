// A digital input that may not be open: a missing chip or a line taken by another process must
// not stop the hub. The hub comes up, the State says what is missing, and the input is opened
// again every retry interval until it works (then the error goes away by itself).
#pragma once

#include <memory>
#include <string>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/hal/backend.h"
#include "hubrt/runtime/text_buffer.h"

namespace hubrt::hubs {

// Not thread-safe: owned by one node on the cycle thread. Opening (the first time and on retry)
// allocates; reading an open input does not.
class ReopeningInput {
 public:
  static constexpr Duration kDefaultRetryInterval = std::chrono::seconds(2);

  ReopeningInput(hal::Backend& backend, hal::DigitalInputConfig config,
                 Duration retry_interval = kDefaultRetryInterval);

  // Tries to open now (at construction time of the hub); a failure is kept and retried later.
  void open_now(Time now);
  // The level, opening the input first if it is closed and the retry interval has passed.
  // Errors: kUnavailable while not open; the device's own errors when a read fails.
  Result<bool> read(Time now) noexcept;

  [[nodiscard]] bool is_open() const noexcept { return input_ != nullptr; }
  // Why the input is not open (empty when it is).
  [[nodiscard]] std::string_view open_error() const noexcept { return open_error_.view(); }
  [[nodiscard]] const hal::DigitalInputConfig& config() const noexcept { return config_; }

 private:
  hal::Backend* backend_;
  hal::DigitalInputConfig config_;
  Duration retry_interval_;
  std::unique_ptr<hal::DigitalInput> input_;
  runtime::TextBuffer<191> open_error_;
  Time next_attempt_{};
};

}  // namespace hubrt::hubs
