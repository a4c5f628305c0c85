// Wiring one node into a hub for the node-type layout: its command topic (shared by every node
// of its type), its own State topic, and the Node that runs its logic.
#pragma once

#include <memory>

#include <fmt/format.h>

#include "hubrt/dds/topic.h"
#include "hubrt/hub_api/black_box_streams.h"
#include "hubrt/hub_api/dds_ports.h"
#include "hubrt/hub_api/hub_type.h"
#include "hubrt/hub_api/topic_names.h"
#include "hubrt/msgs/type_info.h"
#include "hubrt/msgs/typed.h"
#include "hubrt/runtime/node.h"
#include "hubrt/runtime/reflected_message_ops.h"

namespace hubrt::hub_api {

// Holds a node's DDS entities. Members are destroyed in reverse order: reader and writer go
// before the topics they use.
template <runtime::NodeLogic Logic>
struct NodeTypePorts {
  using Command = msgs::typed::wire_t<typename Logic::Command>;
  using State = msgs::typed::wire_t<typename Logic::State>;
  dds::Topic<Command> command_topic;
  dds::Topic<State> state_topic;
  DdsCommandSource<Command> source;
  DdsStateSink<State> sink;
};

// The MessageOps of a generated type, one per type for the program's life.
template <class T>
const runtime::MessageOps& message_ops() {
  static const runtime::ReflectedMessageOps ops(msgs::type_info_of<T>());
  return ops;
}

// Adds `logic` as node `node.name` with DDS ports of the node-type layout.
// Errors: the DDS entity that could not be created, naming the node and topic.
template <runtime::NodeLogic Logic>
Expected<void> add_node_type_oriented(const HubContext& context, runtime::Hub& hub,
                                      const config::NodeConfig& node, Logic logic) {
  using Command = msgs::typed::wire_t<typename Logic::Command>;
  using State = msgs::typed::wire_t<typename Logic::State>;
  const auto fail = [&](const Error& error) {
    return make_error(error.code, fmt::format("node '{}': {}", node.name, error.message));
  };
  const runtime::Waker waker = context.waker;
  auto command_topic = dds::Topic<Command>::create(
      context.participant, node_command_topic(context.config.ros_namespace, Logic::kType));
  if (!command_topic) return fail(command_topic.error());
  // The listener marks that a command arrived (the hub steps this node first) and wakes the cycle.
  auto arrived = std::make_shared<std::atomic<bool>>(true);
  auto reader = dds::Reader<Command>::create(context.participant, *command_topic,
                                             dds::Qos::ros2_default(kCommandHistoryDepth), [waker, arrived] {
                                               arrived->store(true, std::memory_order_release);
                                               waker.wake();
                                             });
  if (!reader) return fail(reader.error());
  auto state_topic = dds::Topic<State>::create(
      context.participant, node_state_topic(context.config.ros_namespace, context.config.name, node.name));
  if (!state_topic) return fail(state_topic.error());
  // A new reader of the State wakes the cycle, which publishes it at once (Node::publish_if_due):
  // a subscriber that was waiting for the hub gets a State as soon as discovery completes, not
  // one period later (the States written before that reached nobody).
  auto writer = dds::Writer<State>::create(context.participant, *state_topic, dds::Qos::ros2_default(),
                                           [waker] { waker.wake(); });
  if (!writer) return fail(writer.error());
  reader->set_sample_hook(
      black_box_stream(context.black_box, node_command_topic(context.config.ros_namespace, Logic::kType),
                       msgs::type_info_of<Command>(), dds::Qos::ros2_default(kCommandHistoryDepth), true));
  writer->set_sample_hook(black_box_stream(
      context.black_box, node_state_topic(context.config.ros_namespace, context.config.name, node.name),
      msgs::type_info_of<State>(), dds::Qos::ros2_default(), false));

  auto ports = std::make_shared<NodeTypePorts<Logic>>(
      NodeTypePorts<Logic>{std::move(*command_topic), std::move(*state_topic),
                           DdsCommandSource<Command>(std::move(*reader), context.clock, arrived),
                           DdsStateSink<State>(std::move(*writer))});
  runtime::NodeOptions options;
  options.name = node.name;
  options.command_timeout = context.config.command_timeout;
  options.clock_tolerance = context.config.clock_tolerance;
  options.addressing = runtime::Addressing::kIgnoreOthers;
  options.immediate_state_interval = context.config.immediate_state_interval;
  options.log = context.log;
  hub.add_node(std::make_unique<runtime::Node<Logic>>(std::move(options), std::move(logic), ports->source,
                                                      ports->sink, message_ops<Command>()));
  hub.keep_alive(std::move(ports));
  return {};
}

}  // namespace hubrt::hub_api
