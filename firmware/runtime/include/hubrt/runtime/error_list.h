// The `error_list` of a State: rebuilt every cycle from what is wrong right now, in storage sized
// once, then copied into the State's bounded `sequence<string<191>, 16>` (copy_to()).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "hubrt/runtime/text_buffer.h"

namespace hubrt::runtime {

class ErrorList {
 public:
  static constexpr std::size_t kMaxEntries = 16;
  static constexpr std::size_t kMaxLength = 191;

  void clear() noexcept {
    count_ = 0;
    dropped_ = 0;
  }

  // Adds one message. When the list is full the message is dropped and counted; the last entry
  // then says how many were dropped, so an operator never sees a silently short list. A message
  // that is not valid UTF-8 (it quotes bytes a peer or a device sent) is stored with those bytes
  // escaped (\xED): one bad string in error_list would make the whole State unreadable to a
  // ROS 2 client or to JSON tools.
  template <class... Args>
  void add(fmt::format_string<Args...> spec, Args&&... args) noexcept {
    if (count_ == kMaxEntries) {
      ++dropped_;
      entries_[kMaxEntries - 1].format("... and {} more errors", dropped_ + 1);
      return;
    }
    entries_[count_].format(spec, std::forward<Args>(args)...);
    entries_[count_].make_valid_utf8();
    ++count_;
  }

  [[nodiscard]] std::size_t size() const noexcept { return count_; }
  [[nodiscard]] bool empty() const noexcept { return count_ == 0; }
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
  std::size_t count_ = 0;
  std::size_t dropped_ = 0;
};

}  // namespace hubrt::runtime
