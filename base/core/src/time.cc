#include "hubrt/base/time.h"

#include <ctime>

namespace hubrt {
namespace {

std::int64_t read_ns(clockid_t id) noexcept {
  timespec ts{};
  clock_gettime(id, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

// 2026-01-01T00:00:00Z, an arbitrary recognisable epoch for manual wall time.
constexpr std::int64_t kManualWallEpochNs = 1'767'225'600LL * 1'000'000'000;
// One day in, so that subtracting a timeout from an early time never goes negative.
constexpr std::int64_t kManualMonoStartNs = 86'400LL * 1'000'000'000;

}  // namespace

Instant SystemClock::now() const noexcept {
  return Instant{Time(Duration(read_ns(CLOCK_MONOTONIC))), WallTime{read_ns(CLOCK_REALTIME)}};
}

ManualClock::ManualClock() noexcept
    : mono_ns_(kManualMonoStartNs), wall_offset_ns_(kManualWallEpochNs - kManualMonoStartNs) {}

Instant ManualClock::now() const noexcept {
  const std::int64_t mono = mono_ns_.load(std::memory_order_acquire);
  return Instant{Time(Duration(mono)), WallTime{mono + wall_offset_ns_}};
}

void ManualClock::advance(Duration d) noexcept {
  mono_ns_.fetch_add(d.count(), std::memory_order_acq_rel);
}

void ManualClock::set(Time t) noexcept {
  mono_ns_.store(t.time_since_epoch().count(), std::memory_order_release);
}

}  // namespace hubrt
