// Contact debouncing as pure logic: samples and their times go in, the debounced level comes out.
#pragma once

#include <optional>

#include "hubrt/base/time.h"

namespace hubrt::hal {

// A new level is reported only once it has been sampled continuously for `window`: a sample at
// time t that differs from the reported level starts a candidate; the candidate is reported by the
// first sample at or after t + window that still shows it, and dropped by any sample that shows
// the reported level again. Only what is sampled is seen: a bounce between two samples is
// invisible here (see PulseCatcher for lines whose backend records edges).
//
// The first sample is reported as it is: there is nothing to debounce it against.
// A window of zero passes every sample through.
// Not thread-safe; never allocates; times must not go backwards.
class Debouncer {
 public:
  explicit Debouncer(Duration window) noexcept : window_(window) {}

  // Feeds the raw level sampled at `now` and returns the debounced level.
  bool update(bool raw, Time now) noexcept;

  // The debounced level, or nothing before the first sample.
  [[nodiscard]] std::optional<bool> level() const noexcept { return stable_; }
  [[nodiscard]] Duration window() const noexcept { return window_; }
  // Forgets everything: the next sample is reported as it is.
  void reset() noexcept;

 private:
  Duration window_;
  std::optional<bool> stable_;
  bool candidate_pending_ = false;
  Time candidate_since_{};
};

}  // namespace hubrt::hal
