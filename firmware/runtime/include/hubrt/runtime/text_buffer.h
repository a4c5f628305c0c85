// Fixed-capacity text that never allocates: the storage behind strings that the cycle puts on
// the wire (error messages, names echoed in State).
#pragma once

#include <array>
#include <cstddef>
#include <iterator>
#include <string_view>

#include <fmt/format.h>

namespace hubrt::runtime {

template <std::size_t Capacity>
class TextBuffer {
 public:
  static constexpr std::size_t kCapacity = Capacity;

  // Replaces the content; text beyond the capacity is cut and marked with "...".
  void assign(std::string_view text) noexcept {
    const std::size_t n = text.size() < Capacity ? text.size() : Capacity;
    text.copy(data_.data(), n);
    length_ = n;
    data_[n] = '\0';
    if (text.size() > Capacity) mark_truncated();
  }

  // Formats into the buffer without allocating; output beyond the capacity is cut.
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

  void clear() noexcept {
    length_ = 0;
    data_[0] = '\0';
  }
  [[nodiscard]] const char* c_str() const noexcept { return data_.data(); }
  [[nodiscard]] std::string_view view() const noexcept { return {data_.data(), length_}; }
  [[nodiscard]] bool empty() const noexcept { return length_ == 0; }

 private:
  void mark_truncated() noexcept {
    if (Capacity >= 3) {
      for (std::size_t i = Capacity - 3; i < Capacity; ++i) data_[i] = '.';
    }
  }

  std::array<char, Capacity + 1> data_{};
  std::size_t length_ = 0;
};

}  // namespace hubrt::runtime
