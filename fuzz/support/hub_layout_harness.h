// Command validation in the hub layout from raw CDR: the hub-level command (<Hub>Command, one
// fragment per node) is deserialised by Cyclone, taken by the hub-level node, and its fragments
// are distributed to the nodes, each validated by its own node — the pieces hubrt::assembly's
// NodeWiring puts together for `layout: hub`, minus DDS. Stepped in the Hub's order: distributor,
// nodes, collector.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "hubrt/hub_api/hub_layout.h"

#include "node_harness.h"
#include "station_files.h"

namespace hubrt::fuzz {

template <class HubTypes>
class HubLayoutUnderFuzz {
 public:
  using HubCommand = msgs::typed::wire_t<typename HubTypes::Command>;
  using HubState = msgs::typed::wire_t<typename HubTypes::State>;

  // Adds node `name` (a field of the hub-level types) running `logic`, as NodeWiring::add does.
  template <runtime::NodeLogic Logic>
  void add(const std::string& name, Logic logic) {
    auto command_offset = hub_api::detail::struct_field_offset(
        msgs::type_info_of<HubCommand>(), name,
        msgs::type_info_of<msgs::typed::wire_t<typename Logic::Command>>(), "fuzz");
    if (!command_offset) setup_failed(command_offset.error().message);
    auto state_offset = hub_api::detail::struct_field_offset(
        msgs::type_info_of<HubState>(), name,
        msgs::type_info_of<msgs::typed::wire_t<typename Logic::State>>(), "fuzz");
    if (!state_offset) setup_failed(state_offset.error().message);
    auto route = std::make_unique<hub_api::detail::NodeRoute<Logic>>(*command_offset, *state_offset, name);
    auto node = std::make_unique<runtime::Node<Logic>>(
        options(name), std::move(logic), route->source(), route->sink(),
        ops_of<msgs::typed::wire_t<typename Logic::Command>>());
    route->attach(*node);
    routes_.push_back(std::move(route));
    nodes_.push_back(std::move(node));
  }

  // Decodes `input` as the hub command and runs it: once with it, then kCyclesAfter without.
  void run(std::span<const std::uint8_t> input, const std::string& hub_name, ManualClock& clock) {
    const CdrDecoder& decoder = CdrDecoder::of(msgs::type_info_of<HubCommand>());
    HubCommand command{};
    if (!decoder.decode(input, &command)) return;
    {
      runtime::Node<hub_api::detail::HubLevelLogic<HubTypes>> hub_node(
          options(hub_name), hub_api::detail::HubLevelLogic<HubTypes>(routes_), source_, sink_,
          ops_of<HubCommand>());
      hub_node.logic().watch(hub_node.tracker(), hub_node.last_valid_command());
      source_.post(&command);
      for (int cycle = 0; cycle <= kCyclesAfter; ++cycle) {
        clock.advance(kCycle);
        const Instant now = clock.now();
        hub_node.advance(now);
        for (const auto& node : nodes_) node->step(now);
        hub_node.rebuild_state(now.mono);
        hub_node.publish(now).ignore();
      }
      for (const auto& node : nodes_) node->enter_safe_state();
    }
    decoder.free_sample(&command);
  }

 private:
  static runtime::NodeOptions options(const std::string& name) {
    runtime::NodeOptions options;
    options.name = name;
    options.command_timeout = std::chrono::milliseconds(100);
    options.addressing = runtime::Addressing::kRejectOthers;
    options.log = quiet_logger();
    return options;
  }

  std::vector<std::unique_ptr<hub_api::detail::Route>> routes_;
  std::vector<std::unique_ptr<runtime::NodeBase>> nodes_;
  OneShotSource<HubCommand> source_;
  DiscardingSink<HubState> sink_;
};

}  // namespace hubrt::fuzz
