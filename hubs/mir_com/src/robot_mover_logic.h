// The robot mover node (the paper's Robot Mover family, Table 2) for a MiR100: moves the
// platform to named positions through its mission queue, pauses and continues it, clears its
// error — by reconciling, at most once per status, what the platform does with what the command
// in force asks (the paper's state-based commands: a repeated command changes nothing).
//
// Safe state: whenever the node is not operational (no command within the timeout, a fault, the
// platform not answering) the platform is paused — PUT /status state_id 4, sent once and again
// only if a later status still shows it running (safe_hold in the State). A mission in progress
// is kept: "continue" (or the same "move" again) lets it go on. hubd stopping also pauses it (the
// device's request-on-close).
//
// What it latches (a fault until a reset): a move that failed (the platform has no such position,
// refused the mission, aborted it). The platform's own Error state is a fault while it lasts; a
// reset clears it (PUT /status clear_error), leaving the platform paused.
#pragma once

#include <array>
#include <memory>
#include <string_view>

#include "hubrt/runtime/node.h"

#include "mir_com_messages.h"
#include "mir_link.h"
#include "mir_settings.h"

namespace hubrt::mir_com {

class RobotMoverLogic {
 public:
  using Command = hub_msgs::RobotMoverCommandView;
  using State = hub_msgs::RobotMoverState;
  static constexpr std::string_view kType = "robot_mover";
  static constexpr std::array<std::string_view, 5> kActions{"move", "pause", "continue", "clear_error",
                                                            "reset"};

  // `device`: the platform's asynchronous HTTP device, opened by the hub type. Sets its
  // request-on-close to "pause".
  RobotMoverLogic(const RobotMoverSettings& settings, std::unique_ptr<MirDevice> device) noexcept;
  RobotMoverLogic(RobotMoverLogic&&) noexcept = default;
  RobotMoverLogic& operator=(RobotMoverLogic&&) noexcept = default;

  // robot_type MIR100, our robot_name, pose_type POSITION or empty, a valid pose_name for "move",
  // speed_scal and acc_scal in [0, 1], goal_toll >= 0.
  bool validate(const Command& command, runtime::Problem& problem) const noexcept;
  void read_inputs(Time now) noexcept;
  // kDevicesMissing: no status within answer_within; kFault: a failed move (latched) or the
  // platform in Error / emergency stop; else kOk.
  runtime::NodeCondition condition() const noexcept;
  void update(const Command* in_force, Time now) noexcept;
  void reset() noexcept;
  void report(State& state, runtime::ErrorList& errors, Time now) const noexcept;
  // Pauses the platform (best effort: the device sends it when closed, after the request in flight).
  void enter_safe_state() noexcept;

  [[nodiscard]] const MirLink& link() const noexcept { return link_; }
  [[nodiscard]] bool safe_hold() const noexcept { return safe_hold_; }

 private:
  enum class Phase : std::uint8_t { kIdle, kFinding, kPosting, kRunning };

  void on_completion(const MirCompletion& done) noexcept;
  void hold_paused(Time now) noexcept;
  void follow(const Command& command, Time now) noexcept;
  void follow_move(Time now) noexcept;
  // PUT /status state_id `state_id`, unless one went out since the last status (or within
  // answer_within while the platform does not answer).
  void control(const hal::HttpRequest& request, Time now) noexcept;
  [[nodiscard]] bool platform_stopped() const noexcept;  // Error or emergency stop
  void fail(std::string_view why) noexcept;

  RobotMoverSettings settings_;
  MirLink link_;
  MirCompletion completion_{};
  // The command carried out last (a repeat of it changes nothing).
  hal::FixedText<64> handled_action_;
  hal::FixedText<64> handled_pose_;
  bool has_handled_ = false;
  Phase phase_ = Phase::kIdle;
  hal::FixedText<64> goal_;
  hal::FixedText<40> goal_guid_;
  int mission_id_ = 0;
  hal::FixedText<16> mission_state_;
  bool mission_turn_ = false;  // alternate GET /mission_queue/{id} and GET /status while running
  hal::FixedText<64> actual_pose_;
  hal::FixedText<16> done_action_;
  bool control_sent_ = false;
  Time control_at_{};
  bool clear_pending_ = false;
  bool safe_hold_ = true;
  bool failed_ = false;
  hal::FixedText<160> failure_;
  Time now_{};
};

}  // namespace hubrt::mir_com
