// Tails that mean something on a noisy host (issue 33 point 1). Rounds (10 by default), each
// taking turns, in an order that rotates from round to round, through:
//   own        this process as the planner (bench/support/echo_peer.h) of the Dock ECU at its
//              shipped 10 Hz and of the raw pong, command by command: sparse (20-120 ms apart) and
//              back to back (bursts within the hub's budget of immediate States);
//   external   the same from an independent planner in another process, a small C program
//              (bench/programs/c_planner.c), so that a tail both see is not one planner's;
//   heartbeat  a second hubd at 100 Hz and the raw writer (hubrt_bench_raw_peer heartbeat) at
//              100 Hz side by side: the jitter of their States' arrivals at a subscriber here;
//   bare       a bare clock_nanosleep loop here at 100 Hz: how late the host wakes a sleeper.
// Each round gives its own hub / baseline ratios of p95 and p99 (bench/support/tail_rounds.h:
// median and spread over the rounds; a round whose baseline stalled is shown and not judged), the
// host's steal time and load. The Dock ECU runs with `--trace-stages`: each slow hub round trip
// (above the raw pong's p95 in its round) is put down to the hub or to the host and transport by
// the stamps of its command step (bench/support/stage_attribution.h).
#include "tails.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <sstream>
#include <thread>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "hubrt/runtime/immediate_state_budget.h"

#include "bench_common.h"
#include "echo_peer.h"
#include "echo_setup.h"
#include "median.h"
#include "periodic_window.h"
#include "proc_stats.h"
#include "raw_dds.h"
#include "stage_attribution.h"
#include "tail_rounds.h"

