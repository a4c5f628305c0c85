// A hub file (hubs/<hub>/<hub>.yaml) as hubd --check reads it (hubrt::assembly's start-up): the
// hub configuration loader, the hub type's reading of its node settings (requirements()), and the
// check of those requirements against the host-sim board.
#include <cstddef>
#include <cstdint>
#include <string>

#include "hubrt/assembly/hub_types.h"
#include "hubrt/config/hub_config.h"
#include "hubrt/config/yaml_map.h"
#include "hubrt/hal/board/board_requirements.h"

#include "station_files.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const hubrt::hal::BoardConfig& board = hubrt::fuzz::host_sim_board();
  const std::string text(reinterpret_cast<const char*>(data), size);
  auto root = hubrt::config::YamlMap::load_string(text, "fuzz.yaml");
  if (!root) return 0;
  auto config = hubrt::config::parse_hub_config(*root);
  if (!config) return 0;
  const hubrt::hub_api::HubType* type = hubrt::assembly::find_hub_type(config->type);
  if (type == nullptr) return 0;
  auto required = type->requirements(*config);
  if (!required) return 0;
  (void)hubrt::hal::check_requirements(board, *required);
  return 0;
}
