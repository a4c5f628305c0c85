#include "echo_setup.h"

#include <fmt/format.h>

#include "hubrt/runtime/immediate_state_budget.h"

#include "bench_common.h"
#include "raw_dds.h"

namespace hubrt::bench {

Expected<EchoSides> open_echo_sides(std::uint32_t domain, const std::vector<std::string>& hub_args) {
  auto pong = start_raw_peer({"pong"});
  if (!pong) return std::move(pong).error();
  auto hub = start_hubd(hub_args);
  if (!hub) return std::move(hub).error();
  auto participant = raw_participant(domain);
  if (!participant) return std::move(participant).error();
  auto raw_peer = open_peer(*participant, "raw ping-pong", "rt/bench/ping", "rt/bench/pong");
  if (!raw_peer) return std::move(raw_peer).error();
  auto hub_peer = open_peer(*participant, "hub", "rt/dock/command", "rt/dock_ecu/dock/state");
  if (!hub_peer) {
    return make_error(hub_peer.error().code,
                      fmt::format("{}\n{}", hub_peer.error().message, hub->stderr_text()));
  }
  return EchoSides{std::move(*pong), std::move(*hub), *participant, std::move(*raw_peer),
                   std::move(*hub_peer)};
}

double immediate_state_refill_s() {
  return to_seconds(runtime::kDefaultImmediateStateBurst * runtime::kDefaultImmediateStateInterval) + 0.002;
}

}  // namespace hubrt::bench
