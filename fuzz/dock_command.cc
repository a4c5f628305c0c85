// DockCommand from raw CDR through the intake of a "dock" node (node-type layout): Cyclone's
// deserialiser, then runtime::Node's checks, the logic's validate(), and a few cycles.
#include <cstddef>
#include <cstdint>

#include "node_fixtures.h"
#include "node_harness.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using Logic = hubrt::dock_ecu::DockLogic;
  static const std::string& name = hubrt::fuzz::node_name("dock_ecu", Logic::kType);
  hubrt::fuzz::run_command<Logic>({data, size}, name, hubrt::fuzz::fuzz_clock(),
                                  &hubrt::fuzz::make_dock_logic);
  return 0;
}
