// Counts heap allocations by interposing malloc and friends in the benchmark executable: on the
// calling thread (the cycle) and in the whole process (Cyclone's threads too). Only for builds
// without sanitizers, which interpose the same functions.
#pragma once

#include <cstdint>

namespace hubrt::bench {

// Allocations made so far by the calling thread.
std::uint64_t thread_allocations() noexcept;
// Allocations made so far by every thread of the process.
std::uint64_t process_allocations() noexcept;

}  // namespace hubrt::bench
