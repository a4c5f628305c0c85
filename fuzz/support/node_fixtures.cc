#include "node_fixtures.h"

#include "dock_ecu_hub_type.h"
#include "node_harness.h"
#include "rsp_ecu_hub_type.h"
#include "scripted_devices.h"
#include "station_files.h"
#include "tool_ecu_hub_type.h"

namespace hubrt::fuzz {
namespace {

class RobotHoldsTool final : public tool_ecu::ToolHolderView {
 public:
  tool_ecu::HolderReading read(Time /*now*/) noexcept override { return {true, true, "smart_tool"}; }
};

template <class T>
T or_die(Expected<T> value) {
  if (!value) setup_failed(value.error().message);
  return std::move(*value);
}

const config::NodeConfig& node_config(std::string_view hub, std::string_view type) {
  return node_of_type(hub_file(hub), type);
}

}  // namespace

ManualClock& fuzz_clock() {
  static ManualClock clock;
  return clock;
}

const std::string& node_name(std::string_view hub, std::string_view type) {
  return node_config(hub, type).name;
}

dock_ecu::DockLogic make_dock_logic() {
  static const auto slots =
      or_die(dock_ecu::parse_slots(node_config("dock_ecu", dock_ecu::DockLogic::kType)));
  return or_die(dock_ecu::DockLogic::create(
      slots, or_die(dock_ecu::open_slot_sensors(slots, host_sim_board(), scripted_backend(fuzz_clock()),
                                                fuzz_clock().now().mono))));
}

rsp_ecu::RspLogic make_rsp_logic() {
  static const auto settings =
      or_die(rsp_ecu::parse_rsp_settings(node_config("rsp_ecu", rsp_ecu::RspLogic::kType)));
  static rsp_ecu::DockInput dock{"dock", "/dock_ecu/dock/state", std::chrono::milliseconds(500),
                                 hub_msgs_msg_dds__DockState__desc, 0};
  return or_die(rsp_ecu::RspLogic::create(
      settings,
      or_die(rsp_ecu::open_rsp_devices(settings, host_sim_board(), scripted_backend(fuzz_clock()),
                                       fuzz_clock().now().mono)),
      dock, fuzz_clock().now().mono));
}

tool_ecu::SmartToolLogic make_smart_tool_logic() {
  static const auto settings =
      or_die(tool_ecu::parse_smart_tool_settings(node_config("tool_ecu", tool_ecu::SmartToolLogic::kType)));
  scripted_backend(fuzz_clock()).can() = CanScript{};
  return or_die(tool_ecu::SmartToolLogic::create(
      settings,
      or_die(tool_ecu::open_smart_tool_devices(settings, host_sim_board(), scripted_backend(fuzz_clock()),
                                               fuzz_clock().now().mono)),
      std::make_unique<RobotHoldsTool>(), fuzz_clock().now().mono, quiet_logger()));
}

namespace {
const tool_ecu::LiftSettings& lift_settings() {
  static const auto settings =
      or_die(tool_ecu::parse_lift_settings(node_config("tool_ecu", tool_ecu::LiftLogic::kType)));
  return settings;
}
tool_ecu::LiftLogic make_lift(const tool_ecu::LiftSettings& settings) {
  return or_die(tool_ecu::LiftLogic::create(settings, scripted_backend(fuzz_clock()).modbus().open(),
                                            fuzz_clock().now().mono, quiet_logger()));
}
}  // namespace

tool_ecu::LiftLogic make_lift_logic() {
  return make_lift(lift_settings());
}

tool_ecu::LiftLogic make_lift_logic_lockstep() {
  tool_ecu::LiftSettings settings = lift_settings();
  settings.poll_interval = Duration::zero();
  return make_lift(settings);
}

}  // namespace hubrt::fuzz
