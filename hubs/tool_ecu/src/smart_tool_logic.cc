// The smart tool node's cycle: construction, command validation, reading the inputs and
// watching the faults, the cycle's update, reset and the safe state. What the command and the
// inputs may do is decided in smart_tool_interlocks.cc, a run is driven through the controller in
// smart_tool_run_sequence.cc, and the State is written in smart_tool_report.cc.
#include "smart_tool_logic.h"

#include <algorithm>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace hubrt::tool_ecu {

namespace st = protocol::smart_tool;

// --- construction ------------------------------------------------------------------------------

Expected<SmartToolLogic> SmartToolLogic::create(const SmartToolSettings& settings, SmartToolDevices devices,
                                                std::unique_ptr<ToolHolderView> holder, Time /*now*/,
                                                std::shared_ptr<spdlog::logger> log) {
  return SmartToolLogic(settings, RunLines(std::move(devices.run_forward), std::move(devices.run_reverse)),
                        ArmSensors(std::move(devices.arm)),
                        Inputs{std::move(devices.button_forward), std::move(devices.button_reverse),
                               std::move(devices.torque_reached), std::move(devices.summary_alarm)},
                        ToolController(std::move(devices.bus), settings.node_id), std::move(holder),
                        log ? std::move(log) : spdlog::default_logger());
}

SmartToolLogic::SmartToolLogic(SmartToolSettings settings, RunLines lines, ArmSensors arm, Inputs inputs,
                               ToolController controller, std::unique_ptr<ToolHolderView> holder,
                               std::shared_ptr<spdlog::logger> log)
    : settings_(std::move(settings)),
      lines_(std::move(lines)),
      arm_sensors_(std::move(arm)),
      controller_(std::move(controller)),
      holder_(std::move(holder)),
      log_(std::move(log)),
      inputs_(std::move(inputs)),
      program_rejected_(settings_.programs.size(), false) {}

// --- commands ----------------------------------------------------------------------------------

bool SmartToolLogic::validate(const Command& command, runtime::Problem& problem) const noexcept {
  if (command.action() != "tighten") return true;  // run_id and program mean nothing to the others
  if (command.run_id() == 0) {
    problem.format(
        "tighten needs a run_id from 1 up (it names the tightening; 0 is reserved for manual runs)");
    return false;
  }
  const std::string_view program = command.program();
  for (const ToolProgram& known : settings_.programs) {
    if (known.name == program) return true;
  }
  std::array<std::string_view, SmartToolSettings::kMaxPrograms> names{};
  for (std::size_t i = 0; i < settings_.programs.size(); ++i) names[i] = settings_.programs[i].name;
  problem.format(
      "unknown program '{}' (expected one of: {})", program,
      fmt::join(names.begin(), names.begin() + static_cast<std::ptrdiff_t>(settings_.programs.size()), ", "));
  return false;
}

// --- inputs ------------------------------------------------------------------------------------

bool SmartToolLogic::read_input(hal::SupervisedInput& input, bool& unreadable, Time now) noexcept {
  const Result<bool> level = input.read(now);
  unreadable = !level.is_ok();
  if (level.is_ok()) return level.value();
  input_error_ = level.status().code();
  input_error_signal_ = input.config().signal;
  return false;
}

void SmartToolLogic::read_inputs(Time now) noexcept {
  controller_.poll(now);
  input_error_ = ErrorCode::kOk;
  bool forward_unreadable = false;
  bool reverse_unreadable = false;
  pressed_forward_ = read_input(inputs_.button_forward, forward_unreadable, now);
  pressed_reverse_ = read_input(inputs_.button_reverse, reverse_unreadable, now);
  torque_input_ = read_input(inputs_.torque_reached, torque_unreadable_, now);
  alarm_input_ = read_input(inputs_.summary_alarm, alarm_unreadable_, now);
  inputs_known_ = !forward_unreadable && !reverse_unreadable && !torque_unreadable_ && !alarm_unreadable_;
  arm_ = arm_sensors_.read(now);
  holder_reading_ = holder_->read(now);
  if (operator_) operator_reading_ = operator_->read(now);
  observe_faults(now);

  // The controller reports the program it has selected; one that differs from what it last
  // accepted from us (another program, or none after a reboot) must be selected again.
  if (acked_program_ >= 0 && controller_.has_status() &&
      controller_.status().program !=
          settings_.programs[static_cast<std::size_t>(acked_program_)].program.number) {
    acked_program_ = -1;
  }
}

