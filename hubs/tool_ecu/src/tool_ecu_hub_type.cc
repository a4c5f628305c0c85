#include "tool_ecu_hub_type.h"

#include <algorithm>

#include <fmt/format.h>

#include "hubrt/hal/common/threaded_async_modbus.h"
#include "hubrt/hub_api/hub_layout.h"
#include "hubrt/hub_api/subscriptions.h"
#include "hubrt/hubs/board_devices.h"

#include "lift_drive_stop.h"
#include "lift_logic.h"
#include "smart_tool_logic.h"

namespace hubrt::tool_ecu {

Expected<SmartToolDevices> open_smart_tool_devices(const SmartToolSettings& settings,
                                                   const hal::BoardConfig& board, hal::Backend& backend,
                                                   Time now) {
  constexpr std::string_view kOwner = "smart tool";
  auto forward = hubs::open_board_output(board, backend, kOwner, settings.run_forward, now);
  if (!forward) return std::move(forward).error();
  auto reverse = hubs::open_board_output(board, backend, kOwner, settings.run_reverse, now);
  if (!reverse) return std::move(reverse).error();
  auto home = hubs::open_board_input(board, backend, "arm position", settings.arm.home, now);
  if (!home) return std::move(home).error();
  auto pre_home = hubs::open_board_input(board, backend, "arm position", settings.arm.pre_home, now);
  if (!pre_home) return std::move(pre_home).error();
  auto out_of_range = hubs::open_board_input(board, backend, "arm position", settings.arm.out_of_range, now);
  if (!out_of_range) return std::move(out_of_range).error();
  auto button_forward = hubs::open_board_input(board, backend, kOwner, settings.button_forward, now);
  if (!button_forward) return std::move(button_forward).error();
  auto button_reverse = hubs::open_board_input(board, backend, kOwner, settings.button_reverse, now);
  if (!button_reverse) return std::move(button_reverse).error();
  auto torque = hubs::open_board_input(board, backend, kOwner, settings.torque_reached, now);
  if (!torque) return std::move(torque).error();
  auto alarm = hubs::open_board_input(board, backend, kOwner, settings.summary_alarm, now);
  if (!alarm) return std::move(alarm).error();
  const hal::BoardCanBus* can = board.find_can(settings.bus);
  if (can == nullptr) {
    return make_error(ErrorCode::kNotFound,
                      fmt::format("smart tool: board {} has no CAN bus '{}'", board.file, settings.bus));
  }
  hal::SupervisedCanBus bus(backend, ToolController::bus_config(can->config, settings.node_id));
  bus.open_now(now);
  return SmartToolDevices{std::move(*forward),
                          std::move(*reverse),
                          {std::move(*home), std::move(*pre_home), std::move(*out_of_range)},
                          std::move(*button_forward),
                          std::move(*button_reverse),
                          std::move(*torque),
                          std::move(*alarm),
                          std::move(bus)};
}

namespace {

Error in_node(const config::NodeConfig& node, const Error& error) {
  return make_error(error.code, fmt::format("node '{}': {}", node.name, error.message));
}

class ToolEcuHubType final : public hub_api::HubType {
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
        if (!settings->operator_state.empty() &&
            std::none_of(config.subscriptions.begin(), config.subscriptions.end(),
                         [&](const config::Subscription& s) { return s.name == settings->operator_state; })) {
          return node.settings.error_at(
              "operator_state",
              fmt::format(
                  "node '{}' takes the operator hub's State from subscription '{}', and {} has no such "
                  "subscription (add subscriptions: {{{}: {{topic: /operator_hub/panel/state, type: "
                  "hub_msgs/msg/OperatorPanelState, timeout_ms: 500}}}})",
                  node.name, settings->operator_state, config.file, settings->operator_state));
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
        auto rsp = hub_api::Subscriptions::check<hub_msgs::RspStateView>(config, settings->robot_state);
        if (!rsp) return in_node(node, rsp.error());
        if (!settings->operator_state.empty()) {
          auto panel = hub_api::Subscriptions::check<hub_msgs::OperatorPanelStateView>(
              config, settings->operator_state);
          if (!panel) return in_node(node, panel.error());
        }
        wired = hub_api::NodeWiring<ToolEcuTypes>::check<SmartToolLogic>(config, node);
      } else {
        wired = hub_api::NodeWiring<ToolEcuTypes>::check<LiftLogic>(config, node);
      }
      if (!wired) return wired;
    }
    return {};
  }

