#include "robot_mover_logic.h"

#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace hubrt::mir_com {

namespace mir = protocol::mir;
using mir::MirCall;

RobotMoverLogic::RobotMoverLogic(const RobotMoverSettings& settings,
                                 std::unique_ptr<MirDevice> device) noexcept
    : settings_(settings), link_(std::move(device), settings.link) {
  link_.device().set_request_on_close(mir::set_state(mir::kStatePause));
}

bool RobotMoverLogic::validate(const Command& command, runtime::Problem& problem) const noexcept {
  if (command.robot_type() != kRobotType) {
    problem.format("robot_type must be '{}'", kRobotType);
    return false;
  }
  if (command.robot_name() != settings_.link.robot_name) {
    problem.format("robot_name must be '{}' (this node's platform)", settings_.link.robot_name);
    return false;
  }
  if (!command.pose_type().empty() && command.pose_type() != "POSITION") {
    problem.format("pose_type must be POSITION (a named position of the platform's map) or empty");
    return false;
  }
  if (command.action() == "move" && !mir::valid_position_name(command.pose_name())) {
    problem.format("move needs pose_name: 1 to 40 of letters, digits, '_', '-', '.', ' '");
    return false;
  }
  const auto unit = [](float v) { return std::isfinite(v) && v >= 0.0F && v <= 1.0F; };
  if (!unit(command.speed_scal()) || !unit(command.acc_scal())) {
    problem.format("speed_scal and acc_scal must be within 0..1");
    return false;
  }
  if (!std::isfinite(command.goal_toll()) || command.goal_toll() < 0.0F) {
    problem.format("goal_toll must be a distance >= 0");
    return false;
  }
  return true;
}

void RobotMoverLogic::read_inputs(Time now) noexcept {
  now_ = now;
  if (link_.collect(now, completion_)) on_completion(completion_);
}

bool RobotMoverLogic::platform_stopped() const noexcept {
  const int state = link_.status().state_id;
  return link_.has_status() && (state == mir::kStateError || state == mir::kStateEmergencyStop);
}

runtime::NodeCondition RobotMoverLogic::condition() const noexcept {
  if (!link_.answering(now_)) return runtime::NodeCondition::kDevicesMissing;
  if (failed_ || platform_stopped()) return runtime::NodeCondition::kFault;
  return runtime::NodeCondition::kOk;
}

void RobotMoverLogic::fail(std::string_view why) noexcept {
  failed_ = true;
  failure_.assign_cut(why);
  phase_ = Phase::kIdle;
}

void RobotMoverLogic::on_completion(const MirCompletion& done) noexcept {
  const MirCall call = done.reply.call;
  const bool ok = done.transport.is_ok() && done.reply.ok;
  switch (phase_) {
    case Phase::kFinding:
      if (call != MirCall::kFindPosition) break;
      if (ok) {
        goal_guid_.assign_cut(done.reply.guid.view());
        phase_ = Phase::kPosting;
      } else if (done.transport.is_ok()) {  // answered, but no such position (or refused): latched
        fail(done.reply.problem.view());
      }  // no answer: asked again when the link is idle
      return;
    case Phase::kPosting:
      if (call != MirCall::kPostMission) break;
      if (ok) {
        mission_id_ = done.reply.mission_id;
        mission_state_.assign_cut(done.reply.mission_state.view());
        phase_ = Phase::kRunning;
      } else if (done.transport.is_ok()) {
        fail(done.reply.problem.view());
      }
      return;
    case Phase::kRunning:
      if (call != MirCall::kGetMission || !ok) break;
      mission_state_.assign_cut(done.reply.mission_state.view());
      if (mission_state_.view() == "Done") {
        actual_pose_.assign_cut(goal_.view());
        done_action_.assign("moved");
        phase_ = Phase::kIdle;
      } else if (mission_state_.view() == "Aborted") {
        char text[160];
        const auto out = fmt::format_to_n(text, sizeof text, "mission {} to '{}' was aborted by the platform",
                                          mission_id_, goal_.view());
        fail(std::string_view(text, out.size < sizeof text ? out.size : sizeof text));
      }
      return;
    case Phase::kIdle:
      break;
  }
  if (call == MirCall::kClearError && ok) {
    clear_pending_ = false;
    done_action_.assign("cleared");
  }
}

void RobotMoverLogic::control(const hal::HttpRequest& request, Time now) noexcept {
  // Once per status: wait for the platform's answer to show the effect before asking again; a
  // platform that does not answer is asked again after answer_within.
  if (control_sent_ && link_.status_at() < control_at_ && now - control_at_ < link_.answer_within()) return;
  if (link_.send(request, now)) {
    control_sent_ = true;
    control_at_ = now;
  }
}

