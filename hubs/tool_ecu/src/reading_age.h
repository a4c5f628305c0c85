// The age of a device reading as the State carries it (`reading_age_ms`, `status_age_ms`):
// milliseconds as uint32, saturating, so a reading older than 49 days, or none at all, reads as
// the largest value instead of wrapping to a young one.
#pragma once

#include <cstdint>
#include <limits>

#include "hubrt/base/time.h"

namespace hubrt::tool_ecu {

// The age of a device that was never read.
inline constexpr std::uint32_t kNeverRead = std::numeric_limits<std::uint32_t>::max();

// `age` in milliseconds rounded up, clamped to 0..kNeverRead. Rounded up so that a reading the
// hub judged older than a validity of N ms never shows an age of N (500.3 ms is 501, stale;
// 499.7 ms is 500, current): "age <= validity" and the State's flag always agree. A negative age
// (a reading stamped by another thread just after the cycle took its time) is 0. Thread-safe.
[[nodiscard]] constexpr std::uint32_t saturating_age_ms(Duration age) noexcept {
  const auto ms = std::chrono::ceil<std::chrono::milliseconds>(age).count();
  if (ms <= 0) return 0;
  if (static_cast<std::uint64_t>(ms) >= kNeverRead) return kNeverRead;
  return static_cast<std::uint32_t>(ms);
}

// The age of a reading taken at `read_at`, or kNeverRead when there was none.
[[nodiscard]] constexpr std::uint32_t reading_age_ms(bool ever_read, Time read_at, Time now) noexcept {
  return ever_read ? saturating_age_ms(now - read_at) : kNeverRead;
}

}  // namespace hubrt::tool_ecu
