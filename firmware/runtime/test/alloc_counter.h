// Counts heap allocations by interposing malloc and friends (operator new ends in malloc): per
// thread and in the whole process. The one counter of the project's allocation tests and of the
// cycle benchmark: link target `hubrt_alloc_counter`, which compiles it into the executable.
// Only for builds without a sanitizer (sanitizers interpose the same functions).
#pragma once

#include <cstddef>
#include <cstdint>

namespace hubrt::testing {

// Allocations made so far by the calling thread.
std::uint64_t thread_allocations() noexcept;
// Allocations made so far by every thread of the process (DDS's own threads included).
std::uint64_t process_allocations() noexcept;

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
