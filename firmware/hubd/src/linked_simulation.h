// Which simulation this hubd was linked with (assembly/simulation.h): the development hubd links
// with_simulation.cc (the fake backend and the sim bridge, for simulated boards), the board build
// without_simulation.cc (none). The choice is which file the program is linked from, not an #ifdef.
#pragma once

#include "hubrt/assembly/simulation.h"

namespace hubrt::hubd {

// Null in the board build. Thread-safety: any thread.
const assembly::Simulation* linked_simulation() noexcept;

}  // namespace hubrt::hubd