void SmartToolLogic::observe_faults(Time now) noexcept {
  const bool was_lost = controller_lost_.present();
  const bool was_bus_fault = bus_fault_.present();
  const bool was_alarm = controller_alarm_.present();
  const bool was_summary = summary_alarm_fault_.present();

  const bool online = controller_.online(now);
  bus_fault_.observe(controller_.bus_fault());
  controller_lost_.observe(controller_.ever_heard() && !online);
  const bool alarm =
      online && ((controller_.has_status() && (controller_.status().flags & st::status_flag::kAlarm) != 0) ||
                 controller_.heartbeat().state == st::ControllerState::kAlarm);
  controller_alarm_.observe(alarm);
  summary_alarm_fault_.observe(alarm_input_);

  if (!was_lost && controller_lost_.present()) {
    log_->error("smart tool: controller lost (node {} on {}): no heartbeat for {:.2f} s",
                controller_.node_id(), controller_.can_config().bus, to_seconds(controller_.silent_for(now)));
  }
  if (!was_bus_fault && bus_fault_.present()) log_->error("smart tool: {}", controller_.bus_problem());
  if (!was_alarm && controller_alarm_.present()) {
    log_->error("smart tool: controller alarm (bits 0x{:02x})", controller_.status().alarms);
  }
  if (!was_summary && summary_alarm_fault_.present()) log_->error("smart tool: summary alarm input active");
}

// --- the cycle ---------------------------------------------------------------------------------

runtime::NodeCondition SmartToolLogic::condition() const noexcept {
  if (controller_lost_.latched() || bus_fault_.latched() || controller_alarm_.latched() ||
      summary_alarm_fault_.latched()) {
    return runtime::NodeCondition::kFault;
  }
  const bool inputs_open = inputs_.button_forward.is_open() && inputs_.button_reverse.is_open() &&
                           inputs_.torque_reached.is_open() && inputs_.summary_alarm.is_open();
  const bool devices_open =
      controller_.bus_open() && lines_.all_open() && arm_sensors_.all_open() && inputs_open;
  return devices_open ? runtime::NodeCondition::kOk : runtime::NodeCondition::kDevicesMissing;
}

void SmartToolLogic::update(const Command* in_force, Time now) noexcept {
  Want want = decide(in_force, now);
  if (want.kind != refused_) {
    refused_ = Kind::kNone;
  } else if (refused_ != Kind::kNone) {
    blocked_by_.assign("the controller did not start the run: change the command (or release the button)");
    want = {};
  }

  // Reset alarm goes to the controller once per reset, while nothing runs.
  if (in_force == nullptr || in_force->action() != runtime::kResetAction) alarm_reset_pending_ = false;
  if (alarm_reset_pending_ && controller_.online(now) && controller_.has_status() && !controller_.running() &&
      run_.phase == Phase::kIdle) {
    if ((controller_.status().flags & st::status_flag::kAlarm) == 0 || controller_.reset_alarm().is_ok()) {
      alarm_reset_pending_ = false;
    }
  }

  // A lost controller or a failed bus ends a run at once: nobody can confirm it any more.
  if (run_.phase != Phase::kIdle &&
      (!controller_.bus_open() || bus_fault_.present() || controller_lost_.present())) {
    abort_for_fault();
  }
  const bool same =
      run_.what.kind == want.kind && run_.what.run_id == want.run_id && run_.what.program == want.program;
  if (run_.phase != Phase::kIdle && run_.phase != Phase::kStopping && !same) stop(now);
  advance(now);
  // What advance() just settled must not start again in the same cycle.
  const bool ended_just_now = want.kind == Kind::kTighten && has_done_ && want.run_id == done_run_id_;
  const bool rejected = want.program >= 0 && program_rejected_[static_cast<std::size_t>(want.program)];
  if (ended_just_now || rejected || (want.kind != Kind::kNone && want.kind == refused_)) want = {};
  if (run_.phase == Phase::kIdle && want.kind != Kind::kNone) begin(want, now);
  lines_.drive(wanted_output(), now);
}

void SmartToolLogic::reset() noexcept {
  controller_lost_.reset();
  bus_fault_.reset();
  controller_alarm_.reset();
  summary_alarm_fault_.reset();
  std::fill(program_rejected_.begin(), program_rejected_.end(), false);
  alarm_reset_pending_ = true;
  refused_ = Kind::kNone;
}

void SmartToolLogic::enter_safe_state() noexcept {
  lines_.drive_safe();
  if (run_.phase == Phase::kStarting || run_.phase == Phase::kRunning) controller_.stop().ignore();
}

}  // namespace hubrt::tool_ecu
