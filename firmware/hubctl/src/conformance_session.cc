#include "conformance_session.h"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "session.h"

namespace hubrt::hubctl {
namespace {

std::string last_errors(const std::vector<Observation>& log) {
  if (log.empty() || log.back().errors.empty()) return "none";
  return fmt::format("{}", fmt::join(log.back().errors, "; "));
}

bool echoes(const Observation& o, const PreparedCommand& command) {
  return o.echo == command.json;
}

// The State in which the command took effect (conformance_checks.h: echoing it is not enough).
bool in_force(const Observation& o, const PreparedCommand& command) {
  return command_in_force(o, command.json);
}

}  // namespace

Expected<std::unique_ptr<TargetSession>> TargetSession::open(const dds::Participant& participant,
                                                             const Target& target,
                                                             const Thresholds& thresholds,
                                                             SessionOptions options,
                                                             std::optional<StateStream> early) {
  std::unique_ptr<TargetSession> session(
      new TargetSession(participant, target, thresholds, std::move(options), std::move(early)));
  const double period = target.period_s > 0 ? target.period_s : 0.1;
  session->repeat_s_ = session->options_.repeat_s.value_or(
      target.timeout_s > 0 ? std::clamp(target.timeout_s / 5.0, 0.001, 0.1) : 0.1);
  session->echo_wait_s_ = std::max(1.0, 2 * period + 0.5);
  if (target.commands == nullptr) return session;

  auto channel = CommandChannel::open(participant, target.command_topic, *target.command_type);
  if (!channel) return std::move(channel).error();
  std::vector<PreparedCommand> probes;
  for (std::size_t i = 0; i < target.commands->probes.size(); ++i) {
    auto probe = prepare_command(*target.command_type, target.target_type, target.target_name,
                                 target.commands->probes[i], fmt::format("probe {}", i + 1));
    if (!probe) return std::move(probe).error();
    probes.push_back(std::move(*probe));
  }
  if (probes.size() != 2 || probes[0].json == probes[1].json) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: the two probes of '{}' make the same command", target.profile->file,
                                  target.target_type));
  }
  auto reset = prepare_command(*target.command_type, target.target_type, target.target_name,
                               target.commands->reset, "reset");
  if (!reset) return std::move(reset).error();
  session->commands_.emplace(Commands{std::move(*channel), std::move(probes), std::move(*reset)});
  return session;
}

std::span<const Observation> TargetSession::range(std::size_t from, std::size_t to) const {
  to = std::min(to, log().size());
  from = std::min(from, to);
  return std::span<const Observation>(log()).subspan(from, to - from);
}

const PreparedCommand& TargetSession::other_probe(const nlohmann::ordered_json& echo) const {
  return echo == commands_->probes[0].json ? commands_->probes[1] : commands_->probes[0];
}

std::optional<std::size_t> TargetSession::drive(const PreparedCommand* command, double deadline_s,
                                                const std::function<bool(const Observation&)>& done) {
  std::size_t scan = log().size();
  double next_send = steady_seconds();
  bool wrote = false;
  for (;;) {
    if (done) {
      for (; scan < log().size(); ++scan) {
        if (done(log()[scan])) return scan;
      }
    }
    const double now = steady_seconds();
    if (now >= deadline_s || stop_requested()) return std::nullopt;
    if (command != nullptr && now >= next_send) {
      const double wall = wall_seconds();
      if (commands_->channel.send(*command).is_ok()) {
        if (!wrote) first_send_s_ = now;
        wrote = true;
        last_send_s_ = now;
        last_send_wall_s_ = wall;
      }
      next_send += repeat_s_;
      if (next_send <= now) next_send = now + repeat_s_;  // fell behind: skip, never burst
    }
    const double wake = command != nullptr ? std::min(deadline_s, next_send) : deadline_s;
    if (!states_->pump(wake).is_ok()) return std::nullopt;
  }
}

