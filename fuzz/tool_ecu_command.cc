// ToolEcuCommand from raw CDR through the hub layout: the hub-level node takes it, hands each
// node its fragment, and each node validates its own (support/hub_layout_harness.h).
#include <cstddef>
#include <cstdint>

#include "hub_layout_harness.h"
#include "node_fixtures.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  hubrt::fuzz::HubLayoutUnderFuzz<hubrt::tool_ecu::ToolEcuTypes> hub;
  hub.add(hubrt::fuzz::node_name("tool_ecu", hubrt::tool_ecu::SmartToolLogic::kType),
          hubrt::fuzz::make_smart_tool_logic());
  hub.add(hubrt::fuzz::node_name("tool_ecu", hubrt::tool_ecu::LiftLogic::kType),
          hubrt::fuzz::make_lift_logic());
  hub.run({data, size}, hubrt::fuzz::hub_file("tool_ecu").name, hubrt::fuzz::fuzz_clock());
  return 0;
}
