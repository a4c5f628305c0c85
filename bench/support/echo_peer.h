// One planner-side peer of a command -> echo round trip over the Cyclone C API: a DockCommand
// writer, a DockState reader and a waitset; used by the echo latency benchmark and by the DDS
// Security one (the same round trip to a secured and an unsecured hub).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <dds/dds.h>

#include "hubrt/base/status.h"

namespace hubrt::bench {

struct Peer {
  std::string name;
  dds_entity_t writer = 0;
  dds_entity_t reader = 0;
  dds_entity_t waitset = 0;
  std::vector<double> latencies_ms;
  std::size_t lost = 0;
};

// One command out, until the State echoing its action is back: seconds, or -1 if none within a
// second. `other_state_between`, when given, says whether another State (a hub's heartbeat, still
// echoing the command before) arrived in between: the hub was publishing it when the command came.
// `sent_at`, when given, gets the moment the command was written (mono_now(), CLOCK_MONOTONIC).
double round_trip(const Peer& peer, const char* action, bool* other_state_between = nullptr,
                  double* sent_at = nullptr);

// Writer on `command_topic`, reader on `state_topic` (DDS names), waiting up to 20 s for a reader
// of the commands. Errors: Cyclone's refusal, or nobody reading (kTimeout).
Expected<Peer> open_peer(dds_entity_t participant, std::string name, const std::string& command_topic,
                         const std::string& state_topic);

// `samples` round trips alternating two actions (each takes effect, so each is answered at once);
// recorded into latencies_ms when `record`, lost ones counted. `gap_s`: a pause after each round
// trip (a hub's immediate States come from a token bucket of 4 refilled one per
// immediate_state_interval, 10 ms by default: more commands back to back than that measure the
// budget rather than the path).
void run_block(Peer& peer, std::size_t samples, bool record, double gap_s = 0.0);

}  // namespace hubrt::bench
