// The board build of hubd: no fake backend, no simulators, no sim bridge (linked_simulation.h).
#include "linked_simulation.h"

namespace hubrt::hubd {

const assembly::Simulation* linked_simulation() noexcept {
  return nullptr;
}

}  // namespace hubrt::hubd