std::vector<CheckResult> TargetSession::run() {
  std::vector<CheckResult> out;
  if (!states_) {
    auto states = StateStream::open(*participant_, target_.state_topic, *target_.state_type);
    if (!states) {
      out.push_back(failed("setup", "subscribing", states.error().message));
      return out;
    }
    states_.emplace(std::move(*states));
  } else if (!states_->restart().is_ok()) {
    out.push_back(failed("setup", "subscribing", "taking States failed"));
    return out;
  }
  auto matched = states_->wait_matched(options_.discovery_timeout_s);
  if (!matched) {
    out.push_back(failed("first_state", "first State", matched.error().message));
    return out;
  }
  matched_at_s_ = *matched;
  bool ok = run_heartbeat(out);
  const bool wants_commands =
      enabled("semantics") || enabled("latency") || enabled("watchdog") || enabled("reset");
  if (ok && wants_commands) {
    if (!commands_) {
      out.push_back(
          failed("commands", "command checks",
                 fmt::format("cannot command this node: {}", fmt::join(target_.command_problems, "; "))));
      ok = false;
    } else if (auto matched_commands = commands_->channel.wait_matched(options_.discovery_timeout_s);
               !matched_commands) {
      out.push_back(failed("commands", "command checks",
                           fmt::format("{} (is {} the right command topic?)",
                                       matched_commands.error().message, target_.command_topic)));
      ok = false;
    }
  }
  if (ok && enabled("semantics")) ok = run_semantics(out);
  if (ok && enabled("latency")) ok = run_latency(out);
  if (ok && enabled("watchdog")) ok = run_watchdog(out);
  if (ok && enabled("reset")) run_reset(out);
  out.push_back(check_sequence(log(), thresholds_));
  return out;
}

bool TargetSession::run_heartbeat(std::vector<CheckResult>& out) {
  const double period = target_.period_s;
  const auto first =
      drive(nullptr, steady_seconds() + options_.discovery_timeout_s + 2 * std::max(period, 0.0),
            [](const Observation&) { return true; });
  // With --launch the stream listened from discovery on and holds the true first arrival.
  std::optional<double> elapsed;
  if (options_.launched_at_s && states_->first_arrival_s()) {
    elapsed = *states_->first_arrival_s() - *options_.launched_at_s;
  } else if (first) {
    elapsed = log()[*first].arrival_s - matched_at_s_;
  }
  CheckResult first_state =
      check_first_state(elapsed, options_.launched_at_s ? "since start" : "since discovered", thresholds_);
  first_state.detail =
      options_.launched_at_s
          ? "from starting the hub to the first State received here, DDS discovery included"
          : "from discovering the hub's State writer to its first State (the hub was already "
            "running; start it with --launch to measure its start-up)";
  out.push_back(std::move(first_state));
  if (!first) return false;
  if (period <= 0) {
    out.push_back(
        failed("rate_error", "rate error",
               "the expected rate is unknown: the hub publishes no /diagnostics and no profile gives "
               "rate_hz; give --rate"));
    return false;
  }
  std::size_t quiet_from = *first;
  if (log()[*first].fresh) {
    // A command from before may still be in force: its watchdog will end it.
    const double wait = (target_.timeout_s > 0 ? target_.timeout_s : 5.0) + 2 * period + 0.5;
    const auto idle = drive(nullptr, steady_seconds() + wait, [](const Observation& o) { return !o.fresh; });
    if (!idle) {
      out.push_back(check_fresh_before(range(*first, log().size())));
      return false;
    }
    quiet_from = *idle;
  }
  if (enabled("heartbeat")) {
    const std::size_t from = log().size();
    drive(nullptr, steady_seconds() + options_.heartbeat_s);
    const auto window = range(from, log().size());
    for (CheckResult& r : check_heartbeat(measure_heartbeat(window, period), period, thresholds_))
      out.push_back(std::move(r));
  }
  CheckResult before = check_fresh_before(range(quiet_from, log().size()));
  out.push_back(before);
  return before.verdict == Verdict::kPass;
}

