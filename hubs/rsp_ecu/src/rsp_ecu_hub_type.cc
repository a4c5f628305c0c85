#include "rsp_ecu_hub_type.h"

#include <fmt/format.h>

#include "hubrt/assembly/hub_layout.h"
#include "hubrt/assembly/subscriptions.h"

#include "rsp_logic.h"

namespace hubrt::rsp_ecu {
namespace {

class RspEcuHubType final : public assembly::HubType {
 public:
  [[nodiscard]] std::string_view name() const noexcept override { return "rsp_ecu"; }

  [[nodiscard]] Expected<hal::BoardRequirements> requirements(
      const config::HubConfig& config) const override {
    hal::BoardRequirements required;
    required.hub = config.type;
    for (const config::NodeConfig& node : config.nodes) {
      if (node.type != RspLogic::kType) {
        return node.settings.error_at(
            "type",
            fmt::format("an rsp_ecu hub has nodes of type '{}' only, not '{}'", RspLogic::kType, node.type));
      }
      auto settings = parse_rsp_settings(node);
      if (!settings) return std::move(settings).error();
      // The interlock cannot work without the Dock ECU's State: say so before anything opens.
      const bool subscribed =
          std::any_of(config.subscriptions.begin(), config.subscriptions.end(),
                      [&](const config::Subscription& s) { return s.name == settings->dock_subscription; });
      if (!subscribed) {
        return node.settings.error(fmt::format(
            "node '{}' needs the Dock ECU State as subscription '{}', and {} has no such subscription "
            "(add subscriptions: {{{}: {{topic: /dock_ecu/dock/state, type: hub_msgs/msg/DockState}}}})",
            node.name, settings->dock_subscription, config.file, settings->dock_subscription));
      }
      add_requirements(*settings, required);
    }
    return required;
  }

  [[nodiscard]] Expected<void> check(const config::HubConfig& config) const override {
    for (const config::NodeConfig& node : config.nodes) {
      auto settings = parse_rsp_settings(node);
      if (!settings) return std::move(settings).error();
      auto dock =
          assembly::Subscriptions::check<hub_msgs::DockStateView>(config, settings->dock_subscription);
      if (!dock) return dock;
      auto wired = assembly::NodeWiring<RspEcuTypes>::check<RspLogic>(config, node);
      if (!wired) return wired;
    }
    return {};
  }

  [[nodiscard]] Expected<void> build(const assembly::HubContext& context, runtime::Hub& hub) const override {
    auto wiring = assembly::NodeWiring<RspEcuTypes>::create(context, hub);
    if (!wiring) return std::move(wiring).error();
    const Time now = context.clock.now().mono;
    for (const config::NodeConfig& node : context.config.nodes) {
      auto settings = parse_rsp_settings(node);
      if (!settings) return std::move(settings).error();
      auto dock = context.subscriptions.get<hub_msgs::DockStateView>(settings->dock_subscription);
      if (!dock) return std::move(dock).error();
      auto logic = RspLogic::create(*settings, context.board, context.backend, **dock, now);
      if (!logic) {
        return make_error(logic.error().code, fmt::format("node '{}': {}", node.name, logic.error().message));
      }
      auto added = wiring->add(node, std::move(*logic));
      if (!added) return added;
    }
    return wiring->finish();
  }
};

}  // namespace

const assembly::HubType& rsp_ecu_hub_type() noexcept {
  static const RspEcuHubType type;
  return type;
}

}  // namespace hubrt::rsp_ecu
