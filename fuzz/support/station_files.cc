#include "station_files.h"

#include <cstdio>
#include <cstdlib>
#include <map>

#include "hubrt/hal/board/board_loader.h"

namespace hubrt::fuzz {

std::string source_path(std::string_view relative) {
  return std::string(HUBRT_SOURCE_DIR) + "/" + std::string(relative);
}

void setup_failed(std::string_view what) {
  std::fprintf(stderr, "fuzz harness setup: %.*s\n", static_cast<int>(what.size()), what.data());
  std::abort();
}

const hal::BoardConfig& host_sim_board() {
  static const hal::BoardConfig board = [] {
    auto loaded = hal::load_board(source_path("boards/host-sim.yaml"));
    if (!loaded) setup_failed(loaded.error().message);
    return std::move(*loaded);
  }();
  return board;
}

const config::HubConfig& hub_file(std::string_view hub) {
  static std::map<std::string, config::HubConfig, std::less<>> loaded;
  if (auto found = loaded.find(hub); found != loaded.end()) return found->second;
  const std::string name(hub);
  auto config = config::load_hub_config(source_path("hubs/" + name + "/" + name + ".yaml"));
  if (!config) setup_failed(config.error().message);
  return loaded.emplace(name, std::move(*config)).first->second;
}

const config::NodeConfig& node_of_type(const config::HubConfig& hub, std::string_view type) {
  for (const config::NodeConfig& node : hub.nodes) {
    if (node.type == type) return node;
  }
  setup_failed(hub.file + " has no node of type " + std::string(type));
}

}  // namespace hubrt::fuzz
