// The command semantics every node shares, independent of message types: which command is in
// force, fresh_msg, t_plus, got_reset, and the command watchdog.
//
//   - A valid, young command "arrives" (command_age.h: stale ones never get here); if its content
//     differs from the echoed one, or no command was in force (first one, or the watchdog had
//     tripped), it *takes effect*: t_plus restarts and the State is published at once. Identical
//     repeats only keep the watchdog fed.
//   - Freshness counts from when a command was *written* (its source timestamp on the hub's
//     clock), not from its arrival: when no valid command younger than the timeout is known, the
//     watchdog trips: the command is no longer in force (the node goes to its safe state),
//     fresh_msg turns false. The old command is never re-applied: only a command that arrives
//     afterwards takes effect. t_plus counts from when the command in force was written.
//   - got_reset is true while the command in force is a reset; a reset acts once, when it takes
//     effect, so a fault that returns while the planner keeps sending reset stays visible.
#pragma once

#include "hubrt/base/time.h"

namespace hubrt::runtime {

class CommandTracker {
 public:
  enum class Arrival : std::uint8_t {
    kRepeat,      // same content as the command in force: watchdog fed, nothing else
    kTookEffect,  // new content, or the first command after none was in force
  };
  enum class Watchdog : std::uint8_t { kQuiet, kTripped };

  explicit CommandTracker(Duration timeout) noexcept : timeout_(timeout) {}

  // Records a valid command taken at `now` and written at `written` (<= now: now minus its age,
  // CommandAgeJudge). `differs` = its content differs from the echo.
  Arrival on_valid_command(Time now, Time written, bool differs, bool is_reset) noexcept;
  // A command whose age is not known (written when taken).
  Arrival on_valid_command(Time now, bool differs, bool is_reset) noexcept {
    return on_valid_command(now, now, differs, is_reset);
  }
  // Evaluates the watchdog; returns kTripped exactly once per loss of commands.
  Watchdog check(Time now) noexcept;

  [[nodiscard]] bool has_echo() const noexcept { return has_echo_; }
  [[nodiscard]] bool in_force() const noexcept { return in_force_; }
  [[nodiscard]] bool fresh() const noexcept { return in_force_; }
  [[nodiscard]] bool got_reset() const noexcept { return in_force_ && reset_in_force_; }
  // Seconds since the command in force (or the last echoed one) was written; 0 before any.
  [[nodiscard]] double t_plus(Time now) const noexcept;
  [[nodiscard]] Duration timeout() const noexcept { return timeout_; }
  // The age of the youngest valid command known: how long ago it was written.
  [[nodiscard]] Duration since_last_command(Time now) const noexcept { return now - last_written_; }
  // When the cycle last took a valid command (its arrival, not its write).
  [[nodiscard]] Time last_taken() const noexcept { return last_taken_; }

 private:
  Duration timeout_;
  Time took_effect_{};   // written time of the command that took effect
  Time last_written_{};  // written time of the youngest valid command
  Time last_taken_{};
  bool has_echo_ = false;
  bool in_force_ = false;
  bool reset_in_force_ = false;
};

}  // namespace hubrt::runtime
