// The mir_com hub type: the SBC on a MiR100 that translates the planner's Robot Mover and Pose
// Saver commands into the platform's REST API (hubs/mir_com/README.md).
#pragma once

#include "hubrt/hub_api/hub_type.h"

namespace hubrt::mir_com {
const hub_api::HubType& mir_com_hub_type() noexcept;
}  // namespace hubrt::mir_com
