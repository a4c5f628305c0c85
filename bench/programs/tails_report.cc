// The tails bench's verdicts: each figure's rounds judged (tail_rounds.h), the host's state per
// round, and whose each slow hub round trip was (stage_attribution.h); tables on stdout, JSON out.
#include <algorithm>

#include <fmt/format.h>

#include "bench_common.h"
#include "median.h"
#include "tail_rounds.h"
#include "tails.h"

namespace hubrt::bench {
namespace {

// The aims: command -> echo p95 <= 1.1x and p99 <= 1.2x the raw pong; heartbeat jitter
// p99 <= 1.2x the raw writer (no p95 aim: 0).
constexpr double kEchoAimP95 = 1.1;
constexpr double kEchoAimP99 = 1.2;
constexpr double kJitterAimP99 = 1.2;

constexpr const char* kRegimes[2] = {"sparse", "back_to_back"};

struct Figure {
  std::string name;
  TailVerdict verdict;
  double aim_p95;
  double aim_p99;
  [[nodiscard]] bool met() const {
    return verdict.judged_rounds > 0 && (aim_p95 <= 0 || verdict.median_p95 <= aim_p95) &&
           verdict.median_p99 <= aim_p99;
  }
};

nlohmann::ordered_json figure_json(const Figure& f) {
  const TailVerdict& v = f.verdict;
  return {{"ratio_p95", v.ratio_p95},
          {"ratio_p99", v.ratio_p99},
          {"baseline_stalled", v.baseline_stalled},
          {"judged_rounds", v.judged_rounds},
          {"median_p95", v.median_p95},
          {"spread_p95", {v.min_p95, v.max_p95}},
          {"median_p99", v.median_p99},
          {"spread_p99", {v.min_p99, v.max_p99}},
          {"aim_p95", f.aim_p95},
          {"aim_p99", f.aim_p99},
          {"met", f.met()}};
}

// Slow hub round trips (above the raw pong's p95 of the same round and regime), each put down to
// the part of it that grew the most against the run's typical round trip (stage_attribution.h).
struct Blame {
  std::size_t slow = 0;
  std::size_t untraced = 0;
  std::size_t by_stage[5] = {};

