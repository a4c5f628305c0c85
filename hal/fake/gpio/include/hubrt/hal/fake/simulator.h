// A simulated device, advanced lazily: it keeps what is scheduled (a valve reaching its end
// position, a contact bounce) and applies it when the simulation is brought up to a time.
#pragma once

#include "hubrt/base/time.h"

namespace hubrt::hal::fake {

class Simulator {
 public:
  virtual ~Simulator() = default;
  Simulator(const Simulator&) = delete;
  Simulator& operator=(const Simulator&) = delete;

  // Applies, in time order and at their own times, every change scheduled at or before `now`.
  virtual void advance_to(Time now) = 0;

 protected:
  Simulator() = default;
};

}  // namespace hubrt::hal::fake
