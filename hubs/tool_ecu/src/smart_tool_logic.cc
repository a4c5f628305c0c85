#include "smart_tool_logic.h"

#include <algorithm>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "reading_age.h"

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

// --- deciding ----------------------------------------------------------------------------------

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
  if (program >= 0 && program_rejected_[static_cast<std::size_t>(program)]) {
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

// --- acting ------------------------------------------------------------------------------------

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

void SmartToolLogic::begin(const Want& want, Time now) noexcept {
  if (controller_.running()) {  // an earlier run is still winding down: wait for it
    blocked_by_.assign("waiting for the controller to end its run");
    return;
  }
  run_ = Run{};
  run_.what = want;
  run_.phase_since = now;
  if (is_forward(want.kind) && selected_program() != want.program) {
    run_.phase = Phase::kSelecting;
    run_.sent_at = now;
    controller_.select(settings_.programs[static_cast<std::size_t>(want.program)].program).ignore();
    return;
  }
  send_start(now);
}

void SmartToolLogic::send_start(Time now) noexcept {
  run_.phase = Phase::kStarting;
  run_.phase_since = now;
  run_.sent_at = now;
  run_.expected_counter = static_cast<std::uint8_t>(controller_.status().run_counter + 1);
  run_.status_seen_at_send = controller_.status_count();
  const st::Direction direction =
      is_forward(run_.what.kind) ? st::Direction::kForward : st::Direction::kReverse;
  controller_.start(direction).ignore();  // a failure shows as a bus fault; the start then times out
}

void SmartToolLogic::stop(Time now) noexcept {
  if (run_.phase == Phase::kSelecting) {  // nothing was started
    run_ = Run{};
    return;
  }
  controller_.stop().ignore();
  run_.phase = Phase::kStopping;
  run_.phase_since = now;
  run_.sent_at = now;
  run_.status_seen_at_send = controller_.status_count();
}

void SmartToolLogic::advance(Time now) noexcept {
  const bool forward = is_forward(run_.what.kind);
  std::optional<st::RunResult> result = controller_.take_result();
  if (result && (run_.phase == Phase::kIdle || run_.phase == Phase::kSelecting || !forward ||
                 result->run_counter != run_.expected_counter)) {
    note_late_result(*result);
    result.reset();
  }
  if (run_.phase == Phase::kIdle) {
    controller_.take_ack().reset();  // answers to selects we no longer wait for
    return;
  }
  if (result) {
    finish(&*result, 0);
    return;
  }
  const st::Status& status = controller_.status();
  const bool newer_status = controller_.status_count() > run_.status_seen_at_send;
  const bool this_run = status.run_counter == run_.expected_counter;
  if (newer_status && this_run && (status.flags & st::status_flag::kRunning) != 0) run_.confirmed = true;
  if (newer_status && run_.confirmed && this_run && (status.flags & st::status_flag::kRunning) == 0 &&
      !run_.ended) {
    run_.ended = true;
    run_.ended_at = now;
  }

  switch (run_.phase) {
    case Phase::kSelecting: {
      const st::Program& wanted = settings_.programs[static_cast<std::size_t>(run_.what.program)].program;
      const std::optional<st::ProgramAck> ack = controller_.take_ack();
      if (ack && ack->program == wanted) {
        if (ack->code == st::AckCode::kAccepted) {
          acked_program_ = run_.what.program;
          send_start(now);
          return;
        }
        if (ack->code == st::AckCode::kInvalid) {
          program_rejected_[static_cast<std::size_t>(run_.what.program)] = true;
          log_->error("smart tool: the controller rejected program '{}' (number {}) as invalid",
                      settings_.programs[static_cast<std::size_t>(run_.what.program)].name, wanted.number);
          run_ = Run{};
          return;
        }
      }
      if (now - run_.sent_at >= settings_.resend_after) {  // busy, or the ack was lost: ask again
        controller_.select(wanted).ignore();
        run_.sent_at = now;
      }
      return;
    }
    case Phase::kStarting:
      if (run_.confirmed) {
        run_.phase = Phase::kRunning;
        run_.phase_since = now;
      } else if (now - run_.phase_since > settings_.start_timeout) {
        log_->warn("smart tool: the controller did not confirm the start within {:.2f} s",
                   to_seconds(settings_.start_timeout));
        if (run_.what.kind == Kind::kTighten) {
          finish(nullptr, kNotStarted);
        } else {
          refused_ = run_.what.kind;
          run_ = Run{};
        }
      }
      return;
    case Phase::kRunning:
      if (!run_.ended) return;
      if (!forward) {
        run_ = Run{};  // a reverse run ends without a result (alarm, or stopped)
      } else if (now - run_.ended_at > settings_.start_timeout) {
        finish(nullptr, kNoResult);
      }
      return;
    case Phase::kStopping: {
      const bool idle_now = newer_status && (status.flags & st::status_flag::kRunning) == 0;
      if (idle_now && (!forward || !run_.confirmed) && !this_run) {
        // The start never took: there is no result to wait for.
        if (run_.what.kind == Kind::kTighten) {
          finish(nullptr, kNotStarted);
        } else {
          run_ = Run{};
        }
      } else if (idle_now && !forward) {
        run_ = Run{};
      } else if (now - run_.phase_since > settings_.start_timeout && (idle_now || run_.ended)) {
        finish(nullptr, kNoResult | st::nok_reason::kStoppedByCommand);
      } else if (!idle_now && now - run_.sent_at >= settings_.resend_after) {
        controller_.stop().ignore();
        run_.sent_at = now;
      }
      return;
    }
    case Phase::kIdle:
      return;
  }
}

void SmartToolLogic::finish(const st::RunResult* result, std::uint16_t hub_reasons) noexcept {
  const Kind kind = run_.what.kind;
  if (is_forward(kind)) {
    last_ = LastResult{};
    last_.valid = true;
    last_.from_controller = result != nullptr;
    last_.run_id = kind == Kind::kTighten ? run_.what.run_id : 0;
    last_.program = run_.what.program;
    last_.run_counter = run_.expected_counter;
    if (result != nullptr) {
      last_.ok = result->ok;
      last_.torque_cnm = result->torque_cnm;
      last_.angle_ddeg = result->angle_ddeg;
      last_.reasons = result->nok_reasons;
    } else {
      last_.ok = false;
      last_.torque_cnm = controller_.status().torque_cnm;  // the last values seen
      last_.angle_ddeg = controller_.status().angle_ddeg;
      last_.reasons = hub_reasons;
    }
    log_->info("smart tool: run {} ({}) ended {}: {:.2f} Nm, {:.1f} deg{}", last_.run_id,
               settings_.programs[static_cast<std::size_t>(last_.program)].name, last_.ok ? "OK" : "NOK",
               st::to_newton_metres(last_.torque_cnm), st::to_degrees(last_.angle_ddeg),
               last_.from_controller ? "" : " (as the hub saw it)");
  }
  if (kind == Kind::kTighten) {
    has_done_ = true;
    done_run_id_ = run_.what.run_id;
  }
  run_ = Run{};
}

void SmartToolLogic::abort_for_fault() noexcept {
  if (run_.phase == Phase::kSelecting) {  // nothing started
    run_ = Run{};
    return;
  }
  controller_.stop().ignore();  // in case it still hears us
  const std::uint16_t reason = controller_lost_.present() ? kControllerLost : kBusFault;
  if (is_forward(run_.what.kind)) {
    finish(nullptr, reason);
  } else {
    run_ = Run{};
  }
}

void SmartToolLogic::note_late_result(const st::RunResult& result) noexcept {
  // The controller reports a run it lost the link during once it is back (bus-off): it knows the
  // final values better than the hub did.
  if (last_.valid && !last_.from_controller && result.run_counter == last_.run_counter) {
    last_.from_controller = true;
    last_.ok = result.ok;
    last_.torque_cnm = result.torque_cnm;
    last_.angle_ddeg = result.angle_ddeg;
    last_.reasons = result.nok_reasons;
    log_->info("smart tool: the controller's result of run {} came late: {}", last_.run_id,
               last_.ok ? "OK" : "NOK");
  }
}

int SmartToolLogic::selected_program() const noexcept {
  return acked_program_;
}

RunOutput SmartToolLogic::wanted_output() const noexcept {
  if (run_.phase != Phase::kStarting && run_.phase != Phase::kRunning) return RunOutput::kIdle;
  if (run_.ended) return RunOutput::kIdle;
  return is_forward(run_.what.kind) ? RunOutput::kForward : RunOutput::kReverse;
}

std::string_view SmartToolLogic::activity() const noexcept {
  if (run_.phase == Phase::kIdle) return "idle";
  if (run_.phase == Phase::kStopping) return "stopping";
  switch (run_.what.kind) {
    case Kind::kTighten:
      return "tightening";
    case Kind::kLoosen:
      return "loosening";
    case Kind::kManualForward:
      return "manual_forward";
    case Kind::kManualReverse:
      return "manual_reverse";
    case Kind::kNone:
      break;
  }
  return "idle";
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

// --- State -------------------------------------------------------------------------------------

void SmartToolLogic::report_status(State& state, Time now) noexcept {
  const bool fresh = controller_.status_fresh(now);
  state.set_status_fresh(fresh);
  state.set_status_age_ms(reading_age_ms(controller_.has_status(), controller_.status_received_at(), now));
  if (!fresh) {
    // A status older than its validity is not shown as current (the wire contract's "unknown").
    alarms_text_.assign("unknown");
    selected_text_.assign("unknown");
    state.set_controller_alarms(alarms_text_.view());
    state.set_selected_program(selected_text_.view());
    state.set_torque_nm(0.0F);
    state.set_angle_deg(0.0F);
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
  result.set_torque_nm(static_cast<float>(st::to_newton_metres(last_.torque_cnm)));
  result.set_angle_deg(static_cast<float>(st::to_degrees(last_.angle_ddeg)));
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
