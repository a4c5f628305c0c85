// Counting and awaiting the remote endpoints matched with one of ours (tests and tools only).
#pragma once

#include <cstdint>
#include <string>

#include <dds/dds.h>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"

namespace hubrt::dds::detail {

enum class EndpointKind { kWriter, kReader };

// Current number of matched readers (for a writer) or writers (for a reader). Never allocates.
Result<std::uint32_t> matched_count(dds_entity_t endpoint, EndpointKind kind) noexcept;

// Polls matched_count() until it reaches `wanted` or `timeout` passes.
// Errors: kTimeout "<what>: <n> matched after <t> s, wanted <wanted>"; Cyclone errors as Errors.
Expected<void> wait_for_matched(dds_entity_t endpoint, EndpointKind kind, std::uint32_t wanted,
                                Duration timeout, const std::string& what);

}  // namespace hubrt::dds::detail
