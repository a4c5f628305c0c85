#include "hubrt/runtime/stage_trace.h"

#include <algorithm>
#include <cstdio>

#include <fmt/format.h>

namespace hubrt::runtime {
namespace {

std::int64_t ns_of(Time t) noexcept {
  return t.time_since_epoch().count();
}

}  // namespace

StageTrace::StageTrace(std::size_t capacity, const Clock& clock)
    : clock_(&clock), ring_(std::max<std::size_t>(capacity, 1)) {}

void StageTrace::note_wake() noexcept {
  std::int64_t none = 0;
  // 1 ns at least: 0 means "no wake" (a ManualClock never reads 0 either).
  const std::int64_t now = std::max<std::int64_t>(ns_of(clock_->now().mono), 1);
  wake_ns_.compare_exchange_strong(none, now, std::memory_order_relaxed);
}

void StageTrace::begin_step(Time woke) noexcept {
  current_ = StageRecord{};
  current_.listener = Time(Duration(wake_ns_.exchange(0, std::memory_order_relaxed)));
  current_.woke = woke;
}

void StageTrace::node_stepped() noexcept {
  if (current_.stepped == Time{}) current_.stepped = clock_->now().mono;
}

void StageTrace::state_written() noexcept {
  if (current_.written == Time{}) current_.written = clock_->now().mono;
}

void StageTrace::end_step() noexcept {
  ring_[steps_ % ring_.size()] = current_;
  ++steps_;
}

std::vector<StageRecord> StageTrace::records() const {
  const std::size_t held = std::min<std::uint64_t>(steps_, ring_.size());
  std::vector<StageRecord> out;
  out.reserve(held);
  for (std::uint64_t i = steps_ - held; i < steps_; ++i) out.push_back(ring_[i % ring_.size()]);
  return out;
}

Expected<void> StageTrace::write_csv(const std::string& path) const {
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (file == nullptr)
    return make_error(ErrorCode::kIo, fmt::format("cannot write the stage trace {}", path));
  const auto held = records();
  fmt::print(file, "# hubd stage trace: {} command steps, the last {} kept\n", steps_, held.size());
  fmt::print(file, "listener_ns,woke_ns,stepped_ns,written_ns\n");
  for (const StageRecord& r : held) {
    fmt::print(file, "{},{},{},{}\n", ns_of(r.listener), ns_of(r.woke), ns_of(r.stepped), ns_of(r.written));
  }
  const bool failed = std::ferror(file) != 0;
  if (std::fclose(file) != 0 || failed)
    return make_error(ErrorCode::kIo, fmt::format("cannot write the stage trace {}", path));
  return {};
}

}  // namespace hubrt::runtime
