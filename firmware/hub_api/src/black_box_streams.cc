#include "hubrt/hub_api/black_box_streams.h"

#include "hubrt/blackbox/black_box.h"
#include "hubrt/mcap/ros2_qos_yaml.h"
#include "hubrt/msgs/definitions.h"

namespace hubrt::hub_api {

dds::SampleHook* black_box_stream(blackbox::BlackBox* box, const std::string& ros_topic,
                                  const msgs::TypeInfo& type, const dds::Qos& offered, bool received) {
  if (box == nullptr) return nullptr;
  auto schema = msgs::ros2msg_schema(type.ros_name);
  if (!schema) return nullptr;
  blackbox::StreamSpec spec;
  spec.topic = ros_topic;
  spec.type_name = std::string(type.ros_name);
  spec.schema = std::move(*schema);
  // Commands: the hub's reader; the writers that sent them are the planner's. What is recorded is
  // the hub's side either way.
  spec.offered_qos_yaml = mcap::offered_qos_yaml({dds::read_offered_qos(offered.get())});
  spec.received = received;
  return &box->add_stream(std::move(spec));
}

}  // namespace hubrt::hub_api
