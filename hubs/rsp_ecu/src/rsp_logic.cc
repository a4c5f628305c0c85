#include "rsp_logic.h"

#include <algorithm>

#include <fmt/format.h>

#include "unlock_interlock.h"

namespace hubrt::rsp_ecu {

Expected<void> check_lock_valve(const hal::DigitalOutputConfig& lock, std::string_view where) {
  // Energised = open: a board that energised it at start or on faults would drop the tool.
  if (!lock.initial && !lock.safe) return {};
  return make_error(ErrorCode::kInvalidArgument,
                    fmt::format("tool changer: {} drives the lock valve '{}' active (= changer open) "
                                "{}; it must have initial: false and safe: false",
                                where, lock.signal, lock.initial ? "at start" : "on faults"));
}

Expected<RspLogic> RspLogic::create(const RspSettings& settings, RspDevices devices, DockInput& dock,
                                    Time now) {
  if (auto lock = check_lock_valve(devices.lock_valve.config(), "the configuration"); !lock)
    return lock.error();
  if (devices.tool_lines.size() != settings.tool_lines.size() ||
      devices.confirms.size() != settings.gripper_confirms.size()) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("tool changer: {} tool-ID lines and {} confirms handed in, the settings "
                                  "name {} and {}",
                                  devices.tool_lines.size(), devices.confirms.size(),
                                  settings.tool_lines.size(), settings.gripper_confirms.size()));
  }
  const auto lines = [](std::vector<hal::SupervisedInput>& inputs) {
    std::vector<Line> made;
    made.reserve(inputs.size());
    for (hal::SupervisedInput& input : inputs) made.push_back(Line{std::move(input)});
    return made;
  };
  // The gripper line opens at the board's initial level: that is "as it is" until told otherwise.
  const bool gripper_initial = devices.gripper_valve.config().initial;
  Devices owned{std::move(devices.lock_valve), std::move(devices.gripper_valve), lines(devices.tool_lines),
                lines(devices.confirms), Line{std::move(devices.pressure)}};
  RspLogic logic(settings, dock, std::move(owned), now);
  logic.gripper_grab_ = gripper_initial;
  return logic;
}

RspLogic::RspLogic(const RspSettings& settings, DockInput& dock, Devices devices, Time now)
    : dock_(&dock),
      devices_(std::move(devices)),
      tool_readings_(settings.tool_lines.size()),
      lock_(settings.lock_actuation, now),
      gripper_(settings.gripper_confirm) {
  for (const ToolLine& tool : settings.tool_lines) tool_names_.push_back(tool.tool);
  gripper_tool_ = static_cast<std::size_t>(
      std::find(tool_names_.begin(), tool_names_.end(), settings.gripper_tool) - tool_names_.begin());
  unlock_blocked_.assign("inputs not read yet");
}

bool RspLogic::validate(const Command& command, runtime::Problem& problem) const noexcept {
  const std::string_view gripper = command.gripper();
  if (std::find(kGripperStates.begin(), kGripperStates.end(), gripper) == kGripperStates.end()) {
    problem.format("unknown gripper state '{}' (expected grab, release, keep, or empty for keep)", gripper);
    return false;
  }
  if (command.action() == "unlock" && !unlock_allowed_) {
    problem.format("unlock refused: {}; lock kept closed", unlock_blocked_.view());
    return false;
  }
  return true;
}

void RspLogic::read_line(Line& line, Time now) noexcept {
  const Result<bool> level = line.input.read(now);
  line.readable = level.is_ok();
  line.level = level.value_or(false);
  line.failure = level.status().code();
}

void RspLogic::read_inputs(Time now) noexcept {
  for (std::size_t i = 0; i < devices_.tool_lines.size(); ++i) {
    read_line(devices_.tool_lines[i], now);
    tool_readings_[i] = ToolLineReading{devices_.tool_lines[i].readable, devices_.tool_lines[i].level};
  }
  tool_ = decode_tool_id(tool_readings_);

  for (Line& confirm : devices_.confirms) read_line(confirm, now);
  const Line& a = devices_.confirms[0];
  const Line& b = devices_.confirms[1];
  gripper_.observe(a.readable, a.level, b.readable, b.level, now);

  read_pressure(now);
  lock_.pressure(pressure_ok_, now);
  lock_.advance(now);
  // The confirm lines belong to the gripper on its tool: without that tool on the changer there
  // is nothing to confirm, and without pressure the gripper cannot move.
  const bool gripper_on_changer = tool_.is_one() && tool_.index == gripper_tool_;
  gripper_.supervise(gripper_on_changer && pressure_ok_, now);
  evaluate_permission(now);
}

void RspLogic::read_pressure(Time now) noexcept {
  Line& line = devices_.pressure;
  read_line(line, now);
  // A switch that cannot be read proves no pressure: treated as a failure.
  pressure_ok_ = line.readable && line.level;
  if (pressure_ok_ || pressure_fault_) return;
  pressure_fault_ = true;
  if (line.readable) {
    pressure_fault_text_.format("pressure failure: supply pressure lost ({} off)",
                                line.input.config().signal);
  } else {
    pressure_fault_text_.format("pressure failure: pressure switch {} cannot be read",
                                line.input.config().signal);
  }
}

