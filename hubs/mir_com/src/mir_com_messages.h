// The mir_com hub's message types: the classes generated from robot_mover.idl, pose_saver.idl and
// mir_com.idl (firmware/msgs/README.md, "Typed accessors"); the _typed.h headers also register
// the topics.
#pragma once

#include <string_view>

#include "mir_com_reflect.h"
#include "mir_com_typed.h"
#include "pose_saver_reflect.h"
#include "pose_saver_typed.h"
#include "robot_mover_reflect.h"
#include "robot_mover_typed.h"

namespace hubrt::mir_com {

// The C structs on the wire, for tests that talk DDS directly (logic uses the classes).
using RobotMoverCommand = hub_msgs::RobotMoverCommand::Wire;
using RobotMoverState = hub_msgs::RobotMoverState::Wire;
using PoseSaverCommand = hub_msgs::PoseSaverCommand::Wire;
using PoseSaverState = hub_msgs::PoseSaverState::Wire;

// The hub layout's types (NodeWiring's HubTypes).
struct MirComTypes {
  using Command = hub_msgs::MirComCommandView;
  using State = hub_msgs::MirComState;
  static constexpr std::string_view kType = "mir_com";
};

// The one robot type these node types drive.
inline constexpr std::string_view kRobotType = "MIR100";

}  // namespace hubrt::mir_com
