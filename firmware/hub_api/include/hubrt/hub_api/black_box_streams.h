// A hub's topics in its black box (hubrt/blackbox/black_box.h): the command readers and State
// writers a hub type makes show their samples to it, when the hub has one (HubContext::black_box).
#pragma once

#include <string>

#include "hubrt/dds/qos.h"
#include "hubrt/dds/sample_hook.h"
#include "hubrt/msgs/type_info.h"

namespace hubrt::blackbox {
class BlackBox;
}

namespace hubrt::hub_api {

// Adds `ros_topic` of `type` to `box` (schema: its ros2msg text; the QoS `offered` by the hub's own
// endpoint) and returns the hook to set on the reader (`received`: commands) or writer; nullptr
// when `box` is null or the program has no .msg definition of the type (then the topic is not
// recorded). Before the black box is sealed; not thread-safe.
dds::SampleHook* black_box_stream(blackbox::BlackBox* box, const std::string& ros_topic,
                                  const msgs::TypeInfo& type, const dds::Qos& offered, bool received);

}  // namespace hubrt::hub_api
