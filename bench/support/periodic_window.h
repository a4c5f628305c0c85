// The periodic parts of a tails round (bench/programs/tails.cc): a window of States from two
// periodic publishers at once (the hub's heartbeat and the raw writer's), as a subscriber sees
// them, and a window of a bare clock_nanosleep loop in this process (no DDS at all: how late the
// host wakes a sleeper, the floor under every other figure of the round).
#pragma once

#include <string>
#include <vector>

#include <dds/dds.h>

#include "hubrt/base/status.h"

namespace hubrt::bench {

// |arrival interval - period| in ms of each stream's consecutive States.
struct JitterWindow {
  std::vector<double> first_ms;
  std::vector<double> second_ms;
};

// Subscribes to the DockStates on DDS topics `first` and `second` (the QoS of raw_dds.h), waits
// up to 10 s for both to arrive, drops `settle_s` of them, then records `window_s` of arrivals.
// Errors: Cyclone's refusal; kTimeout when either never arrives.
Expected<JitterWindow> jitter_window(dds_entity_t participant, const std::string& first,
                                     const std::string& second, double rate_hz, double settle_s,
                                     double window_s);

// A clock_nanosleep loop on absolute deadlines at `rate_hz` for `window_s`: how late each wake-up
// was, in ms.
std::vector<double> bare_loop_lateness_ms(double rate_hz, double window_s);

}  // namespace hubrt::bench
