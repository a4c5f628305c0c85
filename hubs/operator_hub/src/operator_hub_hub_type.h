// The operator hub type: nodes of type "operator_panel" (RFID operator verification and the
// confirm button), written as docs/new-hub.md says.
#pragma once

#include "hubrt/hub_api/hub_type.h"

namespace hubrt::operator_hub {
const hub_api::HubType& operator_hub_hub_type() noexcept;
}  // namespace hubrt::operator_hub
