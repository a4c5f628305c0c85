// The QoS of every command writer hubctl makes — `send`, the scenarios and the recordings `play`
// replays, the conformance probes — in one place, so that a change to how hubctl commands (a
// lifespan, say) reaches all of them.
#pragma once

#include "hubrt/dds/qos.h"

namespace hubrt::hubctl {

// ROS 2's default profile (reliable, volatile, keep-last 10), as a planner's command publisher.
inline dds::Qos command_writer_qos() {
  return dds::Qos::ros2_default();
}

}  // namespace hubrt::hubctl
