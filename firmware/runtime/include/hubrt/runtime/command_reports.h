// What a node says about the commands it did not follow, so that the planner (error_list), the
// operator (the log) and tools (/diagnostics counters) learn why:
//   - rejected: a bad command (its reason formatted into problem()), or one stamped in the future
//     beyond the clock tolerance;
//   - stale: too old to act (command_age.h), or queued while the hub could not run.
// Each kind stays in error_list for one command timeout (a rejection until a valid command takes
// effect), and is logged when its reason changes or at most once a second, so that a planner
// repeating a bad or late command at 100 Hz does not flood the journal.
#pragma once

#include <cstdint>
#include <string_view>

#include <spdlog/logger.h>

#include "hubrt/base/time.h"
#include "hubrt/runtime/command_age.h"
#include "hubrt/runtime/error_list.h"
#include "hubrt/runtime/message_ops.h"

namespace hubrt::runtime {

// Thread-safety: cycle thread only. Allocation-free after construction.
class CommandReports {
 public:
  // `node` names the node in log lines and must outlive this object; `log` is not null.
  CommandReports(std::string_view node, Duration visible_for, spdlog::logger* log) noexcept
      : node_(node), visible_for_(visible_for), log_(log) {}

  // Where a rejection's reason is formatted before rejected() is called.
  [[nodiscard]] Problem& problem() noexcept { return rejection_; }
  // Counts the rejection whose reason is in problem(); logs it (rate-limited).
  void rejected(Time now) noexcept;
  // A command judged stale or queued (judged.verdict), taken at `now`: counted, reported, logged.
  void stale(Time now, const JudgedAge& judged) noexcept;
  // A valid command took effect: the last rejection no longer needs showing.
  void clear_rejection() noexcept { has_rejection_ = false; }

  // Adds the reports still visible at `now` to `errors`.
  void add_to(ErrorList& errors, Time now) const noexcept;

  [[nodiscard]] std::uint64_t rejected_count() const noexcept { return rejected_; }
  [[nodiscard]] std::uint64_t stale_count() const noexcept { return stale_; }

 private:
  struct RateLimit {
    Problem last;
    Time at{};
    bool ever = false;
    // True when `text` should be logged now; remembers it.
    bool due(std::string_view text, Time now) noexcept;
  };

  std::string_view node_;
  Duration visible_for_;
  spdlog::logger* log_;
  Problem rejection_;
  Time rejected_at_{};
  bool has_rejection_ = false;
  RateLimit rejection_log_;
  Problem stale_text_;
  Time stale_at_{};
  bool has_stale_ = false;
  RateLimit stale_log_;
  std::uint64_t rejected_ = 0;
  std::uint64_t stale_ = 0;
};

}  // namespace hubrt::runtime
