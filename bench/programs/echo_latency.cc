// Command -> echo latency of a hub, side by side with a raw Cyclone ping-pong of the same payload.
//
// Both peers are separate processes on loopback: hubd (Dock ECU, fake backend) and
// hubrt_bench_raw_peer pong (the C API, same types, same QoS). This process is the planner for both,
// also on the C API: it writes a DockCommand and waits (waitset) for the DockState echoing it.
// Commands alternate between two actions so that each one takes effect on the hub and is answered
// at once. Blocks of both sides alternate, so machine noise hits both alike.
#include <cstring>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "hubrt/msgs/typed.h"

#include "bench_common.h"
#include "dock.h"
#include "echo_peer.h"
#include "raw_dds.h"

namespace hubrt::bench {
namespace {

int run(const std::string& out, std::size_t rounds, std::size_t per_block, double hub_rate) {
  auto domain = join_private_domain();
  if (!domain) return fmt::print(stderr, "{}\n", domain.error().message), 1;
  auto pong = start_raw_peer({"pong"});
  if (!pong) return fmt::print(stderr, "{}\n", pong.error().message), 1;
  auto hub = start_hubd({"--hub", "dock_ecu", "--rate", fmt::format("{}", hub_rate)});
  if (!hub) return fmt::print(stderr, "{}\n", hub.error().message), 1;
  auto participant = raw_participant(domain->domain_id());
  if (!participant) return fmt::print(stderr, "{}\n", participant.error().message), 1;
  auto raw = open_peer(*participant, "raw ping-pong", "rt/bench/ping", "rt/bench/pong");
  if (!raw) return fmt::print(stderr, "{}\n", raw.error().message), 1;
  auto hub_peer = open_peer(*participant, "hub", "rt/dock/command", "rt/dock_ecu/dock/state");
  if (!hub_peer) return fmt::print(stderr, "{}\n{}\n", hub_peer.error().message, hub->stderr_text()), 1;

  progress(fmt::format("echo latency: {} rounds of {} round trips per side (hub at {} Hz)", rounds, per_block,
                       hub_rate));
  run_block(*raw, 50, false);  // warm-up: discovery settles, caches fill
  run_block(*hub_peer, 50, false);
  for (std::size_t round = 0; round < rounds; ++round) {
    run_block(*raw, per_block, true);
    run_block(*hub_peer, per_block, true);
  }
  dds_delete(*participant);
  stop(*hub);
  stop(*pong);

  const auto raw_s = summary_of(raw->latencies_ms);
  const auto hub_s = summary_of(hub_peer->latencies_ms);
  nlohmann::ordered_json result;
  result["payload"] = "DockCommand (3 strings) out, DockState (header, name, echo, 4 slots) back";
  result["qos"] = "reliable, volatile, keep-last 10, XCDR1, loopback";
  result["hub_rate_hz"] = hub_rate;
  result["raw_ms"] = summary_json(raw->latencies_ms);
  result["hub_ms"] = summary_json(hub_peer->latencies_ms);
  result["raw_lost"] = raw->lost;
  result["hub_lost"] = hub_peer->lost;
  result["ratio_p50"] = raw_s.p50 > 0 ? hub_s.p50 / raw_s.p50 : 0.0;
  result["ratio_p99"] = raw_s.p99 > 0 ? hub_s.p99 / raw_s.p99 : 0.0;
  progress(fmt::format("echo latency: raw p50 {:.3f} ms p99 {:.3f} ms; hub p50 {:.3f} ms p99 {:.3f} ms",
                       raw_s.p50, raw_s.p99, hub_s.p50, hub_s.p99));
  if (auto ok = write_json(out, result); !ok) return fmt::print(stderr, "{}\n", ok.error().message), 1;
  return 0;
}

}  // namespace
}  // namespace hubrt::bench

int main(int argc, char** argv) {
  CLI::App app{"Command -> echo latency: hub vs raw Cyclone ping-pong"};
  std::string out = "echo.json";
  std::size_t rounds = 10;
  std::size_t per_block = 200;
  double hub_rate = 100;
  app.add_option("--out", out, "Result file (JSON)");
  app.add_option("--rounds", rounds, "Alternating blocks per side");
  app.add_option("--per-block", per_block, "Round trips per block");
  app.add_option("--hub-rate", hub_rate, "The hub's cycle rate in Hz");
  CLI11_PARSE(app, argc, argv);
  return hubrt::bench::run(out, rounds, per_block, hub_rate);
}
