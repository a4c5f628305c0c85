#include "rsp_ecu_hub_type.h"

#include <fmt/format.h>

#include "hubrt/hub_api/hub_layout.h"
#include "hubrt/hub_api/subscriptions.h"
#include "hubrt/hubs/board_devices.h"

#include "rsp_logic.h"

namespace hubrt::rsp_ecu {

Expected<RspDevices> open_rsp_devices(const RspSettings& settings, const hal::BoardConfig& board,
                                      hal::Backend& backend, Time now) {
  constexpr std::string_view kOwner = "tool changer";
  const hal::BoardOutput* lock_entry = board.find_output(settings.lock_valve);
  if (lock_entry != nullptr) {
    if (auto lock = check_lock_valve(lock_entry->config, fmt::format("board {}", board.file)); !lock) {
      return std::move(lock).error();
    }
  }
  const auto inputs = [&](const auto& signals,
                          auto signal_of) -> Expected<std::vector<hal::SupervisedInput>> {
    std::vector<hal::SupervisedInput> opened;
    for (const auto& entry : signals) {
      auto input = hubs::open_board_input(board, backend, kOwner, signal_of(entry), now);
      if (!input) return std::move(input).error();
      opened.push_back(std::move(*input));
    }
    return opened;
  };
  auto lock = hubs::open_board_output(board, backend, kOwner, settings.lock_valve, now);
  if (!lock) return std::move(lock).error();
  auto gripper = hubs::open_board_output(board, backend, kOwner, settings.gripper_valve, now);
  if (!gripper) return std::move(gripper).error();
  auto tools =
      inputs(settings.tool_lines, [](const ToolLine& line) -> const std::string& { return line.signal; });
  if (!tools) return std::move(tools).error();
  auto confirms = inputs(settings.gripper_confirms,
                         [](const std::string& signal) -> const std::string& { return signal; });
  if (!confirms) return std::move(confirms).error();
  auto pressure = hubs::open_board_input(board, backend, kOwner, settings.pressure_switch, now);
  if (!pressure) return std::move(pressure).error();
  return RspDevices{std::move(*lock), std::move(*gripper), std::move(*tools), std::move(*confirms),
                    std::move(*pressure)};
}

namespace {

class RspEcuHubType final : public hub_api::HubType {
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
      auto dock = hub_api::Subscriptions::check<hub_msgs::DockStateView>(config, settings->dock_subscription);
      if (!dock) return dock;
      auto wired = hub_api::NodeWiring<RspEcuTypes>::check<RspLogic>(config, node);
      if (!wired) return wired;
    }
    return {};
  }

  [[nodiscard]] Expected<void> build(const hub_api::HubContext& context, runtime::Hub& hub) const override {
    auto wiring = hub_api::NodeWiring<RspEcuTypes>::create(context, hub);
    if (!wiring) return std::move(wiring).error();
    const Time now = context.clock.now().mono;
    for (const config::NodeConfig& node : context.config.nodes) {
      auto settings = parse_rsp_settings(node);
      if (!settings) return std::move(settings).error();
      auto dock = context.subscriptions.get<hub_msgs::DockStateView>(settings->dock_subscription);
      if (!dock) return std::move(dock).error();
      auto devices = open_rsp_devices(*settings, context.board, context.backend, now);
      if (!devices) {
        return make_error(devices.error().code,
                          fmt::format("node '{}': {}", node.name, devices.error().message));
      }
      auto logic = RspLogic::create(*settings, std::move(*devices), **dock, now);
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

const hub_api::HubType& rsp_ecu_hub_type() noexcept {
  static const RspEcuHubType type;
  return type;
}

}  // namespace hubrt::rsp_ecu
