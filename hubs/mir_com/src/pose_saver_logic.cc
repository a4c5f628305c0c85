#include "pose_saver_logic.h"

namespace hubrt::mir_com {

namespace mir = protocol::mir;
using mir::MirCall;

bool PoseSaverLogic::validate(const Command& command, runtime::Problem& problem) const noexcept {
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
  if (command.action() == "update" && !mir::valid_position_name(command.pose_name())) {
    problem.format("update needs pose_name: 1 to 40 of letters, digits, '_', '-', '.', ' '");
    return false;
  }
  return true;
}

void PoseSaverLogic::read_inputs(Time now) noexcept {
  now_ = now;
  if (!link_.collect(now, completion_)) return;
  const MirCall call = completion_.reply.call;
  const bool ok = completion_.transport.is_ok() && completion_.reply.ok;
  if (phase_ == Phase::kReading && call == MirCall::kGetStatus && ok &&
      completion_.submitted_at >= reading_since_) {
    phase_ = Phase::kSaving;
  } else if (phase_ == Phase::kSaving && call == MirCall::kPostPosition) {
    if (ok) {
      done_action_.assign("updated");
      saved_pose_.assign_cut(pose_.view());
      saved_x_ = saving_x_;
      saved_y_ = saving_y_;
      saved_yaw_ = saving_yaw_;
      phase_ = Phase::kIdle;
    } else if (completion_.transport.is_ok()) {  // answered and refused: latched
      failed_ = true;
      failure_.assign_cut(completion_.reply.problem.view());
      phase_ = Phase::kIdle;
    }  // no answer: posted again when the link is idle
  }
}

runtime::NodeCondition PoseSaverLogic::condition() const noexcept {
  if (!link_.answering(now_)) return runtime::NodeCondition::kDevicesMissing;
  if (failed_) return runtime::NodeCondition::kFault;
  return runtime::NodeCondition::kOk;
}

void PoseSaverLogic::update(const Command* in_force, Time now) noexcept {
  now_ = now;
  if (in_force == nullptr) {
    phase_ = Phase::kIdle;  // abandoned before its POST
    link_.poll_status(now);
    return;
  }
  const std::string_view action = in_force->action();
  const bool fresh =
      !has_handled_ || handled_action_.view() != action || handled_pose_.view() != in_force->pose_name();
  if (fresh) {
    has_handled_ = true;
    handled_action_.assign_cut(action);
    handled_pose_.assign_cut(in_force->pose_name());
    if (action == "update") {
      pose_.assign_cut(in_force->pose_name());
      done_action_.clear();
      phase_ = Phase::kReading;
      reading_since_ = now;
    } else {
      phase_ = Phase::kIdle;
      done_action_.clear();
    }
  }
  if (link_.busy()) return;
  if (phase_ == Phase::kReading) {
    link_.send(mir::get_status(), now);  // a pose read after the command, not an older one
  } else if (phase_ == Phase::kSaving) {
    const mir::MirStatus& status = link_.status();
    saving_x_ = status.x;
    saving_y_ = status.y;
    saving_yaw_ = status.yaw_deg;
    link_.send(mir::post_position(pose_.view(), status.x, status.y, status.yaw_deg, status.map_id.view()),
               now);
  } else {
    link_.poll_status(now);
  }
}

void PoseSaverLogic::reset() noexcept {
  failed_ = false;
  failure_.clear();
  has_handled_ = false;
  phase_ = Phase::kIdle;
}

void PoseSaverLogic::report(State& state, runtime::ErrorList& errors, Time now) const noexcept {
  state.set_robot_name(settings_.link.robot_name);
  state.set_done_action(done_action_.view());
  state.set_busy(phase_ != Phase::kIdle);
  state.set_saved_pose(saved_pose_.view());
  state.set_x(saved_x_);
  state.set_y(saved_y_);
  state.set_yaw(saved_yaw_);
  link_.report(errors, now);
  if (failed_) errors.add("saving pose '{}' failed (reset to clear): {}", pose_.view(), failure_.view());
}

}  // namespace hubrt::mir_com
