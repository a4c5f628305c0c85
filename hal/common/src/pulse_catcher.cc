#include "hubrt/hal/common/pulse_catcher.h"

namespace hubrt::hal {

bool PulseCatcher::report(bool current, bool saw_other_level) noexcept {
  if (!reported_.has_value() || current != *reported_) {
    reported_ = current;
  } else if (saw_other_level) {
    reported_ = !current;
  }
  return *reported_;
}

}  // namespace hubrt::hal
