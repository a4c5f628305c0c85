// The settings of mir_com's nodes (hubs/mir_com/README.md, "Settings"), read from the hub file.
#pragma once

#include <string>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/config/hub_config.h"
#include "hubrt/hal/board/board_requirements.h"

namespace hubrt::mir_com {

// What both node types share: the platform's HTTP device and how it is polled.
struct MirLinkSettings {
  std::string device;                              // the board's HTTP device, e.g. "mir"
  std::string robot_name;                          // what commands must name in robot_name, e.g. "mir100"
  Duration poll = std::chrono::milliseconds(200);  // least time between two GET /status
  Duration answer_within = std::chrono::milliseconds(2000);  // no status for this long: not answering
};

struct RobotMoverSettings {
  MirLinkSettings link;
  std::string move_mission;                     // guid of the platform's "move to position" mission
  std::string position_parameter = "Position";  // that mission's position parameter
};

struct PoseSaverSettings {
  MirLinkSettings link;
};

// Errors name file:line (unknown keys, a guid or name the MiR API would refuse, ranges).
Expected<RobotMoverSettings> parse_robot_mover_settings(const config::NodeConfig& node);
Expected<PoseSaverSettings> parse_pose_saver_settings(const config::NodeConfig& node);

void add_requirements(const MirLinkSettings& settings, hal::BoardRequirements& requirements);

}  // namespace hubrt::mir_com
