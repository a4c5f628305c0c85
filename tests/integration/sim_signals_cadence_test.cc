// Issue 16, point 4 (nothing rebuilt or written per cycle that did not change): a simulated hub's
// sim bridge writes /sim/<hub>/signals when a signal changes, when a reader matches, and at least
// every 100 ms (kSimSignalsKeepAlive), not on every cycle: at 1 kHz that was a second DDS write per
// cycle beside the State. An assembled Dock ECU (fake backend) runs 1000 cycles at 1 kHz with its
// signals unchanged while a reader in this process counts the samples.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <thread>

#include <gtest/gtest.h>

#include "hubrt/assembly/hub_assembly.h"
#include "hubrt/dds/participant.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/topic.h"
#include "hubrt/sim/sim_bridge_stage.h"
#include "hubrt/test_support/test_domain.h"

#include "assembled_sim_dock.h"

namespace hubrt {
namespace {

using Signals = hub_msgs_msg_dds__SimSignals_;

// A reader of the Dock ECU's simulation signals in a participant of its own, matched to the hub's
// writer, deep enough to keep every sample the hub could write in a test's window (one per cycle).
struct SignalsWatcher {
  dds::Participant participant;
  dds::Topic<Signals> topic;
  dds::Reader<Signals> reader;
};

Expected<SignalsWatcher> watch_signals(const test_support::TestDomain& domain) {
  auto participant = dds::Participant::create(domain.config(), "signals_watcher");
  if (!participant) return std::move(participant).error();
  auto topic = dds::Topic<Signals>::create(*participant, sim::sim_signals_topic("dock_ecu"));
  if (!topic) return std::move(topic).error();
  auto reader = dds::Reader<Signals>::create(*participant, *topic, dds::Qos::ros2_default(5000));
  if (!reader) return std::move(reader).error();
  if (!reader->wait_for_writers(1, std::chrono::seconds(20))) {
    return make_error(ErrorCode::kTimeout, "the hub's signals writer was not matched within 20 s");
  }
  return SignalsWatcher{std::move(*participant), std::move(*topic), std::move(*reader)};
}

TEST(SimSignalsCadence, WrittenOnChangeAndKeepAliveNotEveryCycle) {
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  SystemClock clock;
  auto assembled = integration::assemble_sim_dock(*domain, clock, 1000);
  ASSERT_TRUE(assembled) << assembled.error().message;
  runtime::Hub& hub = *(*assembled)->hub;

  auto watcher = watch_signals(*domain);
  ASSERT_TRUE(watcher) << watcher.error().message;
  auto& reader = watcher->reader;

  constexpr int kCycles = 1000;
  timespec next{};
  clock_gettime(CLOCK_MONOTONIC, &next);
  const auto run = [&](int cycles) {
    for (int i = 0; i < cycles; ++i) {
      hub.cycle(clock.now());
      next.tv_nsec += 1'000'000;
      if (next.tv_nsec >= 1'000'000'000) {
        next.tv_nsec -= 1'000'000'000;
        ++next.tv_sec;
      }
      while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr) == EINTR) {
      }
    }
  };
  run(200);  // the reader matched: the bridge writes at once; the outputs settle
  dds::Sample<Signals> sample;
  while (reader.take_next(sample).value_or(false)) {
  }
  const auto started = std::chrono::steady_clock::now();
  run(kCycles);
  const auto elapsed = std::chrono::steady_clock::now() - started;
  std::size_t received = 0;
  // Delivery in this process is synchronous; a short grace for Cyclone's delivery thread anyway.
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  while (reader.take_next(sample).value_or(false)) ++received;
  // One keep-alive per 100 ms of the window (it lasts longer than 1 s when the machine is loaded).
  const auto keep_alives = static_cast<std::size_t>(elapsed / sim::kSimSignalsKeepAlive) + 2;
  std::printf("[signals] %d cycles in %.0f ms: %zu SimSignals samples (keep-alive bound %zu)\n", kCycles,
              std::chrono::duration<double, std::milli>(elapsed).count(), received, keep_alives);
  EXPECT_GE(received, 1u);
  EXPECT_LE(received, keep_alives);
}

// A ManualClock that counts how often the test's thread reads it. The fake GPIO reads the clock
// once per level read or write (FakeGpio::advance brings its simulators to now), so the count per
// cycle is how much of the simulated world a cycle touches. Reads from other threads (Cyclone's
// listeners) are not counted, so the count is the same in every run.
class CountingClock final : public Clock {
 public:
  [[nodiscard]] Instant now() const noexcept override {
    if (std::this_thread::get_id() == owner_) reads_.fetch_add(1, std::memory_order_relaxed);
    return manual_.now();
  }
  void advance(Duration by) noexcept { manual_.advance(by); }
  [[nodiscard]] std::uint64_t reads() const noexcept { return reads_.load(); }

 private:
  ManualClock manual_;
  std::thread::id owner_ = std::this_thread::get_id();
  mutable std::atomic<std::uint64_t> reads_{0};
};

// Issue 16, point 4: while no reader of /sim/<hub>/signals is matched (a hub in the bench, a test
// without the station model), the bridge does not even read the signals: a level read per signal,
// each bringing every simulator up to now, for a sample nobody would receive. Once a reader
// matches, it reads and writes them as before. On a manual clock: the clock reads per cycle without
// a reader are fewer than with one, by at least one per signal of the board.
TEST(SimSignalsCadence, NotReadWhileNobodyListens) {
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  CountingClock clock;
  auto assembled = integration::assemble_sim_dock(*domain, clock, 1000);
  ASSERT_TRUE(assembled) << assembled.error().message;
  runtime::Hub& hub = *(*assembled)->hub;
  constexpr int kCycles = 100;
  const auto clock_reads_per_cycle = [&] {
    hub.cycle(clock.now());  // settles what the last change started (a new reader, a first cycle)
    clock.advance(std::chrono::milliseconds(1));
    const std::uint64_t before = clock.reads();
    for (int i = 0; i < kCycles; ++i) {
      hub.cycle(clock.now());
      clock.advance(std::chrono::milliseconds(1));
    }
    return (clock.reads() - before) / kCycles;
  };
  const std::uint64_t unheard = clock_reads_per_cycle();

  auto watcher = watch_signals(*domain);
  ASSERT_TRUE(watcher) << watcher.error().message;
  auto& reader = watcher->reader;
  const std::uint64_t heard = clock_reads_per_cycle();

  const auto signals =
      static_cast<std::uint64_t>((*assembled)->board.inputs.size() + (*assembled)->board.outputs.size());
  std::printf(
      "[signals] clock reads per cycle: %llu with no reader of the signals, %llu with one (%llu signals)\n",
      static_cast<unsigned long long>(unheard), static_cast<unsigned long long>(heard),
      static_cast<unsigned long long>(signals));
  EXPECT_GE(heard, unheard + signals) << "the bridge reads the signals even when nobody listens";
  // The reader got the signals once it matched (the bridge writes at once for a new reader).
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // Cyclone's delivery, in this process
  dds::Sample<Signals> sample;
  EXPECT_TRUE(reader.take_next(sample).value_or(false));
}

}  // namespace
}  // namespace hubrt
