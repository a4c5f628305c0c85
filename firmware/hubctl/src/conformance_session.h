// Runs the conformance suite against one target over DDS: listens to its heartbeat, commands it
// the way a planner does (and the ways a planner fails: going silent, coming back), and hands what
// it observed to the checks in conformance_checks.h.
//
// Phases, in order (each can be left out):
//   heartbeat  no commands: first State, fresh_msg false, rate, jitter
//   semantics  probe 1 repeated, then probe 2: fresh_msg, t_plus growing and restarting, repeats silent
//   latency    probes alternated, each written once: command -> echo latency, echo verbatim
//   watchdog   silence until the trip (twice): delay, error_list, safe state; then no stale re-apply
//              when a new command returns and t_plus restarting when the same one returns
//   reset      got_reset before, during and after the reset command
// Sequence numbers are checked over everything received.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/dds/participant.h"

#include "command_channel.h"
#include "conformance_checks.h"
#include "conformance_target.h"
#include "state_stream.h"

namespace hubrt::hubctl {

inline constexpr std::array<std::string_view, 5> kPhases{"heartbeat", "semantics", "latency", "watchdog",
                                                         "reset"};

struct SessionOptions {
  double heartbeat_s = 5.0;             // the heartbeat window
  double hold_s = 1.0;                  // how long one command repeats in the semantics phase
  std::size_t latency_samples = 100;    // commands written in the latency phase
  std::optional<double> repeat_s;       // the planner's repetition period; default: timeout / 5, <= 100 ms
  double discovery_timeout_s = 5.0;     // waiting for the hub's writer and reader
  std::optional<double> launched_at_s;  // steady time the hub was started (--launch)
  std::set<std::string, std::less<>> phases{kPhases.begin(), kPhases.end()};
};

// Thread-safety: a session is used by one thread; sessions of different targets may run in
// parallel on one participant.
class TargetSession {
 public:
  // Prepares the commands (if the target can be commanded) and their writer. `early` is a stream
  // already listening since the hub was discovered (--launch, to time its first State); without
  // it run() subscribes when it starts. `participant` must outlive the session.
  // Errors: DDS entities that could not be created; a profile value the command type refuses.
  static Expected<std::unique_ptr<TargetSession>> open(const dds::Participant& participant,
                                                       const Target& target, const Thresholds& thresholds,
                                                       SessionOptions options,
                                                       std::optional<StateStream> early = std::nullopt);

  // Runs the phases and returns every check's result, in the order they ran.
  std::vector<CheckResult> run();

  [[nodiscard]] const Target& target() const noexcept { return target_; }

 private:
  TargetSession(const dds::Participant& participant, Target target, const Thresholds& thresholds,
                SessionOptions options, std::optional<StateStream> early)
      : participant_(&participant),
        target_(std::move(target)),
        thresholds_(thresholds),
        options_(std::move(options)),
        states_(std::move(early)) {}

  struct Commands {
    CommandChannel channel;
    std::vector<PreparedCommand> probes;  // two
    PreparedCommand reset;
  };

  // Writes `command` (if any) every repeat period and takes States until one satisfies `done`
  // (if given) or `deadline_s` passes. Returns the index in the log of the State that satisfied it.
  std::optional<std::size_t> drive(const PreparedCommand* command, double deadline_s,
                                   const std::function<bool(const Observation&)>& done = {});
  // The probe whose content differs from `echo` (probe 1 if neither matches).
  const PreparedCommand& other_probe(const nlohmann::ordered_json& echo) const;
  [[nodiscard]] bool enabled(std::string_view phase) const { return options_.phases.contains(phase); }
  [[nodiscard]] const std::vector<Observation>& log() const noexcept { return states_->log(); }
  [[nodiscard]] std::span<const Observation> range(std::size_t from, std::size_t to) const;

  bool run_heartbeat(std::vector<CheckResult>& out);
  bool run_semantics(std::vector<CheckResult>& out);
  bool run_latency(std::vector<CheckResult>& out);
  bool run_watchdog(std::vector<CheckResult>& out);
  bool run_reset(std::vector<CheckResult>& out);
  // Makes sure some probe is in force (for phases run without the ones before).
  bool ensure_commanded(std::vector<CheckResult>& out);

  const dds::Participant* participant_;
  Target target_;
  Thresholds thresholds_;
  SessionOptions options_;
  std::optional<StateStream> states_;
  std::optional<Commands> commands_;
  double matched_at_s_ = 0;
  double repeat_s_ = 0.1;
  double echo_wait_s_ = 1.0;
  double first_send_s_ = 0;      // the first write of the last drive() that wrote
  double last_send_s_ = 0;       // the last write of any drive()
  double last_send_wall_s_ = 0;  // the same write on the wall clock (its source timestamp)
};

}  // namespace hubrt::hubctl
