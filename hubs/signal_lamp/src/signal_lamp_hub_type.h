// The signal lamp hub type: nodes of type "lamp", one board output each. The smallest hub type,
// written as docs/new-hub.md says.
#pragma once

#include "hubrt/hub_api/hub_type.h"

namespace hubrt::signal_lamp {
const hub_api::HubType& signal_lamp_hub_type() noexcept;
}  // namespace hubrt::signal_lamp
