#include "tool_ecu_hub_type.h"

#include <algorithm>

#include <fmt/format.h>

#include "hubrt/assembly/hub_layout.h"
#include "hubrt/assembly/subscriptions.h"

#include "lift_logic.h"
#include "smart_tool_logic.h"

namespace hubrt::tool_ecu {
namespace {

Error in_node(const config::NodeConfig& node, const Error& error) {
  return make_error(error.code, fmt::format("node '{}': {}", node.name, error.message));
}

class ToolEcuHubType final : public assembly::HubType {
 public:
  [[nodiscard]] std::string_view name() const noexcept override { return "tool_ecu"; }

  [[nodiscard]] Expected<hal::BoardRequirements> requirements(
      const config::HubConfig& config) const override {
    hal::BoardRequirements required;
    required.hub = config.type;
    for (const config::NodeConfig& node : config.nodes) {
      if (node.type == SmartToolLogic::kType) {
        auto settings = parse_smart_tool_settings(node);
        if (!settings) return std::move(settings).error();
        // The interlock cannot work without the RSP ECU's State: say so before anything opens.
        const bool subscribed =
            std::any_of(config.subscriptions.begin(), config.subscriptions.end(),
                        [&](const config::Subscription& s) { return s.name == settings->robot_state; });
        if (!subscribed) {
          return node.settings.error(fmt::format(
              "node '{}' needs the RSP ECU State as subscription '{}', and {} has no such subscription (add "
              "subscriptions: {{{}: {{topic: /rsp_ecu/rsp/state, type: hub_msgs/msg/RspState, timeout_ms: "
              "500}}}})",
              node.name, settings->robot_state, config.file, settings->robot_state));
        }
        add_requirements(*settings, required);
      } else if (node.type == LiftLogic::kType) {
        auto settings = parse_lift_settings(node);
        if (!settings) return std::move(settings).error();
        add_requirements(*settings, required);
      } else {
        return node.settings.error_at("type",
                                      fmt::format("a tool_ecu hub has nodes of type '{}' or '{}', not '{}'",
                                                  SmartToolLogic::kType, LiftLogic::kType, node.type));
      }
    }
    return required;
  }

  [[nodiscard]] Expected<void> check(const config::HubConfig& config) const override {
    for (const config::NodeConfig& node : config.nodes) {
      Expected<void> wired;
      if (node.type == SmartToolLogic::kType) {
        auto settings = parse_smart_tool_settings(node);
        if (!settings) return std::move(settings).error();
        auto rsp = assembly::Subscriptions::check<hub_msgs::RspStateView>(config, settings->robot_state);
        if (!rsp) return in_node(node, rsp.error());
        wired = assembly::NodeWiring<ToolEcuTypes>::check<SmartToolLogic>(config, node);
      } else {
        wired = assembly::NodeWiring<ToolEcuTypes>::check<LiftLogic>(config, node);
      }
      if (!wired) return wired;
    }
    return {};
  }

  [[nodiscard]] Expected<void> build(const assembly::HubContext& context, runtime::Hub& hub) const override {
    auto wiring = assembly::NodeWiring<ToolEcuTypes>::create(context, hub);
    if (!wiring) return std::move(wiring).error();
    const Time now = context.clock.now().mono;
    for (const config::NodeConfig& node : context.config.nodes) {
      Expected<void> added;
      if (node.type == SmartToolLogic::kType) {
        added = add_smart_tool(context, node, *wiring, now);
      } else {
        added = add_lift(context, node, *wiring);
      }
      if (!added) return added;
    }
    return wiring->finish();
  }

 private:
  static Expected<void> add_smart_tool(const assembly::HubContext& context, const config::NodeConfig& node,
                                       assembly::NodeWiring<ToolEcuTypes>& wiring, Time now) {
    auto settings = parse_smart_tool_settings(node);
    if (!settings) return std::move(settings).error();
    auto rsp = context.subscriptions.get<hub_msgs::RspStateView>(settings->robot_state);
    if (!rsp) return in_node(node, rsp.error());
    auto logic = SmartToolLogic::create(*settings, context.board, context.backend,
                                        std::make_unique<RspToolHolder>(**rsp), now, context.log);
    if (!logic) return in_node(node, logic.error());
    return wiring.add(node, std::move(*logic));
  }

  static Expected<void> add_lift(const assembly::HubContext& context, const config::NodeConfig& node,
                                 assembly::NodeWiring<ToolEcuTypes>& wiring) {
    auto settings = parse_lift_settings(node);
    if (!settings) return std::move(settings).error();
    auto logic = LiftLogic::create(*settings, context.board, context.backend, context.clock, context.log);
    if (!logic) return in_node(node, logic.error());
    return wiring.add(node, std::move(*logic));
  }
};

}  // namespace

const assembly::HubType& tool_ecu_hub_type() noexcept {
  static const ToolEcuHubType type;
  return type;
}

}  // namespace hubrt::tool_ecu
