// The QoS of every command writer hubctl makes — `send`, the scenarios and the recordings `play`
// replays, the conformance probes, the Foxglove clients' commands — in one place, so that a change
// to how hubctl commands reaches all of them.
#pragma once

#include <chrono>
#include <cstdint>

#include "hubrt/dds/qos.h"

namespace hubrt::hubctl {

// The LIFESPAN hubctl's command writers give their samples unless told otherwise (--lifespan-ms):
// the hub file's default command timeout (command_timeout_ms, 1000 ms), because a command older
// than its node's timeout can never act (runtime/command_age.h). For a hub configured with another
// timeout, pass its command_timeout_ms (every hub publishes it in /diagnostics). What LIFESPAN
// does and does not protect: dds::Qos::lifespan, docs/interop.md.
inline constexpr std::uint32_t kDefaultCommandLifespanMs = 1000;

// ROS 2's default profile (reliable, volatile, keep-last 10), as a planner's command publisher,
// with LIFESPAN `lifespan_ms` (0: none). Unregistering does not dispose, as rmw_cyclonedds makes
// every ROS 2 publisher (rmw_node.cpp, create_readwrite_qos): the writer can be announced
// (greet_readers), and its end leaves readers "no writers" where Cyclone's default leaves
// "disposed".
inline dds::Qos command_writer_qos(std::uint32_t lifespan_ms = kDefaultCommandLifespanMs) {
  dds::Qos qos = dds::Qos::ros2_default();
  qos.dispose_on_unregister(false);
  if (lifespan_ms > 0) qos.lifespan(std::chrono::milliseconds(lifespan_ms));
  return qos;
}

}  // namespace hubrt::hubctl
