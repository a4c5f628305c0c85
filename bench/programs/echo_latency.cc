// Command -> echo latency of a hub, side by side with a raw Cyclone pong of the same payload, in
// the two regimes of issue 16 point 8:
//   sparse        a planner commanding every 20-120 ms (uniformly random gaps, as Sequence Planner
//                 does): every command finds both processes asleep, so wake-ups dominate;
//   back to back  each command written as soon as the echo of the one before is back: the path
//                 itself, threads and caches hot.
// Both peers are separate processes on loopback: hubd (Dock ECU, fake backend) and
// hubrt_bench_raw_peer pong (the C API, same types, same QoS: takes the command from a waitset and
// writes the State with its echo at once). This process is the planner for both, also on the C
// API: it writes a DockCommand and waits (waitset) for the DockState echoing it. Commands alternate
// between two actions so that each one takes effect on the hub and is answered at once. Hub and
// raw take turns command by command (sparse) or burst by burst (back to back), in an order that
// alternates, so machine noise hits both alike.
//
// Robust comparison (the figures are tens of microseconds on a shared machine): the run is cut
// into rounds, each measuring both sides interleaved command by command or burst by burst, so a
// drifting load hits both alike; each round gives its own hub / raw ratios, and the result is the
// median of the rounds' ratios with their spread (the pooled percentiles are kept too). Both
// answering processes are pinned to the same CPU (every thread), the planner to the others, so
// neither side gets a core the other does not.
//
// Back to back within the hub's budget of immediate States (runtime/immediate_state_budget.h, a
// token bucket of kDefaultImmediateStateBurst refilled one per immediate_state_interval_ms): a
// planner answering every echo at once without a pause is a flood by the wire contract and gets
// its States at the refill rate. So the back-to-back regime sends bursts of `burst` commands, each
// right after the echo of the one before, and pauses for the bucket to refill; the first command
// of a burst comes after a pause (that is the sparse regime's case) and is not recorded.
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <random>
#include <string>
#include <thread>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "hubrt/runtime/immediate_state_budget.h"

#include "bench_common.h"
#include "echo_peer.h"
#include "echo_setup.h"
#include "median.h"
#include "raw_dds.h"

namespace hubrt::bench {
namespace {

// One answering side (raw pong or hub) and what it measured in each regime.
struct Side {
  explicit Side(Peer* answering) : peer(answering) {}
  Peer* peer;
  std::size_t sent = 0;  // commands sent, for the alternating action
  std::vector<double> back_to_back_ms;
  std::vector<double> sparse_ms;
  // Recorded round trips during which another State (the hub's heartbeat) arrived first, and the
  // recorded ones without: the tail's share that is the hub's periodic cycle.
  std::size_t with_heartbeat = 0;
  std::vector<double> without_heartbeat_ms;
  std::size_t lost = 0;

  // One round trip; recorded into `into` unless null.
  void round_trip_into(std::vector<double>* into) {
    bool heartbeat = false;
    const double rtt = round_trip(*peer, sent++ % 2 == 0 ? "monitor" : "reset", &heartbeat);
    if (rtt < 0) {
      ++lost;
    } else if (into != nullptr) {
      into->push_back(rtt * 1e3);
      if (heartbeat) {
        ++with_heartbeat;
      } else {
        without_heartbeat_ms.push_back(rtt * 1e3);
      }
    }
  }
};

// Pins every thread of process `pid` to the CPUs in `cpus` (threads started later inherit it from
// the thread that starts them). Returns the number of threads pinned, 0 when none could be.
std::size_t pin_process(pid_t pid, const cpu_set_t& cpus) {
  std::size_t pinned = 0;
  std::error_code ec;
  for (const auto& task : std::filesystem::directory_iterator(fmt::format("/proc/{}/task", pid), ec)) {
    const pid_t tid = static_cast<pid_t>(std::stol(task.path().filename().string()));
    if (sched_setaffinity(tid, sizeof cpus, &cpus) == 0) ++pinned;
  }
  return pinned;
}

cpu_set_t cpu_set_of(int first, int last) {
  cpu_set_t set;
  CPU_ZERO(&set);
  for (int cpu = first; cpu <= last; ++cpu) CPU_SET(cpu, &set);
  return set;
}

void pause_s(double seconds) {
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
}

// Bursts of `burst` back-to-back round trips, the first of each unrecorded, until `samples` are
// recorded per side; `refill_s` of pause after each pair of bursts.
void run_back_to_back(Side& raw, Side& hub, std::size_t samples, std::size_t burst, double refill_s) {
  for (std::size_t round = 0; hub.back_to_back_ms.size() < samples && round < 4 * samples; ++round) {
    Side* order[2] = {&raw, &hub};
    if (round % 2 == 1) std::swap(order[0], order[1]);
    for (Side* side : order) {
      side->round_trip_into(nullptr);
      for (std::size_t i = 1; i < burst; ++i) side->round_trip_into(&side->back_to_back_ms);
    }
    pause_s(refill_s);
  }
}

// `commands` round trips per side, each after a gap drawn uniformly from 20-120 ms (seeded: every
// run draws the same gaps for the same round).
void run_sparse(Side& raw, Side& hub, std::size_t commands, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> gap_s(0.020, 0.120);
  for (std::size_t i = 0; i < commands; ++i) {
    Side* order[2] = {&raw, &hub};
    if (i % 2 == 1) std::swap(order[0], order[1]);
    for (Side* side : order) side->round_trip_into(&side->sparse_ms);
    pause_s(gap_s(random));
  }
}

// The samples of one regime: pooled, and per round.
struct Regime {
  std::vector<double> raw_ms;
  std::vector<double> hub_ms;
  std::vector<double> ratio_p50;  // one per round
  std::vector<double> ratio_p99;
  nlohmann::ordered_json rounds = nlohmann::ordered_json::array();
  std::size_t hub_with_heartbeat = 0;
  std::vector<double> hub_without_heartbeat_ms;