bool TargetSession::run_semantics(std::vector<CheckResult>& out) {
  const PreparedCommand& first = commands_->probes[0];
  const PreparedCommand& second = commands_->probes[1];
  const double hold = std::max({options_.hold_s, 5 * repeat_s_, 3 * target_.period_s});
  const auto echoed_first = drive(&first, steady_seconds() + echo_wait_s_,
                                  [&](const Observation& o) { return in_force(o, first); });
  if (!echoed_first) {
    out.push_back(failed("semantics", "command takes effect",
                         fmt::format("{} was never echoed with fresh_msg = true within {:.1f} s; last "
                                     "error_list: {}",
                                     first.label, echo_wait_s_, last_errors(log()))));
    return false;
  }
  drive(&first, log()[*echoed_first].arrival_s + hold);
  const std::size_t held_end = log().size();
  const auto echoed_second = drive(&second, steady_seconds() + echo_wait_s_,
                                   [&](const Observation& o) { return in_force(o, second); });
  if (!echoed_second) {
    out.push_back(failed("semantics", "command takes effect",
                         fmt::format("{} was never echoed with fresh_msg = true within {:.1f} s; last "
                                     "error_list: {}",
                                     second.label, echo_wait_s_, last_errors(log()))));
    return false;
  }
  drive(&second, log()[*echoed_second].arrival_s + hold / 2);
  const auto held = range(*echoed_first, held_end);
  out.push_back(check_fresh_while_commanded(range(*echoed_first, log().size())));
  out.push_back(check_t_plus_grows(held, thresholds_));
  out.push_back(check_t_plus_restarts(log()[*echoed_second], &log()[*echoed_second - 1], thresholds_));
  out.push_back(check_repeats_silent(held, target_.period_s, thresholds_));
  return true;
}

bool TargetSession::run_latency(std::vector<CheckResult>& out) {
  std::vector<double> latencies_ms;
  std::size_t lost = 0;
  // The hub publishes at most one immediate State per immediate_interval_s (its budget, README's
  // wire contract): a change sent sooner after the last one is echoed only by a later State,
  // which would measure the budget, not the hub. The echo's arrival is after the hub published
  // it, so waiting the interval (plus a millisecond) from the arrival is enough.
  double ready_s = 0;
  for (std::size_t i = 0; i < options_.latency_samples && !stop_requested(); ++i) {
    if (steady_seconds() < ready_s) drive(nullptr, ready_s);
    // Always the probe the hub does not echo now, so that it takes effect and is published at once.
    const PreparedCommand& next = other_probe(log().empty() ? nlohmann::ordered_json() : log().back().echo);
    const double sent_at = steady_seconds();
    const double sent_wall = wall_seconds();
    if (!commands_->channel.send(next).is_ok()) {
      ++lost;
      continue;
    }
    first_send_s_ = last_send_s_ = sent_at;
    last_send_wall_s_ = sent_wall;
    const auto echoed =
        drive(nullptr, sent_at + echo_wait_s_, [&](const Observation& o) { return echoes(o, next); });
    if (echoed) {
      latencies_ms.push_back((log()[*echoed].arrival_s - sent_at) * 1e3);
      ready_s = log()[*echoed].arrival_s + target_.immediate_interval_s + 0.001;
    } else {
      ++lost;
    }
  }
  for (CheckResult& r : check_echo_latency(latencies_ms, lost, thresholds_)) out.push_back(std::move(r));
  return !latencies_ms.empty();
}

bool TargetSession::ensure_commanded(std::vector<CheckResult>& out) {
  if (!log().empty() && log().back().fresh) return true;
  const PreparedCommand& probe = commands_->probes[0];
  if (drive(&probe, steady_seconds() + echo_wait_s_,
            [&](const Observation& o) { return in_force(o, probe); })) {
    return true;
  }
  out.push_back(failed("commands", "command takes effect",
                       fmt::format("{} was never echoed with fresh_msg = true; last error_list: {}",
                                   probe.label, last_errors(log()))));
  return false;
}

