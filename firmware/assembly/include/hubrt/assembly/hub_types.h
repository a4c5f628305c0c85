// The hub types built into this program: the registry that hubs/HubTypes.cmake generates from
// every hubs/<hub> folder. Only the composition root (assembly, hubd, tools) looks hub types up;
// hub types themselves never see each other.
#pragma once

#include <span>
#include <string_view>

#include "hubrt/hub_api/hub_type.h"

namespace hubrt::assembly {

// Every hub type built into this program (defined by the hubs/ folder).
std::span<const hub_api::HubType* const> hub_types() noexcept;
// The hub type called `name`, or nullptr.
const hub_api::HubType* find_hub_type(std::string_view name) noexcept;

}  // namespace hubrt::assembly
