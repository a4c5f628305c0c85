// The `error_list` of a State: rebuilt every cycle from what is wrong right now, in storage sized
// once, then copied into the State's bounded `sequence<string<191>, 16>` (copy_to()). An entry is
// formatted again only when its format string or an argument changed since the last cycle
// (FormatKey): a missing device's message, the same for hours, costs a comparison per cycle
// instead of formatting and a UTF-8 check (issue 16: nothing formatted per cycle that did not
// change).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "hubrt/runtime/format_key.h"
#include "hubrt/runtime/text_buffer.h"

namespace hubrt::runtime {

class ErrorList {
 public:
  static constexpr std::size_t kMaxEntries = 16;
  static constexpr std::size_t kMaxLength = 191;
  // Room for a message's format string and arguments (FormatKey): a missing device's message
  // quotes its open error, ~200 bytes, after the slot and signal names. A message whose format
  // string and arguments take more is formatted every time.
  static constexpr std::size_t kMaxKeyBytes = 512;

  void clear() noexcept {
    count_ = 0;
    dropped_ = 0;
  }

  // Adds one message. When the list is full the message is dropped and counted; the last entry
  // then says how many were dropped, so an operator never sees a silently short list. A message
  // that is not valid UTF-8 (it quotes bytes a peer or a device sent) is stored with those bytes
  // escaped (\xED): one bad string in error_list would make the whole State unreadable to a
  // ROS 2 client or to JSON tools. The i-th message after clear() is formatted only when it
  // differs from the i-th of the cycle before in its format string or an argument's value.
  template <class... Args>
  void add(fmt::format_string<Args...> spec, Args&&... args) noexcept {
    if (count_ == kMaxEntries) {
      ++dropped_;
      keys_[kMaxEntries - 1].forget();
      entries_[kMaxEntries - 1].format("... and {} more errors", dropped_ + 1);
      ++formatted_;
      return;
    }
    const std::size_t i = count_++;
    const fmt::string_view text = spec;
    if (keys_[i].update(std::string_view(text.data(), text.size()), args...)) return;  // as the cycle before
    entries_[i].format(spec, std::forward<Args>(args)...);
    entries_[i].make_valid_utf8();
    ++formatted_;
  }

  [[nodiscard]] std::size_t size() const noexcept { return count_; }
  [[nodiscard]] bool empty() const noexcept { return count_ == 0; }
  // How many messages were formatted since construction (the others were the same as the cycle
  // before): for tests and benchmarks.
  [[nodiscard]] std::uint64_t formatted() const noexcept { return formatted_; }
  [[nodiscard]] std::string_view at(std::size_t i) const noexcept { return entries_[i].view(); }
  [[nodiscard]] bool contains(std::string_view fragment) const noexcept {
    for (std::size_t i = 0; i < count_; ++i) {
      if (entries_[i].view().find(fragment) != std::string_view::npos) return true;
    }
    return false;
  }

  // Replaces the entries of a State's error_list (a generated SequenceRef of string<kMaxLength>,
  // at most kMaxEntries: the IDL bounds match these, so nothing is cut).
  template <class Sequence>
  void copy_to(const Sequence& seq) const noexcept {
    seq.clear();
    for (std::size_t i = 0; i < count_; ++i) seq.push_back(entries_[i].view());
  }

 private:
  std::array<TextBuffer<kMaxLength>, kMaxEntries> entries_{};
  std::array<FormatKey<kMaxKeyBytes>, kMaxEntries> keys_;  // what entries_[i] was formatted from
  std::size_t count_ = 0;
  std::uint64_t formatted_ = 0;
  std::size_t dropped_ = 0;
};

}  // namespace hubrt::runtime
