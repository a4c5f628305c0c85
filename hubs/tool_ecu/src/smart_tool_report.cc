// The smart tool's State: the run, the interlock inputs, the controller's status (or "unknown"
// when it is stale), the last tightening's result with its reasons as text, and the errors list.
#include <limits>

#include "reading_age.h"
#include "smart_tool_logic.h"

namespace hubrt::tool_ecu {

namespace st = protocol::smart_tool;

namespace {

constexpr std::pair<std::uint16_t, std::string_view> kReasonNames[] = {
    {st::nok_reason::kTorqueLow, "torque low"},
    {st::nok_reason::kAngleLow, "angle low"},
    {st::nok_reason::kAngleHigh, "angle high"},
    {st::nok_reason::kStoppedByCommand, "stopped by command"},
    {st::nok_reason::kAlarm, "alarm"},
    {st::nok_reason::kRunTimeout, "run timeout"},
    {st::nok_reason::kLinkLost, "link lost"},
    {SmartToolLogic::kControllerLost, "controller lost"},
    {SmartToolLogic::kBusFault, "CAN bus fault"},
    {SmartToolLogic::kNotStarted, "not started"},
    {SmartToolLogic::kNoResult, "no result from the controller"},
};

constexpr std::pair<std::uint8_t, std::string_view> kAlarmNames[] = {
    {st::alarm_bit::kOvercurrent, "overcurrent"},
    {st::alarm_bit::kOvertemperature, "overtemperature"},
    {st::alarm_bit::kTransducerFault, "transducer fault"},
};

template <std::size_t N, class Bits, std::size_t M>
void join_bits(runtime::TextBuffer<N>& out, Bits bits,
               const std::pair<Bits, std::string_view> (&names)[M]) noexcept {
  out.clear();
  std::array<char, N + 1> text{};
  std::size_t length = 0;
  for (const auto& [bit, name] : names) {
    if ((bits & bit) == 0) continue;
    const std::string_view separator = length == 0 ? "" : ", ";
    if (length + separator.size() + name.size() > N) break;
    separator.copy(text.data() + length, separator.size());
    length += separator.size();
    name.copy(text.data() + length, name.size());
    length += name.size();
  }
  out.assign(std::string_view(text.data(), length));
}

}  // namespace

void SmartToolLogic::report_status(State& state, Time now) noexcept {
  const bool fresh = controller_.status_fresh(now);
  state.set_status_fresh(fresh);
  state.set_status_age_ms(reading_age_ms(controller_.has_status(), controller_.status_received_at(), now));
  if (!fresh) {
    // A status older than its validity is not shown as current (the wire contract's "unknown";
    // NaN for a reading not measured, as ROS's sensor_msgs/BatteryState).
    alarms_text_.assign("unknown");
    selected_text_.assign("unknown");
    state.set_controller_alarms(alarms_text_.view());
    state.set_selected_program(selected_text_.view());
    state.set_torque_nm(std::numeric_limits<float>::quiet_NaN());
    state.set_angle_deg(std::numeric_limits<float>::quiet_NaN());
    return;
  }
  const st::Status& status = controller_.status();
  join_bits(alarms_text_, status.alarms, kAlarmNames);
  state.set_controller_alarms(alarms_text_.view());
  const int selected = selected_program();
  if (selected >= 0) {
    selected_text_.assign(settings_.programs[static_cast<std::size_t>(selected)].name);
  } else if (status.program != 0) {
    selected_text_.format("number {}", status.program);  // not selected by this hub
  } else {
    selected_text_.clear();
  }
  state.set_selected_program(selected_text_.view());
  state.set_torque_nm(static_cast<float>(st::to_newton_metres(status.torque_cnm)));
  state.set_angle_deg(static_cast<float>(st::to_degrees(status.angle_ddeg)));
}

void SmartToolLogic::report(State& state, runtime::ErrorList& errors, Time now) noexcept {
  state.set_output(to_string(lines_.shown()));
  state.set_activity(activity());
  state.set_active_run_id(run_.phase != Phase::kIdle && run_.what.kind == Kind::kTighten ? run_.what.run_id
                                                                                         : 0);
  state.set_blocked_by(blocked_by_.view());
  state.set_robot_holds_tool(holder_reading_.known && holder_reading_.holds);
  state.set_arm_position(to_string(arm_));
  state.set_torque_reached(torque_input_);
  state.set_summary_alarm(alarm_input_);
  state.set_button_forward(pressed_forward_);
  state.set_button_reverse(pressed_reverse_);
  state.set_inputs_known(inputs_known_);
  state.set_controller_online(controller_.online(now));
  report_status(state, now);

  const hub_msgs::SmartToolResultRef result = state.last_result();
  result.set_run_id(last_.run_id);
  result.set_program(last_.valid
                         ? std::string_view(settings_.programs[static_cast<std::size_t>(last_.program)].name)
                         : std::string_view());
  result.set_ok(last_.ok);
  // Before the first run there is no final torque or angle: NaN, not a measured 0.
  constexpr float kNone = std::numeric_limits<float>::quiet_NaN();
  result.set_torque_nm(last_.valid ? static_cast<float>(st::to_newton_metres(last_.torque_cnm)) : kNone);
  result.set_angle_deg(last_.valid ? static_cast<float>(st::to_degrees(last_.angle_ddeg)) : kNone);
  join_bits(reasons_text_, last_.reasons, kReasonNames);
  result.set_nok_reasons(reasons_text_.view());
  result.set_run_counter(last_.run_counter);

  lines_.report(errors);
  arm_sensors_.report(errors);
  for (const hal::SupervisedInput* input :
       {&inputs_.button_forward, &inputs_.button_reverse, &inputs_.torque_reached, &inputs_.summary_alarm}) {
    if (!input->is_open()) errors.add("input {} not available: {}", input->config().signal, input->error());
  }
  if (input_error_ != ErrorCode::kOk && input_error_ != ErrorCode::kUnavailable) {
    errors.add("input {} failed to read: {}", input_error_signal_, to_string(input_error_));
  }
  const hal::CanConfig& can = controller_.can_config();
  if (!controller_.bus_open()) {
    errors.add("CAN bus {} ({}) not available: {}", can.bus, can.interface, controller_.bus_problem());
  } else if (bus_fault_.present()) {
    errors.add("{}; outputs idle", controller_.bus_problem());
  } else if (bus_fault_.only_latched()) {
    errors.add("CAN bus {} ({}) had a fault (bus-off, down or failed I/O); send reset to clear", can.bus,
               can.interface);
  }
  if (controller_.bus_open() && !controller_.ever_heard()) {
    errors.add("tool controller (node {} on {}): no heartbeat since start", controller_.node_id(), can.bus);
  } else if (controller_lost_.present()) {
    errors.add("tool controller lost: no heartbeat for {:.2f} s (limit {:.2f} s); outputs idle",
               to_seconds(controller_.silent_for(now)), to_seconds(st::kControllerLostAfter));
  } else if (controller_lost_.only_latched()) {
    errors.add("tool controller was lost (no heartbeat for more than {:.2f} s); send reset to clear",
               to_seconds(st::kControllerLostAfter));
  }
  if (controller_alarm_.present()) {
    errors.add("tool controller alarm: {}; outputs idle",
               alarms_text_.empty() ? "(no alarm bits)" : alarms_text_.view());
  } else if (controller_alarm_.only_latched()) {
    errors.add("tool controller alarm occurred; send reset to clear");
  }
  if (summary_alarm_fault_.present()) {
    errors.add("summary alarm input active; outputs idle");
  } else if (summary_alarm_fault_.only_latched()) {
    errors.add("summary alarm occurred; send reset to clear");
  }
  for (std::size_t i = 0; i < program_rejected_.size(); ++i) {
    if (program_rejected_[i]) {
      errors.add("program '{}' (number {}) rejected by the controller as invalid; check the hub file",
                 settings_.programs[i].name, settings_.programs[i].program.number);
    }
  }
  if (!holder_reading_.known) errors.add("robot state lost: {}", holder_reading_.detail);
}

}  // namespace hubrt::tool_ecu
