// The hub-oriented layout (paper §5.4, Fig. 3a): one command topic and one State topic per hub.
// A distributor splits the hub command into the node commands; a collector assembles the node
// States into the hub State. Generic over any hub type whose hub-level types follow the
// convention, checked through reflection when the hub is built:
//
//   <Hub>Command_ { target_type; target_name; action;  <NodeCommand> <node name>; ... }
//   <Hub>State_   { header; name; echo; fresh_msg; t_plus; got_reset; error_list;  <NodeState> <node name>;
//   ... }
//
// The hub-level command has its own common semantics (echo, fresh_msg, watchdog) with actions
// "apply" and "reset"; each node fragment is then handled by its node exactly as in the
// node-type layout — validated, echoed, watched. A fragment whose target_type or target_name is
// empty is addressed to that node; a non-empty one must name it (else it is rejected).
#pragma once

#include <array>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "hubrt/hub_api/black_box_streams.h"
#include "hubrt/hub_api/dds_ports.h"
#include "hubrt/hub_api/hub_type.h"
#include "hubrt/hub_api/node_wiring.h"
#include "hubrt/hub_api/topic_names.h"
#include "hubrt/msgs/type_info.h"
#include "hubrt/runtime/node.h"

namespace hubrt::hub_api {

// Hands one fragment per step to a node, with the source timestamp of the hub command it came
// from and the hub's wall clock at that command's take: the node judges its age as the hub-level
// node judged the hub command's.
template <class Command>
class MailboxSource final : public runtime::CommandSource<Command> {
 public:
  void post(const Command& fragment, const runtime::CommandTimes& times) noexcept {
    pending_ = fragment;
    source_time_ = times.source;
    take_wall_ = times.take_wall;
    has_pending_ = true;
  }
  Result<runtime::ReceivedCommand<Command>> next() noexcept override {
    if (!has_pending_) return runtime::ReceivedCommand<Command>{};
    has_pending_ = false;
    return runtime::ReceivedCommand<Command>{&pending_, source_time_, take_wall_};
  }

 private:
  Command pending_{};
  std::optional<WallTime> source_time_;
  std::optional<WallTime> take_wall_;
  bool has_pending_ = false;
};

// A node's State goes nowhere on its own: the collector copies it into the hub State.
template <class State>
class CollectedSink final : public runtime::StateSink<State> {
 public:
  Status publish(const State& /*state*/) noexcept override { return Status::ok(); }
};

namespace detail {

// Where one node's fragment and State live inside the hub-level types.
class Route {
 public:
  virtual ~Route() = default;
  // Posts the node's fragment of `hub_command`, with the hub command's times, to the node.
  virtual void distribute(const void* hub_command, const runtime::CommandTimes& times) noexcept = 0;
  // Copies the node's State into its field of `hub_state` (pointers keep pointing into the node).
  virtual void collect(void* hub_state) const noexcept = 0;
};

template <runtime::NodeLogic Logic>
class NodeRoute final : public Route {
 public:
  using Command = msgs::typed::wire_t<typename Logic::Command>;
  using State = msgs::typed::wire_t<typename Logic::State>;
  NodeRoute(std::size_t command_offset, std::size_t state_offset, std::string node_name)
      : command_offset_(command_offset), state_offset_(state_offset), node_name_(std::move(node_name)) {}

  void attach(const runtime::Node<Logic>& node) noexcept { node_ = &node; }
  MailboxSource<Command>& source() noexcept { return source_; }
  CollectedSink<State>& sink() noexcept { return sink_; }

  void distribute(const void* hub_command, const runtime::CommandTimes& times) noexcept override {
    Command fragment{};
    std::memcpy(&fragment, static_cast<const std::byte*>(hub_command) + command_offset_, sizeof fragment);
    if (msgs::typed::view(fragment.target_type).empty()) msgs::typed::assign(fragment.target_type, type_);
    if (msgs::typed::view(fragment.target_name).empty())
      msgs::typed::assign(fragment.target_name, node_name_);
    source_.post(fragment, times);
  }
  void collect(void* hub_state) const noexcept override {
    std::memcpy(static_cast<std::byte*>(hub_state) + state_offset_, &node_->state().wire(), sizeof(State));
  }

