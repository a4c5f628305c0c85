// The Dock ECU assembled in the test's process on the simulated board (the fake backend and the
// sim bridge of hubrt_assembly_sim), at `rate_hz`, in the test's own domain, with its black box
// recording as in hubd (into a folder of the domain's): what the in-process allocation and cadence
// tests drive cycle by cycle.
#pragma once

#include <memory>
#include <string>

#include "hubrt/assembly/fake_simulation.h"
#include "hubrt/assembly/hub_assembly.h"
#include "hubrt/test_support/test_domain.h"

namespace hubrt::integration {

inline Expected<std::unique_ptr<assembly::AssembledHub>> assemble_sim_dock(
    const test_support::TestDomain& domain, const Clock& clock, double rate_hz) {
  assembly::AssemblyRequest request;
  request.board_file = std::string(HUBRT_SOURCE_DIR) + "/boards/host-sim.yaml";
  request.hub_file = std::string(HUBRT_SOURCE_DIR) + "/hubs/dock_ecu/dock_ecu.yaml";
  request.backend = assembly::BackendKind::kFake;
  request.simulation = &assembly::fake_simulation();
  request.domain = domain.config();
  request.rate_hz = rate_hz;
  request.black_box_directory = "/tmp/hubrt-blackbox-test-" + std::to_string(domain.config().domain_id);
  return assembly::assemble_hub(request, clock);
}

}  // namespace hubrt::integration
