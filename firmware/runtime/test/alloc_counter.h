// Counts heap allocations: per thread and in the whole process. The one counter of the project's
// allocation tests and of the cycle benchmark: link target `hubrt_alloc_counter`, which compiles
// it into the executable. Two ways to see every allocation, chosen when compiling:
// - in a sanitizer build (ASan, TSan), the sanitizer's allocation hooks
//   (__sanitizer_install_malloc_and_free_hooks, <sanitizer/allocator_interface.h>): the sanitizer
//   owns malloc there and runs the hooks on every allocation, malloc and operator new alike;
// - otherwise, by interposing malloc and friends (operator new ends in malloc).
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>

namespace hubrt::testing {

// Allocations made so far by the calling thread.
std::uint64_t thread_allocations() noexcept;
// Allocations made so far by every thread of the process (DDS's own threads included).
std::uint64_t process_allocations() noexcept;
// From this call on, also counts apart the allocations of threads whose name (PR_SET_NAME, as
// pthread_setname_np sets it) is one of `names` (up to kMaxNamedThreads; at most 15 bytes each;
// string literals: kept, not copied), e.g. Cyclone's timed-event thread "tev" and its discovery
// delivery thread "dq.builtins", to tell their lease-driven work from the rest of the process.
// Call once, before the threads counted allocate what is to be measured.
inline constexpr std::size_t kMaxNamedThreads = 4;
void count_allocations_of_threads_named(std::initializer_list<const char*> names) noexcept;
// Allocations counted so far for threads named `name` (one given to the call above; 0 otherwise).
std::uint64_t named_thread_allocations(const char* name) noexcept;
// How this build counts: "sanitizer hooks" or "interposed malloc".
const char* allocation_counting_method() noexcept;

// Allocations by the calling thread while the scope lives; other threads are not counted.
class AllocationScope {
 public:
  AllocationScope() noexcept : start_(thread_allocations()) {}
  AllocationScope(const AllocationScope&) = delete;
  AllocationScope& operator=(const AllocationScope&) = delete;
  [[nodiscard]] std::size_t count() const noexcept {
    return static_cast<std::size_t>(thread_allocations() - start_);
  }

 private:
  std::uint64_t start_;
};

}  // namespace hubrt::testing
