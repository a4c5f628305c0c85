#include "alloc_counter.h"

#include <cstdlib>

// glibc's own entry points, which our definitions forward to.
extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* ptr, std::size_t size);
void* __libc_memalign(std::size_t alignment, std::size_t size);
void __libc_free(void* ptr);
}

namespace {
// Per thread, so that allocations by DDS or other background threads are not attributed to the
// thread under measurement. Constant-initialised TLS: reading it never allocates.
thread_local std::size_t allocations = 0;
thread_local int active_scopes = 0;

void note() noexcept {
  if (active_scopes > 0) ++allocations;
}
}  // namespace

extern "C" {
void* malloc(std::size_t size) {
  note();
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) {
  note();
  return __libc_calloc(count, size);
}
void* realloc(void* ptr, std::size_t size) {
  note();
  return __libc_realloc(ptr, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) {
  note();
  return __libc_memalign(alignment, size);
}
void* memalign(std::size_t alignment, std::size_t size) {
  note();
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, std::size_t alignment, std::size_t size) {
  note();
  void* p = __libc_memalign(alignment, size);
  if (p == nullptr) return 12;  // ENOMEM
  *out = p;
  return 0;
}
void free(void* ptr) {
  __libc_free(ptr);
}
}

namespace hubrt::testing {

AllocationScope::AllocationScope() noexcept : start_(allocations) {
  ++active_scopes;
}
AllocationScope::~AllocationScope() {
  --active_scopes;
}
std::size_t AllocationScope::count() const noexcept {
  return allocations - start_;
}

}  // namespace hubrt::testing