 private:
  std::size_t command_offset_;
  std::size_t state_offset_;
  std::string node_name_;
  std::string type_{Logic::kType};
  const runtime::Node<Logic>* node_ = nullptr;
  MailboxSource<Command> source_;
  CollectedSink<State> sink_;
};

// The hub-level command's own logic: distribute while a hub command is in force, collect always.
template <class HubTypes>
class HubLevelLogic {
 public:
  using Command = typename HubTypes::Command;
  using State = typename HubTypes::State;
  static constexpr std::string_view kType = HubTypes::kType;
  static constexpr std::array<std::string_view, 2> kActions{"apply", "reset"};

  explicit HubLevelLogic(std::vector<std::unique_ptr<Route>>& routes) : routes_(&routes) {}

  // The hub-level node's tracker and its last valid command's times: fragments go out only in
  // steps where a hub command arrived, with its source timestamp and the time of its take.
  void watch(const runtime::CommandTracker& tracker, const runtime::CommandTimes& last_valid) noexcept {
    tracker_ = &tracker;
    last_valid_ = &last_valid;
  }

  bool validate(const Command& /*command*/, runtime::Problem& /*problem*/) const noexcept { return true; }
  void read_inputs(Time /*now*/) noexcept {}
  // The hub-level command has no devices and latches nothing: safe or operational by its command.
  runtime::NodeCondition condition() const noexcept { return runtime::NodeCondition::kOk; }
  // A fragment is posted when a hub command arrives (new or repeated), not every cycle, so each
  // node's watchdog is fed exactly when the hub's is and trips in the same cycle: re-posting the
  // last fragment every cycle would keep a node commanded one timeout longer than its hub.
  void update(const Command* in_force, Time now) noexcept {
    if (in_force == nullptr) return;
    if (tracker_ != nullptr && tracker_->last_taken() != now) return;
    static constexpr runtime::CommandTimes kUnknown{};
    const runtime::CommandTimes& times = last_valid_ != nullptr ? *last_valid_ : kUnknown;
    for (const auto& route : *routes_) route->distribute(&in_force->wire(), times);
  }
  void reset() noexcept {}
  void report(State& state, runtime::ErrorList& /*errors*/, Time /*now*/) noexcept {
    for (const auto& route : *routes_) route->collect(&state.wire());
  }
  void enter_safe_state() noexcept {}

 private:
  std::vector<std::unique_ptr<Route>>* routes_;
  const runtime::CommandTracker* tracker_ = nullptr;
  const runtime::CommandTimes* last_valid_ = nullptr;
};

// The distributor before the nodes, the collector after them; owns the hub-level DDS entities.
template <class HubTypes>
class HubLayoutStage final : public runtime::CycleStage {
 public:
  using HubCommand = msgs::typed::wire_t<typename HubTypes::Command>;
  using HubState = msgs::typed::wire_t<typename HubTypes::State>;

  HubLayoutStage(dds::Topic<HubCommand> command_topic, dds::Topic<HubState> state_topic,
                 DdsCommandSource<HubCommand> source, DdsStateSink<HubState> sink)
      : command_topic_(std::move(command_topic)),
        state_topic_(std::move(state_topic)),
        source_(std::move(source)),
        sink_(std::move(sink)) {}

  void start(runtime::NodeOptions options) {
    node_ = std::make_unique<runtime::Node<HubLevelLogic<HubTypes>>>(
        std::move(options), HubLevelLogic<HubTypes>(routes_), source_, sink_, message_ops<HubCommand>());
    node_->logic().watch(node_->tracker(), node_->last_valid_command());
  }
  // The hub State's error_list carries the hub-wide alerts too (call after start()).
  void watch_alerts(const runtime::HubAlerts& alerts) noexcept { node_->watch_alerts(&alerts); }
  std::vector<std::unique_ptr<Route>>& routes() noexcept { return routes_; }
  [[nodiscard]] const runtime::Node<HubLevelLogic<HubTypes>>& hub_node() const noexcept { return *node_; }

