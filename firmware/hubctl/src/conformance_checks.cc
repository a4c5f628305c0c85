#include "conformance_checks.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "sample_decoder.h"

namespace hubrt::hubctl {
namespace {

std::string ms(double seconds) {
  return fmt::format("{:.3f} ms", seconds * 1e3);
}

std::string describe_seq(const Observation& o) {
  return fmt::format("State seq {}", o.seq);
}

}  // namespace

std::string_view to_string(Verdict verdict) noexcept {
  switch (verdict) {
    case Verdict::kPass:
      return "PASS";
    case Verdict::kFail:
      return "FAIL";
    case Verdict::kInfo:
      return "INFO";
  }
  return "?";
}

CheckResult at_most(std::string id, std::string title, double value, double limit, std::string unit,
                    int decimals) {
  CheckResult r;
  r.id = std::move(id);
  r.title = std::move(title);
  r.verdict = value <= limit ? Verdict::kPass : Verdict::kFail;
  r.value = fmt::format("{:.{}f} {}", value, decimals, unit);
  r.threshold = fmt::format("<= {:.{}f} {}", limit, decimals, unit);
  r.number = value;
  r.limit = limit;
  r.unit = std::move(unit);
  return r;
}

CheckResult failed(std::string id, std::string title, std::string detail) {
  CheckResult r;
  r.id = std::move(id);
  r.title = std::move(title);
  r.verdict = Verdict::kFail;
  r.value = "-";
  r.detail = std::move(detail);
  return r;
}

CheckResult passed(std::string id, std::string title, std::string value, std::string detail) {
  CheckResult r;
  r.id = std::move(id);
  r.title = std::move(title);
  r.verdict = Verdict::kPass;
  r.value = std::move(value);
  r.detail = std::move(detail);
  return r;
}

HeartbeatFigures measure_heartbeat(std::span<const Observation> window, double period_s) {
  HeartbeatFigures f;
  f.states = window.size();
  if (window.size() < 2) return f;
  const double elapsed = window.back().stamp_s - window.front().stamp_s;
  f.rate_hz = elapsed > 0 ? static_cast<double>(window.size() - 1) / elapsed : 0;
  f.rate_error_pct = std::abs(f.rate_hz * period_s - 1.0) * 100.0;
  const auto periods_of = [&](double Observation::*time, Summary& jitter_out, Summary& periods_out) {
    std::vector<double> jitter;
    std::vector<double> periods;
    for (std::size_t i = 1; i < window.size(); ++i) {
      const double period = window[i].*time - window[i - 1].*time;
      periods.push_back(period * 1e3);
      jitter.push_back(std::abs(period - period_s) * 1e3);
    }
    jitter_out = summarize(std::move(jitter));
    periods_out = summarize(std::move(periods));
  };
  periods_of(&Observation::stamp_s, f.jitter_ms, f.period_ms);
  periods_of(&Observation::arrival_s, f.arrival_jitter_ms, f.arrival_period_ms);
  return f;
}

std::vector<CheckResult> check_heartbeat(const HeartbeatFigures& figures, double period_s,
                                         const Thresholds& thresholds) {
  std::vector<CheckResult> out;
  if (figures.states < 2) {
    out.push_back(failed("rate_error", "rate error",
                         fmt::format("only {} State(s) in the heartbeat window", figures.states)));
    return out;
  }
  CheckResult rate =
      at_most("rate_error", "rate error", figures.rate_error_pct, thresholds.rate_error_pct, "%");
  rate.detail = fmt::format("{:.3f} Hz on the hub's stamps over {} States, {:.3f} Hz expected",
                            figures.rate_hz, figures.states, 1.0 / period_s);
  out.push_back(std::move(rate));
  const double period_ms = period_s * 1e3;
  const auto jitter_row = [&](const char* id, const char* title, double value, double pct) {
    const double limit = std::max(pct / 100.0 * period_ms, thresholds.jitter_floor_ms);
    CheckResult r = at_most(id, title, value, limit, "ms", 3);
    r.detail = fmt::format(
        "|period - {:.3f} ms| between the hub's stamps (when it woke); bound {:g} % of the period, at "
        "least {:g} ms",
        period_ms, pct, thresholds.jitter_floor_ms);
    out.push_back(std::move(r));
  };
  jitter_row("jitter_p50", "period jitter p50", figures.jitter_ms.p50, thresholds.jitter_p50_pct);
  jitter_row("jitter_p99", "period jitter p99", figures.jitter_ms.p99, thresholds.jitter_p99_pct);
  jitter_row("jitter_max", "period jitter max", figures.jitter_ms.max, thresholds.jitter_max_pct);
  // Not judged: a late arrival with an on-time stamp is the network or this host, not the hub.
  const auto arrival_row = [&](const char* id, const char* title, double value) {
    CheckResult r;
    r.id = id;
    r.title = title;
    r.verdict = Verdict::kInfo;
    r.value = fmt::format("{:.3f} ms", value);
    r.number = value;
    r.unit = "ms";
    r.detail = fmt::format(
        "|period - {:.3f} ms| between arrivals here: the hub plus delivery plus this host's "
        "scheduling of hubctl; reported, not judged",
        period_ms);
    out.push_back(std::move(r));
  };
  arrival_row("arrival_jitter_p50", "arrival jitter p50", figures.arrival_jitter_ms.p50);
  arrival_row("arrival_jitter_p99", "arrival jitter p99", figures.arrival_jitter_ms.p99);
  arrival_row("arrival_jitter_max", "arrival jitter max", figures.arrival_jitter_ms.max);
  return out;
}

CheckResult check_sequence(std::span<const Observation> all, const Thresholds& thresholds) {
  if (all.empty()) return failed("seq_gaps", "sequence gaps", "no State received");
  std::uint64_t missing = 0;
  std::uint64_t backwards = 0;
  for (std::size_t i = 1; i < all.size(); ++i) {
    const std::uint64_t last = all[i - 1].seq;
    const std::uint64_t seq = all[i].seq;
    if (seq > last + 1) missing += seq - last - 1;
    if (seq <= last) ++backwards;
  }
  CheckResult r = at_most("seq_gaps", "sequence gaps", static_cast<double>(missing + backwards),
                          thresholds.seq_gaps, "", 0);
  r.detail = fmt::format("{} missing, {} repeated or backwards, over {} States (seq {}..{})", missing,
                         backwards, all.size(), all.front().seq, all.back().seq);
  return r;
}

CheckResult check_first_state(std::optional<double> elapsed_s, const std::string& since,
                              const Thresholds& thresholds) {
  const std::string title = "first State " + since;
  if (!elapsed_s) return failed("first_state", title, "no State received");
  CheckResult r = at_most("first_state", title, *elapsed_s * 1e3, thresholds.first_state_ms, "ms", 1);
  return r;
}

bool command_in_force(const Observation& o, const nlohmann::ordered_json& command) {
  return o.fresh && o.echo == command;
}

CheckResult check_fresh_before(std::span<const Observation> uncommanded) {
  const std::string title = "fresh_msg false before commands";
  if (uncommanded.empty()) return failed("fresh_before", title, "no State received before commanding");
  for (const Observation& o : uncommanded) {
    if (o.fresh) {
      return failed("fresh_before", title,
                    fmt::format("{} says fresh_msg = true although nobody commands the node (another planner "
                                "sending to it?)",
                                describe_seq(o)));
    }
  }
  return passed("fresh_before", title, fmt::format("{} States false", uncommanded.size()));
}

CheckResult check_fresh_while_commanded(std::span<const Observation> commanded) {
  const std::string title = "fresh_msg true while commanded";
  if (commanded.empty()) return failed("fresh_while_commanded", title, "no State echoed the command");
  for (const Observation& o : commanded) {
    if (!o.fresh) {
      return failed("fresh_while_commanded", title,
                    fmt::format("{} says fresh_msg = false while the command repeats", describe_seq(o)));
    }
  }
  return passed("fresh_while_commanded", title, fmt::format("{} States true", commanded.size()));
}

CheckResult check_t_plus_grows(std::span<const Observation> held, const Thresholds& thresholds) {
  const std::string title = "t_plus follows wall time";
  if (held.size() < 2)
    return failed("t_plus_grows", title, "fewer than two States while the command repeated");
  const Observation& first = held.front();
  const double tolerance_s = thresholds.t_plus_tolerance_ms / 1e3;
  if (first.t_plus > tolerance_s) {
    return failed("t_plus_grows", title,
                  fmt::format("t_plus was already {:.3f} s in the first State echoing the command ({})",
                              first.t_plus, describe_seq(first)));
  }
  // Judged on the hub's own stamps (when it woke for each cycle), as the period jitter is: the
  // arrivals here carry this process's scheduling too, and a sanitizer build of hubctl stalled
  // 0.4 s on a loaded CI machine failed a hub whose t_plus was exact. The arrivals' figure is
  // reported beside it, so that a hub whose stamps themselves drift still shows.
  double worst = 0;
  double worst_arrival = 0;
  const Observation* worst_at = &first;
  for (std::size_t i = 1; i < held.size(); ++i) {
    const Observation& o = held[i];
    if (o.t_plus + 1e-6 < held[i - 1].t_plus) {
      return failed("t_plus_grows", title,
                    fmt::format("t_plus went backwards from {:.3f} s to {:.3f} s at {}", held[i - 1].t_plus,
                                o.t_plus, describe_seq(o)));
    }
    const double grown = o.t_plus - first.t_plus;
    const double deviation = std::abs(grown - (o.stamp_s - first.stamp_s));
    if (deviation > worst) {
      worst = deviation;
      worst_at = &o;
    }
    worst_arrival = std::max(worst_arrival, std::abs(grown - (o.arrival_s - first.arrival_s)));
  }
  CheckResult r = at_most("t_plus_grows", title, worst * 1e3, thresholds.t_plus_tolerance_ms, "ms", 1);
  r.detail = fmt::format(
      "largest |t_plus - time since the first echo| on the hub's stamps over {} States ({}); "
      "{:.1f} ms on the arrivals here; t_plus reached {:.3f} s",
      held.size(), describe_seq(*worst_at), worst_arrival * 1e3, held.back().t_plus);
  return r;
}

CheckResult check_t_plus_restarts(const Observation& first, const Observation* before,
                                  const Thresholds& thresholds, std::string id, std::string title) {
  const double tolerance_s = thresholds.t_plus_tolerance_ms / 1e3;
  if (before != nullptr && before->t_plus > tolerance_s && first.t_plus >= before->t_plus) {
    return failed(std::move(id), std::move(title),
                  fmt::format("t_plus went on from {:.3f} s to {:.3f} s instead of restarting ({})",
                              before->t_plus, first.t_plus, describe_seq(first)));
  }
  CheckResult r =
      at_most(std::move(id), std::move(title), first.t_plus * 1e3, thresholds.t_plus_tolerance_ms, "ms", 1);
  r.detail = before != nullptr ? fmt::format("t_plus {:.3f} s before the change", before->t_plus) : "";
  return r;
}

CheckResult check_repeats_silent(std::span<const Observation> held, double period_s,
                                 const Thresholds& thresholds) {
  const std::string title = "identical repeats not republished";
  if (held.size() < 2)
    return failed("repeats_silent", title, "fewer than two States while the command repeated");
  const double published = static_cast<double>(held.back().seq - held.front().seq + 1);
  const double cycles = std::round((held.back().stamp_s - held.front().stamp_s) / period_s) + 1;
  const double extra = std::max(0.0, published - cycles);
  CheckResult r = at_most("repeats_silent", title, extra, thresholds.extra_states, "States", 0);
  r.detail = fmt::format("{:.0f} States published over {:.0f} periods of the hub's clock", published, cycles);
  return r;
}

std::vector<CheckResult> check_echo_latency(const std::vector<double>& latencies_ms, std::size_t lost,
                                            const Thresholds& thresholds) {
  std::vector<CheckResult> out;
  const std::size_t sent = latencies_ms.size() + lost;
  if (lost > 0 || latencies_ms.empty()) {
    out.push_back(failed("echo_all", "every changed command echoed",
                         fmt::format("{} of {} commands never came back in an echo", lost, sent)));
  } else {
    out.push_back(passed("echo_all", "every changed command echoed", fmt::format("{}/{}", sent, sent),
                         "each echo equal to the command sent, field by field"));
  }
  if (latencies_ms.empty()) return out;
  const Summary s = summarize(latencies_ms);
  CheckResult p50 = at_most("echo_p50", "command -> echo p50", s.p50, thresholds.echo_p50_ms, "ms", 3);
  p50.detail = fmt::format("{} commands; min {:.3f} ms, max {:.3f} ms", s.count, s.min, s.max);
  out.push_back(std::move(p50));
  out.push_back(at_most("echo_p99", "command -> echo p99", s.p99, thresholds.echo_p99_ms, "ms", 3));
  return out;
}

std::vector<CheckResult> check_watchdog(std::span<const WatchdogRound> rounds, double timeout_s,
                                        double period_s, const std::string& timeout_error,
                                        const Thresholds& thresholds) {
  std::vector<CheckResult> out;
  const std::string title = "watchdog within timeout + period";
  const double lower = timeout_s - 1e-3;  // same clock on our side; 1 ms for rounding
  const double upper = timeout_s + period_s + thresholds.watchdog_slack_ms / 1e3;
  double worst = 0;
  double worst_arrival = 0;
  std::size_t on_stamps = 0;
  std::string problem;
  for (std::size_t i = 0; i < rounds.size() && problem.empty(); ++i) {
    const WatchdogRound& round = rounds[i];
    if (!round.tripped) {
      problem = fmt::format("round {}: fresh_msg never turned false after the commands stopped", i + 1);
      break;
    }
    const double arrived = round.tripped->arrival_s - round.last_command_s;
    worst_arrival = std::max(worst_arrival, arrived);
    if (arrived < lower) {
      problem = fmt::format("round {}: tripped {} after the last command, before the {} timeout", i + 1,
                            ms(arrived), ms(timeout_s));
      break;
    }
    // The stamp counts only between the timeout and the arrival (1 ms for reading two clocks):
    // outside that the two wall clocks disagree (another host, or `clock_tolerance_ms: none`).
    double delay = arrived;
    if (round.last_command_wall_s) {
      const double stamped = round.tripped->stamp_s - *round.last_command_wall_s;
      if (stamped >= lower && stamped <= arrived + 1e-3) {
        delay = stamped;
        ++on_stamps;
      }
    }
    worst = std::max(worst, delay);
  }
  if (!problem.empty()) {
    out.push_back(failed("watchdog", title, problem));
  } else {
    CheckResult r = at_most("watchdog", title, worst * 1e3, upper * 1e3, "ms", 1);
    r.detail = fmt::format(
        "last command -> first State with fresh_msg = false, worst of {} rounds ({} on the hub's stamps; "
        "{} on the arrivals); timeout {}, period {}, slack {:g} ms; never earlier than the timeout",
        rounds.size(), on_stamps, ms(worst_arrival), ms(timeout_s), ms(period_s),
        thresholds.watchdog_slack_ms);
    out.push_back(std::move(r));
  }
  const std::string error_title = "timeout reported in error_list";
  for (std::size_t i = 0; i < rounds.size(); ++i) {
    if (!rounds[i].tripped) continue;
    const auto& errors = rounds[i].tripped->errors;
    const bool found = std::any_of(errors.begin(), errors.end(), [&](const std::string& e) {
      return e.find(timeout_error) != std::string::npos;
    });
    if (!found) {
      out.push_back(failed("watchdog_error", error_title,
                           fmt::format("round {}: no entry containing '{}' in error_list ({} entries)", i + 1,
                                       timeout_error, errors.size())));
      return out;
    }
  }
  out.push_back(passed("watchdog_error", error_title, fmt::format("'{}'", timeout_error)));
  return out;
}

CheckResult check_safe_state(std::span<const Observation> tripped,
                             const std::vector<std::pair<std::string, std::string>>& expected) {
  const std::string title = "safe-state fields";
  if (expected.empty()) {
    CheckResult r;
    r.id = "safe_state";
    r.title = title;
    r.verdict = Verdict::kInfo;
    r.value = "none declared";
    r.detail = "the profile declares no safe-state fields for this node type";
    return r;
  }
  if (tripped.empty()) return failed("safe_state", title, "no State after the watchdog tripped");
  for (const Observation& o : tripped) {
    for (const auto& [path, text] : expected) {
      const auto value = json_at(o.state, path);
      if (!json_matches_text(value, text)) {
        return failed(
            "safe_state", title,
            fmt::format("{}: {} is {}, expected {}", describe_seq(o), path, safe_dump(value), text));
      }
    }
  }
  return passed("safe_state", title,
                fmt::format("{} field(s) in {} States", expected.size(), tripped.size()));
}

CheckResult check_no_stale_reapply(std::span<const Observation> between, const Observation& returned,
                                   const nlohmann::ordered_json& sent, double sent_at_s,
                                   const Thresholds& thresholds, std::string id, std::string title) {
  if (between.empty())
    return failed(std::move(id), std::move(title), "no State between the trip and the return");
  const nlohmann::ordered_json& tripped_echo = between.front().echo;
  for (const Observation& o : between) {
    if (o.fresh) {
      return failed(std::move(id), std::move(title),
                    fmt::format("{} says fresh_msg = true before any new command was sent: the old command "
                                "acted again",
                                describe_seq(o)));
    }
    if (o.echo != tripped_echo) {
      return failed(std::move(id), std::move(title),
                    fmt::format("{} changed its echo to {} while no command was sent", describe_seq(o),
                                safe_dump(o.echo)));
    }
  }
  if (returned.arrival_s < sent_at_s) {
    return failed(std::move(id), std::move(title),
                  fmt::format("{} was fresh before the new command was written", describe_seq(returned)));
  }
  if (returned.echo != sent) {
    return failed(std::move(id), std::move(title),
                  fmt::format("{} is fresh but echoes {} instead of the command just sent {}",
                              describe_seq(returned), safe_dump(returned.echo), safe_dump(sent)));
  }
  CheckResult r = at_most(std::move(id), std::move(title), returned.t_plus * 1e3,
                          thresholds.t_plus_tolerance_ms, "ms", 1);
  r.detail =
      fmt::format("{} States in safe state, unchanged; then only the new command acted, t_plus restarted",
                  between.size());
  if (r.verdict == Verdict::kFail) {
    r.detail =
        fmt::format("t_plus is {:.3f} s in the first fresh State: it did not restart", returned.t_plus);
  }
  return r;
}

CheckResult check_got_reset(std::span<const Observation> before, std::span<const Observation> during,
                            std::span<const Observation> after) {
  const std::string title = "got_reset only while reset is in force";
  if (before.empty() || during.empty() || after.empty()) {
    return failed("got_reset", title,
                  fmt::format("missing States: {} before, {} during, {} after the reset command",
                              before.size(), during.size(), after.size()));
  }
  for (const Observation& o : before) {
    if (o.got_reset)
      return failed("got_reset", title, fmt::format("{}: true before any reset", describe_seq(o)));
  }
  for (const Observation& o : during) {
    if (!o.got_reset)
      return failed("got_reset", title, fmt::format("{}: false while reset repeats", describe_seq(o)));
  }
  for (const Observation& o : after) {
    if (o.got_reset)
      return failed("got_reset", title,
                    fmt::format("{}: still true after another command took effect", describe_seq(o)));
  }
  return passed("got_reset", title,
                fmt::format("{} / {} / {} States", before.size(), during.size(), after.size()),
                "false before, true during, false after");
}

nlohmann::ordered_json json_at(const nlohmann::ordered_json& value, std::string_view path) {
  const nlohmann::ordered_json* at = &value;
  while (!path.empty()) {
    const auto dot = path.find('.');
    std::string_view part = path.substr(0, dot);
    path = dot == std::string_view::npos ? std::string_view() : path.substr(dot + 1);
    std::optional<std::size_t> index;
    if (const auto bracket = part.find('['); bracket != std::string_view::npos && part.back() == ']') {
      std::size_t i = 0;
      const std::string_view digits = part.substr(bracket + 1, part.size() - bracket - 2);
      const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), i);
      if (ec != std::errc() || end != digits.data() + digits.size()) return nullptr;
      index = i;
      part = part.substr(0, bracket);
    }
    if (!at->is_object()) return nullptr;
    const auto it = at->find(std::string(part));
    if (it == at->end()) return nullptr;
    at = &*it;
    if (index) {
      if (!at->is_array() || *index >= at->size()) return nullptr;
      at = &(*at)[*index];
    }
  }
  return *at;
}

bool json_matches_text(const nlohmann::ordered_json& value, std::string_view text) {
  if (value.is_boolean()) {
    if (text == "true" || text == "1") return value.get<bool>();
    if (text == "false" || text == "0") return !value.get<bool>();
    return false;
  }
  if (value.is_number()) {
    double expected = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), expected);
    if (ec != std::errc() || end != text.data() + text.size()) return false;
    const double actual = value.get<double>();
    return std::abs(actual - expected) <= 1e-6 * std::max(1.0, std::abs(expected));
  }
  if (value.is_string()) return value.get<std::string>() == text;
  return !value.is_null() && safe_dump(value) == text;
}

}  // namespace hubrt::hubctl
