// Whose a slow round trip was (issue 33 point 1): the hub's, or the host's and the transport's.
// `hubd --trace-stages FILE` stamps each command step on CLOCK_MONOTONIC (runtime/stage_trace.h:
// listener -> woke -> stepped -> written); a planner on the same host stamps sending the command
// and taking its echo on the same clock. The round trip's time between the listener's and the
// write's stamps was spent in the hub; before the listener (the command on its way, the hub's DDS
// receive thread not yet run) and after the write (the State on its way, the planner not yet
// woken) it was the host's and the transport's.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "hubrt/base/status.h"

namespace hubrt::bench {

// One command step of the trace, in ns; stepped and written 0 when no command took effect.
struct TracedStep {
  std::int64_t listener = 0;
  std::int64_t woke = 0;
  std::int64_t stepped = 0;
  std::int64_t written = 0;
};

// The trace's complete steps (those with all four stamps), sorted by listener stamp.
// Errors: kIo naming the file when it cannot be read or a line is not four numbers.
Expected<std::vector<TracedStep>> read_stage_trace(const std::string& path);

// One round trip as its planner saw it, in ns.
struct TimedRoundTrip {
  std::int64_t sent = 0;
  std::int64_t echo = 0;
};

struct Attribution {
  bool traced = false;            // a complete step of the trace lies within the round trip
  std::int64_t to_listener = 0;   // sent -> listener: transport and the hub's receive thread
  std::int64_t wake = 0;          // listener -> woke: the cycle thread's wake-up
  std::int64_t step = 0;          // woke -> stepped: command checked, logic, State built
  std::int64_t write = 0;         // stepped -> written: the State written
  std::int64_t from_written = 0;  // written -> echo: transport and the planner's wake-up
};

// The first step of `steps` (sorted by listener) whose listener and written stamps lie within
// `rtt`; not traced when none does (the command was taken by a periodic cycle, or the ring wrapped).
Attribution attribute(const TimedRoundTrip& rtt, const std::vector<TracedStep>& steps);

// Where a slow round trip's extra time went: the part that exceeds its typical duration (the
// median over the traced round trips of the same run) by the most. Inside the hub: wake, step,
// write; outside: before the listener, after the write.
enum class LateStage { kToListener, kWake, kStep, kWrite, kFromWritten };
inline constexpr const char* kLateStageNames[] = {"to_listener", "wake", "step", "write", "from_written"};
[[nodiscard]] inline bool in_hub(LateStage s) noexcept {
  return s == LateStage::kWake || s == LateStage::kStep || s == LateStage::kWrite;
}

// The median of each part over the traced ones of `round_trips` (the untraced are skipped).
Attribution typical_of(const std::vector<Attribution>& round_trips);

// The part of `slow` (traced) that exceeds `typical`'s by the most.
LateStage late_stage(const Attribution& slow, const Attribution& typical);

}  // namespace hubrt::bench
