// The conformance verdicts on made-up observations: each check passes a hub that behaves and
// fails the misbehaviour it exists for.
#include "conformance_checks.h"

#include <algorithm>
#include <span>

#include <gtest/gtest.h>

namespace hubrt::hubctl {
namespace {

const Thresholds kDefaults = default_thresholds();

// States every `period` s from t0 with consecutive sequence numbers; the hub stamps them at
// the same instants (its wall clock offset by 1e9 s, to show only differences matter).
std::vector<Observation> heartbeat(std::size_t n, double period, double t0 = 100.0, std::uint64_t seq0 = 1) {
  std::vector<Observation> out;
  for (std::size_t i = 0; i < n; ++i) {
    Observation o;
    o.arrival_s = t0 + static_cast<double>(i) * period;
    o.stamp_s = 1e9 + o.arrival_s;
    o.seq = seq0 + i;
    out.push_back(o);
  }
  return out;
}

nlohmann::ordered_json command(const char* action) {
  nlohmann::ordered_json c;
  c["target_type"] = "dock";
  c["target_name"] = "dock";
  c["action"] = action;
  return c;
}

// A command in force from arrival of states[0] on: fresh, echoing it, t_plus from 0.
void commanded(std::vector<Observation>& states, const char* action) {
  const double start = states.front().arrival_s;
  for (Observation& o : states) {
    o.fresh = true;
    o.echo = command(action);
    o.t_plus = o.arrival_s - start;
  }
}

CheckResult find(const std::vector<CheckResult>& results, const std::string& id) {
  for (const CheckResult& r : results) {
    if (r.id == id) return r;
  }
  ADD_FAILURE() << "no check " << id;
  return {};
}

TEST(Heartbeat, ASteadyHeartbeatPasses) {
  const auto states = heartbeat(51, 0.1);
  const HeartbeatFigures f = measure_heartbeat(states, 0.1);
  EXPECT_NEAR(f.rate_hz, 10.0, 1e-9);
  EXPECT_NEAR(f.jitter_ms.max, 0.0, 1e-3);  // stamps near 1e9 s resolve to about 1e-4 ms
  for (const CheckResult& r : check_heartbeat(f, 0.1, kDefaults)) {
    if (r.id.starts_with("arrival_")) {
      EXPECT_EQ(r.verdict, Verdict::kInfo) << r.id << ": reported, never judged";
    } else {
      EXPECT_EQ(r.verdict, Verdict::kPass) << r.id;
    }
  }
}

TEST(Heartbeat, AHubAtTheWrongRateFails) {
  const auto states = heartbeat(51, 0.102);  // a hub that sleeps 2 ms too long every cycle
  const auto results = check_heartbeat(measure_heartbeat(states, 0.1), 0.1, kDefaults);
  EXPECT_EQ(find(results, "rate_error").verdict, Verdict::kFail);
  EXPECT_NEAR(*find(results, "rate_error").number, 1.96, 0.01);
}

TEST(Heartbeat, AStallLongerThanTwoPeriodsFailsTheMaximumNotTheMedian) {
  auto states = heartbeat(51, 0.1);
  for (std::size_t i = 25; i < states.size(); ++i) {  // the hub woke 150 ms late once, then kept its pace
    states[i].stamp_s += 0.15;
    states[i].arrival_s += 0.15;
  }
  const auto results = check_heartbeat(measure_heartbeat(states, 0.1), 0.1, kDefaults);
  EXPECT_EQ(find(results, "jitter_max").verdict, Verdict::kFail);
  EXPECT_NEAR(*find(results, "jitter_max").number, 150.0, 1e-3);
  EXPECT_EQ(find(results, "jitter_p50").verdict, Verdict::kPass);
}

TEST(Heartbeat, JitterBoundsHaveAFloorAtHighRates) {
  auto states = heartbeat(1001, 0.001);
  for (std::size_t i = 0; i < states.size(); i += 2) {
    states[i].stamp_s += 0.0008;  // 0.8 ms scheduling noise in the hub's wake-ups
    states[i].arrival_s += 0.0008;
  }
  const auto results = check_heartbeat(measure_heartbeat(states, 0.001), 0.001, kDefaults);
  // 25 % of 1 ms would be 0.25 ms; the 2 ms floor keeps scheduler noise from failing the hub.
  EXPECT_EQ(find(results, "jitter_p99").verdict, Verdict::kPass);
  EXPECT_DOUBLE_EQ(*find(results, "jitter_p99").limit, 2.0);
}

// Issue 16, point 7: a stalled receiver is not a late hub.
TEST(Heartbeat, AStalledReceiverDoesNotFailAHubWhoseStampsAreOnTime) {
  auto states = heartbeat(51, 0.1);
  // hubctl's host stalled for 400 ms: States 20..24 arrive together at the end of the stall, and
  // the first State of the window arrived 80 ms late (the stall began before the window).
  for (std::size_t i = 20; i < 25; ++i) states[i].arrival_s = states[24].arrival_s + 0.001;
  states[0].arrival_s += 0.08;
  const HeartbeatFigures f = measure_heartbeat(states, 0.1);
  const auto results = check_heartbeat(f, 0.1, kDefaults);
  for (const char* id : {"rate_error", "jitter_p50", "jitter_p99", "jitter_max"})
    EXPECT_EQ(find(results, id).verdict, Verdict::kPass) << id << ": " << find(results, id).value;
  EXPECT_NEAR(f.rate_hz, 10.0, 1e-6) << "the rate is the hub's, from its stamps";
  // What the receiver saw is still reported, unjudged: the stall shows there.
  EXPECT_EQ(find(results, "arrival_jitter_max").verdict, Verdict::kInfo);
  // State 20 arrived 401 ms after State 19 (a 100 ms period plus the 400 ms stall, plus 1 ms).
  EXPECT_NEAR(*find(results, "arrival_jitter_max").number, 401.0, 1e-3);
  EXPECT_NEAR(f.jitter_ms.max, 0.0, 1e-3);
}

TEST(Heartbeat, AHubThatWakesLateFailsEvenWhenDeliveryHidesIt) {
  auto states = heartbeat(51, 0.1);
  // The hub woke 60 ms late every fifth cycle (and caught up after); arrivals here happen to be
  // evenly spaced (e.g. a receiver that polls), so only the stamps show the hub's lateness.
  for (std::size_t i = 5; i < states.size(); i += 5) states[i].stamp_s += 0.06;
  const auto results = check_heartbeat(measure_heartbeat(states, 0.1), 0.1, kDefaults);
  EXPECT_EQ(find(results, "jitter_p99").verdict, Verdict::kFail);  // 60 ms > 25 % of 100 ms
  EXPECT_NEAR(*find(results, "jitter_p99").number, 60.0, 1e-3);
  EXPECT_NEAR(*find(results, "arrival_jitter_max").number, 0.0, 1e-3);
}

TEST(Sequence, GapsAndRepeatsAreCounted) {
  auto states = heartbeat(10, 0.1);
  EXPECT_EQ(check_sequence(states, kDefaults).verdict, Verdict::kPass);
  states[4].seq = states[3].seq;                                       // repeated
  for (std::size_t i = 6; i < states.size(); ++i) states[i].seq += 2;  // two lost
  const CheckResult r = check_sequence(states, kDefaults);
  EXPECT_EQ(r.verdict, Verdict::kFail);
  EXPECT_EQ(*r.number, 4.0) << r.detail;  // 4 -> 4 (repeat), 4 -> 6 (one missing), 6 -> 9 (two missing)
}

TEST(FirstState, MissingOrLateFails) {
  EXPECT_EQ(check_first_state(std::nullopt, "since start", kDefaults).verdict, Verdict::kFail);
  EXPECT_EQ(check_first_state(0.04, "since start", kDefaults).verdict, Verdict::kPass);
  EXPECT_EQ(check_first_state(1.5, "since start", kDefaults).verdict, Verdict::kFail);
}

TEST(Fresh, TrueWhileUncommandedFails) {
  auto states = heartbeat(5, 0.1);
  EXPECT_EQ(check_fresh_before(states).verdict, Verdict::kPass);
  states[3].fresh = true;
  EXPECT_EQ(check_fresh_before(states).verdict, Verdict::kFail);
}

TEST(Fresh, FalseWhileCommandedFails) {
  auto states = heartbeat(5, 0.1);
  commanded(states, "monitor");
  EXPECT_EQ(check_fresh_while_commanded(states).verdict, Verdict::kPass);
  states[2].fresh = false;
  EXPECT_EQ(check_fresh_while_commanded(states).verdict, Verdict::kFail);
}

// The net tier's failure of 2026-11-28: an earlier planner's last command equalled the first probe,
// and a State the node published before the probe reached it (watchdog tripped: fresh_msg false,
// t_plus 10.4 s since that planner's command) arrived after the probe was sent. Taken for the
// probe's effect, it failed fresh_while_commanded and t_plus_grows on a hub that behaved.
TEST(CommandInForce, AStaleEchoOfTheSameCommandIsNotItsEffect) {
  auto states = heartbeat(2, 0.1);
  for (Observation& o : states) {
    o.echo = command("monitor");
    o.t_plus = 10.366 + (o.arrival_s - states.front().arrival_s);
  }
  auto probed = heartbeat(6, 0.1, states.back().arrival_s + 0.1, 3);
  commanded(probed, "monitor");
  states.insert(states.end(), probed.begin(), probed.end());
  const auto effect = std::find_if(states.begin(), states.end(), [](const Observation& o) {
    return command_in_force(o, command("monitor"));
  });
  ASSERT_EQ(effect - states.begin(), 2);
  const std::span<const Observation> held(effect, states.end());
  EXPECT_EQ(check_fresh_while_commanded(held).verdict, Verdict::kPass);
  EXPECT_EQ(check_t_plus_grows(held, kDefaults).verdict, Verdict::kPass);
  // From the stale echo on, both fail: what the conformance run reported.
  EXPECT_EQ(check_fresh_while_commanded(states).verdict, Verdict::kFail);
  EXPECT_EQ(check_t_plus_grows(states, kDefaults).verdict, Verdict::kFail);
  EXPECT_FALSE(command_in_force(states[2], command("reset")));
}

TEST(TPlus, FollowingWallTimePasses) {
  auto states = heartbeat(11, 0.1);
  commanded(states, "monitor");
  EXPECT_EQ(check_t_plus_grows(states, kDefaults).verdict, Verdict::kPass);
}

// CI's TSan run of 2026-12-01: hubctl stalled 0.4 s while the hub's first echo was on its way, so
// the arrivals said t_plus ran 0.43 s ahead of time. The hub's stamps say it did not.
TEST(TPlus, AReceiverThatStalledDoesNotFailAnExactTPlus) {
  auto states = heartbeat(11, 0.1);
  commanded(states, "monitor");
  states.front().arrival_s += 0.4;  // the first echo taken late; t_plus and the stamps are exact
  const CheckResult r = check_t_plus_grows(states, kDefaults);
  EXPECT_EQ(r.verdict, Verdict::kPass) << r.detail;
  EXPECT_NE(r.detail.find("400.0 ms on the arrivals"), std::string::npos) << r.detail;
}

TEST(TPlus, AStuckOrSlowTPlusFails) {
  auto stuck = heartbeat(11, 0.1);
  commanded(stuck, "monitor");
  for (Observation& o : stuck) o.t_plus = 0;  // never grows
  EXPECT_EQ(check_t_plus_grows(stuck, kDefaults).verdict, Verdict::kFail);

  auto slow = heartbeat(11, 0.1);
  commanded(slow, "monitor");
  for (Observation& o : slow) o.t_plus *= 0.9;  // a clock 10 % slow
  EXPECT_EQ(check_t_plus_grows(slow, kDefaults).verdict, Verdict::kFail);
}

TEST(TPlus, ARepeatThatRestartsTPlusFails) {
  // t_plus falling back to 0 at every repetition: repeats treated as new commands.
  auto states = heartbeat(11, 0.1);
  commanded(states, "monitor");
  states[5].t_plus = 0;
  EXPECT_EQ(check_t_plus_grows(states, kDefaults).verdict, Verdict::kFail);
}

TEST(TPlus, RestartsOnAChangedCommand) {
  auto before = heartbeat(11, 0.1);
  commanded(before, "monitor");
  Observation changed = before.back();
  changed.echo = command("reset");
  changed.t_plus = 0.0;
  EXPECT_EQ(check_t_plus_restarts(changed, &before.back(), kDefaults).verdict, Verdict::kPass);
  changed.t_plus = before.back().t_plus + 0.1;  // went on counting
  EXPECT_EQ(check_t_plus_restarts(changed, &before.back(), kDefaults).verdict, Verdict::kFail);
}

TEST(Repeats, RepublishingEveryRepetitionFails) {
  auto states = heartbeat(11, 0.1);  // 1 s of heartbeat
  commanded(states, "monitor");
  EXPECT_EQ(check_repeats_silent(states, 0.1, kDefaults).verdict, Verdict::kPass);
  // The same second, but the hub published an extra State for each of 10 repetitions.
  auto chatty = heartbeat(11, 0.1);
  commanded(chatty, "monitor");
  for (std::size_t i = 0; i < chatty.size(); ++i) chatty[i].seq = 1 + 2 * i;
  const CheckResult r = check_repeats_silent(chatty, 0.1, kDefaults);
  EXPECT_EQ(r.verdict, Verdict::kFail);
  EXPECT_EQ(*r.number, 10.0);
}

TEST(EchoLatency, PercentilesAndLostCommands) {
  std::vector<double> latencies(100, 0.2);
  latencies[99] = 5.0;
  auto results = check_echo_latency(latencies, 0, kDefaults);
  EXPECT_EQ(find(results, "echo_all").verdict, Verdict::kPass);
  EXPECT_EQ(find(results, "echo_p50").verdict, Verdict::kPass);
  EXPECT_EQ(find(results, "echo_p99").verdict, Verdict::kPass);
  results = check_echo_latency(latencies, 1, kDefaults);
  EXPECT_EQ(find(results, "echo_all").verdict, Verdict::kFail);
  // A hub that answers only at its next 10 Hz cycle: half a period on average.
  results = check_echo_latency(std::vector<double>(100, 50.0), 0, kDefaults);
  EXPECT_EQ(find(results, "echo_p50").verdict, Verdict::kFail);
}

Observation tripped_at(double arrival, bool with_error = true) {
  Observation o;
  o.arrival_s = arrival;
  o.fresh = false;
  o.echo = command("monitor");
  if (with_error)
    o.errors.push_back("command timeout: no valid command for 1.05 s (limit 1.00 s); outputs in safe state");
  return o;
}

TEST(Watchdog, TripWithinTimeoutPlusPeriodPasses) {
  const std::vector<WatchdogRound> rounds{{10.0, tripped_at(11.05), std::nullopt},
                                          {20.0, tripped_at(21.10), std::nullopt}};
  const auto results = check_watchdog(rounds, 1.0, 0.1, "command timeout", kDefaults);
  EXPECT_EQ(find(results, "watchdog").verdict, Verdict::kPass);
  EXPECT_EQ(find(results, "watchdog_error").verdict, Verdict::kPass);
}

TEST(Watchdog, LateEarlyMissingOrUnreportedTripsFail) {
  const std::vector<WatchdogRound> late{{10.0, tripped_at(11.3), std::nullopt}};
  EXPECT_EQ(find(check_watchdog(late, 1.0, 0.1, "command timeout", kDefaults), "watchdog").verdict,
            Verdict::kFail);
  const std::vector<WatchdogRound> early{{10.0, tripped_at(10.5), std::nullopt}};
  EXPECT_EQ(find(check_watchdog(early, 1.0, 0.1, "command timeout", kDefaults), "watchdog").verdict,
            Verdict::kFail);
  const std::vector<WatchdogRound> never{{10.0, std::nullopt, std::nullopt}};
  EXPECT_EQ(find(check_watchdog(never, 1.0, 0.1, "command timeout", kDefaults), "watchdog").verdict,
            Verdict::kFail);
  const std::vector<WatchdogRound> silent{{10.0, tripped_at(11.05, false), std::nullopt}};
  EXPECT_EQ(find(check_watchdog(silent, 1.0, 0.1, "command timeout", kDefaults), "watchdog_error").verdict,
            Verdict::kFail);
}

// The hub's wall clock as in heartbeat(): 1e9 s ahead of the receiver's steady clock.
constexpr double kWall = 1e9;

// A trip whose State the hub stamped `stamp` s after the last write, and which arrived `arrival` s
// after it (the write at 10.0 on the steady clock, kWall + 10.0 on the wall clock).
WatchdogRound stamped_round(double stamp, double arrival) {
  Observation o = tripped_at(10.0 + arrival);
  o.stamp_s = kWall + 10.0 + stamp;
  return WatchdogRound{10.0, o, kWall + 10.0};
}

CheckResult watchdog_verdict(const WatchdogRound& round) {
  return find(check_watchdog(std::span(&round, 1), 1.0, 0.1, "command timeout", kDefaults), "watchdog");
}

// As CI's t_plus failure of 2026-12-01, at the trip: the hub went safe 1.05 s after the write by
// its own stamp, and hubctl, stalled, took the State 0.55 s later. On the arrival alone it failed.
TEST(Watchdog, AReceiverThatStalledDoesNotFailATimelyTrip) {
  const CheckResult r = watchdog_verdict(stamped_round(1.05, 1.6));
  EXPECT_EQ(r.verdict, Verdict::kPass) << r.detail;
  EXPECT_NEAR(*r.number, 1050.0, 1e-3);
  EXPECT_NE(r.detail.find("1 on the hub's stamps; 1600.000 ms on the arrivals"), std::string::npos)
      << r.detail;
  WatchdogRound unstamped = stamped_round(1.05, 1.6);
  unstamped.last_command_wall_s.reset();  // no wall time: the arrival is all there is
  EXPECT_EQ(watchdog_verdict(unstamped).verdict, Verdict::kFail);
}

TEST(Watchdog, ATripLateByItsOwnStampFails) {
  const CheckResult r = watchdog_verdict(stamped_round(1.4, 1.41));
  EXPECT_EQ(r.verdict, Verdict::kFail) << r.detail;
  EXPECT_NEAR(*r.number, 1400.0, 1e-3);
}

// A stamp before the timeout or after the arrival shows clocks that disagree, not the hub's delay:
// the arrival judges, and a late one fails however early the stamp claims the trip was.
TEST(Watchdog, AStampOfAnotherClockIsNotBelieved) {
  EXPECT_EQ(watchdog_verdict(stamped_round(0.5, 1.6)).verdict, Verdict::kFail);
  EXPECT_EQ(watchdog_verdict(stamped_round(-3.0, 1.6)).verdict, Verdict::kFail);
  const CheckResult after = watchdog_verdict(stamped_round(1.2, 1.1));
  EXPECT_EQ(after.verdict, Verdict::kPass) << after.detail;
  EXPECT_NEAR(*after.number, 1100.0, 1e-3);
  // Early by the arrival fails even if the stamp says otherwise.
  EXPECT_EQ(watchdog_verdict(stamped_round(1.05, 0.5)).verdict, Verdict::kFail);
}

TEST(SafeState, DeclaredFieldsAreChecked) {
  Observation o = tripped_at(11.0);
  o.state = nlohmann::ordered_json::parse(
      R"({"rsp": {"locked": true, "safe_state": true}, "slots": [{"occupied": false}]})");
  const std::vector<Observation> states{o};
  EXPECT_EQ(check_safe_state(states, {}).verdict, Verdict::kInfo);
  EXPECT_EQ(check_safe_state(states, {{"rsp.locked", "true"}, {"slots[0].occupied", "false"}}).verdict,
            Verdict::kPass);
  const CheckResult wrong = check_safe_state(states, {{"rsp.locked", "false"}});
  EXPECT_EQ(wrong.verdict, Verdict::kFail);
  EXPECT_NE(wrong.detail.find("rsp.locked is true"), std::string::npos) << wrong.detail;
  EXPECT_EQ(check_safe_state(states, {{"rsp.missing", "true"}}).verdict, Verdict::kFail);
}

TEST(NoStaleReapply, OnlyTheNewCommandActsAfterSilence) {
  std::vector<Observation> between{tripped_at(11.0), tripped_at(11.1), tripped_at(11.2)};
  Observation back;
  back.arrival_s = 11.25;
  back.fresh = true;
  back.echo = command("reset");
  back.t_plus = 0;
  EXPECT_EQ(check_no_stale_reapply(between, back, command("reset"), 11.2, kDefaults, "x", "x").verdict,
            Verdict::kPass);
}

TEST(NoStaleReapply, TheOldCommandActingAgainFails) {
  std::vector<Observation> between{tripped_at(11.0), tripped_at(11.1)};
  Observation back;
  back.arrival_s = 11.25;
  back.fresh = true;
  back.t_plus = 0;
  // Fresh again, but echoing the command from before the silence, not the one just sent.
  back.echo = command("monitor");
  EXPECT_EQ(check_no_stale_reapply(between, back, command("reset"), 11.2, kDefaults, "x", "x").verdict,
            Verdict::kFail);
  // Fresh before anything was sent.
  back.echo = command("reset");
  EXPECT_EQ(check_no_stale_reapply(between, back, command("reset"), 11.3, kDefaults, "x", "x").verdict,
            Verdict::kFail);
  // Something took effect during the silence.
  between[1].fresh = true;
  EXPECT_EQ(check_no_stale_reapply(between, back, command("reset"), 11.2, kDefaults, "x", "x").verdict,
            Verdict::kFail);
}

TEST(NoStaleReapply, TheSameCommandReturningMustRestartTPlus) {
  std::vector<Observation> between{tripped_at(11.0), tripped_at(11.1)};
  Observation back;
  back.arrival_s = 11.25;
  back.fresh = true;
  back.echo = command("monitor");
  back.t_plus = 1.4;  // carried on from before the silence: the stale command was resumed
  EXPECT_EQ(check_no_stale_reapply(between, back, command("monitor"), 11.2, kDefaults, "x", "x").verdict,
            Verdict::kFail);
  back.t_plus = 0;
  EXPECT_EQ(check_no_stale_reapply(between, back, command("monitor"), 11.2, kDefaults, "x", "x").verdict,
            Verdict::kPass);
}

TEST(GotReset, TrueOnlyWhileResetIsInForce) {
  auto before = heartbeat(3, 0.1);
  auto during = heartbeat(3, 0.1, 101);
  auto after = heartbeat(3, 0.1, 102);
  for (Observation& o : during) o.got_reset = true;
  EXPECT_EQ(check_got_reset(before, during, after).verdict, Verdict::kPass);
  after[2].got_reset = true;  // latched
  EXPECT_EQ(check_got_reset(before, during, after).verdict, Verdict::kFail);
  after[2].got_reset = false;
  during[1].got_reset = false;  // acts once and forgets while reset still repeats
  EXPECT_EQ(check_got_reset(before, during, after).verdict, Verdict::kFail);
  EXPECT_EQ(check_got_reset({}, during, after).verdict, Verdict::kFail);
}

TEST(JsonPath, FindsNestedFieldsAndComparesText) {
  const auto state = nlohmann::ordered_json::parse(R"({"a": {"b": [1, {"c": "x"}]}, "f": 0.5, "t": true})");
  EXPECT_EQ(json_at(state, "a.b[1].c"), "x");
  EXPECT_TRUE(json_at(state, "a.b[2]").is_null());
  EXPECT_TRUE(json_at(state, "nope").is_null());
  EXPECT_TRUE(json_matches_text(json_at(state, "f"), "0.5"));
  EXPECT_FALSE(json_matches_text(json_at(state, "f"), "0.6"));
  EXPECT_TRUE(json_matches_text(json_at(state, "t"), "true"));
  EXPECT_TRUE(json_matches_text(json_at(state, "t"), "1"));
  EXPECT_FALSE(json_matches_text(json_at(state, "t"), "false"));
  EXPECT_FALSE(json_matches_text(json_at(state, "nope"), "null"));
}

}  // namespace
}  // namespace hubrt::hubctl