bool TargetSession::run_watchdog(std::vector<CheckResult>& out) {
  if (!ensure_commanded(out)) return false;
  const double timeout = target_.timeout_s;
  const double period = target_.period_s;
  const double trip_wait = timeout + period + thresholds_.watchdog_slack_ms / 1e3 + 1.0;
  const double quiet = std::max(3 * period, 0.3);
  const auto not_fresh = [](const Observation& o) { return !o.fresh; };
  const auto is_fresh = [](const Observation& o) { return o.fresh; };
  std::vector<WatchdogRound> rounds;
  std::vector<Observation> in_safe_state;
  std::vector<CheckResult> returns;

  // Round 1: the planner goes silent, then comes back with a different command.
  const PreparedCommand* returned_with = nullptr;
  rounds.push_back(WatchdogRound{last_send_s_, std::nullopt, last_send_wall_s_});
  const auto trip = drive(nullptr, last_send_s_ + trip_wait, not_fresh);
  if (trip) {
    rounds.back().tripped = log()[*trip];
    drive(nullptr, steady_seconds() + quiet);
    const PreparedCommand& fresh_command = other_probe(log()[*trip].echo);
    const auto back = drive(&fresh_command, steady_seconds() + echo_wait_s_, is_fresh);
    if (back) {
      const auto between = range(*trip, *back);
      in_safe_state.insert(in_safe_state.end(), between.begin(), between.end());
      returns.push_back(check_no_stale_reapply(between, log()[*back], fresh_command.json, first_send_s_,
                                               thresholds_, "no_stale_reapply",
                                               "no stale re-apply; new command acts"));
      returned_with = &fresh_command;
    } else {
      returns.push_back(
          failed("no_stale_reapply", "no stale re-apply; new command acts",
                 fmt::format("fresh_msg never came back after {} was sent", fresh_command.label)));
    }
  }

  // Round 2: silent again, then back with the very command that was in force before.
  if (returned_with != nullptr && returns.back().verdict != Verdict::kFail) {
    const PreparedCommand& same = *returned_with;
    // Long enough for t_plus to grow clearly beyond the tolerance, so a restart is visible.
    drive(&same,
          steady_seconds() + std::max({3 * repeat_s_, 2 * thresholds_.t_plus_tolerance_ms / 1e3, period}));
    rounds.push_back(WatchdogRound{last_send_s_, std::nullopt, last_send_wall_s_});
    const auto trip2 = drive(nullptr, last_send_s_ + trip_wait, not_fresh);
    if (trip2) {
      rounds.back().tripped = log()[*trip2];
      drive(nullptr, steady_seconds() + quiet);
      const auto back = drive(&same, steady_seconds() + echo_wait_s_, is_fresh);
      if (back) {
        const auto between = range(*trip2, *back);
        in_safe_state.insert(in_safe_state.end(), between.begin(), between.end());
        returns.push_back(check_no_stale_reapply(between, log()[*back], same.json, first_send_s_, thresholds_,
                                                 "same_command_restarts",
                                                 "same command after silence restarts"));
      } else {
        returns.push_back(
            failed("same_command_restarts", "same command after silence restarts",
                   fmt::format("fresh_msg never came back after {} was sent again", same.label)));
      }
    }
  }

  const std::string& timeout_error = target_.profile->timeout_error;
  for (CheckResult& r : check_watchdog(rounds, timeout, period, timeout_error, thresholds_))
    out.push_back(std::move(r));
  out.push_back(check_safe_state(in_safe_state, target_.commands->safe_state.fields));
  bool ok = true;
  for (CheckResult& r : returns) {
    ok = ok && r.verdict != Verdict::kFail;
    out.push_back(std::move(r));
  }
  return ok && rounds.size() == 2 && rounds.back().tripped.has_value();
}

bool TargetSession::run_reset(std::vector<CheckResult>& out) {
  const PreparedCommand& reset = commands_->reset;
  const PreparedCommand* normal = nullptr;
  for (const PreparedCommand& probe : commands_->probes) {
    if (probe.json != reset.json) {
      normal = &probe;
      break;
    }
  }
  if (normal == nullptr) {
    out.push_back(
        failed("got_reset", "got_reset", "both probes are the reset command: nothing to compare with"));
    return false;
  }
  const double settle = std::max(3 * repeat_s_, 3 * target_.period_s);
  struct Span {
    std::size_t from = 0;
    std::size_t to = 0;
  };
  const auto hold = [&](const PreparedCommand& command) -> std::optional<Span> {
    const auto echoed = drive(&command, steady_seconds() + echo_wait_s_,
                              [&](const Observation& o) { return in_force(o, command); });
    if (!echoed) return std::nullopt;
    drive(&command, log()[*echoed].arrival_s + settle);
    return Span{*echoed, log().size()};
  };
  const auto before = hold(*normal);
  const auto during = before ? hold(reset) : std::nullopt;
  const auto after = during ? hold(*normal) : std::nullopt;
  const auto span_of = [&](const std::optional<Span>& s) {
    return s ? range(s->from, s->to) : std::span<const Observation>();
  };
  out.push_back(check_got_reset(span_of(before), span_of(during), span_of(after)));
  return out.back().verdict != Verdict::kFail;
}

}  // namespace hubrt::hubctl
