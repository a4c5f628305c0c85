// The command semantics every node shares, independent of message types: which command is in
// force, fresh_msg, t_plus, got_reset, and the command watchdog.
//
//   - A valid command "arrives"; if its content differs from the echoed one, or no command was
//     in force (first one, or the watchdog had tripped), it *takes effect*: t_plus restarts and
//     the State is published at once. Identical repeats only keep the watchdog fed.
//   - When no valid command has arrived for longer than the timeout, the watchdog trips: the
//     command is no longer in force (the node goes to its safe state), fresh_msg turns false.
//     The old command is never re-applied: only a command that arrives afterwards takes effect.
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

  // Records a valid command arriving at `now`. `differs` = its content differs from the echo.
  Arrival on_valid_command(Time now, bool differs, bool is_reset) noexcept;
  // Evaluates the watchdog; returns kTripped exactly once per loss of commands.
  Watchdog check(Time now) noexcept;

  [[nodiscard]] bool has_echo() const noexcept { return has_echo_; }
  [[nodiscard]] bool in_force() const noexcept { return in_force_; }
  [[nodiscard]] bool fresh() const noexcept { return in_force_; }
  [[nodiscard]] bool got_reset() const noexcept { return in_force_ && reset_in_force_; }
  // Seconds since the command in force (or the last echoed one) took effect; 0 before any.
  [[nodiscard]] double t_plus(Time now) const noexcept;
  [[nodiscard]] Duration timeout() const noexcept { return timeout_; }
  [[nodiscard]] Duration since_last_command(Time now) const noexcept { return now - last_arrival_; }

 private:
  Duration timeout_;
  Time took_effect_{};
  Time last_arrival_{};
  bool has_echo_ = false;
  bool in_force_ = false;
  bool reset_in_force_ = false;
};

}  // namespace hubrt::runtime
