// Deep operations on one generated message type that the generic node needs and C structs do
// not give: compare two commands, copy one into arena storage, and check every field of it.
#pragma once

#include <cstddef>

#include "hubrt/runtime/arena.h"
#include "hubrt/runtime/text_buffer.h"

namespace hubrt::runtime {

using Problem = TextBuffer<160>;

// Thread-safety: implementations are immutable after construction; all calls are reentrant.
class MessageOps {
 public:
  virtual ~MessageOps() = default;
  // True when every field of `a` and `b` is equal (strings by content, sequences element-wise).
  [[nodiscard]] virtual bool equal(const void* a, const void* b) const noexcept = 0;
  // Deep-copies `src` over `dst`; strings and sequences of `dst` are placed in `arena`, which is
  // reset first. Returns false when the arena is too small (dst is then left zeroed).
  [[nodiscard]] virtual bool copy_into(const void* src, void* dst, Arena& arena) const noexcept = 0;
  // Checks what no command may carry, whatever its type: strings longer than `max_length` bytes,
  // not UTF-8 or with control characters; floating-point values that are NaN or infinite.
  // On failure returns false and describes the first offending field in `problem`.
  [[nodiscard]] virtual bool check_fields(const void* msg, std::size_t max_length,
                                          Problem& problem) const noexcept = 0;
};

}  // namespace hubrt::runtime
