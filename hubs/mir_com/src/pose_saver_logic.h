// The pose saver node (the paper's Pose Saver family, Table 3) for a MiR100: "update" saves the
// platform's current pose under pose_name as a position of its map (GET /status for a fresh pose,
// then POST /positions), once per command (a repeat changes nothing; "idle" or another name in
// between, or a reset, lets the same name be saved again). It moves nothing: its safe state is
// to send nothing (a save under way when the node stops being operational is abandoned before
// its POST).
//
// What it latches (a fault until a reset): a save the platform refused.
#pragma once

#include <array>
#include <limits>
#include <memory>
#include <string_view>

#include "hubrt/runtime/node.h"

#include "mir_com_messages.h"
#include "mir_link.h"
#include "mir_settings.h"

namespace hubrt::mir_com {

class PoseSaverLogic {
 public:
  using Command = hub_msgs::PoseSaverCommandView;
  using State = hub_msgs::PoseSaverState;
  static constexpr std::string_view kType = "pose_saver";
  static constexpr std::array<std::string_view, 3> kActions{"update", "idle", "reset"};

  PoseSaverLogic(const PoseSaverSettings& settings, std::unique_ptr<MirDevice> device) noexcept
      : settings_(settings), link_(std::move(device), settings.link) {}
  PoseSaverLogic(PoseSaverLogic&&) noexcept = default;
  PoseSaverLogic& operator=(PoseSaverLogic&&) noexcept = default;

  // robot_type MIR100, our robot_name, pose_type POSITION or empty, a valid pose_name for "update".
  bool validate(const Command& command, runtime::Problem& problem) const noexcept;
  void read_inputs(Time now) noexcept;
  // kDevicesMissing: no status within answer_within; kFault: a refused save (latched); else kOk.
  runtime::NodeCondition condition() const noexcept;
  void update(const Command* in_force, Time now) noexcept;
  void reset() noexcept;
  void report(State& state, runtime::ErrorList& errors, Time now) const noexcept;
  void enter_safe_state() noexcept {}  // nothing moves

  [[nodiscard]] const MirLink& link() const noexcept { return link_; }

 private:
  enum class Phase : std::uint8_t { kIdle, kReading, kSaving };

  PoseSaverSettings settings_;
  MirLink link_;
  MirCompletion completion_{};
  hal::FixedText<64> handled_action_;
  hal::FixedText<64> handled_pose_;
  bool has_handled_ = false;
  Phase phase_ = Phase::kIdle;
  hal::FixedText<64> pose_;  // the name being saved
  Time reading_since_{};
  hal::FixedText<64> done_action_;
  hal::FixedText<64> saved_pose_;
  float saving_x_ = 0, saving_y_ = 0, saving_yaw_ = 0;  // the pose being posted
  // The pose last saved; NaN (ROS's "not measured") until one is.
  float saved_x_ = std::numeric_limits<float>::quiet_NaN();
  float saved_y_ = std::numeric_limits<float>::quiet_NaN();
  float saved_yaw_ = std::numeric_limits<float>::quiet_NaN();
  bool failed_ = false;
  hal::FixedText<160> failure_;
  Time now_{};
};

}  // namespace hubrt::mir_com
