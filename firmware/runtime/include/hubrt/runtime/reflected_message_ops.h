// MessageOps for any generated type, driven by its reflection table (hubrt/msgs/type_info.h).
#pragma once

#include "hubrt/msgs/type_info.h"
#include "hubrt/runtime/message_ops.h"

namespace hubrt::runtime {

// Thread-safety: immutable; all calls reentrant. Allocation-free.
class ReflectedMessageOps final : public MessageOps {
 public:
  explicit ReflectedMessageOps(const msgs::TypeInfo& type) noexcept : type_(type) {}

  [[nodiscard]] bool equal(const void* a, const void* b) const noexcept override;
  [[nodiscard]] bool copy_into(const void* src, void* dst, Arena& arena) const noexcept override;
  [[nodiscard]] bool check_fields(const void* msg, std::size_t max_length,
                                  Problem& problem) const noexcept override;
  [[nodiscard]] const msgs::TypeInfo& type() const noexcept { return type_; }

 private:
  const msgs::TypeInfo& type_;
};

// Why `text` is not acceptable in a command string, or nullptr when it is: at most `max_length`
// bytes, well-formed UTF-8 per RFC 3629 (hubrt::is_valid_utf8: no overlongs, no encoded
// surrogates, nothing above U+10FFFF), no control characters. Reads at most max_length + 1 bytes.
const char* string_problem(const char* text, std::size_t max_length) noexcept;
// The same for text already delimited (a bounded string's bytes up to its NUL).
const char* string_problem(std::string_view bytes, std::size_t max_length) noexcept;

}  // namespace hubrt::runtime
