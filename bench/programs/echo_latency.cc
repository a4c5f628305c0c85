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
// Back to back within the hub's budget of immediate States (runtime/immediate_state_budget.h, a
// token bucket of kDefaultImmediateStateBurst refilled one per immediate_state_interval_ms): a
// planner answering every echo at once without a pause is a flood by the wire contract and gets
// its States at the refill rate. So the back-to-back regime sends bursts of `burst` commands, each
// right after the echo of the one before, and pauses for the bucket to refill; the first command
// of a burst comes after a pause (that is the sparse regime's case) and is not recorded.
#include <algorithm>
#include <chrono>
#include <random>
#include <thread>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "hubrt/runtime/immediate_state_budget.h"

#include "bench_common.h"
#include "echo_peer.h"
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
  std::size_t lost = 0;

  // One round trip; recorded into `into` unless null.
  void round_trip_into(std::vector<double>* into) {
    const double rtt = round_trip(*peer, sent++ % 2 == 0 ? "monitor" : "reset");
    if (rtt < 0) {
      ++lost;
    } else if (into != nullptr) {
      into->push_back(rtt * 1e3);
    }
  }
};

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
// run draws the same gaps).
void run_sparse(Side& raw, Side& hub, std::size_t commands) {
  std::mt19937 random(16);
  std::uniform_real_distribution<double> gap_s(0.020, 0.120);
  for (std::size_t i = 0; i < commands; ++i) {
    Side* order[2] = {&raw, &hub};
    if (i % 2 == 1) std::swap(order[0], order[1]);
    for (Side* side : order) side->round_trip_into(&side->sparse_ms);
    pause_s(gap_s(random));
  }
}

nlohmann::ordered_json regime_json(const std::vector<double>& raw_ms, const std::vector<double>& hub_ms) {
  const auto raw_s = summary_of(raw_ms);
  const auto hub_s = summary_of(hub_ms);
  nlohmann::ordered_json j;
  j["raw_ms"] = summary_json(raw_ms);
  j["hub_ms"] = summary_json(hub_ms);
  j["ratio_p50"] = raw_s.p50 > 0 ? hub_s.p50 / raw_s.p50 : 0.0;
  j["ratio_p99"] = raw_s.p99 > 0 ? hub_s.p99 / raw_s.p99 : 0.0;
  progress(fmt::format(
      "  raw p50 {:.3f} ms p99 {:.3f} ms; hub p50 {:.3f} ms p99 {:.3f} ms: {:.2f}x / {:.2f}x", raw_s.p50,
      raw_s.p99, hub_s.p50, hub_s.p99, j["ratio_p50"].get<double>(), j["ratio_p99"].get<double>()));
  return j;
}

struct Options {
  std::string out = "echo.json";
  std::size_t back_to_back = 1500;
  std::size_t sparse = 600;
  double hub_rate = 100;
};

int run(const Options& o) {
  auto domain = join_private_domain();
  if (!domain) return fmt::print(stderr, "{}\n", domain.error().message), 1;
  auto pong = start_raw_peer({"pong"});
  if (!pong) return fmt::print(stderr, "{}\n", pong.error().message), 1;
  auto hub = start_hubd({"--hub", "dock_ecu", "--rate", fmt::format("{}", o.hub_rate)});
  if (!hub) return fmt::print(stderr, "{}\n", hub.error().message), 1;
  auto participant = raw_participant(domain->domain_id());
  if (!participant) return fmt::print(stderr, "{}\n", participant.error().message), 1;
  auto raw_peer = open_peer(*participant, "raw ping-pong", "rt/bench/ping", "rt/bench/pong");
  if (!raw_peer) return fmt::print(stderr, "{}\n", raw_peer.error().message), 1;
  auto hub_peer = open_peer(*participant, "hub", "rt/dock/command", "rt/dock_ecu/dock/state");
  if (!hub_peer) return fmt::print(stderr, "{}\n{}\n", hub_peer.error().message, hub->stderr_text()), 1;

  const std::size_t burst = runtime::kDefaultImmediateStateBurst;
  // The bucket refills `burst` tokens in burst x interval; 2 ms more for the hub's wake-up.
  const double refill_s = to_seconds(burst * runtime::kDefaultImmediateStateInterval) + 0.002;
  run_block(*raw_peer, 50, false, refill_s);  // warm-up: discovery settles, caches fill
  run_block(*hub_peer, 50, false, refill_s);
  Side raw(&*raw_peer);
  Side hub_side(&*hub_peer);
  progress(fmt::format("echo latency, back to back: {} round trips per side in bursts of {} (hub at {} Hz)",
                       o.back_to_back, burst, o.hub_rate));
  run_back_to_back(raw, hub_side, o.back_to_back, burst, refill_s);
  const auto back_to_back = regime_json(raw.back_to_back_ms, hub_side.back_to_back_ms);
  progress(fmt::format("echo latency, sparse: {} commands per side, 20-120 ms apart", o.sparse));
  run_sparse(raw, hub_side, o.sparse);
  const auto sparse = regime_json(raw.sparse_ms, hub_side.sparse_ms);
  dds_delete(*participant);
  stop(*hub);
  stop(*pong);

  nlohmann::ordered_json result;
  result["payload"] = "DockCommand (3 strings) out, DockState (header, name, echo, 4 slots) back";
  result["qos"] = "reliable, volatile, keep-last 10, XCDR1, loopback";
  result["hub_rate_hz"] = o.hub_rate;
  result["burst"] = burst;
  result["refill_ms"] = refill_s * 1e3;
  result["raw_lost"] = raw.lost;
  result["hub_lost"] = hub_side.lost;
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
  CLI11_PARSE(app, argc, argv);
  return hubrt::bench::run(o);
}
