// Time as the runtime sees it. Node logic never reads a clock: the cycle passes time in, so a
// test drives it with ManualClock and gets the same outputs every run.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>

namespace hubrt {

using Duration = std::chrono::nanoseconds;
// Monotonic time. Only differences between two Times mean anything.
using Time = std::chrono::time_point<std::chrono::steady_clock, Duration>;

// Wall-clock time in nanoseconds since the Unix epoch, as stamped into message headers.
struct WallTime {
  std::int64_t ns_since_epoch = 0;
};

// The two readings a cycle needs: monotonic for logic and deadlines, wall for stamps.
struct Instant {
  Time mono;
  WallTime wall;
};

// Thread-safety: implementations must allow now() from any thread.
class Clock {
 public:
  virtual ~Clock() = default;
  [[nodiscard]] virtual Instant now() const noexcept = 0;
};

// CLOCK_MONOTONIC and CLOCK_REALTIME of the host.
class SystemClock final : public Clock {
 public:
  [[nodiscard]] Instant now() const noexcept override;
};

// A clock that moves only when told. Starts at a fixed, non-zero instant so that "time zero"
// bugs show up in tests.
class ManualClock final : public Clock {
 public:
  ManualClock() noexcept;
  [[nodiscard]] Instant now() const noexcept override;
  void advance(Duration d) noexcept;
  void set(Time t) noexcept;

 private:
  std::atomic<std::int64_t> mono_ns_;
  std::int64_t wall_offset_ns_;
};

constexpr double to_seconds(Duration d) noexcept {
  return std::chrono::duration<double>(d).count();
}

}  // namespace hubrt
