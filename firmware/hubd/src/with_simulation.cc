// The development hubd: runs simulated boards too (linked_simulation.h).
#include "hubrt/assembly/fake_simulation.h"

#include "linked_simulation.h"

namespace hubrt::hubd {

const assembly::Simulation* linked_simulation() noexcept {
  return &assembly::fake_simulation();
}

}  // namespace hubrt::hubd