  void add(const Samples& raw, const Samples& hub, const std::vector<TracedStep>& trace,
           const Attribution& typical) {
    const double threshold = summary_of(raw.ms).p95;
    for (std::size_t i = 0; i < hub.ms.size(); ++i) {
      if (hub.ms[i] <= threshold) continue;
      ++slow;
      const Attribution a = attribute(hub.timed[i], trace);
      if (a.traced) {
        ++by_stage[static_cast<int>(late_stage(a, typical))];
      } else {
        ++untraced;
      }
    }
  }
  [[nodiscard]] std::size_t hub_late() const {
    return by_stage[static_cast<int>(LateStage::kWake)] + by_stage[static_cast<int>(LateStage::kStep)] +
           by_stage[static_cast<int>(LateStage::kWrite)];
  }
  [[nodiscard]] nlohmann::ordered_json json() const {
    nlohmann::ordered_json j = {{"slow", slow}, {"untraced", untraced}, {"hub_late", hub_late()}};
    for (int s = 0; s < 5; ++s) j[fmt::format("late_{}", kLateStageNames[s])] = by_stage[s];
    return j;
  }
};

// The typical (median) parts of every traced hub round trip of the run, both planners; `traced`
// gets how many there were.
Attribution typical_round_trip(const std::vector<Round>& rounds, const std::vector<TracedStep>& trace,
                               std::size_t& traced) {
  std::vector<Attribution> all;
  for (const Round& r : rounds) {
    for (const PlannerRound* p : {&r.own, &r.external}) {
      for (const auto& regime : p->s) {
        for (const TimedRoundTrip& t : regime[1].timed) all.push_back(attribute(t, trace));
      }
    }
  }
  traced = static_cast<std::size_t>(
      std::count_if(all.begin(), all.end(), [](const Attribution& a) { return a.traced; }));
  return typical_of(all);
}

double us(std::int64_t ns) {
  return static_cast<double>(ns) * 1e-3;
}

std::string cell(double ratio, bool stalled) {
  return stalled ? fmt::format("{:.2f} (stalled)", ratio) : fmt::format("{:.2f}", ratio);
}

}  // namespace

int report(const std::vector<Round>& rounds, const std::vector<TracedStep>& trace, const Options& o) {
  std::vector<Figure> figures;
  for (int planner = 0; planner < 2; ++planner) {
    for (int regime = 0; regime < 2; ++regime) {
      std::vector<RoundTails> tails;
      for (const Round& r : rounds) {
        const PlannerRound& p = planner == 0 ? r.own : r.external;
        tails.push_back(round_tails(p.s[regime][1].ms, p.s[regime][0].ms));
      }
      figures.push_back({fmt::format("echo, {}, {} planner", kRegimes[regime], planner == 0 ? "own" : "C"),
                         judge_tails(tails), kEchoAimP95, kEchoAimP99});
    }
  }
  std::vector<RoundTails> jitter;
  std::vector<double> bare_p99;
  for (const Round& r : rounds) {
    jitter.push_back(round_tails(r.heartbeat.first_ms, r.heartbeat.second_ms));
    bare_p99.push_back(summary_of(r.bare_ms).p99);
  }
  figures.push_back({fmt::format("heartbeat jitter at a subscriber, {} Hz", o.heartbeat_rate),
                     judge_tails(jitter), 0.0, kJitterAimP99});
  const double usual_bare = median_of(bare_p99);
  std::size_t traced = 0;
  const Attribution typical = typical_round_trip(rounds, trace, traced);

  nlohmann::ordered_json per_round = nlohmann::ordered_json::array();
  fmt::print("| round | order | steal s | load | bare loop p99 ms |");
  for (const Figure& f : figures) fmt::print(" {} p95 / p99 |", f.name);
  fmt::print(
      " slow hub round trips late in the hub: wake / step / write; in the host |\n|---|---|---|---|---|");
  for (std::size_t i = 0; i < figures.size(); ++i) fmt::print("---|");
  fmt::print("---|\n");
  for (std::size_t r = 0; r < rounds.size(); ++r) {
    const Round& round = rounds[r];
    const bool host_stalled = bare_p99[r] > kBaselineStallFactor * usual_bare;
    Blame blame;
    for (int regime = 0; regime < 2; ++regime) {
      blame.add(round.own.s[regime][0], round.own.s[regime][1], trace, typical);
      blame.add(round.external.s[regime][0], round.external.s[regime][1], trace, typical);
    }
    fmt::print("| {} | {} | {:.2f} | {:.2f} | {:.3f}{} |", r + 1, round.order, round.steal_s, round.load,
               bare_p99[r], host_stalled ? " (stalled)" : "");
    nlohmann::ordered_json j = {{"order", round.order},         {"steal_s", round.steal_s},
                                {"load_1min", round.load},      {"bare_p99_ms", bare_p99[r]},
                                {"host_stalled", host_stalled}, {"slow_hub_round_trips", blame.json()}};
    for (const Figure& f : figures) {
      const bool stalled = f.verdict.baseline_stalled[r];
      fmt::print(" {} / {} |", cell(f.verdict.ratio_p95[r], stalled), cell(f.verdict.ratio_p99[r], stalled));
    }
    std::size_t lost[2] = {0, 0};
    for (int regime = 0; regime < 2; ++regime) {
      for (int side = 0; side < 2; ++side) {
        lost[side] += round.own.s[regime][side].lost + round.external.s[regime][side].lost;
        j[fmt::format("own_{}_{}", kRegimes[regime], side == 0 ? "raw" : "hub")] =
            summary_json(round.own.s[regime][side].ms);
        j[fmt::format("c_planner_{}_{}", kRegimes[regime], side == 0 ? "raw" : "hub")] =
            summary_json(round.external.s[regime][side].ms);
      }
    }
    j["heartbeat_hub_jitter_ms"] = summary_json(round.heartbeat.first_ms);
    j["heartbeat_raw_jitter_ms"] = summary_json(round.heartbeat.second_ms);
    j["lost_raw"] = lost[0];
    j["lost_hub"] = lost[1];
    fmt::print(" {} of {}: {} / {} / {}; host {}; untraced {} |\n", blame.hub_late(), blame.slow,
               blame.by_stage[static_cast<int>(LateStage::kWake)],
               blame.by_stage[static_cast<int>(LateStage::kStep)],
               blame.by_stage[static_cast<int>(LateStage::kWrite)],
               blame.slow - blame.hub_late() - blame.untraced, blame.untraced);
    per_round.push_back(std::move(j));
  }
  fmt::print(
      "\n| figure | judged rounds | p95 ratio, median (spread) | p99 ratio, median (spread) | aim | met |\n");
  fmt::print("|---|---|---|---|---|---|\n");
  nlohmann::ordered_json verdicts;
  for (const Figure& f : figures) {
    const TailVerdict& v = f.verdict;
    const std::string aim = f.aim_p95 > 0
                                ? fmt::format("p95 <= {:.1f}x, p99 <= {:.1f}x", f.aim_p95, f.aim_p99)
                                : fmt::format("p99 <= {:.1f}x", f.aim_p99);
    fmt::print("| {} | {} of {} | {:.2f}x ({:.2f}-{:.2f}) | {:.2f}x ({:.2f}-{:.2f}) | {} | {} |\n", f.name,
               v.judged_rounds, rounds.size(), v.median_p95, v.min_p95, v.max_p95, v.median_p99, v.min_p99,
               v.max_p99, aim, f.met() ? "yes" : "no");
    verdicts[f.name] = figure_json(f);
  }
  fmt::print(
      "\nThe typical hub round trip (the median of each part over the {} hub round trips the trace of {} "
      "command steps covers): {:.1f} us to the listener, wake {:.1f}, step {:.1f}, write {:.1f}, {:.1f} us "
      "from "
      "the write to the planner.\n",
      traced, trace.size(), us(typical.to_listener), us(typical.wake), us(typical.step), us(typical.write),
      us(typical.from_written));
  nlohmann::ordered_json result;
  result["rounds"] = rounds.size();
  result["per_side_per_round"] = {{"sparse", o.sparse}, {"back_to_back", o.back_to_back}};
  result["hub_rate_hz"] = o.hub_rate;
  result["heartbeat_rate_hz"] = o.heartbeat_rate;
  result["window_s"] = o.window_s;
  result["stall_factor"] = kBaselineStallFactor;
  result["traced_command_steps"] = trace.size();
  result["traced_hub_round_trips"] = traced;
  result["typical_hub_round_trip_us"] = {{"to_listener", us(typical.to_listener)},
                                         {"wake", us(typical.wake)},
                                         {"step", us(typical.step)},
                                         {"write", us(typical.write)},
                                         {"from_written", us(typical.from_written)}};
  result["verdicts"] = verdicts;
  result["per_round"] = per_round;
  if (auto ok = write_json(o.out, result); !ok) return fmt::print(stderr, "{}\n", ok.error().message), 1;
  return 0;
}

}  // namespace hubrt::bench