  void before_nodes(const Instant& now) noexcept override { took_effect_ = node_->advance(now); }
  void note_late(const Instant& now, Duration late, Time discard_until) noexcept override {
    node_->note_late(now, late, discard_until);
  }
  void after_nodes(const Instant& now, bool publish_all, bool nodes_took_effect) noexcept override {
    node_->rebuild_state(now.mono);
    // The hub State is what goes on the wire, so the budget of immediate States applies to it.
    if (publish_all) {
      node_->publish(now).ignore();
    } else {
      node_->publish_if_due(now, took_effect_ || nodes_took_effect).ignore();
    }
  }
  [[nodiscard]] std::uint64_t states_deferred() const noexcept override { return node_->states_deferred(); }
  [[nodiscard]] const runtime::NodeBase* hub_level_node() const noexcept override { return node_.get(); }

 private:
  dds::Topic<HubCommand> command_topic_;
  dds::Topic<HubState> state_topic_;
  DdsCommandSource<HubCommand> source_;
  DdsStateSink<HubState> sink_;
  std::vector<std::unique_ptr<Route>> routes_;
  std::unique_ptr<runtime::Node<HubLevelLogic<HubTypes>>> node_;
  bool took_effect_ = false;
};

// The offset of field `name` of `outer` when it is a struct of type `inner`.
Expected<std::size_t> struct_field_offset(const msgs::TypeInfo& outer, std::string_view name,
                                          const msgs::TypeInfo& inner, std::string_view hub_file);

}  // namespace detail

// Adds nodes to a hub with the layout its configuration asks for. HubTypes names the hub-level
// types: `using Command = <Hub>CommandView; using State = <Hub>State; static constexpr
// std::string_view kType = "...";` (the generated typed classes; <idl>_typed.h registers the topics).
template <class HubTypes>
class NodeWiring {
 public:
  using HubCommand = msgs::typed::wire_t<typename HubTypes::Command>;
  using HubState = msgs::typed::wire_t<typename HubTypes::State>;

  // What add() checks of node `node` in the configuration alone (hub layout: the hub-level
  // messages have a field `node.name` of Logic's types), without DDS (`hubd --check`).
  // Errors: as add().
  template <runtime::NodeLogic Logic>
  static Expected<void> check(const config::HubConfig& config, const config::NodeConfig& node) {
    if (config.layout != config::Layout::kHub) return {};
    auto command_offset = detail::struct_field_offset(
        msgs::type_info_of<HubCommand>(), node.name,
        msgs::type_info_of<msgs::typed::wire_t<typename Logic::Command>>(), config.file);
    if (!command_offset) return std::move(command_offset).error();
    auto state_offset = detail::struct_field_offset(
        msgs::type_info_of<HubState>(), node.name,
        msgs::type_info_of<msgs::typed::wire_t<typename Logic::State>>(), config.file);
    if (!state_offset) return std::move(state_offset).error();
    return {};
  }