  // The hub's round trips that found it publishing a heartbeat (another State came first).
  void add_heartbeats(const Side& hub) {
    hub_with_heartbeat += hub.with_heartbeat;
    hub_without_heartbeat_ms.insert(hub_without_heartbeat_ms.end(), hub.without_heartbeat_ms.begin(),
                                    hub.without_heartbeat_ms.end());
  }

  // Adds one round's samples of both sides.
  void add_round(const std::vector<double>& raw, const std::vector<double>& hub) {
    const auto r = summary_of(raw);
    const auto h = summary_of(hub);
    const double p50 = r.p50 > 0 ? h.p50 / r.p50 : 0.0;
    const double p99 = r.p99 > 0 ? h.p99 / r.p99 : 0.0;
    ratio_p50.push_back(p50);
    ratio_p99.push_back(p99);
    rounds.push_back({{"n", std::min(raw.size(), hub.size())},
                      {"raw_p50", r.p50},
                      {"raw_p99", r.p99},
                      {"hub_p50", h.p50},
                      {"hub_p99", h.p99},
                      {"ratio_p50", p50},
                      {"ratio_p99", p99}});
    raw_ms.insert(raw_ms.end(), raw.begin(), raw.end());
    hub_ms.insert(hub_ms.end(), hub.begin(), hub.end());
  }

