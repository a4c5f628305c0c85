// How much memory a hub's black box takes when its hub file does not say (`memory_kib` absent):
// enough for `span` of what this hub sends and receives at its own rates, not one size for every
// hub. A fixed 8 MiB ring, touched at start, added 8 MB to every hub's RSS (a board hub went from
// 8.8 to 17.3 MB, docs/benchmarks.md), while 60 s of a 10 Hz Dock ECU's traffic is about 0.2 MB.
#pragma once

#include <cstddef>

#include "hubrt/base/time.h"

namespace hubrt::blackbox {

// What a hub records per second, from its hub file.
struct RecordedRates {
  double states_per_second = 0;       // nodes x the hub's rate (each node's State every period)
  double commands_per_second = 0;     // the planner's commands it may receive (an allowance)
  double diagnostics_per_second = 0;  // its /diagnostics rate
};

// Bytes per ring entry (payload + Ring::kEntryOverhead, rounded up), with room to spare over what
// the station's hubs send (read from black box files of the simulated station, 2026-11-29: a
// DockState 163 bytes on average, at most 252; a command 40; a /diagnostics message about 1.1 kB,
// at most 1.3 kB). A hub whose samples are bigger keeps a shorter span: the oldest give way.
inline constexpr std::size_t kStateEntryBytes = 320;
inline constexpr std::size_t kCommandEntryBytes = 128;
inline constexpr std::size_t kDiagnosticsEntryBytes = 2048;
// Commands a node may receive per second in the sizing: a planner commanding every 50 ms. A faster
// planner (or a flood) shortens the span kept, and never grows the memory.
inline constexpr double kCommandsPerNodePerSecond = 20;
inline constexpr std::size_t kMinRingBytes = std::size_t{64} << 10;  // the hub file's lower bound
inline constexpr std::size_t kMaxRingBytes = std::size_t{8} << 20;   // the fixed size it had before

// The rates of a hub of `nodes` nodes at `rate_hz`, publishing /diagnostics at `diagnostics_hz`.
RecordedRates hub_recorded_rates(std::size_t nodes, double rate_hz, double diagnostics_hz) noexcept;

// span x the rates x the entry sizes, rounded up to 4 KiB, within [kMinRingBytes, kMaxRingBytes].
std::size_t ring_bytes_for(Duration span, const RecordedRates& rates) noexcept;

}  // namespace hubrt::blackbox
