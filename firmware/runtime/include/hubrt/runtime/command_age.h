// How old a command is, and whether it may still act (DESIGN.md §3, "Commands age"; README, the
// wire contract). A command is as old as its writer's source timestamp says, not as old as its
// arrival: a sample that waited in a socket while the hub was stopped, in a reliable writer's
// history while a link was down, or behind a stalled cycle is as stale as it is old.
//
//   age = hub wall clock when the cycle takes the command − the command's source timestamp
//
// "When it takes the command" is read by the source right after the take where it can
// (ReceivedCommand::take_wall), not the cycle's reading from before it began taking: a cycle
// thread preempted between the two would otherwise judge a command written meanwhile as stamped
// in the future, and one written just inside the timeout as younger than it is.
//
//   - age > command timeout: stale. It never takes effect and never feeds the watchdog.
//   - age < −tolerance (stamped in the future beyond the clocks' agreed accuracy): rejected, the
//     skew named in error_list. Within the tolerance a future stamp counts as age 0.
//   - otherwise the command is young: it acts, and its freshness runs out one command timeout
//     after it was written (a command that waited 0.9 s of a 1 s timeout leaves 0.1 s).
//
// With the clocks not synced (hub file `clock_tolerance_ms: none`) ages cannot be judged: a
// command counts as written when it was taken. In both modes the hub refuses what queued while it
// could not run: after the cycle was held up for longer than the command timeout (SIGSTOP, a VM
// pause, a cycle blocked), every command taken until it has caught up is discarded
// (begin_discarding; Hub::note_late decides the window).
#pragma once

#include <cstdint>
#include <optional>

#include "hubrt/base/time.h"

namespace hubrt::runtime {

// How far the station's clocks are trusted to agree; std::nullopt: not synced.
using ClockTolerance = std::optional<Duration>;

// The default clock tolerance. chrony keeps hosts on one LAN within well under a millisecond of
// each other once synced, a few milliseconds across a VPN; 50 ms leaves room for that and for a
// host that has just stepped its clock, and is small against the 1 s command timeout, so a clock
// ahead by up to the tolerance lengthens a command's freshness by at most 5 % (docs/hub-config.md).
inline constexpr Duration kDefaultClockTolerance = std::chrono::milliseconds(50);

// When a command was written and when this hub took it: what its age is judged from, and what a
// recorder of the command path keeps.
struct CommandTimes {
  std::optional<WallTime> source;  // the writer's clock (ReceivedCommand::source_time)
  Instant taken;                   // the hub's clocks when the cycle began taking from its source
  // The hub's wall clock right after the take (ReceivedCommand::take_wall); absent: taken.wall.
  std::optional<WallTime> take_wall;
};

enum class AgeVerdict : std::uint8_t {
  kYoung,      // may act, as written at JudgedAge::written
  kStale,      // older than the command timeout: dropped, counted
  kFuture,     // stamped in the future beyond the tolerance: rejected
  kUnstamped,  // no source timestamp (0) while the clocks are synced: rejected, its age unknown
  kQueued,     // taken while the hub catches up after a stall: dropped, counted
};

struct JudgedAge {
  AgeVerdict verdict = AgeVerdict::kYoung;
  // When the command was written, on the hub's monotonic clock (taken.mono − age, never later
  // than taken.mono): what its freshness and t_plus count from.
  Time written{};
  // Hub wall clock at the take − source timestamp, as seen (negative: stamped in the future); 0
  // when the command has no source timestamp. Includes the transport's latency.
  Duration offset{0};
};

// One node's judge of its commands' ages; keeps the clock offsets it saw and the stall window.
// Thread-safety: cycle thread only. Allocation-free.
class CommandAgeJudge {
 public:
  CommandAgeJudge(Duration timeout, ClockTolerance tolerance) noexcept
      : timeout_(timeout), tolerance_(tolerance) {}

  // Judges one command taken at times.taken; records its clock offset when it has a stamp.
  JudgedAge judge(const CommandTimes& times) noexcept;

  // Commands taken before `until` are discarded as queued (a stall ended; Hub::note_late).
  void begin_discarding(Time until) noexcept {
    if (until > discard_until_) discard_until_ = until;
  }
  [[nodiscard]] bool discarding(Time now) const noexcept { return now < discard_until_; }

  [[nodiscard]] Duration timeout() const noexcept { return timeout_; }
  [[nodiscard]] const ClockTolerance& tolerance() const noexcept { return tolerance_; }
  // Whether a stamped command was seen, the offset of the last one and the largest in magnitude
  // (signed) since start: the clock skew /diagnostics shows.
  [[nodiscard]] bool offset_seen() const noexcept { return offset_seen_; }
  [[nodiscard]] Duration last_offset() const noexcept { return last_offset_; }
  [[nodiscard]] Duration largest_offset() const noexcept { return largest_offset_; }

 private:
  Duration timeout_;
  ClockTolerance tolerance_;
  Time discard_until_{};
  bool offset_seen_ = false;
  Duration last_offset_{0};
  Duration largest_offset_{0};
};

// How long commands are discarded after a stall longer than the command timeout: until the hub
// has caught up, taken as `kStallSettle` or one period, whichever is longer. What queued while
// the process could not run is in its sockets when it continues, and Cyclone's receive thread,
// running again with the cycle, reads that backlog at once (tests/integration's
// hubd_stale_after_stop_test, with clock_tolerance_ms: none, shows none of it acting): 100 ms
// leaves room for a loaded machine and costs a live planner one or two commands after a stall
// that already made its node safe.
inline constexpr Duration kStallSettle = std::chrono::milliseconds(100);

}  // namespace hubrt::runtime