void RspLogic::evaluate_permission(Time now) noexcept {
  if (fault_latched()) {
    unlock_allowed_ = false;
    unlock_blocked_.format("{} is latched; reset first",
                           pressure_fault_ ? "a pressure failure" : "a gripper failure");
    return;
  }
  unlock_allowed_ = unlock_permitted(tool_, tool_name(), *dock_, now, unlock_blocked_);
}

runtime::NodeCondition RspLogic::condition() const noexcept {
  if (fault_latched()) return runtime::NodeCondition::kFault;
  const auto missing = [](const Line& line) { return !line.input.is_open(); };
  const bool devices_open = devices_.lock_valve.is_open() && devices_.gripper_valve.is_open() &&
                            devices_.pressure.input.is_open() &&
                            std::none_of(devices_.tool_lines.begin(), devices_.tool_lines.end(), missing) &&
                            std::none_of(devices_.confirms.begin(), devices_.confirms.end(), missing);
  return devices_open ? runtime::NodeCondition::kOk : runtime::NodeCondition::kDevicesMissing;
}

void RspLogic::update(const Command* in_force, Time now) noexcept {
  const std::string_view action = in_force == nullptr ? std::string_view() : in_force->action();
  safe_state_ = in_force == nullptr || fault_latched() || action == runtime::kResetAction;
  const bool wants_open = !safe_state_ && action == "unlock";
  unlock_refused_ = wants_open && !unlock_allowed_;
  const bool open = wants_open && unlock_allowed_;
  if (!safe_state_) {
    const std::string_view gripper = in_force->gripper();
    if (gripper == "grab") gripper_grab_ = true;
    if (gripper == "release") gripper_grab_ = false;
  }
  lock_write_ = devices_.lock_valve.write(open, now);
  lock_.drive(open, now);
  gripper_write_ = devices_.gripper_valve.write(gripper_grab_, now);
  gripper_.valve(gripper_grab_, now);
}

void RspLogic::reset() noexcept {
  // A fault still there latches again at the next read: a reset only clears what has gone.
  pressure_fault_ = false;
  pressure_fault_text_.clear();
  gripper_.reset();
}

void RspLogic::enter_safe_state() noexcept {
  devices_.lock_valve.write_if_open(false).ignore();
  safe_state_ = true;
}

std::string_view RspLogic::tool_name() const noexcept {
  switch (tool_.kind) {
    case ToolId::Kind::kNone:
      return "none";
    case ToolId::Kind::kOne:
      return tool_names_[tool_.index];
    case ToolId::Kind::kUndefined:
      return "undefined";
  }
  return "undefined";
}

void RspLogic::report(State& state, runtime::ErrorList& errors, Time /*now*/) noexcept {
  state.set_tool(tool_name());
  state.set_locked(lock_.closed() && tool_.is_one());
  state.set_lock(lock_.name());
  state.set_unlock_allowed(unlock_allowed_);
  state.set_unlock_blocked(unlock_blocked_.view());  // Problem: 160 bytes, the field's bound
  state.set_gripper(gripper_grab_ ? "grab" : "release");
  state.set_gripper_confirm(gripper_.confirm_name());
  state.set_pressure_ok(pressure_ok_);
  // A GPIO line is read every cycle: its reading is current or, when the read failed or the chip
  // is gone, unknown (pressure_ok is then false: no proof of pressure).
  state.set_pressure_known(devices_.pressure.readable);
  state.set_safe_state(safe_state_);

  if (pressure_fault_)
    errors.add("{} (latched: lock held closed, gripper as it is; reset to clear)",
               pressure_fault_text_.view());
  if (gripper_.faulted())
    errors.add("{} (latched: lock held closed, gripper as it is; reset to clear)", gripper_.fault());
  if (unlock_refused_) errors.add("unlock refused: {}; lock kept closed", unlock_blocked_.view());
  const bool lines_readable = std::all_of(tool_readings_.begin(), tool_readings_.end(),
                                          [](const ToolLineReading& r) { return r.readable; });
  if (tool_.kind == ToolId::Kind::kUndefined && lines_readable) {
    std::size_t set = 0;
    std::array<std::string_view, 2> first{};
    for (std::size_t i = 0; i < tool_readings_.size(); ++i) {
      if (!tool_readings_[i].set) continue;
      if (set < first.size()) first[set] = tool_names_[i];
      ++set;
    }
    errors.add("tool id undefined: {} tool-ID lines set at once ({}, {}{})", set, first[0], first[1],
               set > 2 ? ", ..." : "");
  }
  for (const Line& line : devices_.tool_lines) report_line(line, errors);
  for (const Line& line : devices_.confirms) report_line(line, errors);
  report_line(devices_.pressure, errors);
  report_output(devices_.lock_valve, lock_write_, errors);
  report_output(devices_.gripper_valve, gripper_write_, errors);
}

void RspLogic::report_line(const Line& line, runtime::ErrorList& errors) const noexcept {
  if (!line.input.is_open()) {
    errors.add("input {} not available: {}", line.input.config().signal, line.input.error());
  } else if (!line.readable) {
    errors.add("input {} failed to read: {}", line.input.config().signal, to_string(line.failure));
  }
}

void RspLogic::report_output(const hal::SupervisedOutput& output, Status last_write,
                             runtime::ErrorList& errors) noexcept {
  if (!output.is_open()) {
    errors.add("output {} not available: {}", output.config().signal, output.error());
  } else if (!last_write.is_ok()) {
    errors.add("output {} failed to write: {}", output.config().signal, to_string(last_write.code()));
  }
}

}  // namespace hubrt::rsp_ecu
