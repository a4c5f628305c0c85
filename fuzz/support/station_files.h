// The project's own files the harnesses build their nodes from: the host-sim board and the hub
// files under hubs/ (read from the source tree this build came from). Loaded once; a harness that
// cannot load them aborts with the loader's message, since it could fuzz nothing.
#pragma once

#include <string>
#include <string_view>

#include "hubrt/config/hub_config.h"
#include "hubrt/hal/board/board_config.h"

namespace hubrt::fuzz {

// <source tree>/<relative>.
std::string source_path(std::string_view relative);

// boards/host-sim.yaml, the board the simulated station runs on.
const hal::BoardConfig& host_sim_board();

// hubs/<hub>/<hub>.yaml, loaded and checked as hubd does.
const config::HubConfig& hub_file(std::string_view hub);

// The first node of `type` in `hub`.
const config::NodeConfig& node_of_type(const config::HubConfig& hub, std::string_view type);

// Prints "fuzz harness setup: <what>" and aborts.
[[noreturn]] void setup_failed(std::string_view what);

}  // namespace hubrt::fuzz