  [[nodiscard]] Expected<void> build(const hub_api::HubContext& context, runtime::Hub& hub) const override {
    auto wiring = hub_api::NodeWiring<ToolEcuTypes>::create(context, hub);
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

  // The lift drive: stopped by one Modbus write (lift_drive_stop.h). The smart tool needs nothing
  // here: its run lines are GPIO outputs, which hubd drives safe.
  [[nodiscard]] std::vector<hub_api::DeviceStopReport> stop_devices(const config::HubConfig& config,
                                                                    const hal::BoardConfig& board,
                                                                    hal::Backend& backend,
                                                                    Duration timeout) const override {
    std::vector<hub_api::DeviceStopReport> reports;
    for (const config::NodeConfig& node : config.nodes) {
      if (node.type != LiftLogic::kType) continue;
      auto settings = parse_lift_settings(node);
      if (!settings) {
        reports.push_back({node.name, false, settings.error().message});
        continue;
      }
      reports.push_back(stop_lift_drive(*settings, board, backend, timeout));
    }
    return reports;
  }

 private:
  static Expected<void> add_smart_tool(const hub_api::HubContext& context, const config::NodeConfig& node,
                                       hub_api::NodeWiring<ToolEcuTypes>& wiring, Time now) {
    auto settings = parse_smart_tool_settings(node);
    if (!settings) return std::move(settings).error();
    auto rsp = context.subscriptions.get<hub_msgs::RspStateView>(settings->robot_state);
    if (!rsp) return in_node(node, rsp.error());
    auto devices = open_smart_tool_devices(*settings, context.board, context.backend, now);
    if (!devices) return in_node(node, devices.error());
    auto logic = SmartToolLogic::create(*settings, std::move(*devices),
                                        std::make_unique<RspToolHolder>(**rsp), now, context.log);
    if (!logic) return in_node(node, logic.error());
    if (!settings->operator_state.empty()) {
      auto panel = context.subscriptions.get<hub_msgs::OperatorPanelStateView>(settings->operator_state);
      if (!panel) return in_node(node, panel.error());
      logic->require_operator(std::make_unique<OperatorPanelPresence>(**panel));
    }
    return wiring.add(node, std::move(*logic));
  }

  static Expected<void> add_lift(const hub_api::HubContext& context, const config::NodeConfig& node,
                                 hub_api::NodeWiring<ToolEcuTypes>& wiring) {
    auto settings = parse_lift_settings(node);
    if (!settings) return std::move(settings).error();
    auto drive = open_lift_drive(*settings, context.board, context.backend);
    if (!drive) return in_node(node, drive.error());
    auto logic = LiftLogic::create(*settings, std::move(*drive), context.clock.now().mono, context.log);
    if (!logic) return in_node(node, logic.error());
    return wiring.add(node, std::move(*logic));
  }

  // The lift drive's Modbus client from the board, behind the HAL's worker thread: the logic
  // submits and polls, the blocking calls run there.
  // Errors: the device missing from the board (kNotFound), the backend's open_modbus errors
  // (e.g. an RTU serial device that does not exist), naming the device.
  static Expected<std::unique_ptr<hal::AsyncModbus>> open_lift_drive(const LiftSettings& settings,
                                                                     const hal::BoardConfig& board,
                                                                     hal::Backend& backend) {
    const hal::BoardModbusDevice* device = board.find_modbus(settings.device);
    if (device == nullptr) {
      return make_error(ErrorCode::kNotFound,
                        fmt::format("lift: board {} has no Modbus device '{}'", board.file, settings.device));
    }
    auto client = backend.open_modbus(device->config);
    if (!client) return make_error(client.error().code, fmt::format("lift: {}", client.error().message));
    auto drive = hal::open_threaded_async_modbus(
        std::move(*client), hal::batch_request_timeout(device->config), hal::describe_modbus(device->config));
    if (!drive) return make_error(drive.error().code, fmt::format("lift: {}", drive.error().message));
    return std::move(*drive);
  }
};

}  // namespace

const hub_api::HubType& tool_ecu_hub_type() noexcept {
  static const ToolEcuHubType type;
  return type;
}

}  // namespace hubrt::tool_ecu
