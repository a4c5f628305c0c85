#include "lift_logic.h"

#include <cstdlib>
#include <limits>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "hubrt/protocol/lift_drive_modbus.h"

#include "reading_age.h"

namespace hubrt::tool_ecu {

namespace ld = protocol::lift_drive;

namespace {

// Within this of a named position (and in position) the lift is "at" it: the drive's own window.
constexpr int kAtWindowTenthMm = 5;

}  // namespace

std::string_view fault_name(std::uint16_t code) noexcept {
  switch (static_cast<ld::FaultCode>(code)) {
    case ld::FaultCode::kNone:
      return "";
    case ld::FaultCode::kOvercurrent:
      return "overcurrent";
    case ld::FaultCode::kFollowingError:
      return "following error";
    case ld::FaultCode::kOvertemperature:
      return "overtemperature";
    case ld::FaultCode::kWatchdog:
      return "communication watchdog";
  }
  return "unknown";
}

Expected<LiftLogic> LiftLogic::create(const LiftSettings& settings, std::unique_ptr<hal::AsyncModbus> drive,
                                      Time now, std::shared_ptr<spdlog::logger> log) {
  if (drive == nullptr) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("lift: no drive device for '{}'", settings.device));
  }
  return LiftLogic(settings, std::move(drive), now, log ? std::move(log) : spdlog::default_logger());
}

LiftLogic::LiftLogic(LiftSettings settings, std::unique_ptr<hal::AsyncModbus> drive, Time created,
                     std::shared_ptr<spdlog::logger> log)
    : settings_(std::move(settings)),
      link_(std::move(drive), settings_.poll_interval, settings_.drive_watchdog_ms),
      endpoint_(link_.description()),
      created_(created),
      last_now_(created),
      log_(std::move(log)) {
  intent_.speed_mm_s = settings_.speed_mm_s;
}

