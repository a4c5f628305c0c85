// The checks of the heartbeat conformance suite, as pure functions of what was observed on the
// wire: the States received (with their arrival time) and the commands sent. No DDS here, so
// every verdict can be tested with made-up observations — including the failures.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "conformance_thresholds.h"
#include "stats.h"

namespace hubrt::hubctl {

// One State as the suite received it.
struct Observation {
  double arrival_s = 0;  // the receiver's steady clock, seconds
  double stamp_s = 0;    // header.stamp: the hub's wall clock when it built the State, seconds
  std::uint64_t seq = 0;
  bool fresh = false;
  double t_plus = 0;
  bool got_reset = false;
  nlohmann::ordered_json echo;
  std::vector<std::string> errors;
  nlohmann::ordered_json state;  // the whole State, for safe-state fields
};

enum class Verdict : std::uint8_t { kPass, kFail, kInfo };
std::string_view to_string(Verdict verdict) noexcept;

struct CheckResult {
  std::string id;     // stable key, e.g. "rate_error"
  std::string title;  // what a reader sees, e.g. "rate error"
  Verdict verdict = Verdict::kInfo;
  std::string value;             // measured, as text: "0.03 %"
  std::string threshold;         // the bound, as text: "<= 1 %"
  std::string detail;            // what failed, or how it was measured
  std::optional<double> number;  // the measured figure, for --json
  std::optional<double> limit;   // the bound, for --json
  std::string unit;
};

// The checks of one category give their verdict with these helpers.
CheckResult at_most(std::string id, std::string title, double value, double limit, std::string unit,
                    int decimals = 2);
CheckResult failed(std::string id, std::string title, std::string detail);
CheckResult passed(std::string id, std::string title, std::string value, std::string detail = {});

// --- heartbeat (no commands) --------------------------------------------------------------------

// The hub is judged on its own stamps: header.stamp is when the hub woke for the cycle, so the
// periods between stamps are the hub's schedule, whatever happened to the States on their way and
// to the receiver (a stalled or loaded host running hubctl delays arrivals in bunches, which says
// nothing about the hub). What the receiver saw is measured too and reported beside it, unjudged.
struct HeartbeatFigures {
  std::size_t states = 0;
  double rate_hz = 0;  // from the stamps of the first and last State
  double rate_error_pct = 0;
  Summary jitter_ms;          // |stamp period - nominal period|: the hub's wake-ups (judged)
  Summary period_ms;          // stamp periods as they are
  Summary arrival_jitter_ms;  // |arrival period - nominal period|: hub + delivery + receiver (reported)
  Summary arrival_period_ms;  // arrival periods as they are
};

// Rate from the stamps of the first and last State, jitter from every consecutive pair (of stamps,
// and of arrivals). Needs at least two States (else a zero result with states < 2).
HeartbeatFigures measure_heartbeat(std::span<const Observation> window, double period_s);

// rate_error, jitter_p50, jitter_p99, jitter_max (judged, on stamps); arrival_jitter_p50,
// arrival_jitter_p99, arrival_jitter_max (Verdict::kInfo: measured at the receiver).
std::vector<CheckResult> check_heartbeat(const HeartbeatFigures& figures, double period_s,
                                         const Thresholds& thresholds);

// Missing, repeated or backwards sequence numbers over everything received from one writer.
CheckResult check_sequence(std::span<const Observation> all, const Thresholds& thresholds);

// first_state: `elapsed_s` from start (or discovery, per `since`) to the first State.
CheckResult check_first_state(std::optional<double> elapsed_s, const std::string& since,
                              const Thresholds& thresholds);

// --- command semantics --------------------------------------------------------------------------

// Whether `command` is in force in the State `o`: echoed with fresh_msg = true. Echoing it is not
// enough: a node keeps echoing the last command it took after its watchdog ended it, so when an
// earlier planner's last command equals the one sent now, States the node published before the
// new one reached it echo it already (fresh_msg false, t_plus counting from the earlier command).
bool command_in_force(const Observation& o, const nlohmann::ordered_json& command);

// fresh_before: no State claims a fresh command while nobody commands the node.
CheckResult check_fresh_before(std::span<const Observation> uncommanded);

// fresh_while_commanded: every State from the first echo on says fresh_msg = true while the
// planner keeps repeating (`commanded` starts at the first State echoing the command).
CheckResult check_fresh_while_commanded(std::span<const Observation> commanded);

// t_plus_grows: while one command repeats, t_plus follows the hub's stamps from the State that
// first echoed it (`held[0]`), within the tolerance, and starts near zero.
CheckResult check_t_plus_grows(std::span<const Observation> held, const Thresholds& thresholds);

// t_plus_restarts: the first State echoing a changed command (`first`) has t_plus near zero and
// below the last t_plus of the command before (`before`, if any).
CheckResult check_t_plus_restarts(const Observation& first, const Observation* before,
                                  const Thresholds& thresholds, std::string id = "t_plus_restarts",
                                  std::string title = "t_plus restarts on a new command");

// repeats_silent: identical repeats publish nothing extra: among `held` (States while one
// command repeats), count those beyond one per period of the hub's own clock.
CheckResult check_repeats_silent(std::span<const Observation> held, double period_s,
                                 const Thresholds& thresholds);

// echo_latency p50 and p99 over `latencies_ms`; `lost` commands never echoed fail the check.
std::vector<CheckResult> check_echo_latency(const std::vector<double>& latencies_ms, std::size_t lost,
                                            const Thresholds& thresholds);

// --- watchdog and what follows ------------------------------------------------------------------

struct WatchdogRound {
  double last_command_s = 0;           // when the last command was written (steady clock)
  std::optional<Observation> tripped;  // first State with fresh_msg = false after that
  // The same write on the wall clock, what its DDS source timestamp says. The hub counts its
  // timeout from there (README, "Commands age"), so the trip's stamp minus this is the hub's delay.
  std::optional<double> last_command_wall_s;
};

// watchdog: the trip came no earlier than the timeout and no later than timeout + one period
// (+ slack) after the last command, for every round; plus the timeout reported in error_list.
// "Earlier" is judged on the trip's arrival (it cannot arrive before it happened); "later" on the
// hub's stamp when it lies between the two, because a receiver that stalls delays only the arrival.
std::vector<CheckResult> check_watchdog(std::span<const WatchdogRound> rounds, double timeout_s,
                                        double period_s, const std::string& timeout_error,
                                        const Thresholds& thresholds);

// safe_state: every `expected` field (path -> value as text) of every State in `tripped` (from
// the trip until commands returned) has the expected value.
CheckResult check_safe_state(std::span<const Observation> tripped,
                             const std::vector<std::pair<std::string, std::string>>& expected);

// no_stale_reapply: after the trip nothing takes effect until a command is sent again:
// `between` (trip .. just before the first fresh State) are all not fresh and keep the echo of
// the trip State; then `returned` (the first fresh State) echoes `sent` (the command sent after
// the silence, written at `sent_at_s`), arrived after it was written, and restarted t_plus.
CheckResult check_no_stale_reapply(std::span<const Observation> between, const Observation& returned,
                                   const nlohmann::ordered_json& sent, double sent_at_s,
                                   const Thresholds& thresholds, std::string id, std::string title);

// got_reset: false while a non-reset command is in force (`before`, `after`), true in every
// State while the reset command is (`during`), each span starting at the first State echoing it.
CheckResult check_got_reset(std::span<const Observation> before, std::span<const Observation> during,
                            std::span<const Observation> after);

// A dotted path ("echo.action", "rsp.locked", "slots[1].occupied") in a State as JSON; null when
// absent.
nlohmann::ordered_json json_at(const nlohmann::ordered_json& value, std::string_view path);
// Whether a JSON value equals the text of a profile value: booleans as true/false/1/0, numbers
// numerically (1e-6 relative), strings exactly.
bool json_matches_text(const nlohmann::ordered_json& value, std::string_view text);

}  // namespace hubrt::hubctl
