// Where a command's time went inside the hub, stage by stage: Cyclone's listener on the command
// reader wakes the cycle (listener), the cycle thread's wait returns (woke), the node whose command
// took effect has stepped — command taken and checked, logic run, State built (stepped) — and that
// State is written (written). For the benchmarks (bench/programs/tails.cc, issue 33): a slow round
// trip whose time went between the stages' stamps was the hub's; one whose time went before the
// listener or after the write was the host's or the transport's.
//
// Opt-in (`hubd --trace-stages FILE`): off unless asked for, on boards too. A fixed ring sized at
// construction (the only allocation), stamped on the cycle thread without allocating or locking,
// written out as CSV at exit; the oldest records give way when it is full.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"

namespace hubrt::runtime {

// One command step's stamps on the trace's clock (monotonic); a zero Time for a stage that did
// not happen (no wake stamp: the step came from a wake() before tracing began; no stepped/written:
// no command took effect).
struct StageRecord {
  Time listener{};
  Time woke{};
  Time stepped{};
  Time written{};
};

class StageTrace {
 public:
  // Holds the last `capacity` command steps (at least 1); stamps with `clock`, which must outlive
  // the trace and allow now() from any thread.
  StageTrace(std::size_t capacity, const Clock& clock);

  // Any thread, async-signal-safe, allocation-free (Waker::wake calls it): the first wake since
  // the cycle last took one is stamped; later ones until then are the same step's.
  void note_wake() noexcept;

  // The cycle thread, allocation-free: a command step begins, woken at `woke` (the runner's
  // reading); the first node whose command took effect stepped; its State was written; the step
  // ends (the record goes into the ring).
  void begin_step(Time woke) noexcept;
  void node_stepped() noexcept;
  void state_written() noexcept;
  void end_step() noexcept;

  // Not while the cycle runs (after it stopped): the records held, oldest first, and how many
  // steps were recorded in all (more than held when the ring wrapped).
  [[nodiscard]] std::vector<StageRecord> records() const;
  [[nodiscard]] std::uint64_t steps() const noexcept { return steps_; }

  // Writes "listener_ns,woke_ns,stepped_ns,written_ns" and one line per record, oldest first
  // (nanoseconds of the trace's clock, 0 for a stage that did not happen), after a comment line
  // saying how many steps were recorded and how many the ring dropped. Not while the cycle runs.
  // Errors: kIo naming the file.
  Expected<void> write_csv(const std::string& path) const;

 private:
  const Clock* clock_;
  std::vector<StageRecord> ring_;
  std::atomic<std::int64_t> wake_ns_{0};  // 0: no wake since the last begin_step
  StageRecord current_;
  std::uint64_t steps_ = 0;
};

}  // namespace hubrt::runtime
