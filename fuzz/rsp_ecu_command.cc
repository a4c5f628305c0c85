// RspEcuCommand from raw CDR through the hub layout: the hub-level node takes it, hands each
// node its fragment, and each node validates its own (support/hub_layout_harness.h).
#include <cstddef>
#include <cstdint>

#include "hub_layout_harness.h"
#include "node_fixtures.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  hubrt::fuzz::HubLayoutUnderFuzz<hubrt::rsp_ecu::RspEcuTypes> hub;
  hub.add(hubrt::fuzz::node_name("rsp_ecu", hubrt::rsp_ecu::RspLogic::kType), hubrt::fuzz::make_rsp_logic());
  hub.run({data, size}, hubrt::fuzz::hub_file("rsp_ecu").name, hubrt::fuzz::fuzz_clock());
  return 0;
}
