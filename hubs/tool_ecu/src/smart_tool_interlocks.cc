// The smart tool's interlocks (DESIGN.md §2, the header's comment): what the command in force and
// the buttons ask for this cycle, and what forbids it (said in blocked_by_ for the State).
#include "smart_tool_logic.h"

namespace hubrt::tool_ecu {

bool SmartToolLogic::fault_blocks() noexcept {
  if (!controller_.bus_open()) {
    blocked_by_.format("CAN bus {} not available", controller_.can_config().bus);
  } else if (bus_fault_.active()) {
    blocked_by_.assign(bus_fault_.present() ? "CAN bus fault" : "CAN bus fault (latched: send reset)");
  } else if (!controller_.ever_heard()) {
    blocked_by_.assign("no heartbeat from the tool controller yet");
  } else if (controller_lost_.active()) {
    blocked_by_.assign(controller_lost_.present() ? "tool controller lost"
                                                  : "tool controller was lost (latched: send reset)");
  } else if (controller_alarm_.active()) {
    blocked_by_.assign(controller_alarm_.present() ? "tool controller alarm"
                                                   : "tool controller alarm (latched: send reset)");
  } else if (summary_alarm_fault_.active()) {
    blocked_by_.assign(summary_alarm_fault_.present() ? "summary alarm"
                                                      : "summary alarm (latched: send reset)");
  } else if (alarm_unreadable_) {
    blocked_by_.assign("summary alarm input unreadable");
  } else {
    return false;
  }
  return true;
}

bool SmartToolLogic::planner_blocked(bool forward, int program) noexcept {
  if (fault_blocks()) return true;
  if (operator_ && !operator_reading_.verified) {
    blocked_by_.format("no verified operator: {}", operator_reading_.detail);
  } else if (program >= 0 && program_rejected_[static_cast<std::size_t>(program)]) {
    blocked_by_.format("program '{}' was rejected by the controller (latched: send reset)",
                       settings_.programs[static_cast<std::size_t>(program)].name);
  } else if (!holder_reading_.known) {
    blocked_by_.format("robot's grip on the tool unknown: {}", holder_reading_.detail);
  } else if (!holder_reading_.holds) {
    blocked_by_.format("the robot does not hold the smart tool (RSP ECU reports tool '{}')",
                       holder_reading_.detail);
  } else if (arm_ != ArmPosition::kOperating) {
    blocked_by_.format("arm not in operating position ({})", to_string(arm_));
  } else if (forward && (torque_input_ || torque_unreadable_)) {
    blocked_by_.assign(torque_unreadable_ ? "torque-reached input unreadable" : "torque reached");
  } else if (!controller_.has_status()) {
    blocked_by_.assign("no status from the tool controller yet");
  } else {
    return false;
  }
  return true;
}

SmartToolLogic::Want SmartToolLogic::manual() noexcept {
  if (!pressed_forward_ && !pressed_reverse_) return {};
  if (pressed_forward_ && pressed_reverse_) {
    blocked_by_.assign("both manual buttons pressed");
    return {};
  }
  if (fault_blocks()) return {};
  if (!holder_reading_.known) {
    blocked_by_.format("manual buttons disabled: robot's grip on the tool unknown: {}",
                       holder_reading_.detail);
  } else if (holder_reading_.holds) {
    blocked_by_.assign("manual buttons disabled: the robot holds the smart tool");
  } else if (!controller_.has_status()) {
    blocked_by_.assign("no status from the tool controller yet");
  } else if (pressed_reverse_) {
    return Want{Kind::kManualReverse, 0, -1};
  } else if (settings_.manual_program < 0) {
    blocked_by_.assign("manual forward disabled: no manual_program in the hub file");
  } else if (torque_input_ || torque_unreadable_) {
    blocked_by_.assign(torque_unreadable_ ? "torque-reached input unreadable" : "torque reached");
  } else if (settings_.manual_program >= 0 &&
             program_rejected_[static_cast<std::size_t>(settings_.manual_program)]) {
    blocked_by_.assign("manual program was rejected by the controller (latched: send reset)");
  } else {
    return Want{Kind::kManualForward, 0, settings_.manual_program};
  }
  return {};
}

SmartToolLogic::Want SmartToolLogic::decide(const Command* in_force, Time /*now*/) noexcept {
  blocked_by_.clear();
  if (in_force == nullptr) return {};  // the safe state: idle, buttons ignored
  const std::string_view action = in_force->action();
  if (action == "idle") return manual();
  if (action == "tighten") {
    if (has_done_ && in_force->run_id() == done_run_id_) return {};  // this tightening has ended
    int program = -1;
    for (std::size_t i = 0; i < settings_.programs.size(); ++i) {
      if (settings_.programs[i].name == in_force->program()) program = static_cast<int>(i);
    }
    if (program < 0 || planner_blocked(true, program)) return {};
    return Want{Kind::kTighten, in_force->run_id(), program};
  }
  if (action == "loosen") {
    if (planner_blocked(false, -1)) return {};
    return Want{Kind::kLoosen, 0, -1};
  }
  if (action == "inhibit" && (pressed_forward_ || pressed_reverse_)) {
    blocked_by_.assign("manual buttons disabled: inhibit command");
  }
  return {};  // inhibit, reset
}

}  // namespace hubrt::tool_ecu