int LiftLogic::position_index(std::string_view name) const noexcept {
  for (std::size_t i = 0; i < settings_.positions.size(); ++i) {
    if (settings_.positions[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

bool LiftLogic::validate(const Command& command, runtime::Problem& problem) const noexcept {
  if (command.action() != "move") return true;  // position means nothing to stop and reset
  if (position_index(command.position()) >= 0) return true;
  std::array<std::string_view, LiftSettings::kMaxPositions> names{};
  for (std::size_t i = 0; i < settings_.positions.size(); ++i) names[i] = settings_.positions[i].name;
  problem.format("unknown position '{}' (expected one of: {})", command.position(),
                 fmt::join(names.begin(),
                           names.begin() + static_cast<std::ptrdiff_t>(settings_.positions.size()), ", "));
  return false;
}

void LiftLogic::read_inputs(Time now) noexcept {
  last_now_ = now;
  link_.poll(now);
  snap_ = link_.snapshot();
  online_ = snap_.answered && now - snap_.read_at <= settings_.answer_within;
  const bool was_lost = not_answering_.present();
  const bool was_fault = drive_fault_.present();
  // Before its first answer the drive is reported but not latched: it may boot after the hub.
  not_answering_.observe(snap_.answered && !online_);
  drive_fault_.observe(online_ && (snap_.status_word & ld::status::kFault) != 0);
  if (!was_lost && not_answering_.present()) {
    log_->error("lift: drive {} stopped answering ({})", endpoint_, to_string(snap_.last_error));
  }
  if (!was_fault && drive_fault_.present()) {
    log_->error("lift: drive fault {} ({})", snap_.fault_code, fault_name(snap_.fault_code));
  }
}

runtime::NodeCondition LiftLogic::condition() const noexcept {
  if (not_answering_.latched() || drive_fault_.latched()) return runtime::NodeCondition::kFault;
  return snap_.answered ? runtime::NodeCondition::kOk : runtime::NodeCondition::kDevicesMissing;
}

void LiftLogic::update(const Command* in_force, Time now) noexcept {
  target_ = -1;
  LiftIntent intent = intent_;
  intent.mode = LiftIntent::Mode::kStop;
  if (in_force != nullptr && in_force->action() == "move") {
    target_ = position_index(in_force->position());
    const bool may_move = online_ && !not_answering_.active() && !drive_fault_.active();
    if (target_ >= 0 && may_move) {
      intent.mode = LiftIntent::Mode::kMove;
      intent.target_tenth_mm = settings_.positions[static_cast<std::size_t>(target_)].tenth_mm;
    }
  }
  intent_ = intent;
  last_now_ = now;
  link_.send(intent_, now);
}

void LiftLogic::reset() noexcept {
  not_answering_.reset();
  drive_fault_.reset();
  ++intent_.reset_requests;  // sent with this cycle's update()
  intent_.mode = LiftIntent::Mode::kStop;
}

void LiftLogic::enter_safe_state() noexcept {
  intent_.mode = LiftIntent::Mode::kStop;
  link_.poll(last_now_);  // a request that completed since the cycle no longer holds the stop back
  link_.send(intent_, last_now_);
}

void LiftLogic::report_reading(State& state, bool current) const noexcept {
  if (!current) {
    // The last reading is older than its validity: nothing of it is shown as current (the wire
    // contract's "unknown": "", NaN, false; NaN is ROS's "not measured", sensor_msgs/BatteryState).
    // Above all `moving` is not true from it, and not "at".
    state.set_at(std::string_view());
    state.set_position_mm(std::numeric_limits<float>::quiet_NaN());
    state.set_speed_mm_s(std::numeric_limits<float>::quiet_NaN());
    state.set_enabled(false);
    state.set_moving(false);
    state.set_in_position(false);
    state.set_fault(false);
    state.set_fault_code(0);
    state.set_fault_text("unknown");
    return;
  }
  const int at = position_at();
  state.set_at(at >= 0 ? std::string_view(settings_.positions[static_cast<std::size_t>(at)].name)
                       : std::string_view());
  state.set_position_mm(static_cast<float>(ld::to_mm(snap_.position_tenth_mm)));
  state.set_speed_mm_s(static_cast<float>(snap_.speed_mm_s));
  state.set_enabled((snap_.status_word & ld::status::kEnabled) != 0);
  state.set_moving((snap_.status_word & ld::status::kMoving) != 0);
  state.set_in_position((snap_.status_word & ld::status::kInPosition) != 0);
  state.set_fault((snap_.status_word & ld::status::kFault) != 0);
  state.set_fault_code(snap_.fault_code);
  state.set_fault_text(fault_name(snap_.fault_code));
}

void LiftLogic::report_unknown_motion(runtime::ErrorList& errors) const noexcept {
  // The hub cannot stop a drive it cannot reach (a write goes out only after a successful read),
  // so "stopped" would be a guess: the drive carries on with its last command until its own
  // communication watchdog trips (docs/protocols/lift-drive-modbus.md, "Watchdog").
  const bool was_moving = (snap_.status_word & ld::status::kMoving) != 0;
  if (settings_.drive_watchdog_ms == 0) {
    errors.add(
        "lift motion unknown: last seen at {:.1f} mm{}; the drive's watchdog is off "
        "(drive_watchdog_ms 0), so it finishes its last command",
        ld::to_mm(snap_.position_tenth_mm), was_moving ? ", moving" : "");
  } else {
    errors.add(
        "lift motion unknown: last seen at {:.1f} mm{}; the drive's own watchdog stops it "
        "{} ms after the last request it got",
        ld::to_mm(snap_.position_tenth_mm), was_moving ? ", moving" : "", settings_.drive_watchdog_ms);
  }
}

int LiftLogic::position_at() const noexcept {
  if (!online_ || (snap_.status_word & ld::status::kInPosition) == 0) return -1;
  for (std::size_t i = 0; i < settings_.positions.size(); ++i) {
    if (std::abs(int{settings_.positions[i].tenth_mm} - int{snap_.position_tenth_mm}) <= kAtWindowTenthMm) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

void LiftLogic::report(State& state, runtime::ErrorList& errors, Time now) noexcept {
  state.set_target(target_ >= 0
                       ? std::string_view(settings_.positions[static_cast<std::size_t>(target_)].name)
                       : std::string_view());
  state.set_target_mm(target_ >= 0 ? static_cast<float>(ld::to_mm(
                                         settings_.positions[static_cast<std::size_t>(target_)].tenth_mm))
                                   : 0.0F);
  // Judged again at the State's own time: a State rebuilt later than read_inputs() (a command
  // taking effect mid-cycle) must not show a reading that has gone stale meanwhile.
  const bool current = snap_.answered && now - snap_.read_at <= settings_.answer_within;
  state.set_drive_online(current);
  state.set_reading_age_ms(reading_age_ms(snap_.answered, snap_.read_at, now));
  report_reading(state, current);

  if (!snap_.answered) {
    if (now - created_ > settings_.answer_within) {
      errors.add("lift drive {}: no answer since start (last error: {}); lift state unknown", endpoint_,
                 to_string(snap_.last_error));
    }
  } else if (not_answering_.present()) {
    errors.add(
        "lift drive {} not answering for {:.2f} s (limit {:.2f} s, last error: {}); lift state unknown",
        endpoint_, to_seconds(now - snap_.read_at), to_seconds(settings_.answer_within),
        to_string(snap_.last_error));
    report_unknown_motion(errors);
  } else if (not_answering_.only_latched()) {
    errors.add("lift drive {} stopped answering for a while; send reset to clear", endpoint_);
  }
  if (drive_fault_.present()) {
    errors.add("lift drive fault {} ({}); lift stopped; send reset to clear", snap_.fault_code,
               fault_name(snap_.fault_code));
  } else if (drive_fault_.only_latched()) {
    errors.add("lift drive had a fault; send reset to clear");
  }
  if (snap_.write_refused) {
    errors.add("lift drive {} refused the command (exception answer): is the target within its travel?",
               endpoint_);
  }
}

}  // namespace hubrt::tool_ecu
