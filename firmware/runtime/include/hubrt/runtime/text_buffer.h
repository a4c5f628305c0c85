// Fixed-capacity text that never allocates: the storage behind strings that the cycle puts on
// the wire (error messages, names echoed in State). Cutting never splits a UTF-8 character, so
// valid UTF-8 put in stays valid UTF-8.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <iterator>
#include <span>
#include <string_view>

#include <fmt/format.h>

#include "hubrt/base/utf8.h"

namespace hubrt::runtime {

template <std::size_t Capacity>
class TextBuffer {
 public:
  static constexpr std::size_t kCapacity = Capacity;

  // Replaces the content; text beyond the capacity is cut (at a character) and marked with "...".
  void assign(std::string_view text) noexcept {
    const std::size_t n = text.size() < Capacity ? text.size() : Capacity;
    text.copy(data_.data(), n);
    length_ = n;
    data_[n] = '\0';
    if (text.size() > Capacity) mark_truncated();
  }

  // Formats into the buffer without allocating; output beyond the capacity is cut (at a
  // character) and marked with "...".
  template <class... Args>
  void format(fmt::format_string<Args...> spec, Args&&... args) noexcept {
    try {
      const auto result = fmt::format_to_n(data_.data(), Capacity, spec, std::forward<Args>(args)...);
      length_ = result.size < Capacity ? result.size : Capacity;
      data_[length_] = '\0';
      if (result.size > Capacity) mark_truncated();
    } catch (...) {  // fmt only throws on a malformed spec, which format_string rejects at compile time
      assign("(unformattable message)");
    }
  }

  // Leaves valid UTF-8 as it is; otherwise rewrites the content with its bad bytes (and control
  // characters and backslashes) escaped as append_escaped_utf8() does, cut to the capacity.
  // Allocation-free (a copy on the stack).
  void make_valid_utf8() noexcept {
    if (is_valid_utf8(view())) return;
    std::array<char, Capacity> original{};
    const std::size_t n = length_;
    std::copy_n(data_.data(), n, original.data());
    const std::string_view source(original.data(), n);
    EscapedUtf8 escaped = append_escaped_utf8(source, std::span<char>(data_.data(), Capacity));
    if (!escaped.complete && Capacity >= 3) {
      escaped = append_escaped_utf8(source, std::span<char>(data_.data(), Capacity - 3));
      for (std::size_t i = 0; i < 3; ++i) data_[escaped.written++] = '.';
    }
    length_ = escaped.written;
    data_[length_] = '\0';
  }

  void clear() noexcept {
    length_ = 0;
    data_[0] = '\0';
  }
  [[nodiscard]] const char* c_str() const noexcept { return data_.data(); }
  [[nodiscard]] std::string_view view() const noexcept { return {data_.data(), length_}; }
  [[nodiscard]] bool empty() const noexcept { return length_ == 0; }

 private:
  // Puts "..." over the end, backing off to the start of the character it would overwrite, so
  // that no lead byte is left without its continuation bytes.
  void mark_truncated() noexcept {
    if (Capacity < 3) return;
    std::size_t cut = Capacity - 3;
    while (cut > 0 && (static_cast<unsigned char>(data_[cut]) & 0xc0) == 0x80) --cut;
    for (std::size_t i = 0; i < 3; ++i) data_[cut + i] = '.';
    length_ = cut + 3;
    data_[length_] = '\0';
  }

  std::array<char, Capacity + 1> data_{};
  std::size_t length_ = 0;
};

}  // namespace hubrt::runtime