  // Errors: the hub-level DDS entities (hub layout only).
  static Expected<NodeWiring> create(const HubContext& context, runtime::Hub& hub) {
    NodeWiring wiring(context, hub);
    if (context.config.layout != config::Layout::kHub) return wiring;
    const auto& ns = context.config.ros_namespace;
    const runtime::Waker waker = context.waker;
    auto command_topic =
        dds::Topic<HubCommand>::create(context.participant, hub_command_topic(ns, context.config.name));
    if (!command_topic) return std::move(command_topic).error();
    auto reader = dds::Reader<HubCommand>::create(context.participant, *command_topic,
                                                  dds::Qos::ros2_default(kCommandHistoryDepth),
                                                  [waker] { waker.wake(); });
    if (!reader) return std::move(reader).error();
    auto state_topic =
        dds::Topic<HubState>::create(context.participant, hub_state_topic(ns, context.config.name));
    if (!state_topic) return std::move(state_topic).error();
    // A new reader of the hub State wakes the cycle, which publishes it at once (Node::publish_if_due).
    auto writer = dds::Writer<HubState>::create(context.participant, *state_topic, dds::Qos::ros2_default(),
                                                [waker] { waker.wake(); });
    if (!writer) return std::move(writer).error();
    reader->set_sample_hook(black_box_stream(context.black_box, hub_command_topic(ns, context.config.name),
                                             msgs::type_info_of<HubCommand>(),
                                             dds::Qos::ros2_default(kCommandHistoryDepth), true));
    writer->set_sample_hook(black_box_stream(context.black_box, hub_state_topic(ns, context.config.name),
                                             msgs::type_info_of<HubState>(), dds::Qos::ros2_default(),
                                             false));
    wiring.stage_ = std::make_unique<detail::HubLayoutStage<HubTypes>>(
        std::move(*command_topic), std::move(*state_topic),
        DdsCommandSource<HubCommand>(std::move(*reader), context.clock),
        DdsStateSink<HubState>(std::move(*writer)));
    return wiring;
  }

  // Adds one node. Hub layout: node.name must be a field of the hub command (of the node's
  // Command type) and of the hub State (of its State type). Errors name the hub file.
  template <runtime::NodeLogic Logic>
  Expected<void> add(const config::NodeConfig& node, Logic logic) {
    if (stage_ == nullptr) return add_node_type_oriented(context_, hub_, node, std::move(logic));
    const auto& file = context_.config.file;
    auto command_offset =
        detail::struct_field_offset(msgs::type_info_of<HubCommand>(), node.name,
                                    msgs::type_info_of<msgs::typed::wire_t<typename Logic::Command>>(), file);
    if (!command_offset) return std::move(command_offset).error();
    auto state_offset =
        detail::struct_field_offset(msgs::type_info_of<HubState>(), node.name,
                                    msgs::type_info_of<msgs::typed::wire_t<typename Logic::State>>(), file);
    if (!state_offset) return std::move(state_offset).error();
    auto route = std::make_unique<detail::NodeRoute<Logic>>(*command_offset, *state_offset, node.name);
    runtime::NodeOptions options;
    options.name = node.name;
    options.command_timeout = context_.config.command_timeout;
    options.clock_tolerance = context_.config.clock_tolerance;
    options.addressing = runtime::Addressing::kRejectOthers;
    // Its State only goes into the hub State, whose own budget bounds what goes on the wire; a
    // budget here would only keep the embedded header from being restamped.
    options.immediate_state_interval = Duration::zero();
    options.log = context_.log;
    auto added = std::make_unique<runtime::Node<Logic>>(
        std::move(options), std::move(logic), route->source(), route->sink(),
        message_ops<msgs::typed::wire_t<typename Logic::Command>>());
    route->attach(*added);
    stage_->routes().push_back(std::move(route));
    hub_.add_node(std::move(added));
    return {};
  }

  // Hub layout: installs the distributor and collector. Call once, after the last add().
  Expected<void> finish() {
    if (stage_ == nullptr) return {};
    runtime::NodeOptions options;
    options.name = context_.config.name;
    options.command_timeout = context_.config.command_timeout;
    options.clock_tolerance = context_.config.clock_tolerance;
    options.addressing = runtime::Addressing::kRejectOthers;  // the topic is this hub's own
    options.immediate_state_interval = context_.config.immediate_state_interval;
    options.log = context_.log;
    stage_->start(std::move(options));
    stage_->watch_alerts(hub_.alerts());
    hub_.add_stage(std::move(stage_));
    return {};
  }

 private:
  NodeWiring(const HubContext& context, runtime::Hub& hub) : context_(context), hub_(hub) {}

  const HubContext& context_;
  runtime::Hub& hub_;
  std::unique_ptr<detail::HubLayoutStage<HubTypes>> stage_;
};

}  // namespace hubrt::hub_api
