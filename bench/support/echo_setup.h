// The two answering sides of the command -> echo benchmarks (echo_latency, tails), started and
// opened alike: the raw pong and hubd's Dock ECU as processes, and this process's planner peers of
// both on one raw participant.
#pragma once

#include <string>
#include <vector>

#include "hubrt/test_support/child_process.h"

#include "echo_peer.h"

namespace hubrt::bench {

struct EchoSides {
  test_support::ChildProcess pong;
  test_support::ChildProcess hub;
  dds_entity_t participant = 0;
  Peer raw_peer;
  Peer hub_peer;
};

// Starts `hubrt_bench_raw_peer pong` and hubd with `hub_args` (the Dock ECU's, e.g. "--hub",
// "dock_ecu", "--rate", "10") in `domain`, and opens a planner peer of each. Errors: what failed to
// start or open; hubd's stderr with its peer's failure.
Expected<EchoSides> open_echo_sides(std::uint32_t domain, const std::vector<std::string>& hub_args);

// The pause after a burst of immediate States for the hub's token bucket (runtime/
// immediate_state_budget.h) to refill: `burst` tokens take burst x interval; 2 ms more for the
// hub's wake-up.
double immediate_state_refill_s();

}  // namespace hubrt::bench