namespace hubrt::bench {
namespace {

void own_round_trip(Peer& peer, std::size_t& sent, Samples* into) {
  double at = 0;
  const double rtt = round_trip(peer, sent++ % 2 == 0 ? "monitor" : "reset", nullptr, &at);
  if (rtt < 0) {
    if (into != nullptr) ++into->lost;
  } else if (into != nullptr) {
    into->add({static_cast<std::int64_t>(at * 1e9), static_cast<std::int64_t>((at + rtt) * 1e9)});
  }
}

// The same sequence as c_planner.c: sparse pairs in alternating order with a 20-120 ms gap, then
// bursts of `burst` per side (the first unrecorded) with `refill_s` after each pair of bursts.
void run_own(Peer* peers[2], PlannerRound& out, const Options& o, std::size_t burst, double refill_s,
             unsigned seed) {
  std::size_t sent[2] = {0, 0};
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> gap_s(0.020, 0.120);
  for (std::size_t i = 0; i < o.sparse; ++i) {
    for (std::size_t k = 0; k < 2; ++k) {
      const std::size_t side = (i + k) % 2;
      own_round_trip(*peers[side], sent[side], &out.s[0][side]);
    }
    std::this_thread::sleep_for(std::chrono::duration<double>(gap_s(random)));
  }
  for (std::size_t recorded = 0, round = 0; recorded < o.back_to_back; recorded += burst - 1, ++round) {
    for (std::size_t k = 0; k < 2; ++k) {
      const std::size_t side = (round + k) % 2;
      own_round_trip(*peers[side], sent[side], nullptr);
      for (std::size_t j = 1; j < burst; ++j) own_round_trip(*peers[side], sent[side], &out.s[1][side]);
    }
    std::this_thread::sleep_for(std::chrono::duration<double>(refill_s));
  }
}

Expected<void> run_external(PlannerRound& out, const Options& o, std::size_t burst, double refill_s,
                            unsigned seed) {
  auto planner = test_support::ChildProcess::start(
      HUBRT_C_PLANNER_PATH, {std::to_string(o.sparse), std::to_string(o.back_to_back), std::to_string(burst),
                             std::to_string(std::lround(refill_s * 1e3)), std::to_string(seed)});
  if (!planner) return std::move(planner).error();
  auto status = planner->wait(std::chrono::seconds(600));
  if (!status) return std::move(status).error();
  if (!status->exited_with(0)) {
    return make_error(ErrorCode::kInternal,
                      fmt::format("c_planner: {}\n{}", status->describe(), planner->stderr_text()));
  }
  std::istringstream lines(planner->stdout_text());
  std::string regime;
  std::string side;
  bool done = false;
  while (lines >> regime) {
    if (regime == "done") {
      done = true;
      break;
    }
    if (regime == "lost") {
      lines >> regime >> side;
      if (regime != "warmup") ++out.s[regime == "sparse" ? 0 : 1][side == "hub" ? 1 : 0].lost;
      continue;
    }
    std::int64_t sent = 0;
    std::int64_t echo = 0;
    int between = 0;
    lines >> side >> sent >> echo >> between;
    if (!lines) break;
    out.s[regime == "sparse" ? 0 : 1][side == "hub" ? 1 : 0].add({sent, echo});
  }
  if (!done) return make_error(ErrorCode::kInternal, "c_planner: its output ended before 'done'");
  return {};
}

Expected<JitterWindow> run_heartbeat(dds_entity_t participant, const Options& o) {
  const std::string hz = fmt::format("{}", o.heartbeat_rate);
  auto hub = start_hubd({"--hub", "dock_ecu", "--name", "dock_hb", "--rate", hz, "--no-black-box"});
  if (!hub) return std::move(hub).error();
  auto raw = start_raw_peer({"heartbeat", "--rate", hz});
  if (!raw) return std::move(raw).error();
  auto window = jitter_window(participant, "rt/dock_hb/dock/state", "rt/bench/heartbeat", o.heartbeat_rate,
                              0.5, o.window_s);
  stop(*raw);
  stop(*hub);
  return window;
}

int run(const Options& o) {
  auto domain = join_private_domain();
  if (!domain) return fmt::print(stderr, "{}\n", domain.error().message), 1;
  const std::string trace_file =
      (std::filesystem::temp_directory_path() / fmt::format("hubrt-tails-trace-{}.csv", getpid())).string();
  auto sides = open_echo_sides(
      domain->domain_id(),
      {"--hub", "dock_ecu", "--rate", fmt::format("{}", o.hub_rate), "--trace-stages", trace_file});
  if (!sides) return fmt::print(stderr, "{}\n", sides.error().message), 1;
  const std::size_t burst = runtime::kDefaultImmediateStateBurst;
  const double refill_s = immediate_state_refill_s();
  run_block(sides->raw_peer, 50, false, refill_s);  // warm-up
  run_block(sides->hub_peer, 50, false, refill_s);
  Peer* peers[2] = {&sides->raw_peer, &sides->hub_peer};

  std::vector<Round> rounds(std::max<std::size_t>(o.rounds, 1));
  const char* phases[4] = {"own", "external", "heartbeat", "bare"};
  for (std::size_t r = 0; r < rounds.size(); ++r) {
    Round& round = rounds[r];
    const double steal_before = machine_steal_s();
    for (std::size_t k = 0; k < 4; ++k) {
      const std::string phase = phases[(r + k) % 4];
      round.order += (k == 0 ? "" : " ") + phase;
      progress(fmt::format("tails: round {} of {}, {}", r + 1, rounds.size(), phase));
      const auto seed = static_cast<unsigned>(16 + r);
      if (phase == "own") run_own(peers, round.own, o, burst, refill_s, seed);
      if (phase == "external") {
        if (auto ok = run_external(round.external, o, burst, refill_s, seed); !ok) {
          return fmt::print(stderr, "{}\n", ok.error().message), 1;
        }
      }
      if (phase == "heartbeat") {
        auto window = run_heartbeat(sides->participant, o);
        if (!window) return fmt::print(stderr, "{}\n", window.error().message), 1;
        round.heartbeat = std::move(*window);
      }
      if (phase == "bare") round.bare_ms = bare_loop_lateness_ms(o.heartbeat_rate, o.window_s);
    }
    round.steal_s = machine_steal_s() - steal_before;
    double load[1] = {0};
    if (getloadavg(load, 1) == 1) round.load = load[0];
  }
  dds_delete(sides->participant);
  stop(sides->hub);
  stop(sides->pong);
  auto trace = read_stage_trace(trace_file);
  if (!trace) return fmt::print(stderr, "{}\n{}\n", trace.error().message, sides->hub.stderr_text()), 1;
  std::filesystem::remove(trace_file);
  return report(rounds, *trace, o);
}

}  // namespace
}  // namespace hubrt::bench

int main(int argc, char** argv) {
  CLI::App app{"Tails of the hub against its baselines in interleaved rounds (issue 33 point 1)"};
  hubrt::bench::Options o;
  app.add_option("--out", o.out, "Result file (JSON)");
  app.add_option("--rounds", o.rounds, "Rounds, each taking turns through every part")
      ->check(CLI::Range(1, 1000));
  app.add_option("--sparse", o.sparse, "Commands per side per round 20-120 ms apart")
      ->check(CLI::Range(1, 100000));
  app.add_option("--back-to-back", o.back_to_back, "Recorded back-to-back round trips per side per round")
      ->check(CLI::Range(1, 100000));
  app.add_option("--hub-rate", o.hub_rate,
                 "The commanded hub's cycle rate in Hz (its shipped 10 by default)");
  app.add_option("--heartbeat-rate", o.heartbeat_rate, "The heartbeat part's rate in Hz, hub and raw writer");
  app.add_option("--window", o.window_s, "Seconds of the heartbeat and the bare loop per round");
  CLI11_PARSE(app, argc, argv);
  return hubrt::bench::run(o);
}