  // The aims are judged on ratio_p50 / ratio_p99: the median of the rounds' ratios (each round
  // measured both sides under the same load); pooled_ratio_* are the ratios of the pooled
  // percentiles, for comparison with earlier runs.
  nlohmann::ordered_json json() const {
    const auto raw_s = summary_of(raw_ms);
    const auto hub_s = summary_of(hub_ms);
    nlohmann::ordered_json j;
    j["raw_ms"] = summary_json(raw_ms);
    j["hub_ms"] = summary_json(hub_ms);
    j["ratio_p50"] = median_of(ratio_p50);
    j["ratio_p99"] = median_of(ratio_p99);
    j["ratio_p50_spread"] = {*std::min_element(ratio_p50.begin(), ratio_p50.end()),
                             *std::max_element(ratio_p50.begin(), ratio_p50.end())};
    j["ratio_p99_spread"] = {*std::min_element(ratio_p99.begin(), ratio_p99.end()),
                             *std::max_element(ratio_p99.begin(), ratio_p99.end())};
    j["pooled_ratio_p50"] = raw_s.p50 > 0 ? hub_s.p50 / raw_s.p50 : 0.0;
    j["pooled_ratio_p99"] = raw_s.p99 > 0 ? hub_s.p99 / raw_s.p99 : 0.0;
    j["rounds"] = rounds;
    j["hub_with_heartbeat_between"] = hub_with_heartbeat;
    j["hub_without_heartbeat_ms"] = summary_json(hub_without_heartbeat_ms);
    progress(fmt::format(
        "  pooled: raw p50 {:.3f} ms p99 {:.3f} ms; hub p50 {:.3f} ms p99 {:.3f} ms; median of {} rounds' "
        "ratios: p50 {:.2f}x ({:.2f}-{:.2f}), p99 {:.2f}x ({:.2f}-{:.2f})",
        raw_s.p50, raw_s.p99, hub_s.p50, hub_s.p99, ratio_p50.size(), j["ratio_p50"].get<double>(),
        j["ratio_p50_spread"][0].get<double>(), j["ratio_p50_spread"][1].get<double>(),
        j["ratio_p99"].get<double>(), j["ratio_p99_spread"][0].get<double>(),
        j["ratio_p99_spread"][1].get<double>()));
    return j;
  }
};

struct Options {
  std::string out = "echo.json";
  std::size_t back_to_back = 3000;
  std::size_t sparse = 600;
  std::size_t rounds = 6;
  double hub_rate = 100;
  bool pin = true;
};

int run(const Options& o) {
  auto domain = join_private_domain();
  if (!domain) return fmt::print(stderr, "{}\n", domain.error().message), 1;
  auto sides =
      open_echo_sides(domain->domain_id(), {"--hub", "dock_ecu", "--rate", fmt::format("{}", o.hub_rate)});
  if (!sides) return fmt::print(stderr, "{}\n", sides.error().message), 1;
  const std::size_t burst = runtime::kDefaultImmediateStateBurst;
  const double refill_s = immediate_state_refill_s();
  std::size_t raw_lost = 0;
  std::size_t hub_lost = 0;
  // The same CPU for both answering processes, every thread of each; the planner on the others.
  nlohmann::ordered_json pinning;
  const int cpus = static_cast<int>(std::thread::hardware_concurrency());
  if (o.pin && cpus >= 2) {
    const cpu_set_t peers = cpu_set_of(cpus - 1, cpus - 1);
    const cpu_set_t planner = cpu_set_of(0, cpus - 2);
    pinning["peers_cpu"] = cpus - 1;
    pinning["planner_cpus"] = cpus == 2 ? std::string("0") : fmt::format("0-{}", cpus - 2);
    pinning["raw_threads"] = pin_process(sides->pong.pid(), peers);
    pinning["hub_threads"] = pin_process(sides->hub.pid(), peers);
    pinning["planner_threads"] = pin_process(getpid(), planner);
  } else {
    pinning["peers_cpu"] = nullptr;
  }
  run_block(sides->raw_peer, 50, false, refill_s);  // warm-up: discovery settles, caches fill
  run_block(sides->hub_peer, 50, false, refill_s);
  const std::size_t rounds = std::max<std::size_t>(o.rounds, 1);
  Regime back_to_back_regime;
  Regime sparse_regime;
  progress(fmt::format(
      "echo latency, back to back: {} round trips per side in bursts of {} (hub at {} Hz), {} rounds",
      o.back_to_back, burst, o.hub_rate, rounds));
  for (std::size_t r = 0; r < rounds; ++r) {
    Side raw(&sides->raw_peer);
    Side hub_side(&sides->hub_peer);
    run_back_to_back(raw, hub_side, std::max<std::size_t>(o.back_to_back / rounds, 1), burst, refill_s);
    back_to_back_regime.add_round(raw.back_to_back_ms, hub_side.back_to_back_ms);
    back_to_back_regime.add_heartbeats(hub_side);
    raw_lost += raw.lost;
    hub_lost += hub_side.lost;
  }
  const auto back_to_back = back_to_back_regime.json();
  progress(fmt::format("echo latency, sparse: {} commands per side, 20-120 ms apart, {} rounds", o.sparse,
                       rounds));
  for (std::size_t r = 0; r < rounds; ++r) {
    Side raw(&sides->raw_peer);
    Side hub_side(&sides->hub_peer);
    run_sparse(raw, hub_side, std::max<std::size_t>(o.sparse / rounds, 1), static_cast<unsigned>(16 + r));
    sparse_regime.add_round(raw.sparse_ms, hub_side.sparse_ms);
    sparse_regime.add_heartbeats(hub_side);
    raw_lost += raw.lost;
    hub_lost += hub_side.lost;
  }
  const auto sparse = sparse_regime.json();
  dds_delete(sides->participant);
  stop(sides->hub);
  stop(sides->pong);

  nlohmann::ordered_json result;
  result["payload"] = "DockCommand (3 strings) out, DockState (header, name, echo, 4 slots) back";
  result["qos"] = "reliable, volatile, keep-last 10, XCDR1, loopback";
  result["hub_rate_hz"] = o.hub_rate;
  result["burst"] = burst;
  result["refill_ms"] = refill_s * 1e3;
  result["rounds"] = rounds;
  result["pinning"] = pinning;
  result["raw_lost"] = raw_lost;
  result["hub_lost"] = hub_lost;
  result["back_to_back"] = back_to_back;
  result["sparse"] = sparse;
  if (auto ok = write_json(o.out, result); !ok) return fmt::print(stderr, "{}\n", ok.error().message), 1;
  return 0;
}

}  // namespace
}  // namespace hubrt::bench

int main(int argc, char** argv) {
  CLI::App app{"Command -> echo latency: hub vs raw Cyclone pong, back to back and sparse (20-120 ms)"};
  hubrt::bench::Options o;
  app.add_option("--out", o.out, "Result file (JSON)");
  app.add_option("--back-to-back", o.back_to_back, "Recorded back-to-back round trips per side");
  app.add_option("--sparse", o.sparse, "Commands per side 20-120 ms apart");
  app.add_option("--hub-rate", o.hub_rate, "The hub's cycle rate in Hz");
  app.add_option("--rounds", o.rounds,
                 "Rounds per regime, each measuring both sides interleaved; ratios are the median of the "
                 "rounds'");
  app.add_flag("--pin,!--no-pin", o.pin,
               "Pin both answering processes to the last CPU and the planner to the others (default on)");
  CLI11_PARSE(app, argc, argv);
  return hubrt::bench::run(o);
}