void RobotMoverLogic::hold_paused(Time now) noexcept {
  safe_hold_ = true;
  if (!link_.has_status()) {
    link_.poll_status(now);  // to know whether it runs
    return;
  }
  const int state = link_.status().state_id;
  if (state != mir::kStatePause && !platform_stopped()) {
    control(mir::set_state(mir::kStatePause), now);
  }
  link_.poll_status(now);
}

void RobotMoverLogic::update(const Command* in_force, Time now) noexcept {
  now_ = now;
  if (clear_pending_ && !link_.busy()) {
    link_.send(mir::clear_error(), now);
    return;
  }
  if (in_force == nullptr) {
    hold_paused(now);
    return;
  }
  safe_hold_ = false;
  follow(*in_force, now);
}

void RobotMoverLogic::follow(const Command& command, Time now) noexcept {
  const std::string_view action = command.action();
  const bool fresh =
      !has_handled_ || handled_action_.view() != action || handled_pose_.view() != command.pose_name();
  if (fresh) {
    has_handled_ = true;
    handled_action_.assign_cut(action);
    handled_pose_.assign_cut(command.pose_name());
    if (action == "move") {
      goal_.assign_cut(command.pose_name());
      goal_guid_.clear();
      actual_pose_.clear();
      mission_id_ = 0;
      mission_state_.clear();
      phase_ = Phase::kFinding;
    }
  }
  if (link_.busy()) return;
  const int state = link_.status().state_id;
  if (action == "move") {
    follow_move(now);
  } else if (action == "pause") {
    if (state != mir::kStatePause) {
      control(mir::set_state(mir::kStatePause), now);
    } else {
      done_action_.assign("paused");
    }
  } else if (action == "continue") {
    if (state == mir::kStatePause) {
      control(mir::set_state(mir::kStateReady), now);
    } else if (!platform_stopped()) {
      done_action_.assign("continued");
    }
  } else if (action == "clear_error" && platform_stopped()) {
    control(mir::clear_error(), now);
  }
  link_.poll_status(now);
}

void RobotMoverLogic::follow_move(Time now) noexcept {
  switch (phase_) {
    case Phase::kFinding:
      link_.send(mir::find_position(goal_.view()), now);
      return;
    case Phase::kPosting:
      link_.send(mir::post_mission(settings_.move_mission, settings_.position_parameter, goal_guid_.view()),
                 now);
      return;
    case Phase::kRunning:
      // A platform paused (by us, while not operational, or by someone at the platform) goes on.
      if (link_.status().state_id == mir::kStatePause) {
        control(mir::set_state(mir::kStateReady), now);
        return;
      }
      if (link_.status_due(now)) {
        mission_turn_ = !mission_turn_;
        if (mission_turn_) {
          link_.send(mir::get_mission(mission_id_), now);
          return;
        }
      }
      return;
    case Phase::kIdle:
      return;
  }
}

void RobotMoverLogic::reset() noexcept {
  failed_ = false;
  failure_.clear();
  phase_ = Phase::kIdle;
  has_handled_ = false;
  if (platform_stopped()) clear_pending_ = true;
}

void RobotMoverLogic::report(State& state, runtime::ErrorList& errors, Time now) const noexcept {
  const mir::MirStatus& status = link_.status();
  state.set_robot_name(settings_.link.robot_name);
  state.set_moving(phase_ == Phase::kRunning && status.state_id == mir::kStateExecuting &&
                   mission_state_.view() == "Executing");
  state.set_actual_pose(actual_pose_.view());
  state.set_done_action(done_action_.view());
  state.set_safe_hold(safe_hold_);
  state.set_answering(link_.answering(now));
  state.set_platform_state_id(static_cast<std::uint8_t>(status.state_id));
  state.set_platform_state(status.state_text.view());
  // The platform's readings only while it answers: NaN (ROS's "not measured", as
  // sensor_msgs/BatteryState) before its first answer and once its last one is too old.
  const bool measured = link_.answering(now);
  constexpr float kUnknown = std::numeric_limits<float>::quiet_NaN();
  state.set_x(measured ? status.x : kUnknown);
  state.set_y(measured ? status.y : kUnknown);
  state.set_yaw(measured ? status.yaw_deg : kUnknown);
  state.set_battery(measured ? status.battery_percent : kUnknown);
  state.set_mission_id(mission_id_);
  state.set_mission_state(mission_state_.view());
  state.set_mission_text(status.mission_text.view());
  state.set_goal_pose(phase_ == Phase::kIdle ? std::string_view() : goal_.view());
  link_.report(errors, now);
  if (failed_) errors.add("move failed (reset to clear): {}", failure_.view());
  if (platform_stopped()) {
    errors.add("platform in state {} ({}), {} error(s){}{}", status.state_text.view(), status.state_id,
               status.error_count, status.error_count > 0 ? ", first: " : "", status.first_error.view());
  }
}

void RobotMoverLogic::enter_safe_state() noexcept {
  // The device sends its request-on-close (pause) when the hub closes it.
  safe_hold_ = true;
}

}  // namespace hubrt::mir_com
