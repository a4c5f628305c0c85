// Counts heap allocations made by the calling thread while a scope is active, by interposing
// malloc and friends (operator new ends in malloc). Link the object library into a test
// executable that is not built with a sanitizer (sanitizers interpose malloc themselves).
#pragma once

#include <cstddef>

namespace hubrt::testing {

class AllocationScope {
 public:
  AllocationScope() noexcept;
  ~AllocationScope();
  AllocationScope(const AllocationScope&) = delete;
  AllocationScope& operator=(const AllocationScope&) = delete;
  // Allocations by this thread since the scope began.
  [[nodiscard]] std::size_t count() const noexcept;

 private:
  std::size_t start_;
};

}  // namespace hubrt::testing
