// The `error_list` of a State: rebuilt every cycle from what is wrong right now, in storage sized
// once, and bound into the wire sample without copying.
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
    pointers_[count_] = const_cast<char*>(entries_[count_].c_str());  // NOLINT: the wire type wants char*
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

  // Points an idlc `sequence<string>` (fields _maximum, _length, _buffer, _release) at our
  // storage. The sample must not be freed with DDS_FREE_ALL while bound.
  template <class Sequence>
  void bind(Sequence& seq) noexcept {
    seq._maximum = static_cast<std::uint32_t>(kMaxEntries);
    seq._length = static_cast<std::uint32_t>(count_);
    seq._buffer = pointers_.data();
    seq._release = false;
  }

 private:
  std::array<TextBuffer<kMaxLength>, kMaxEntries> entries_{};
  std::array<char*, kMaxEntries> pointers_{};
  std::size_t count_ = 0;
  std::size_t dropped_ = 0;
};

}  // namespace hubrt::runtime
