// The simulation of hubrt_assembly_sim: the fake backend (hal/fake) and the sim bridge
// (firmware/sim). Linked only into the programs that run simulated boards (the development hubd,
// tests, benchmarks), never into the board build of hubd (simulation.h).
#pragma once

#include "hubrt/assembly/simulation.h"

namespace hubrt::hal::fake {
class FakeBackend;
}

namespace hubrt::assembly {

// The one instance (stateless). Thread-safety: const, callable from any thread.
const Simulation& fake_simulation() noexcept;

// The FakeBackend behind a backend fake_simulation() opened (test hooks: inputs, faults).
hal::fake::FakeBackend& fake_backend_of(Simulation::SimulatedBackend& backend) noexcept;

}  // namespace hubrt::assembly
