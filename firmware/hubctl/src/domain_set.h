// Several DDS domains at once, for the plant-wide tools (`hubctl list/watch/record --domain
// 10-41`): a plant runs one domain per station (docs/plant.md), and a tool that watches the plant
// joins each of them with a participant of its own.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "hubrt/base/status.h"

namespace hubrt::hubctl {

// The most domains one hubctl joins: each is a Cyclone domain instance of its own in the process
// (its own threads and sockets), so a typo such as 0-232 fails here instead of starting
// 233 of them.
inline constexpr std::size_t kMaxPlantDomains = 64;

// "10-41", "3", "3,5,7-9" (blanks around the parts allowed): the ids in ascending order, each
// once. Thread-safe. Errors (kInvalidArgument, naming the part): empty text or part, a part that
// is not a number or a range "A-B" with A <= B, an id above dds::kMaxDomainId, an id named twice
// (also by overlapping ranges), more than kMaxPlantDomains ids.
Expected<std::vector<std::uint32_t>> parse_domain_set(std::string_view text);

// The ids back as parse_domain_set reads them, ranges folded: {10, 11, 12, 20} -> "10-12,20".
// Thread-safe.
std::string format_domain_set(const std::vector<std::uint32_t>& ids);

}  // namespace hubrt::hubctl
